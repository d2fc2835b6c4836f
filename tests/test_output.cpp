// Output writers: VTK ImageData + pvd series, CSV, probes, progress.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "solver/io/csv.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/model/probes.hpp"
#include "solver/app/progress.hpp"
#include "solver/io/vtk.hpp"

namespace fs = std::filesystem;
using namespace refmap;

namespace {

class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    path_ = fs::temp_directory_path() /
            ("refmap_test_" + tag + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path operator/(const std::string& f) const { return path_ / f; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The value of attribute `attr` in the first element after `from` that has it.
std::string attribute(const std::string& xml, const std::string& attr, std::size_t from = 0) {
  const std::string key = " " + attr + "=\"";
  const auto p = xml.find(key, from);
  if (p == std::string::npos) return "<missing>";
  const auto b = p + key.size();
  return xml.substr(b, xml.find('"', b) - b);
}

Grid small_grid() {
  Grid g;
  g.nx = 5;
  g.ny = 3;
  g.dx = 0.25;
  g.x0 = 0.5;
  g.y0 = -1.0;
  return g;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// VTK

TEST(Vtk, ImageDataHeaderAndRawBytes) {
  TempDir dir("vtk");
  const Grid g = small_grid();
  Field p(g.nx, g.ny, 2, -99.0), u(g.nx, g.ny, 2, -99.0), v(g.nx, g.ny, 2, -99.0);  // ghosts must not be written
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      p(i, j) = i + 10.0 * j + 0.125;
      u(i, j) = std::sin(i + 0.1 * j);
      v(i, j) = -1.0 / (1 + i + j);
    }
  const fs::path file = dir / "frame.vti";
  write_vti(file.string(), g, {{"p", &p}, {"rho", &u}}, {{"velocity", &u, &v}}, 0.375);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  const std::string s = slurp(file);

  // header
  ASSERT_EQ(s.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\"", 0), 0u);
  EXPECT_EQ(attribute(s, "byte_order"), "LittleEndian");
  EXPECT_EQ(attribute(s, "header_type"), "UInt64");
  EXPECT_EQ(attribute(s, "WholeExtent"), "0 5 0 3 0 0");
  EXPECT_EQ(attribute(s, "Origin"), "0.5 -1 0");
  EXPECT_EQ(attribute(s, "Spacing"), "0.25 0.25 1");
  EXPECT_EQ(attribute(s, "Extent", s.find("<Piece")), "0 5 0 3 0 0");
  EXPECT_NE(s.find("<DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">0.375</DataArray>"),
            std::string::npos);
  const std::size_t pa = s.find("Name=\"p\""), ra = s.find("Name=\"rho\""), va = s.find("Name=\"velocity\"");
  ASSERT_NE(pa, std::string::npos);
  ASSERT_NE(ra, std::string::npos);
  ASSERT_NE(va, std::string::npos);
  EXPECT_LT(s.find("<CellData"), pa);
  const std::size_t ncell = 15;
  EXPECT_EQ(attribute(s, "offset", pa), "0");
  EXPECT_EQ(attribute(s, "offset", ra), std::to_string(8 + 8 * ncell));
  EXPECT_EQ(attribute(s, "offset", va), std::to_string(2 * (8 + 8 * ncell)));
  EXPECT_EQ(attribute(s, "NumberOfComponents", va), "3");

  // appended data: '_' then blocks of [UInt64 nbytes][Float64 ...]
  const std::string marker = "<AppendedData encoding=\"raw\">";
  const std::size_t am = s.find(marker);
  ASSERT_NE(am, std::string::npos);
  const std::size_t base = s.find('_', am + marker.size()) + 1;
  auto u64 = [&](std::size_t off) { std::uint64_t x; std::memcpy(&x, s.data() + base + off, 8); return x; };
  auto f64 = [&](std::size_t off) { double x; std::memcpy(&x, s.data() + base + off, 8); return x; };

  EXPECT_EQ(u64(0), 8 * ncell);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) EXPECT_EQ(f64(8 + 8 * (j * g.nx + i)), p(i, j)) << i << "," << j;
  const std::size_t voff = 2 * (8 + 8 * ncell);
  EXPECT_EQ(u64(voff), 3 * 8 * ncell);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t c = voff + 8 + 24 * (j * g.nx + i);
      EXPECT_EQ(f64(c), u(i, j));
      EXPECT_EQ(f64(c + 8), v(i, j));
      EXPECT_EQ(f64(c + 16), 0.0);
    }
  const std::size_t end = base + voff + 8 + 24 * ncell;
  EXPECT_EQ(s.substr(end), "\n  </AppendedData>\n</VTKFile>\n");
}

TEST(Vtk, RejectsFieldsOfTheWrongSize) {
  TempDir dir("vtk");
  const Grid g = small_grid();
  Field face(g.nx + 1, g.ny);
  EXPECT_THROW(write_vti((dir / "x.vti").string(), g, {{"uf", &face}}, {}, 0.0), std::invalid_argument);
  EXPECT_THROW(write_vti((dir.path() / "no_such_dir" / "x.vti").string(), g, {}, {}, 0.0), std::runtime_error);
}

TEST(Vtk, PvdSeriesIsCompleteAfterEveryAdd) {
  TempDir dir("pvd");
  const fs::path pvd = dir / "run.pvd";
  PvdSeries series(pvd.string());
  std::string s = slurp(pvd);
  EXPECT_NE(s.find("<VTKFile type=\"Collection\""), std::string::npos);
  EXPECT_EQ(s.find("<DataSet"), std::string::npos);
  series.add(0.0, "frames/frame_000000.vti");
  s = slurp(pvd);
  EXPECT_NE(s.find("<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"frames/frame_000000.vti\"/>"), std::string::npos);
  EXPECT_NE(s.find("</Collection>\n</VTKFile>\n"), std::string::npos);
  series.add(0.1, "frames/a&b.vti");
  s = slurp(pvd);
  EXPECT_NE(s.find("file=\"frames/frame_000000.vti\""), std::string::npos);
  EXPECT_NE(s.find("<DataSet timestep=\"0.10000000000000001\" group=\"\" part=\"0\" file=\"frames/a&amp;b.vti\"/>"),
            std::string::npos)
      << s;
  EXPECT_EQ(series.size(), 2u);
  EXPECT_FALSE(fs::exists(pvd.string() + ".tmp"));
}

// ---------------------------------------------------------------------------------------
// CSV

TEST(Csv, HeaderCommentsRowsAndFlushOnDestruction) {
  TempDir dir("csv");
  const fs::path f = dir / "d.csv";
  {
    CsvWriter w(f.string(), {"t", "ke", "div"}, "refmap diagnostics\nscene: cavity\n# already a comment\n");
    // header is on disk at once
    EXPECT_EQ(slurp(f), "# refmap diagnostics\n# scene: cavity\n# already a comment\nt,ke,div\n");
    w.row({0.0, 0.5, 1e-14});
    w.row({0.1, 1.0 / 3.0, -2.5});
    EXPECT_EQ(w.rows(), 2);
    EXPECT_THROW(w.row({1.0, 2.0}), std::invalid_argument);
  }
  EXPECT_EQ(slurp(f),
            "# refmap diagnostics\n# scene: cavity\n# already a comment\nt,ke,div\n0,0.5,1e-14\n0.1,0.3333333333,-2.5\n");
}

TEST(Csv, ExplicitFlushAndNoComment) {
  TempDir dir("csv");
  const fs::path f = dir / "d.csv";
  CsvWriter w(f.string(), {"a"});
  w.row({42.0});
  w.flush();
  EXPECT_EQ(slurp(f), "a\n42\n");
}

TEST(Csv, UnopenableFileThrows) {
  TempDir dir("csv");
  EXPECT_THROW(CsvWriter((dir.path() / "missing" / "x.csv").string(), {"a"}), std::runtime_error);
}

// ---------------------------------------------------------------------------------------
// probes

TEST(Probe, LinearFieldIsReproducedExactly) {
  Grid g;
  g.nx = 12;
  g.ny = 8;
  g.dx = 0.125;
  g.x0 = -0.3;
  g.y0 = 0.2;
  const double a = 0.7, b = -1.3, c = 2.1;
  Field f(g.nx, g.ny, 2);
  for (int j = -2; j < g.ny + 2; ++j)
    for (int i = -2; i < g.nx + 2; ++i) f(i, j) = a + b * g.xc(i) + c * g.yc(j);  // ghosts extrapolated linearly
  auto exact = [&](double x, double y) { return a + b * x + c * y; };
  const double X1 = g.x0 + g.lx(), Y1 = g.y0 + g.ly();
  // corners, walls, cell centres, faces
  for (auto [x, y] : std::vector<std::pair<double, double>>{{g.x0, g.y0}, {X1, Y1}, {g.x0, Y1}, {X1, g.y0},
                                                             {g.xc(3), g.yc(4)}, {g.xf(5), g.yf(2)}, {g.x0, 0.5}})
    EXPECT_NEAR(sample_bilinear(g, f, x, y), exact(x, y), 1e-13) << x << "," << y;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(g.x0, X1), uy(g.y0, Y1);
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), y = uy(rng);
    EXPECT_NEAR(sample_bilinear(g, f, x, y), exact(x, y), 1e-13);
  }
  EXPECT_THROW(sample_bilinear(g, f, X1 + 0.01, 0.5), std::out_of_range);
  EXPECT_THROW(sample_bilinear(g, f, 0.0, g.y0 - 0.01), std::out_of_range);
}

TEST(Probe, NoSlipWallGhostsGiveZeroOnTheWall) {
  Grid g;
  g.nx = 8;
  g.ny = 8;
  g.dx = 1.0 / 8;
  Field u(g.nx, g.ny, 2);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) u(i, j) = 1.0 + std::sin(g.xc(i)) * g.yc(j) + i;
  // no-slip bottom/top walls, and a wall moving at speed 2 on the top: ghost = 2*U - interior
  for (int i = -1; i <= g.nx; ++i) {
    const int ii = std::clamp(i, 0, g.nx - 1);
    u(i, -1) = -u(ii, 0);
    u(i, g.ny) = 2 * 2.0 - u(ii, g.ny - 1);
  }
  for (int j = -1; j <= g.ny; ++j) {  // side walls: no-slip
    u(-1, j) = -u(0, j);
    u(g.nx, j) = -u(g.nx - 1, j);
  }
  for (double x : {g.xc(0), g.xc(3), 0.4, g.xc(7)}) {
    EXPECT_NEAR(sample_bilinear(g, u, x, 0.0), 0.0, 1e-15) << x;
    EXPECT_NEAR(sample_bilinear(g, u, x, 1.0), 2.0, 1e-14) << x;
  }
  for (double y : {g.yc(0), 0.33, g.yc(7)}) {
    EXPECT_NEAR(sample_bilinear(g, u, 0.0, y), 0.0, 1e-15) << y;
    EXPECT_NEAR(sample_bilinear(g, u, 1.0, y), 0.0, 1e-15) << y;
  }
  // at a cell centre the sample is the cell value
  EXPECT_DOUBLE_EQ(sample_bilinear(g, u, g.xc(2), g.yc(5)), u(2, 5));
}

TEST(Probe, PeriodicGhostsInterpolateAcrossTheSeam) {
  Grid g;
  g.nx = 8;
  g.ny = 8;
  g.dx = 1.0 / 8;
  Field f(g.nx, g.ny, 2);
  for (int j = -2; j < g.ny + 2; ++j)
    for (int i = 0; i < g.nx; ++i) f(i, j) = i * 1.0 + 0.1 * j;
  for (int j = -2; j < g.ny + 2; ++j)
    for (int k = 1; k <= 2; ++k) {
      f(-k, j) = f(g.nx - k, j);
      f(g.nx - 1 + k, j) = f(k - 1, j);
    }
  const double y = g.yc(3);
  const double seam = 0.5 * (f(0, 3) + f(g.nx - 1, 3));
  EXPECT_DOUBLE_EQ(sample_bilinear(g, f, 0.0, y), seam);
  EXPECT_DOUBLE_EQ(sample_bilinear(g, f, 1.0, y), seam);
}

TEST(Probe, CsvFile) {
  TempDir dir("probe");
  Grid g;
  g.nx = 10;
  g.ny = 10;
  g.dx = 0.1;
  Field f(g.nx, g.ny, 2);
  for (int j = -2; j < g.ny + 2; ++j)
    for (int i = -2; i < g.nx + 2; ++i) f(i, j) = 1.0 / 3.0 + g.xc(i) * 2.0 - g.yc(j);
  ProbeSpec p;
  p.name = "line";
  p.field = "u";
  p.x0 = 0.0;
  p.y0 = 0.5;
  p.x1 = 1.0;
  p.y1 = 0.3;
  p.points = 7;
  const fs::path file = dir / "line.csv";
  write_probe_csv(file.string(), p, g, f);
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,value");
  int n = 0;
  while (std::getline(in, line)) {
    double x, y, val;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &x, &y, &val), 3) << line;
    const double s = n / 6.0;
    EXPECT_NEAR(x, s, 1e-15);
    EXPECT_NEAR(y, 0.5 - 0.2 * s, 1e-15);
    EXPECT_EQ(val, sample_bilinear(g, f, x, y)) << "17 digits must round-trip exactly";
    EXPECT_NEAR(val, 1.0 / 3.0 + 2 * x - y, 1e-13);
    if (n == 0) {
      char b[40];
      std::snprintf(b, sizeof b, "%.17g", val);
      EXPECT_EQ(line, std::string("0,0.5,") + b);
    }
    if (n == 6) {
      EXPECT_EQ(x, 1.0);
      EXPECT_EQ(y, 0.3);
    }
    ++n;
  }
  EXPECT_EQ(n, 7);
}

// ---------------------------------------------------------------------------------------
// progress

TEST(Output, ProgressDurations) {
  EXPECT_EQ(Progress::format_duration(12.34), "12.3s");
  EXPECT_EQ(Progress::format_duration(245), "4m05s");
  EXPECT_EQ(Progress::format_duration(3720), "1h02m");
  EXPECT_EQ(Progress::format_duration(-1), "?");
}

TEST(Output, ProgressLogLinesWhenNotATerminal) {
  // stderr of the test runner is captured; the log-line path must run without a terminal
  ::testing::internal::CaptureStderr();
  {
    Progress pr(0.0, 1.0, 1e-9, true);
    EXPECT_FALSE(pr.live());
    pr.update(0.25, 10, 0.025, 7, 3e-11);
    pr.message("hello");
    pr.finish();
    Progress off(0.0, 1.0, 1e-9, false);
    off.update(0.5, 1, 0.1, 1, 0.0);
    off.message("not shown");
    off.finish();
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("[refmap] t 0.25/1 ( 25.0%)  eta "), std::string::npos) << err;
  EXPECT_NE(err.find("step 10  dt 2.500e-02  poisson 7 it (res 3.0e-11)"), std::string::npos) << err;
  EXPECT_NE(err.find("\nhello\n"), std::string::npos) << err;
  EXPECT_EQ(err.find("t 0.5/1"), std::string::npos) << "disabled progress printed: " << err;
  EXPECT_EQ(err.find("not shown"), std::string::npos) << "disabled progress printed: " << err;
}
