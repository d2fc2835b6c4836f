#pragma once
// Zalesak slotted disk (BENCHMARKS.md section 4): disc of radius r centred at (cx, cy) with
// a slot of width w cut from the bottom up to y = top. Unit-square form: radius 0.15,
// centre (0.5, 0.75), slot |x - 0.5| <= 0.025, y <= 0.85; the [0,100]^2 form is scale 100.
//   phi()     exact signed distance (negative inside): min distance to the boundary pieces
//             (outer arc, the two slot walls, the slot top), signed by the inside test;
//   phi_csg() the common CSG level set max(d_disc, -d_slot) (not a distance near the slot
//             mouth and corners).
#include <algorithm>
#include <cmath>

namespace refmap::geometry {

struct SlottedDisk {
  double cx = 0.5, cy = 0.75, r = 0.15, w = 0.05, top = 0.85;

  static SlottedDisk unit() { return {}; }
  static SlottedDisk hundred() { return {50.0, 75.0, 15.0, 5.0, 85.0}; }

  double disc(double x, double y) const { return std::hypot(x - cx, y - cy) - r; }

  /// signed distance to the slot rectangle |x - cx| <= w/2, cy - 2r <= y <= top
  double slot(double x, double y) const {
    const double hx = 0.5 * w, y0 = cy - 2.0 * r, yc = 0.5 * (y0 + top), hy = 0.5 * (top - y0);
    const double qx = std::fabs(x - cx) - hx, qy = std::fabs(y - yc) - hy;
    const double ox = std::max(qx, 0.0), oy = std::max(qy, 0.0);
    return std::hypot(ox, oy) + std::min(std::max(qx, qy), 0.0);
  }

  bool inside(double x, double y) const { return disc(x, y) < 0.0 && slot(x, y) > 0.0; }

  double phi_csg(double x, double y) const { return std::max(disc(x, y), -slot(x, y)); }

  double phi(double x, double y) const {
    const double hx = 0.5 * w;
    const double yb = cy - std::sqrt(r * r - hx * hx);  // where the slot walls meet the circle
    // outer arc: the circle without its bottom part |x - cx| < w/2
    const double px = x - cx, py = y - cy, rho = std::hypot(px, py);
    double d;
    if (rho > 0.0 && !(py < 0.0 && std::fabs(px) * r < hx * rho))
      d = std::fabs(rho - r);  // radial projection lies on the arc
    else
      d = std::min(std::hypot(x - (cx - hx), y - yb), std::hypot(x - (cx + hx), y - yb));
    auto seg = [](double x, double y, double ax, double ay, double bx, double by) {
      const double ex = bx - ax, ey = by - ay;
      const double t = std::clamp(((x - ax) * ex + (y - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
      return std::hypot(x - ax - t * ex, y - ay - t * ey);
    };
    d = std::min(d, seg(x, y, cx - hx, yb, cx - hx, top));
    d = std::min(d, seg(x, y, cx + hx, yb, cx + hx, top));
    d = std::min(d, seg(x, y, cx - hx, top, cx + hx, top));
    return inside(x, y) ? -d : d;
  }
};

}  // namespace refmap::geometry
