#include "solver/io/checkpoint_io.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fcntl.h>
#include <unistd.h>

namespace refmap {

namespace {

constexpr char kMagic[8] = {'R', 'E', 'F', 'M', 'A', 'P', 'C', 'K'};
// 2: the contact velocity scale (contact.U) and the rigid bodies' force records
// (body<k>.region.*, body<k>.end.*) of docs/bodies.md; a version-1 file is refused by name
// 3: the contact pairs in contact as a list (contact.touching) instead of an N x N table
// (contact.pair_state), and the byte and row counts of solids.csv (run.solids_*)
constexpr std::uint32_t kVersion = 3;
constexpr std::size_t kHeader = 8 + 4 + 8 + 8;  // magic, version, payload size, checksum

std::uint64_t fnv1a64(const unsigned char* p, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

template <class T>
void append_pod(std::vector<unsigned char>& out, const T& v) {
  const auto* b = reinterpret_cast<const unsigned char*>(&v);
  out.insert(out.end(), b, b + sizeof v);
}

}  // namespace

void CheckpointWriter::put_bytes(const std::string& tag, const void* data, std::size_t n) {
  append_pod(payload_, std::uint32_t(tag.size()));
  payload_.insert(payload_.end(), tag.begin(), tag.end());
  append_pod(payload_, std::uint64_t(n));
  const auto* b = static_cast<const unsigned char*>(data);
  payload_.insert(payload_.end(), b, b + n);
}

template <class T>
static void put_array(CheckpointWriter& w, const std::string& tag, const Array2<T>& f) {
  const std::int64_t shape[3] = {f.nx(), f.ny(), f.ng()};
  w.put_bytes(tag + ".shape", shape, sizeof shape);
  w.put_bytes(tag, f.raw(), f.raw_size() * sizeof(T));
}

void CheckpointWriter::put_field(const std::string& tag, const Field& f) { put_array(*this, tag, f); }
void CheckpointWriter::put_mask(const std::string& tag, const Mask& m) { put_array(*this, tag, m); }

void CheckpointWriter::save(const std::string& path) const {
  unsigned char head[kHeader];
  const std::uint64_t size = payload_.size(), sum = fnv1a64(payload_.data(), payload_.size());
  std::memcpy(head, kMagic, 8);
  std::memcpy(head + 8, &kVersion, 4);
  std::memcpy(head + 12, &size, 8);
  std::memcpy(head + 20, &sum, 8);
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write checkpoint " + tmp + ": " + std::strerror(errno));
  auto write_all = [&](const unsigned char* p, std::size_t n) {
    while (n > 0) {
      const ssize_t k = ::write(fd, p, n);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0) return false;
      p += k;
      n -= std::size_t(k);
    }
    return true;
  };
  const bool ok = write_all(head, kHeader) && write_all(payload_.data(), payload_.size()) &&
                  ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  if (!ok) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write checkpoint " + tmp + ": " + std::strerror(err));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename checkpoint " + tmp + " to " + path + ": " + ec.message());
  }
}

CheckpointReader::CheckpointReader(const std::string& path) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot open it");
  std::vector<unsigned char> all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (all.size() < kHeader || std::memcmp(all.data(), kMagic, 8) != 0)
    fail("not a refmap checkpoint (no REFMAPCK header)");
  std::uint32_t version;
  std::uint64_t size, sum;
  std::memcpy(&version, all.data() + 8, 4);
  std::memcpy(&size, all.data() + 12, 8);
  std::memcpy(&sum, all.data() + 20, 8);
  if (version != kVersion)
    fail("format version " + std::to_string(version) + ", this refmap reads version " + std::to_string(kVersion));
  if (all.size() - kHeader != size)
    fail("truncated or padded: " + std::to_string(all.size() - kHeader) + " payload bytes, the header says " +
         std::to_string(size));
  payload_.assign(all.begin() + kHeader, all.end());
  if (fnv1a64(payload_.data(), payload_.size()) != sum) fail("corrupted (checksum mismatch)");
}

CheckpointReader CheckpointReader::from_payload(const std::vector<unsigned char>& payload, const std::string& name) {
  CheckpointReader r;
  r.path_ = name;
  r.payload_ = payload;
  return r;
}

void CheckpointReader::fail(const std::string& what) const {
  throw CheckpointError("checkpoint " + path_ + ": " + what);
}

std::vector<unsigned char> CheckpointReader::get_bytes(const std::string& tag) {
  auto take = [&](std::size_t n) {
    if (payload_.size() - pos_ < n) fail("record '" + tag + "' runs past the end");
    const unsigned char* p = payload_.data() + pos_;
    pos_ += n;
    return p;
  };
  std::uint32_t tl;
  std::memcpy(&tl, take(4), 4);
  const unsigned char* t = take(tl);
  const std::string got(reinterpret_cast<const char*>(t), tl);
  if (got != tag) fail("expected record '" + tag + "', found '" + got + "'");
  std::uint64_t n;
  std::memcpy(&n, take(8), 8);
  const unsigned char* d = take(std::size_t(n));
  return std::vector<unsigned char>(d, d + n);
}

double CheckpointReader::get_f64(const std::string& tag) {
  const auto b = get_bytes(tag);
  if (b.size() != sizeof(double)) fail("record '" + tag + "' has the wrong size");
  double v;
  std::memcpy(&v, b.data(), sizeof v);
  return v;
}

std::int64_t CheckpointReader::get_i64(const std::string& tag) {
  const auto b = get_bytes(tag);
  if (b.size() != sizeof(std::int64_t)) fail("record '" + tag + "' has the wrong size");
  std::int64_t v;
  std::memcpy(&v, b.data(), sizeof v);
  return v;
}

std::string CheckpointReader::get_string(const std::string& tag) {
  const auto b = get_bytes(tag);
  return std::string(b.begin(), b.end());
}

std::vector<double> CheckpointReader::get_f64s(const std::string& tag) {
  const auto b = get_bytes(tag);
  if (b.size() % sizeof(double)) fail("record '" + tag + "' has the wrong size");
  std::vector<double> v(b.size() / sizeof(double));
  if (!v.empty()) std::memcpy(v.data(), b.data(), b.size());
  return v;
}

template <class T>
static void get_array(CheckpointReader& r, const std::string& tag, Array2<T>& f) {
  const auto s = r.get_bytes(tag + ".shape");
  std::int64_t shape[3];
  if (s.size() != sizeof shape) throw CheckpointError("checkpoint " + r.path() + ": record '" + tag + ".shape' has the wrong size");
  std::memcpy(shape, s.data(), sizeof shape);
  if (shape[0] < 0 || shape[1] < 0 || shape[2] < 0 || shape[0] > (1 << 24) || shape[1] > (1 << 24) || shape[2] > 16)
    throw CheckpointError("checkpoint " + r.path() + ": record '" + tag + "' has an impossible shape");
  f.resize(int(shape[0]), int(shape[1]), int(shape[2]));
  const auto d = r.get_bytes(tag);
  if (d.size() != f.raw_size() * sizeof(T))
    throw CheckpointError("checkpoint " + r.path() + ": record '" + tag + "' has the wrong size");
  if (!d.empty()) std::memcpy(f.raw(), d.data(), d.size());
}

void CheckpointReader::get_field(const std::string& tag, Field& f) { get_array(*this, tag, f); }
void CheckpointReader::get_mask(const std::string& tag, Mask& m) { get_array(*this, tag, m); }

}  // namespace refmap
