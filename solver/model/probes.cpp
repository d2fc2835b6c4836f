#include "solver/model/probes.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace refmap {

double sample_bilinear(const Grid& g, const Field& f, double x, double y) {
  if (f.ng() < 1) throw std::invalid_argument("sample_bilinear: the field has no ghost cells");
  const double eps = 1e-9 * g.dx;
  const double xmax = g.x0 + g.lx(), ymax = g.y0 + g.ly();
  if (!(x >= g.x0 - eps && x <= xmax + eps && y >= g.y0 - eps && y <= ymax + eps)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "sample_bilinear: point (%.10g, %.10g) is outside the domain [%.10g, %.10g] x [%.10g, %.10g]",
                  x, y, g.x0, xmax, g.y0, ymax);
    throw std::out_of_range(buf);
  }
  // s = position in units of cells, measured from the centre of cell 0: s in [-1/2, n - 1/2]
  const double sx = (x - g.x0) / g.dx - 0.5;
  const double sy = (y - g.y0) / g.dx - 0.5;
  int i = int(std::floor(sx)), j = int(std::floor(sy));
  // the stencil (i, i+1) must stay within [-1, n]
  i = std::clamp(i, -1, f.nx() - 1);
  j = std::clamp(j, -1, f.ny() - 1);
  const double fx = std::clamp(sx - i, 0.0, 1.0);
  const double fy = std::clamp(sy - j, 0.0, 1.0);
  const double a = f(i, j), b = f(i + 1, j), c = f(i, j + 1), d = f(i + 1, j + 1);
  return (1.0 - fy) * ((1.0 - fx) * a + fx * b) + fy * ((1.0 - fx) * c + fx * d);
}

void write_probe_csv(const std::string& path, const ProbeSpec& p, const Grid& g, const Field& f) {
  if (p.points < 2) throw std::invalid_argument("write_probe_csv: probe '" + p.name + "' needs >= 2 points");
  errno = 0;
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out)
    throw std::runtime_error("cannot write probe file " + path + ": " + (errno ? std::strerror(errno) : "open failed"));
  bool ok = std::fputs("x,y,value\n", out) >= 0;
  const int n = p.points;
  for (int k = 0; k < n && ok; ++k) {
    const double s = double(k) / double(n - 1);
    const double x = k == n - 1 ? p.x1 : p.x0 + s * (p.x1 - p.x0);
    const double y = k == n - 1 ? p.y1 : p.y0 + s * (p.y1 - p.y0);
    ok = std::fprintf(out, "%.17g,%.17g,%.17g\n", x, y, sample_bilinear(g, f, x, y)) > 0;
  }
  ok = (std::fclose(out) == 0) && ok;
  if (!ok) throw std::runtime_error("cannot write probe file " + path + ": write failed");
}

}  // namespace refmap
