// Initial level sets phi0 (solver/shape): exact signed distances of the analytic shapes,
// checked against hand-computed values and brute-force sampling of the boundary; the
// bilinear tabulated level set and its file errors; the factory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/model/shape.hpp"

using namespace refmap;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Pt {
  double x, y;
};

/// Distance from p to the polyline through `pts` (closed if `closed`).
double polyline_distance(const std::vector<Pt>& pts, bool closed, double px, double py) {
  double best = 1e300;
  const std::size_t n = pts.size(), m = closed ? n : n - 1;
  for (std::size_t k = 0; k < m; ++k) {
    const Pt a = pts[k], b = pts[(k + 1) % n];
    const double ex = b.x - a.x, ey = b.y - a.y, l2 = ex * ex + ey * ey;
    double t = l2 > 0 ? ((px - a.x) * ex + (py - a.y) * ey) / l2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, std::hypot(px - a.x - t * ex, py - a.y - t * ey));
  }
  return best;
}

/// Distance from p to the parametric curve c(t), t in [t0, t1] (periodic if `closed`):
/// sampled at m points, then every local minimum of the samples refined by golden-section
/// search, so the result is accurate to round-off.
double curve_distance(const std::function<Pt(double)>& c, double t0, double t1, bool closed, double px,
                      double py, int m = 4096) {
  auto dist = [&](double t) {
    const Pt q = c(t);
    return std::hypot(q.x - px, q.y - py);
  };
  std::vector<double> d(m + 1);
  for (int k = 0; k <= m; ++k) d[k] = dist(t0 + (t1 - t0) * k / m);
  double best = 1e300;
  const double h = (t1 - t0) / m;
  for (int k = 0; k <= m; ++k) {
    const double dl = k > 0 ? d[k - 1] : (closed ? d[m - 1] : 1e300);
    const double dr = k < m ? d[k + 1] : (closed ? d[1] : 1e300);
    if (d[k] > dl || d[k] > dr) continue;
    double a = t0 + (k - 1) * h, b = t0 + (k + 1) * h;
    if (!closed) a = std::max(a, t0), b = std::min(b, t1);
    constexpr double r = 0.6180339887498949;
    double x1 = b - r * (b - a), x2 = a + r * (b - a), f1 = dist(x1), f2 = dist(x2);
    for (int it = 0; it < 80; ++it) {
      if (f1 < f2) { b = x2; x2 = x1; f2 = f1; x1 = b - r * (b - a); f1 = dist(x1); }
      else { a = x1; x1 = x2; f1 = f2; x2 = a + r * (b - a); f2 = dist(x2); }
    }
    best = std::min({best, f1, f2, d[k]});
  }
  return best;
}

double segment_distance(Pt a, Pt b, double px, double py) {
  return polyline_distance({a, b}, false, px, py);
}

/// |grad phi0| by central differences with step h
double grad_norm(const Shape& s, double x, double y, double h = 1e-7) {
  const double gx = (s.phi0(x + h, y) - s.phi0(x - h, y)) / (2 * h);
  const double gy = (s.phi0(x, y + h) - s.phi0(x, y - h)) / (2 * h);
  return std::hypot(gx, gy);
}

/// fraction of random points of the box where |grad phi0| = 1 to `tol`; also checks
/// the 1-Lipschitz bound everywhere
double unit_gradient_fraction(const Shape& s, BoundingBox b, double margin, double tol, int n = 4000) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(b.xmin - margin, b.xmax + margin), uy(b.ymin - margin, b.ymax + margin);
  int good = 0;
  for (int k = 0; k < n; ++k) {
    const double x = ux(rng), y = uy(rng);
    const double g = grad_norm(s, x, y);
    EXPECT_LE(g, 1.0 + 1e-5) << "at (" << x << ", " << y << ")";
    if (std::abs(g - 1.0) < tol) ++good;
  }
  return double(good) / n;
}

}  // namespace

// ------------------------------------------------------------------------------ Circle

TEST(ShapeCircle, ExactSignedDistance) {
  Circle c(0.3, -0.2, 0.25);
  EXPECT_DOUBLE_EQ(c.phi0(0.3, -0.2), -0.25);
  EXPECT_NEAR(c.phi0(0.3 + 0.25, -0.2), 0.0, 1e-15);
  EXPECT_NEAR(c.phi0(0.3 + 0.6, -0.2 + 0.8), 0.75, 1e-15);
  EXPECT_NEAR(c.phi0(0.3, -0.1), -0.15, 1e-15);
  const BoundingBox b = c.bbox();
  EXPECT_DOUBLE_EQ(b.xmin, 0.05);
  EXPECT_DOUBLE_EQ(b.xmax, 0.55);
  EXPECT_DOUBLE_EQ(b.ymin, -0.45);
  EXPECT_DOUBLE_EQ(b.ymax, 0.05);
  EXPECT_GT(unit_gradient_fraction(c, b, 0.2, 1e-6), 0.999);
  EXPECT_NE(c.describe().find("circle"), std::string::npos);
  EXPECT_THROW(Circle(0, 0, 0.0), std::invalid_argument);
  EXPECT_THROW(Circle(0, 0, -1.0), std::invalid_argument);
}

// ----------------------------------------------------------------------------- Ellipse

namespace {

void check_ellipse_against_sampling(double cx, double cy, double a, double b, double ang) {
  Ellipse e(cx, cy, a, b, ang);
  const double c = std::cos(ang), s = std::sin(ang);
  auto curve = [&](double th) {
    const double u = a * std::cos(th), v = b * std::sin(th);
    return Pt{cx + c * u - s * v, cy + s * u + c * v};
  };
  std::mt19937 rng(11);
  const BoundingBox bb = e.bbox();
  std::uniform_real_distribution<double> ux(bb.xmin - 0.3, bb.xmax + 0.3), uy(bb.ymin - 0.3, bb.ymax + 0.3);
  std::vector<Pt> probes;
  for (int k = 0; k < 150; ++k) probes.push_back({ux(rng), uy(rng)});
  // the hard spots: centre, on the axes (inside and outside), near the vertices, near
  // the evolute's cusps (+-(a^2-b^2)/a on the major axis)
  const double big = std::max(a, b), small = std::min(a, b);
  const double cusp = (big * big - small * small) / big;
  for (double t : {0.0, 0.3 * cusp, 0.999 * cusp, 1.001 * cusp, 0.5 * (cusp + big), 0.999 * big, big,
                   1.001 * big, 1.7 * big})
    for (double sg : {-1.0, 1.0}) {
      const double u = a >= b ? sg * t : 0.0, v = a >= b ? 0.0 : sg * t;
      probes.push_back({cx + c * u - s * v, cy + s * u + c * v});
      const double u2 = a >= b ? 0.0 : sg * t * small / big, v2 = a >= b ? sg * t * small / big : 0.0;
      probes.push_back({cx + c * u2 - s * v2, cy + s * u2 + c * v2});
    }
  double worst = 0.0;
  for (const Pt& p : probes) {
    const double brute = curve_distance(curve, 0.0, 2 * kPi, true, p.x, p.y);
    const double u = c * (p.x - cx) + s * (p.y - cy), v = -s * (p.x - cx) + c * (p.y - cy);
    const bool inside = (u / a) * (u / a) + (v / b) * (v / b) < 1.0;
    const double phi = e.phi0(p.x, p.y);
    EXPECT_EQ(phi < 0.0, inside) << "sign at (" << p.x << ", " << p.y << ")";
    EXPECT_NEAR(std::abs(phi), brute, 1e-13) << "at (" << p.x << ", " << p.y << ")";
    worst = std::max(worst, std::abs(std::abs(phi) - brute));
    // the closest point is on the ellipse and at that distance
    double qx, qy;
    e.closest_point(p.x, p.y, qx, qy);
    const double qu = c * (qx - cx) + s * (qy - cy), qv = -s * (qx - cx) + c * (qy - cy);
    EXPECT_NEAR((qu / a) * (qu / a) + (qv / b) * (qv / b), 1.0, 1e-12);
    EXPECT_NEAR(std::hypot(qx - p.x, qy - p.y), std::abs(phi), 1e-12);
  }
  std::printf("  ellipse a=%g b=%g angle=%g: max |phi0 - brute force| = %.2e over %zu points\n", a, b,
              ang, worst, probes.size());
}

}  // namespace

TEST(ShapeEllipse, DistanceMatchesBruteForceSampling) {
  check_ellipse_against_sampling(0.5, 0.5, 0.3, 0.15, 0.4);
  check_ellipse_against_sampling(-1.0, 2.0, 0.1, 0.25, -1.1);  // a < b
  check_ellipse_against_sampling(0.0, 0.0, 0.2, 0.2, 0.0);     // a circle
  check_ellipse_against_sampling(0.0, 0.0, 1.0, 0.05, 0.0);    // very eccentric
}

TEST(ShapeEllipse, KnownValuesAndUnitGradient) {
  Ellipse e(1.0, 2.0, 0.4, 0.1, kPi / 2);  // major axis along y after rotation
  EXPECT_NEAR(e.phi0(1.0, 2.0), -0.1, 1e-15);
  EXPECT_NEAR(e.phi0(1.0, 2.5), 0.1, 1e-15);
  EXPECT_NEAR(e.phi0(1.3, 2.0), 0.2, 1e-15);
  const BoundingBox b = e.bbox();
  EXPECT_NEAR(b.xmin, 0.9, 1e-15);
  EXPECT_NEAR(b.xmax, 1.1, 1e-15);
  EXPECT_NEAR(b.ymin, 1.6, 1e-15);
  EXPECT_NEAR(b.ymax, 2.4, 1e-15);
  EXPECT_GT(unit_gradient_fraction(e, b, 0.2, 1e-5), 0.995);
  EXPECT_THROW(Ellipse(0, 0, 0.0, 1.0), std::invalid_argument);
}

// -------------------------------------------------------------------- RoundedRectangle

TEST(ShapeRoundedRectangle, ExactSignedDistance) {
  const double cx = 0.4, cy = 0.6, hw = 0.3, hh = 0.1, rc = 0.05, ang = 0.7;
  RoundedRectangle r(cx, cy, hw, hh, rc, ang);
  const double c = std::cos(ang), s = std::sin(ang);
  auto to_global = [&](double u, double v) { return Pt{cx + c * u - s * v, cy + s * u + c * v}; };
  Pt p = to_global(0, 0);
  EXPECT_NEAR(r.phi0(p.x, p.y), -hh, 1e-15);
  p = to_global(0.5, 0.0);
  EXPECT_NEAR(r.phi0(p.x, p.y), 0.2, 1e-15);
  p = to_global(0.1, -0.3);
  EXPECT_NEAR(r.phi0(p.x, p.y), 0.2, 1e-15);
  // outside a rounded corner: distance to the corner circle
  p = to_global(hw - rc + 0.3, hh - rc + 0.4);
  EXPECT_NEAR(r.phi0(p.x, p.y), 0.5 - rc, 1e-14);
  // brute force against the sampled boundary
  std::vector<Pt> pts;
  const int m = 40000;
  for (int k = 0; k < m; ++k) {
    // the four corner arcs in turn (quadrant q of the angle); the polyline's chords
    // between consecutive arcs are exactly the straight sides
    const double th = 2 * kPi * k / m;
    const int q = int(th / (kPi / 2));
    const double sx = (q == 0 || q == 3) ? 1 : -1, sy = (q < 2) ? 1 : -1;
    const double ucen = sx * (hw - rc), vcen = sy * (hh - rc);
    pts.push_back(to_global(ucen + rc * std::cos(th), vcen + rc * std::sin(th)));
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(-0.2, 1.0), uy(0.0, 1.2);
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), y = uy(rng);
    const double u = c * (x - cx) + s * (y - cy), v = -s * (x - cx) + c * (y - cy);
    const double qx = std::abs(u) - (hw - rc), qy = std::abs(v) - (hh - rc);
    const bool inside = (qx <= 0 && std::abs(v) < hh) || (qy <= 0 && std::abs(u) < hw) ||
                        std::hypot(qx, qy) < rc;
    const double phi = r.phi0(x, y);
    EXPECT_EQ(phi < 0, inside);
    EXPECT_NEAR(std::abs(phi), polyline_distance(pts, true, x, y), 1e-8);
  }
  EXPECT_GT(unit_gradient_fraction(r, r.bbox(), 0.1, 1e-5), 0.995);
  const BoundingBox b = r.bbox();
  const double hx = (hw - rc) * c + (hh - rc) * s + rc;
  EXPECT_NEAR(b.xmax - b.xmin, 2 * hx, 1e-14);
  EXPECT_THROW(RoundedRectangle(0, 0, 0.1, 0.1, 0.2), std::invalid_argument);
  EXPECT_THROW(RoundedRectangle(0, 0, -0.1, 0.1, 0.0), std::invalid_argument);
  // sharp corners (rc = 0)
  RoundedRectangle sq(0, 0, 1, 1, 0);
  EXPECT_NEAR(sq.phi0(2, 2), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(sq.phi0(0.5, 0.2), -0.5, 1e-15);
}

// ------------------------------------------------------------------------- ZalesakDisk

namespace {

/// distance to the boundary of a Zalesak disk: the arc (parametric, refined) and the
/// three slot segments
double zalesak_brute(double cx, double cy, double r, double w, double top, double px, double py) {
  const double yb = cy - std::sqrt(r * r - w * w);
  const double a0 = std::atan2(yb - cy, w);             // right end of the arc
  const double a1 = std::atan2(yb - cy, -w) + 2 * kPi;  // left end, counter-clockwise
  auto arc = [&](double th) { return Pt{cx + r * std::cos(th), cy + r * std::sin(th)}; };
  double d = curve_distance(arc, a0, a1, false, px, py);
  d = std::min(d, segment_distance({cx - w, yb}, {cx - w, top}, px, py));
  d = std::min(d, segment_distance({cx - w, top}, {cx + w, top}, px, py));
  d = std::min(d, segment_distance({cx + w, top}, {cx + w, yb}, px, py));
  return d;
}

}  // namespace

TEST(ShapeZalesak, KnownDistances) {
  ZalesakDisk z(0.5, 0.75, 0.15, 0.025, 0.85);
  const double yb = 0.75 - std::sqrt(0.15 * 0.15 - 0.025 * 0.025);  // 0.602098
  // centre of the disk lies in the slot: nearest are the walls
  EXPECT_NEAR(z.phi0(0.5, 0.75), 0.025, 1e-15);
  // in the slot just below its top
  EXPECT_NEAR(z.phi0(0.5, 0.84), 0.01, 1e-14);
  // solid bridge above the slot
  EXPECT_NEAR(z.phi0(0.5, 0.87), -0.02, 1e-14);
  EXPECT_NEAR(z.phi0(0.51, 0.86), -0.01, 1e-14);
  // near the slot's top corner (0.525, 0.85), inside the solid
  EXPECT_NEAR(z.phi0(0.53, 0.86), -std::hypot(0.005, 0.01), 1e-14);
  // in the solid next to the slot wall, and next to the arc
  EXPECT_NEAR(z.phi0(0.53, 0.75), -0.005, 1e-14);
  EXPECT_NEAR(z.phi0(0.6, 0.75), -0.05, 1e-14);
  // below the slot mouth, outside: nearest are the mouth corners (0.5 +- 0.025, yb)
  EXPECT_NEAR(z.phi0(0.5, 0.55), std::hypot(0.025, yb - 0.55), 1e-14);
  // outside the bottom arc, left of the mouth
  EXPECT_NEAR(z.phi0(0.47, 0.59), std::hypot(0.03, 0.16) - 0.15, 1e-14);
  // far outside: distance to the circle
  EXPECT_NEAR(z.phi0(0.5, 1.2), 0.3, 1e-14);
  EXPECT_NEAR(z.phi0(0.9, 0.75), 0.25, 1e-14);
  const BoundingBox b = z.bbox();
  EXPECT_NEAR(b.xmin, 0.35, 1e-15);
  EXPECT_NEAR(b.ymax, 0.9, 1e-15);
  EXPECT_NE(z.describe().find("zalesak"), std::string::npos);
}

TEST(ShapeZalesak, DistanceMatchesBruteForceAndUnitGradient) {
  const double cx = 0.5, cy = 0.75, r = 0.15, w = 0.025, top = 0.85;
  ZalesakDisk z(cx, cy, r, w, top);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(0.25, 0.75), uy(0.5, 1.0), us(0.47, 0.53), vs(0.55, 0.9);
  double worst = 0.0;
  for (int k = 0; k < 600; ++k) {
    // half of the points concentrated around the slot
    const double x = k % 2 ? ux(rng) : us(rng), y = k % 2 ? uy(rng) : vs(rng);
    const bool inside = std::hypot(x - cx, y - cy) < r && (std::abs(x - cx) > w || y > top);
    const double phi = z.phi0(x, y);
    EXPECT_EQ(phi < 0, inside) << "(" << x << ", " << y << ")";
    const double brute = zalesak_brute(cx, cy, r, w, top, x, y);
    worst = std::max(worst, std::abs(std::abs(phi) - brute));
  }
  std::printf("  Zalesak: max |phi0 - brute force| = %.2e over 600 points\n", worst);
  EXPECT_LT(worst, 1e-13);
  // |grad phi0| = 1 away from the kinks (medial axes); the kinks are a null set
  const double frac = unit_gradient_fraction(z, z.bbox(), 0.1, 1e-5, 8000);
  std::printf("  Zalesak: |grad phi0| = 1 (+-1e-5) at %.2f%% of random points\n", 100 * frac);
  EXPECT_GT(frac, 0.995);
  // rotated copy: phi0 is invariant under rotating the point with the shape
  const double ang = 0.9, c = std::cos(ang), s = std::sin(ang);
  ZalesakDisk zr(cx, cy, r, w, top, ang);
  for (int k = 0; k < 100; ++k) {
    const double x = us(rng), y = vs(rng);
    const double xr = cx + c * (x - cx) - s * (y - cy), yr = cy + s * (x - cx) + c * (y - cy);
    EXPECT_NEAR(zr.phi0(xr, yr), z.phi0(x, y), 1e-14);
  }
}

TEST(ShapeZalesak, RejectsBadSlot) {
  EXPECT_THROW(ZalesakDisk(0.5, 0.75, 0.15, 0.2, 0.85), std::invalid_argument);   // slot wider than disk
  EXPECT_THROW(ZalesakDisk(0.5, 0.75, 0.15, 0.025, 0.95), std::invalid_argument); // cuts the disk in two
  EXPECT_THROW(ZalesakDisk(0.5, 0.75, 0.15, 0.025, 0.55), std::invalid_argument); // below the disk
  EXPECT_THROW(ZalesakDisk(0.5, 0.75, 0.15, 0.0, 0.85), std::invalid_argument);
}

// --------------------------------------------------------------------------- Tabulated

namespace {

std::string table_text(int nx, int ny, double x0, double y0, double dx,
                       const std::function<double(double, double)>& f) {
  std::ostringstream o;
  o.precision(17);
  o << "# a comment line\n" << nx << " " << ny << " " << x0 << " " << y0 << " " << dx << "\n";
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) o << (i ? " " : "") << f(x0 + i * dx, y0 + j * dx);
    o << "\n";
  }
  return o.str();
}

std::string error_of(const std::string& text) {
  std::istringstream in(text);
  try {
    Tabulated t(in, "test.txt");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ShapeTabulated, ReproducesBilinearFunctionExactly) {
  auto f = [](double x, double y) { return -0.7 + 1.3 * x + 0.9 * y - 2.1 * x * y; };
  const std::string text = table_text(7, 5, -0.2, 0.1, 0.25, f);
  std::istringstream in(text);
  Tabulated t(in, "bilinear");
  EXPECT_EQ(t.nx(), 7);
  EXPECT_EQ(t.ny(), 5);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(-0.2, -0.2 + 6 * 0.25), uy(0.1, 0.1 + 4 * 0.25);
  double worst = 0;
  for (int k = 0; k < 2000; ++k) {
    const double x = ux(rng), y = uy(rng);
    worst = std::max(worst, std::abs(t.phi0(x, y) - f(x, y)));
  }
  EXPECT_LT(worst, 1e-14);
  // at the samples and the far corner exactly
  EXPECT_NEAR(t.phi0(-0.2, 0.1), f(-0.2, 0.1), 1e-15);
  EXPECT_NEAR(t.phi0(1.3, 1.1), f(1.3, 1.1), 1e-14);
  // outside: constant extension from the nearest boundary point
  EXPECT_NEAR(t.phi0(5.0, 0.6), f(1.3, 0.6), 1e-14);
  EXPECT_NEAR(t.phi0(-9.0, -9.0), f(-0.2, 0.1), 1e-14);
  EXPECT_TRUE(std::isnan(t.phi0(std::nan(""), 0.5)));  // no out-of-range read
  // the bbox holds every non-positive sample
  const BoundingBox b = t.bbox();
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i) {
      const double x = -0.2 + i * 0.25, y = 0.1 + j * 0.25;
      if (f(x, y) <= 0) {
        EXPECT_GE(x, b.xmin);
        EXPECT_LE(x, b.xmax);
        EXPECT_GE(y, b.ymin);
        EXPECT_LE(y, b.ymax);
      }
    }
}

TEST(ShapeTabulated, SampledCircleFromFile) {
  // a circle's distance sampled on a file, read back through the factory
  const auto path = std::filesystem::temp_directory_path() / "refmap_test_shape_circle.txt";
  Circle c(0.5, 0.5, 0.2);
  {
    std::ofstream o(path);
    o << table_text(41, 41, 0.0, 0.0, 0.025, [&](double x, double y) { return c.phi0(x, y); });
  }
  ShapeParams p;
  p.kind = ShapeKind::Tabulated;
  p.file = path.string();
  const auto t = make_shape(p);
  // bilinear interpolation error of a distance function: O(dx^2 / R) away from the centre
  double worst = 0;
  for (double x = 0.05; x < 0.95; x += 0.0123)
    for (double y = 0.05; y < 0.95; y += 0.0117)
      if (std::hypot(x - 0.5, y - 0.5) > 0.05) worst = std::max(worst, std::abs(t->phi0(x, y) - c.phi0(x, y)));
  EXPECT_LT(worst, 0.025 * 0.025 / 0.05);
  const BoundingBox b = t->bbox();
  EXPECT_LE(b.xmin, 0.3);
  EXPECT_GE(b.xmax, 0.7);
  EXPECT_GT(b.xmin, 0.2);
  EXPECT_NE(t->describe().find("41 x 41"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(ShapeTabulated, MalformedFilesGiveClearErrors) {
  const std::string ok = "3 2 0 0 1\n-1 1 1\n1 1 1\n";
  EXPECT_EQ(error_of(ok), "");
  auto has = [](const std::string& msg, const std::string& part) {
    return msg.find(part) != std::string::npos;
  };
  std::string m;
  m = error_of("3 2 0 0 1\n-1 1\n1 1 1\n");  // missing value in a row
  EXPECT_TRUE(has(m, "line 2") && has(m, "expected nx = 3 values, found 2")) << m;
  m = error_of("3 2 0 0 1\n-1 1 1\n");  // missing row
  EXPECT_TRUE(has(m, "expected ny = 2 rows of values, found 1")) << m;
  m = error_of("3 2 0 0 1\n-1 1 1\n1 1 1\n1 1 1\n");  // extra row
  EXPECT_TRUE(has(m, "line 4") && has(m, "more than ny = 2 rows")) << m;
  m = error_of("3 2 0 0 1\n-1 abc 1\n1 1 1\n");  // non-numeric
  EXPECT_TRUE(has(m, "line 2") && has(m, "column 1") && has(m, "'abc'")) << m;
  m = error_of("3 2 0 0 1\n-1 1 1\n1 1.5x 1\n");  // trailing garbage in a number
  EXPECT_TRUE(has(m, "line 3") && has(m, "'1.5x'")) << m;
  m = error_of("3 2 0 0 1\n-1 nan 1\n1 1 1\n");  // not finite
  EXPECT_TRUE(has(m, "not a finite number")) << m;
  m = error_of("3 2 0 0\n-1 1 1\n1 1 1\n");  // short header
  EXPECT_TRUE(has(m, "line 1") && has(m, "header")) << m;
  m = error_of("3.5 2 0 0 1\n");  // non-integer size
  EXPECT_TRUE(has(m, "integers")) << m;
  m = error_of("3 2 0 0 -1\n-1 1 1\n1 1 1\n");  // bad spacing
  EXPECT_TRUE(has(m, "dx must be > 0")) << m;
  m = error_of("1 2 0 0 1\n-1\n1\n");  // too small
  EXPECT_TRUE(has(m, ">= 2")) << m;
  m = error_of("");  // empty
  EXPECT_TRUE(has(m, "empty")) << m;
  m = error_of("2 2 0 0 1\n1 1\n1 1\n");  // no solid
  EXPECT_TRUE(has(m, "no value <= 0")) << m;
  EXPECT_TRUE(has(error_of("3 2 0 0 1\n-1 1\n1 1 1\n"), "test.txt"));  // names the file
  try {
    Tabulated t("/nonexistent/dir/phi0.txt");
    ADD_FAILURE() << "no exception for a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "cannot open") && has(e.what(), "/nonexistent/dir/phi0.txt")) << e.what();
  }
}

// ----------------------------------------------------------------------------- factory

TEST(ShapeFactory, BuildsEveryKind) {
  ShapeParams p;
  p.kind = ShapeKind::Circle;
  p.cx = 0.5;
  p.cy = 0.5;
  p.radius = 0.2;
  EXPECT_NEAR(make_shape(p)->phi0(0.5, 0.5), -0.2, 1e-15);
  p.kind = ShapeKind::Ellipse;
  p.a = 0.3;
  p.b = 0.1;
  EXPECT_NEAR(make_shape(p)->phi0(0.5, 0.5), -0.1, 1e-15);
  p.kind = ShapeKind::RoundedRectangle;
  p.half_width = 0.3;
  p.half_height = 0.2;
  p.corner_radius = 0.05;
  EXPECT_NEAR(make_shape(p)->phi0(0.5, 0.5), -0.2, 1e-15);
  p.kind = ShapeKind::Zalesak;
  p.cx = 0.5;
  p.cy = 0.75;
  p.radius = 0.15;
  p.slot_half_width = 0.025;
  p.slot_top = 0.85;
  EXPECT_NEAR(make_shape(p)->phi0(0.5, 0.75), 0.025, 1e-15);
  p.kind = ShapeKind(99);  // not a kind: only reachable by a cast
  EXPECT_THROW(make_shape(p), std::invalid_argument);
  p.kind = ShapeKind::Circle;
  p.radius = -1;
  EXPECT_THROW(make_shape(p), std::invalid_argument);
  p.kind = ShapeKind::Tabulated;
  p.file = "";
  EXPECT_THROW(make_shape(p), std::invalid_argument);
  p.file = "/nonexistent/phi0.txt";
  EXPECT_THROW(make_shape(p), std::runtime_error);
}
