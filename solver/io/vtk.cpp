#include "solver/io/vtk.hpp"

#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace refmap {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { if (f) std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

const char* byte_order() { return std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian"; }

std::string fmt17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// Throws for a failed write of `path`; a temporary (".tmp") is removed first, so a full
/// disk leaves no half frame behind (the previous complete file, if any, stays).
[[noreturn]] void io_fail(const std::string& what, const std::string& path) {
  const int err = errno;
  if (path.ends_with(".tmp")) std::remove(path.c_str());
  throw std::runtime_error("cannot write " + path + ": " + what + (err ? std::string(" (") + std::strerror(err) + ")" : ""));
}

void check_field(const Field* f, const Grid& g, const std::string& name) {
  if (!f) throw std::invalid_argument("write_vti: field '" + name + "' is null");
  if (f->nx() != g.nx || f->ny() != g.ny)
    throw std::invalid_argument("write_vti: field '" + name + "' is " + std::to_string(f->nx()) + " x " +
                                std::to_string(f->ny()) + ", the grid is " + std::to_string(g.nx) + " x " +
                                std::to_string(g.ny) + " (only cell-centred fields can be written)");
}

/// Writes `text` to path via path.tmp + rename.
void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  errno = 0;
  FilePtr f(std::fopen(tmp.c_str(), "wb"));
  if (!f) io_fail("cannot open", tmp);
  if (std::fwrite(text.data(), 1, text.size(), f.get()) != text.size()) io_fail("write failed", tmp);
  if (std::fclose(f.release()) != 0) io_fail("close failed", tmp);
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot write " + path + ": rename failed (" + ec.message() + ")");
}

}  // namespace

std::string xml_escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&apos;"; break;
      default: o += c;
    }
  }
  return o;
}

void write_vti(const std::string& path, const Grid& g, const std::vector<VtkScalar>& scalars,
               const std::vector<VtkVector>& vectors, double time) {
  for (const auto& s : scalars) check_field(s.f, g, s.name);
  for (const auto& v : vectors) {
    check_field(v.fx, g, v.name + ".x");
    check_field(v.fy, g, v.name + ".y");
  }
  const std::uint64_t ncell = std::uint64_t(g.nx) * std::uint64_t(g.ny);
  const std::uint64_t scalar_bytes = ncell * sizeof(double);
  const std::uint64_t vector_bytes = 3 * ncell * sizeof(double);

  // ---- XML header
  const std::string ext = "0 " + std::to_string(g.nx) + " 0 " + std::to_string(g.ny) + " 0 0";
  std::string x;
  x += "<?xml version=\"1.0\"?>\n";
  x += std::string("<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"") + byte_order() +
       "\" header_type=\"UInt64\">\n";
  x += "  <ImageData WholeExtent=\"" + ext + "\" Origin=\"" + fmt17(g.x0) + " " + fmt17(g.y0) + " 0\" Spacing=\"" +
       fmt17(g.dx) + " " + fmt17(g.dx) + " 1\">\n";
  x += "    <FieldData>\n";
  x += "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">" + fmt17(time) +
       "</DataArray>\n";
  x += "    </FieldData>\n";
  x += "    <Piece Extent=\"" + ext + "\">\n";
  x += "      <CellData";
  if (!scalars.empty()) x += " Scalars=\"" + xml_escape(scalars.front().name) + "\"";
  if (!vectors.empty()) x += " Vectors=\"" + xml_escape(vectors.front().name) + "\"";
  x += ">\n";
  std::uint64_t offset = 0;
  for (const auto& s : scalars) {
    x += "        <DataArray type=\"Float64\" Name=\"" + xml_escape(s.name) + "\" format=\"appended\" offset=\"" +
         std::to_string(offset) + "\"/>\n";
    offset += sizeof(std::uint64_t) + scalar_bytes;
  }
  for (const auto& v : vectors) {
    x += "        <DataArray type=\"Float64\" Name=\"" + xml_escape(v.name) +
         "\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
    offset += sizeof(std::uint64_t) + vector_bytes;
  }
  x += "      </CellData>\n";
  x += "    </Piece>\n";
  x += "  </ImageData>\n";
  x += "  <AppendedData encoding=\"raw\">\n   _";

  // ---- write
  const std::string tmp = path + ".tmp";
  std::vector<char> iobuf(1 << 20);  // declared before f: it must outlive the FILE
  errno = 0;
  FilePtr f(std::fopen(tmp.c_str(), "wb"));
  if (!f) io_fail("cannot open", tmp);
  std::setvbuf(f.get(), iobuf.data(), _IOFBF, iobuf.size());
  auto put = [&](const void* p, std::size_t n) {
    if (n && std::fwrite(p, 1, n, f.get()) != n) io_fail("write failed", tmp);
  };
  put(x.data(), x.size());
  for (const auto& s : scalars) {
    put(&scalar_bytes, sizeof scalar_bytes);
    const CView fv = s.f->view();
    for (int j = 0; j < g.ny; ++j) put(&fv(0, j), std::size_t(g.nx) * sizeof(double));
  }
  std::vector<double> row(3 * std::size_t(g.nx));
  for (const auto& v : vectors) {
    put(&vector_bytes, sizeof vector_bytes);
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        row[3 * i] = (*v.fx)(i, j);
        row[3 * i + 1] = (*v.fy)(i, j);
        row[3 * i + 2] = 0.0;
      }
      put(row.data(), row.size() * sizeof(double));
    }
  }
  const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
  put(tail.data(), tail.size());
  if (std::fflush(f.get()) != 0) io_fail("write failed", tmp);
  if (std::fclose(f.release()) != 0) io_fail("close failed", tmp);
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot write " + path + ": rename failed (" + ec.message() + ")");
}

PvdSeries::PvdSeries(std::string pvd_path) : path_(std::move(pvd_path)) { write(); }

void PvdSeries::add(double time, const std::string& file_relative_to_pvd) {
  entries_.push_back({time, file_relative_to_pvd});
  write();
}

std::vector<std::pair<double, std::string>> PvdSeries::entries() const {
  std::vector<std::pair<double, std::string>> out;
  for (const auto& e : entries_) out.emplace_back(e.time, e.file);
  return out;
}

void PvdSeries::restore(const std::vector<std::pair<double, std::string>>& entries) {
  entries_.clear();
  for (const auto& [t, f] : entries) entries_.push_back({t, f});
  write();
}

void PvdSeries::write() const {
  if (path_.empty()) return;
  std::string x;
  x += "<?xml version=\"1.0\"?>\n";
  x += std::string("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"") + byte_order() + "\">\n";
  x += "  <Collection>\n";
  for (const auto& e : entries_)
    x += "    <DataSet timestep=\"" + fmt17(e.time) + "\" group=\"\" part=\"0\" file=\"" + xml_escape(e.file) + "\"/>\n";
  x += "  </Collection>\n";
  x += "</VTKFile>\n";
  write_atomically(path_, x);
}

}  // namespace refmap
