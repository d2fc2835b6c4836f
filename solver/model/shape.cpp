// Initial level sets phi0 of solids in their reference configuration (see shape.hpp).
#include "solver/model/shape.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <istream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace refmap {

namespace {

std::string fmt(const char* f, double a = 0, double b = 0, double c = 0, double d = 0,
                double e = 0, double g = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d, e, g);
  return buf;
}

/// sqrt(a^2 + b^2) without std::hypot's overflow protection (several times faster;
/// geometry here is far from the overflow range)
inline double len2d(double a, double b) { return std::sqrt(a * a + b * b); }

bool finite_all(std::initializer_list<double> v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

/// Distance from (y0, y1) (first quadrant, y0, y1 >= 0) to the ellipse with semi-axes
/// e0 >= e1 > 0; (x0, x1) receives the closest point. Follows D. Eberly, "Distance from
/// a point to an ellipse, an ellipsoid, or a hyperellipsoid" (2013): the closest point
/// is x0 = r0 y0 / (s + r0), x1 = y1 / (s + 1), r0 = (e0/e1)^2, where s is the root of
/// G(s) = (r0 z0 / (s + r0))^2 + (z1 / (s + 1))^2 - 1, z = y / e. Two changes for
/// accuracy and speed: the unknown is sigma = s + 1 > 0 (near the major axis inside the
/// ellipse s is within rounding of -1, and y1 / (s + 1) would lose every digit), and the
/// root is found from the fixed-point form sigma = sqrt(Q(sigma)),
/// Q = (r0 z0 sigma / (sigma + r0 - 1))^2 + z1^2, by Newton's method safeguarded by the
/// bracket that the sign of G maintains (geometric bisection when a step leaves it).
double ellipse_distance_q1(double e0, double e1, double y0, double y1, double& x0, double& x1) {
  if (y1 > 0.0) {
    if (y0 > 0.0) {
      const double z0 = y0 / e0, z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g == 0.0) {
        x0 = y0;
        x1 = y1;
        return 0.0;
      }
      const double r0 = (e0 / e1) * (e0 / e1), c = (e0 - e1) * (e0 + e1) / (e1 * e1);  // r0 - 1
      const double n0 = r0 * z0;
      double lo = z1, hi = g < 0.0 ? 1.0 : len2d(n0, z1);
      // first guess from the linearisation at the point (Lagrange multiplier
      // t = 2 F / |grad F|^2, F = z0^2 + z1^2 - 1, s = t / e1^2): second-order accurate
      // near the ellipse
      double sig = 1.0 + g / (2.0 * (z0 * z0 / r0 + z1 * z1));
      if (!(sig > lo && sig < hi)) sig = 0.5 * (lo + hi);
      for (int it = 0; it < 200; ++it) {
        const double w = 1.0 / (sig + c);
        const double q1 = n0 * sig * w;
        const double sq = std::sqrt(q1 * q1 + z1 * z1);
        const double f = sig - sq;  // f < 0 <=> G > 0 <=> sigma left of the root
        if (f == 0.0) break;
        if (f < 0.0) lo = sig; else hi = sig;
        const double dq = 2.0 * q1 * n0 * c * w * w;  // dQ/dsigma
        const double fp = 1.0 - dq / (2.0 * sq);
        double nxt = fp > 0.0 ? sig - f / fp : -1.0;
        // Newton converges quadratically: once a Newton step is below 1e-9 sigma, the
        // error after it is at round-off level
        bool done = std::abs(nxt - sig) <= 1e-9 * sig;
        if (!(nxt > lo && nxt < hi)) {
          nxt = hi > 2.0 * lo ? std::sqrt(lo * hi) : 0.5 * (lo + hi);
          done = false;
        }
        sig = nxt;
        if (done || hi - lo <= 1e-16 * hi) break;
      }
      x0 = r0 * y0 / (sig + c);
      x1 = y1 / sig;
      return len2d(x0 - y0, x1 - y1);
    }
    x0 = 0.0;
    x1 = e1;
    return std::abs(y1 - e1);
  }
  const double numer0 = e0 * y0, denom0 = (e0 - e1) * (e0 + e1);
  if (numer0 < denom0) {
    const double xde0 = numer0 / denom0;
    x0 = e0 * xde0;
    x1 = e1 * std::sqrt(std::max(0.0, 1.0 - xde0 * xde0));
    return len2d(x0 - y0, x1);
  }
  x0 = e0;
  x1 = 0.0;
  return std::abs(y0 - e0);
}

}  // namespace

Shape::~Shape() = default;
std::string Shape::describe() const { return "shape"; }

// ---------------------------------------------------------------------------- Circle

Circle::Circle(double cx, double cy, double r) : cx_(cx), cy_(cy), r_(r) {
  if (!finite_all({cx, cy, r}) || !(r > 0.0))
    throw std::invalid_argument(fmt("circle: need a finite centre and radius > 0 (got r = %g)", r));
}
double Circle::phi0(double X, double Y) const { return len2d(X - cx_, Y - cy_) - r_; }
BoundingBox Circle::bbox() const { return {cx_ - r_, cy_ - r_, cx_ + r_, cy_ + r_}; }
std::string Circle::describe() const {
  return fmt("circle centre (%g, %g) radius %g", cx_, cy_, r_);
}

// --------------------------------------------------------------------------- Ellipse

Ellipse::Ellipse(double cx, double cy, double a, double b, double angle)
    : cx_(cx), cy_(cy), a_(a), b_(b), angle_(angle), c_(std::cos(angle)), s_(std::sin(angle)) {
  if (!finite_all({cx, cy, a, b, angle}) || !(a > 0.0) || !(b > 0.0))
    throw std::invalid_argument(fmt("ellipse: need semi-axes a, b > 0 (got a = %g, b = %g)", a, b));
}

void Ellipse::closest_point(double X, double Y, double& xc, double& yc) const {
  const double dxg = X - cx_, dyg = Y - cy_;
  const double u = c_ * dxg + s_ * dyg, v = -s_ * dxg + c_ * dyg;
  double pu, pv;
  if (a_ >= b_) {
    ellipse_distance_q1(a_, b_, std::abs(u), std::abs(v), pu, pv);
  } else {
    ellipse_distance_q1(b_, a_, std::abs(v), std::abs(u), pv, pu);
  }
  pu = std::copysign(pu, u);
  pv = std::copysign(pv, v);
  xc = cx_ + c_ * pu - s_ * pv;
  yc = cy_ + s_ * pu + c_ * pv;
}

double Ellipse::phi0(double X, double Y) const {
  const double dxg = X - cx_, dyg = Y - cy_;
  const double u = std::abs(c_ * dxg + s_ * dyg), v = std::abs(-s_ * dxg + c_ * dyg);
  double x0, x1, d;
  if (a_ >= b_) d = ellipse_distance_q1(a_, b_, u, v, x0, x1);
  else d = ellipse_distance_q1(b_, a_, v, u, x0, x1);
  const double q = (u / a_) * (u / a_) + (v / b_) * (v / b_);
  return q < 1.0 ? -d : d;
}

BoundingBox Ellipse::bbox() const {
  const double hx = len2d(a_ * c_, b_ * s_), hy = len2d(a_ * s_, b_ * c_);
  return {cx_ - hx, cy_ - hy, cx_ + hx, cy_ + hy};
}
std::string Ellipse::describe() const {
  return fmt("ellipse centre (%g, %g) semi-axes %g, %g angle %g rad", cx_, cy_, a_, b_, angle_);
}

// ------------------------------------------------------------------ RoundedRectangle

RoundedRectangle::RoundedRectangle(double cx, double cy, double hw, double hh, double rc,
                                   double angle)
    : cx_(cx), cy_(cy), hw_(hw), hh_(hh), rc_(rc), angle_(angle), c_(std::cos(angle)),
      s_(std::sin(angle)) {
  if (!finite_all({cx, cy, hw, hh, rc, angle}) || !(hw > 0.0) || !(hh > 0.0))
    throw std::invalid_argument(
        fmt("rounded_rectangle: need half_width, half_height > 0 (got %g, %g)", hw, hh));
  if (!(rc >= 0.0) || rc > std::min(hw, hh))
    throw std::invalid_argument(fmt(
        "rounded_rectangle: corner_radius must be in [0, min(half_width, half_height)] (got %g)", rc));
}

double RoundedRectangle::phi0(double X, double Y) const {
  const double dxg = X - cx_, dyg = Y - cy_;
  const double u = std::abs(c_ * dxg + s_ * dyg), v = std::abs(-s_ * dxg + c_ * dyg);
  const double qx = u - (hw_ - rc_), qy = v - (hh_ - rc_);
  return len2d(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0) - rc_;
}

BoundingBox RoundedRectangle::bbox() const {
  const double ac = std::abs(c_), as = std::abs(s_);
  const double hx = (hw_ - rc_) * ac + (hh_ - rc_) * as + rc_;
  const double hy = (hw_ - rc_) * as + (hh_ - rc_) * ac + rc_;
  return {cx_ - hx, cy_ - hy, cx_ + hx, cy_ + hy};
}
std::string RoundedRectangle::describe() const {
  return fmt("rounded rectangle centre (%g, %g) half-size %g x %g corner radius %g angle %g rad",
             cx_, cy_, hw_, hh_, rc_, angle_);
}

// ------------------------------------------------------------------------ ZalesakDisk

ZalesakDisk::ZalesakDisk(double cx, double cy, double r, double w, double top, double angle)
    : cx_(cx), cy_(cy), r_(r), w_(w), top_(top), angle_(angle), c_(std::cos(angle)),
      s_(std::sin(angle)) {
  if (!finite_all({cx, cy, r, w, top, angle}) || !(r > 0.0))
    throw std::invalid_argument(fmt("zalesak: need radius > 0 (got %g)", r));
  if (!(w > 0.0) || !(w < r))
    throw std::invalid_argument(
        fmt("zalesak: slot_half_width must be in (0, radius) (got %g, radius %g)", w, r));
  yb_ = -std::sqrt(r * r - w * w);
  const double h = top - cy;
  if (!(h > yb_) || !(h < -yb_))
    throw std::invalid_argument(
        fmt("zalesak: slot_top must lie strictly between %g and %g (got %g)", cy + yb_, cy - yb_, top));
}

double ZalesakDisk::phi0(double X, double Y) const {
  const double dxg = X - cx_, dyg = Y - cy_;
  const double u = c_ * dxg + s_ * dyg, v = -s_ * dxg + c_ * dyg;
  const double au = std::abs(u), h = top_ - cy_;
  const double rho = len2d(u, v);
  // arc: the circle minus the gap {|x| < w, y < 0} cut by the slot
  double d;
  if (v < 0.0 && rho > 0.0 && r_ * au < w_ * rho) d = len2d(au - w_, v - yb_);
  else d = std::abs(rho - r_);
  // slot walls |x| = w, yb <= y <= h
  d = std::min(d, len2d(au - w_, v - std::clamp(v, yb_, h)));
  // slot top y = h, |x| <= w
  d = std::min(d, len2d(std::max(au - w_, 0.0), v - h));
  const bool inside = rho < r_ && (au > w_ || v > h);
  return inside ? -d : d;
}

BoundingBox ZalesakDisk::bbox() const { return {cx_ - r_, cy_ - r_, cx_ + r_, cy_ + r_}; }
std::string ZalesakDisk::describe() const {
  return fmt("zalesak slotted disk centre (%g, %g) radius %g slot half-width %g top y %g angle %g rad",
             cx_, cy_, r_, w_, top_, angle_);
}

// -------------------------------------------------------------------------- Tabulated

Tabulated::Tabulated(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("tabulated shape: cannot open file '" + path + "'");
  parse(in, path);
}

Tabulated::Tabulated(std::istream& in, const std::string& name) { parse(in, name); }

Tabulated::Tabulated(int nx, int ny, double x0, double y0, double dx, std::vector<double> values)
    : nx_(nx), ny_(ny), x0_(x0), y0_(y0), dx_(dx), v_(std::move(values)), source_("memory") {
  if (nx < 2 || ny < 2 || !(dx > 0.0) || !finite_all({x0, y0, dx}))
    throw std::invalid_argument("tabulated shape: need nx, ny >= 2, dx > 0");
  if (v_.size() != std::size_t(nx) * std::size_t(ny))
    throw std::invalid_argument("tabulated shape: values.size() != nx * ny");
  for (double x : v_)
    if (!std::isfinite(x)) throw std::invalid_argument("tabulated shape: non-finite value");
  finish();
}

namespace {

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

bool parse_double(std::string_view t, double& x) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  return ec == std::errc() && p == t.data() + t.size() && std::isfinite(x);
}

bool parse_int(std::string_view t, int& x) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  return ec == std::errc() && p == t.data() + t.size();
}

}  // namespace

void Tabulated::parse(std::istream& in, const std::string& name) {
  source_ = name;
  auto fail = [&](long line, const std::string& msg) -> void {
    throw std::runtime_error("tabulated shape '" + name + "'" +
                             (line > 0 ? ", line " + std::to_string(line) : std::string()) +
                             ": " + msg);
  };
  std::string line;
  long lineno = 0;
  bool have_header = false;
  int row = 0;
  while (std::getline(in, line)) {
    ++lineno;
    auto tok = split_ws(line);
    if (tok.empty() || tok.front().front() == '#') continue;
    if (!have_header) {
      if (tok.size() != 5)
        fail(lineno, "expected the header 'nx ny x0 y0 dx' (5 numbers), found " +
                         std::to_string(tok.size()) + " fields");
      if (!parse_int(tok[0], nx_) || !parse_int(tok[1], ny_))
        fail(lineno, "nx and ny must be integers (got '" + std::string(tok[0]) + "', '" +
                         std::string(tok[1]) + "')");
      if (nx_ < 2 || ny_ < 2) fail(lineno, "nx and ny must be >= 2");
      if (!parse_double(tok[2], x0_) || !parse_double(tok[3], y0_) || !parse_double(tok[4], dx_))
        fail(lineno, "x0, y0, dx must be finite numbers");
      if (!(dx_ > 0.0)) fail(lineno, "dx must be > 0");
      if (double(nx_) * double(ny_) > 1e9) fail(lineno, "nx * ny is too large");
      v_.assign(std::size_t(nx_) * std::size_t(ny_), 0.0);
      have_header = true;
      continue;
    }
    if (row >= ny_)
      fail(lineno, "more than ny = " + std::to_string(ny_) + " rows of values");
    if (int(tok.size()) != nx_)
      fail(lineno, "row " + std::to_string(row) + ": expected nx = " + std::to_string(nx_) +
                       " values, found " + std::to_string(tok.size()));
    for (int i = 0; i < nx_; ++i) {
      double x;
      if (!parse_double(tok[i], x))
        fail(lineno, "row " + std::to_string(row) + ", column " + std::to_string(i) +
                         ": not a finite number: '" + std::string(tok[i]) + "'");
      v_[std::size_t(row) * nx_ + i] = x;
    }
    ++row;
  }
  if (!have_header) fail(0, "empty file (expected the header 'nx ny x0 y0 dx')");
  if (row < ny_)
    fail(0, "expected ny = " + std::to_string(ny_) + " rows of values, found " + std::to_string(row));
  finish();
}

void Tabulated::finish() {
  // extent of the cells (between samples) that have a non-positive corner
  int imin = nx_, imax = -1, jmin = ny_, jmax = -1;
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      if (v_[std::size_t(j) * nx_ + i] <= 0.0) {
        imin = std::min(imin, i);
        imax = std::max(imax, i);
        jmin = std::min(jmin, j);
        jmax = std::max(jmax, j);
      }
  if (imax < 0)
    throw std::runtime_error("tabulated shape '" + source_ +
                             "': no value <= 0, the table contains no solid");
  bbox_ = {x0_ + std::max(imin - 1, 0) * dx_, y0_ + std::max(jmin - 1, 0) * dx_,
           x0_ + std::min(imax + 1, nx_ - 1) * dx_, y0_ + std::min(jmax + 1, ny_ - 1) * dx_};
}

double Tabulated::phi0(double X, double Y) const {
  double fx = (X - x0_) / dx_, fy = (Y - y0_) / dx_;
  if (std::isnan(fx) || std::isnan(fy)) return std::numeric_limits<double>::quiet_NaN();
  fx = std::clamp(fx, 0.0, double(nx_ - 1));
  fy = std::clamp(fy, 0.0, double(ny_ - 1));
  const int i = std::min(int(fx), nx_ - 2), j = std::min(int(fy), ny_ - 2);
  const double tx = fx - i, ty = fy - j;
  const double* r0 = v_.data() + std::size_t(j) * nx_ + i;
  const double* r1 = r0 + nx_;
  return (1.0 - ty) * ((1.0 - tx) * r0[0] + tx * r0[1]) + ty * ((1.0 - tx) * r1[0] + tx * r1[1]);
}

BoundingBox Tabulated::bbox() const { return bbox_; }
std::string Tabulated::describe() const {
  return "tabulated level set '" + source_ + "' " + std::to_string(nx_) + " x " +
         std::to_string(ny_) + fmt(" samples from (%g, %g) spacing %g", x0_, y0_, dx_);
}

// ---------------------------------------------------------------------------- factory

std::unique_ptr<Shape> make_shape(const ShapeParams& p) {
  switch (p.kind) {
    case ShapeKind::Circle: return std::make_unique<Circle>(p.cx, p.cy, p.radius);
    case ShapeKind::Ellipse: return std::make_unique<Ellipse>(p.cx, p.cy, p.a, p.b, p.angle);
    case ShapeKind::RoundedRectangle:
      return std::make_unique<RoundedRectangle>(p.cx, p.cy, p.half_width, p.half_height,
                                                p.corner_radius, p.angle);
    case ShapeKind::Zalesak:
      return std::make_unique<ZalesakDisk>(p.cx, p.cy, p.radius, p.slot_half_width, p.slot_top,
                                           p.angle);
    case ShapeKind::Tabulated:
      if (p.file.empty()) throw std::invalid_argument("tabulated shape: no file given");
      return std::make_unique<Tabulated>(p.file);
  }
  throw std::invalid_argument("unknown shape kind " + std::to_string(int(p.kind)));
}

// The scene-file names (solver/io/enum_names.hpp): the canonical ones in the order of the
// choices in error messages and in scenes/README.md, then the aliases.
std::span<const OptionName<ShapeKind>> option_names(ShapeKind) {
  static const OptionName<ShapeKind> n[] = {
      {ShapeKind::Circle, "circle"},
      {ShapeKind::Ellipse, "ellipse"},
      {ShapeKind::RoundedRectangle, "rounded_rectangle"},
      {ShapeKind::Zalesak, "zalesak"},
      {ShapeKind::Tabulated, "tabulated"},
      {ShapeKind::RoundedRectangle, "rectangle"},  // aliases
      {ShapeKind::Zalesak, "zalesak_disk"},
      {ShapeKind::Zalesak, "slotted_disk"},
  };
  return name_list(n);
}

}  // namespace refmap
