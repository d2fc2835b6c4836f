#include "solver/scene/suspension.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace refmap {

double uniform01(std::uint64_t draw) { return double(draw >> 11) * 0x1.0p-53; }

double Particle::area() const { return M_PI * a * b; }

double Placement::area_fraction(const PlacementBox& box) const {
  double s = 0.0;
  for (const Particle& p : particles) s += p.area();
  return s / (box.lx * box.ly);
}

std::vector<double> suspension_radii(const SuspensionSpec& s, const PlacementBox& box) {
  const bool two = s.radius2 > 0.0;
  long n1 = 0, n2 = 0;
  if (s.count > 0) {
    n2 = two ? std::lround(s.fraction2 * double(s.count)) : 0;
    n1 = s.count - n2;
  } else {
    // the number that brings the area closest to the request: the second size's share
    // first (by number, from the mean particle area), the first size then fills the rest
    const double target = s.area_fraction * box.lx * box.ly;
    const double a1 = M_PI * s.radius * s.radius, a2 = M_PI * s.radius2 * s.radius2;
    if (two) {
      const double total = target / ((1.0 - s.fraction2) * a1 + s.fraction2 * a2);
      n2 = std::lround(s.fraction2 * total);
    }
    n1 = std::max(0L, std::lround((target - double(n2) * a2) / a1));
  }
  std::vector<double> r(std::size_t(n1), s.radius);
  r.insert(r.end(), std::size_t(n2), s.radius2);
  // larger first: random sequential addition fills more when the large ones go in first
  std::stable_sort(r.begin(), r.end(), [](double p, double q) { return p > q; });
  return r;
}

namespace {

/// The displacement q - p, by the nearest periodic image.
void nearest_image(const Particle& p, const Particle& q, const PlacementBox& box, double& dx, double& dy) {
  dx = q.x - p.x;
  dy = q.y - p.y;
  if (box.periodic_x) dx -= box.lx * std::round(dx / box.lx);
  if (box.periodic_y) dy -= box.ly * std::round(dy / box.ly);
}

/// Whether a point of ellipse p's boundary (semi-axes grown by h) lies inside ellipse q
/// (grown by h), q displaced by (dx, dy) from p; 256 points.
bool boundary_enters(const Particle& p, const Particle& q, double dx, double dy, double h) {
  const double pa = p.a + h, pb = p.b + h, qa = q.a + h, qb = q.b + h;
  const double cp = std::cos(p.angle), sp = std::sin(p.angle), cq = std::cos(q.angle), sq = std::sin(q.angle);
  constexpr int n = 256;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * M_PI * k / n;
    const double lx = pa * std::cos(t), ly = pb * std::sin(t);
    // the point relative to q's centre, in q's axes
    const double x = cp * lx - sp * ly - dx, y = sp * lx + cp * ly - dy;
    const double X = cq * x + sq * y, Y = -sq * x + cq * y;
    if ((X / qa) * (X / qa) + (Y / qb) * (Y / qb) < 1.0) return true;
  }
  return false;
}

}  // namespace

bool particles_closer_than(const Particle& p, const Particle& q, double gap, const PlacementBox& box) {
  double dx, dy;
  nearest_image(p, q, box, dx, dy);
  const double d = std::hypot(dx, dy);
  if (d >= p.a + q.a + gap) return false;  // the circumscribed circles clear
  if (p.a == p.b && q.a == q.b) return true;  // two discs: exact
  if (d < p.b + q.b + gap) return true;      // the inscribed circles meet
  // an ellipse grown by h in both semi-axes lies inside its offset curve at distance h (its
  // support function is at most the ellipse's plus h), so this test keeps the particles
  // apart and their gap at least close to `gap`
  const double h = 0.5 * gap;
  return boundary_enters(p, q, dx, dy, h) || boundary_enters(q, p, -dx, -dy, h);
}

Placement place_suspension(const SuspensionSpec& s, const PlacementBox& box) {
  const std::vector<double> radii = suspension_radii(s, box);
  Placement out;
  out.requested = long(radii.size());
  std::mt19937_64 rng(std::uint64_t(s.seed));
  auto u = [&] { return uniform01(rng()); };
  const double gap = s.gap * s.radius;
  const double stretch = std::sqrt(s.aspect);
  for (const double r : radii) {
    Particle p;
    p.a = r * stretch;  // the disc's area: a b = r^2
    p.b = r / stretch;
    bool placed = false;
    for (long k = 0; k < s.attempts && !placed; ++k) {
      ++out.attempts;
      p.angle = s.aspect > 1.0 ? M_PI * u() : 0.0;
      const double c = std::cos(p.angle), sn = std::sin(p.angle);
      const double hx = std::sqrt(p.a * p.a * c * c + p.b * p.b * sn * sn);
      const double hy = std::sqrt(p.a * p.a * sn * sn + p.b * p.b * c * c);
      // uniform in the positions that keep `gap` from the walls (a periodic direction: all)
      auto coordinate = [&](double lo, double len, double half, bool periodic) {
        if (periodic) return lo + len * u();
        return lo + half + gap + (len - 2.0 * (half + gap)) * u();
      };
      p.x = coordinate(box.x0, box.lx, hx, box.periodic_x);
      p.y = coordinate(box.y0, box.ly, hy, box.periodic_y);
      if ((!box.periodic_x && box.lx < 2.0 * (hx + gap)) || (!box.periodic_y && box.ly < 2.0 * (hy + gap))) continue;
      placed = true;
      for (const Particle& q : out.particles)
        if (particles_closer_than(p, q, gap, box)) {
          placed = false;
          break;
        }
    }
    if (!placed) break;
    out.particles.push_back(p);
  }
  return out;
}

}  // namespace refmap
