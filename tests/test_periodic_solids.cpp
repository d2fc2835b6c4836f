// Solids across periodic sides (solver/model/periodic_window.hpp, docs/reference_map.md
// "Periodic sides"):
//  - a soft disc carried once around a fully periodic box by a uniform flow (diagonally, so
//    it crosses both seams and the corner, where its window is in four pieces) comes back
//    to its start, one period further on in the unwrapped centroid, with its area within
//    0.5 % and its centroid within 0.1 dx (the goal, docs/reference_map.md);
//  - the same problem placed on the seam and in the middle of the box: a soft disc in a
//    Taylor-Green flow, a rigid disc moved through one on a prescribed path (both forcings)
//    and two discs colliding across the seam. The seam case is the middle case shifted by
//    half the box (a whole number of cells), flow and solids alike, so the two discrete
//    problems are the same up to the relabelling of the cells, and their diagnostics
//    (areas, centroids less the shift, energies, body loads, contact gaps) agree to the
//    round-off of the sums taken in a different order (the Poisson solves, converged to
//    1e-12, the energy sums, the window split at the seam): 1e-13 here, 1e-10 for the rigid
//    body, whose velocity is a numerical derivative of its path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/model/contact.hpp"
#include "solver/model/rigid_body.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/fixtures/scene_text.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

constexpr int kN = 64;  // cells per side of the unit box
constexpr double kDx = 1.0 / kN;
// The solids' centres are off the cell corners by these (fractions of a cell): a disc centred
// on a corner has cells at exactly equal distances, and the round-off of the two placements
// then decides ties (which of two equal cells the fast marching takes first, whether a cell
// is just inside) that change the fields by far more than round-off -- in the middle of the
// box as much as on the seam, so they would hide what is compared
constexpr double kOx = 0.3 * kDx, kOy = 0.19 * kDx;

/// A [[solid]] disc with its centre written to full precision (disc_toml writes 6 digits:
/// the two placements would then be different discs).
std::string disc(const std::string& name, double cx, double cy, double r, double mu_s, const std::string& more) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "center = [%.17g, %.17g]\n", cx, cy);
  std::string t = disc_toml(name, 0.0, 0.0, r, mu_s, more);
  return t.replace(t.find("center = [0, 0]\n"), 16, buf);
}

/// A fully periodic unit box of kN^2 cells and a tight pressure tolerance.
std::string periodic_box(const std::string& extra, double mu) {
  return box_scene(kN, kPeriodic, "[solver]\ntol = 1e-12\n" + extra, mu);
}

/// The Taylor-Green velocity of the unit box shifted by (sx, sy): its value at x is the
/// unshifted one at x + s.
std::string taylor_green(double sx, double sy) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "[initial]\nvelocity = \"expression\"\n"
                "u_expr = \"0.3141592653589793*sin(2*pi*(x + %.17g))*cos(2*pi*(y + %.17g))\"\n"
                "v_expr = \"-0.3141592653589793*cos(2*pi*(x + %.17g))*sin(2*pi*(y + %.17g))\"\n",
                sx, sy, sx, sy);
  return buf;
}

/// What an observable is, for the scale its differences are measured against.
enum class Kind { Area, Position, Velocity, Energy, Force, Torque, Gap };

/// The diagnostics compared between the two placements, per step: for every solid its
/// area, centroid (plus `shift`) and mean velocity; the kinetic and elastic energies; every
/// rigid body's load; every solid's contact gap to the others.
std::vector<std::pair<Kind, double>> observables(const Simulation& sim, double sx, double sy) {
  std::vector<std::pair<Kind, double>> out;
  for (const auto& s : sim.solids()) {
    const SolidDiagnostics d = s->diagnostics(sim.u(), sim.v());
    out.insert(out.end(), {{Kind::Area, d.area}, {Kind::Position, d.cx + sx}, {Kind::Position, d.cy + sy},
                           {Kind::Velocity, d.u}, {Kind::Velocity, d.v}});
  }
  out.push_back({Kind::Energy, sim.kinetic_energy()});
  out.push_back({Kind::Energy, sim.elastic_energy()});
  if (const RigidBodies* b = sim.bodies())
    for (std::size_t k = 0; k < sim.solids().size(); ++k)
      if (b->rigid(int(k)))
        out.insert(out.end(), {{Kind::Force, b->load(int(k)).fx}, {Kind::Force, b->load(int(k)).fy},
                               {Kind::Torque, b->load(int(k)).torque}});
  if (const Contact* c = sim.contact())
    for (std::size_t k = 0; k < sim.solids().size(); ++k) out.push_back({Kind::Gap, c->gap_solid(int(k))});
  return out;
}

/// Per observable over a run: the largest difference between the two placements against
/// its scale -- areas relative to the area, positions and gaps in cells, velocities
/// relative to `velocity`, energies to the largest kinetic energy, forces to the largest
/// force, torques to that times `length` -- and the middle run's extremes.
struct Comparison {
  std::vector<double> diff, lo, hi;
};

/// Runs `middle` and `seam` (the middle scene shifted by -(sx, sy)) for `steps` steps of dt
/// (the same steps in both).
Comparison compare(const std::string& middle, const std::string& seam, double sx, double sy, int steps, double dt,
                   double velocity, double length) {
  Simulation a(load_scene_string(middle, "middle.toml"));
  Simulation b(load_scene_string(seam, "seam.toml"));
  // the seam case's windows do cross a periodic side (else the test would test nothing)
  bool crosses = false;
  for (const auto& s : b.solids())
    crosses = crosses || s->i0() < 0 || s->j0() < 0 || s->i0() + s->ni() > kN || s->j0() + s->nj() > kN;
  EXPECT_TRUE(crosses);
  EXPECT_LE(dt, a.stable_dt());  // a step the solver would take itself
  Comparison c;
  std::vector<Kind> kind;
  double energy = 0.0, force = 0.0;
  for (int n = 0; n <= steps; ++n) {
    if (n > 0) {
      a.step(dt);
      b.step(dt);
    }
    const auto va = observables(a, 0.0, 0.0), vb = observables(b, sx, sy);
    EXPECT_EQ(va.size(), vb.size());
    c.diff.resize(va.size(), 0.0);
    c.lo.resize(va.size(), 1e300);
    c.hi.resize(va.size(), -1e300);
    kind.resize(va.size());
    for (std::size_t k = 0; k < va.size() && k < vb.size(); ++k) {
      kind[k] = va[k].first;
      // positions modulo the period (the images of a solid are one)
      const double dv = va[k].second - vb[k].second;
      c.diff[k] = std::max(c.diff[k], std::abs(kind[k] == Kind::Position ? std::remainder(dv, 1.0) : dv));
      c.lo[k] = std::min(c.lo[k], va[k].second);
      c.hi[k] = std::max(c.hi[k], va[k].second);
      if (kind[k] == Kind::Energy) energy = std::max(energy, std::abs(va[k].second));
      if (kind[k] == Kind::Force) force = std::max(force, std::abs(va[k].second));
    }
  }
  EXPECT_NEAR(a.time(), b.time(), 1e-14);
  for (std::size_t k = 0; k < c.diff.size(); ++k) {
    double scale = 1.0;
    switch (kind[k]) {
      case Kind::Area: scale = std::abs(c.hi[k]); break;
      case Kind::Position:
      case Kind::Gap: scale = kDx; break;
      case Kind::Velocity: scale = velocity; break;
      case Kind::Energy: scale = energy; break;
      case Kind::Force: scale = force; break;
      case Kind::Torque: scale = force * length; break;
    }
    c.diff[k] /= scale;
  }
  return c;
}

void report(const char* what, const std::vector<double>& d) {
  std::printf("[periodic %s] differences seam vs middle (relative; positions and gaps in cells):", what);
  for (double x : d) std::printf(" %.2e", x);
  std::printf("\n");
}

}  // namespace

TEST(PeriodicSolids, DiscCarriedOnceAroundComesBack) {
  // a uniform flow (1, 1) carries a soft disc (rho_s = rho_f) once around the box in t = 1:
  // the flow and the rigid translation are an exact solution, so what is measured is the
  // reference map's transport, the level set and the stress across the seams. Goals from
  // the goal: area within 0.5 %, centroid within 0.1 dx of its start (plus one period).
  // dt = 1/250 moves the disc 0.192 cells a step (not a fraction that repeats the cell
  // offsets every few steps, as the CFL step dx/4 would).
  const int n = 48;
  const double dx = 1.0 / n;
  const std::string text = box_scene(
      n, kPeriodic,
      "[initial]\nvelocity = \"uniform\"\nu = 1.0\nv = 1.0\n" +
          disc_toml("traveller", 0.5, 0.5, 0.15, 1.0, "velocity = \"fluid\"\n"),
      0.01, 1.0);
  Simulation sim(load_scene_string(text, "around.toml"));
  const Solid& s = *sim.solids().at(0);
  const SolidDiagnostics d0 = s.diagnostics(sim.u(), sim.v());
  bool crossed_corner = false;  // the window in four pieces at some step
  double worst_area = 0.0;
  for (int n = 0; n < 250; ++n) {
    ASSERT_LE(1.0 / 250.0, sim.stable_dt());
    sim.step(1.0 / 250.0);
    int pieces = 0;
    s.for_each_piece([&](const WindowPiece&) { ++pieces; });
    crossed_corner = crossed_corner || pieces == 4;
    worst_area = std::max(worst_area, std::abs(s.diagnostics(sim.u(), sim.v()).area / d0.area - 1.0));
  }
  const SolidDiagnostics d1 = s.diagnostics(sim.u(), sim.v());
  const double ex = (d1.cx - 1.0 - d0.cx) / dx, ey = (d1.cy - 1.0 - d0.cy) / dx;
  std::printf("[periodic around] %ld steps to t = %.6f: area %.6e -> %.6e (%.2e, worst %.2e), centroid (%.6f, %.6f) "
              "-> (%.6f, %.6f): error (%.2e, %.2e) dx\n",
              sim.steps(), sim.time(), d0.area, d1.area, d1.area / d0.area - 1.0, worst_area, d0.cx, d0.cy, d1.cx,
              d1.cy, ex, ey);
  EXPECT_TRUE(crossed_corner);
  EXPECT_NEAR(sim.time(), 1.0, 1e-12);
  EXPECT_LT(worst_area, 5e-3);  // the goal's 0.5 %
  EXPECT_LT(std::hypot(ex, ey), 0.1);  // the goal's 0.1 dx
}

TEST(PeriodicSolids, SoftDiscOnTheCornerMatchesTheMiddleInTaylorGreen) {
  // the paper's soft disc in a Taylor-Green vortex (scenes/disc_tgv.toml, here periodic):
  // in the middle, and at the corner of the box (both seams through it) with the flow
  // shifted by half the box, 32 cells each way; 100 steps, t = 0.4
  const std::string middle = disc("disc", 0.5 + kOx, 0.5 + kOy, 0.2, 0.5, "velocity = \"fluid\"\n");
  const std::string corner = disc("disc", kOx, kOy, 0.2, 0.5, "velocity = \"fluid\"\n");
  const auto d = compare(periodic_box(taylor_green(0, 0) + middle, 1e-3),
                         periodic_box(taylor_green(0.5, 0.5) + corner, 1e-3), 0.5, 0.5, 100, 0.004, 0.314, 0.2)
                     .diff;
  report("soft disc", d);
  // round-off (measured: at most 4e-14): the same problem relabelled, sums and sweeps in
  // another order, xi (unwrapped) rounded in another binade
  for (double x : d) EXPECT_LT(x, 1e-12);
}

TEST(PeriodicSolids, RigidDiscOnTheSeamMatchesTheMiddle) {
  // a rigid disc moved on a prescribed path through a Taylor-Green flow, across the seam
  // x = 0 in the shifted case; its load (the forcing's momentum balance, rigid_body.hpp)
  // reads and writes the global fields through the wrapped window; both forcings (the
  // interpolated one samples image points across the seam)
  for (const char* forcing : {"diffuse", "interpolated"}) {
    auto body = [&](double cx, double cy) {
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "[[solid]]\nname = \"body\"\nshape = \"circle\"\ncenter = [%.17g, %.17g]\nradius = 0.12\n"
                    "density = 1.0\nmotion = \"prescribed\"\nforcing = \"%s\"\npath_x = \"%.17g + 0.25*t\"\n"
                    "path_y = \"%.17g\"\n",
                    cx, cy, forcing, cx, cy);
      return std::string(buf);
    };
    const auto d = compare(periodic_box(taylor_green(0, 0) + body(0.4375 + kOx, 0.5 + kOy), 1e-2),
                           periodic_box(taylor_green(0.5, 0.0) + body(-0.0625 + kOx, 0.5 + kOy), 1e-2), 0.5, 0.0, 100, 0.0035,
                           0.314, 0.12)
                       .diff;
    report(forcing, d);
    // round-off, amplified: the body's velocity is a centred difference of its path with a
    // step of 1e-6 (RigidPath::velocity), whose rounding, ~1e-16 / 1e-6, differs between
    // the two placements (measured: at most 8e-11)
    for (double x : d) EXPECT_LT(x, 1e-9) << forcing;
  }
}

TEST(PeriodicSolids, CollisionAcrossTheSeamMatchesTheMiddle) {
  // two soft discs driven at each other; in the shifted case they meet across the seam
  // x = 0 (solid 0 at x = 0.15 moving left, solid 1 at x = 0.85 moving right), so the
  // contact force and the gap between them use the minimal-image displacement. dt = 0.0015
  // is below the contact spring's limit (contact.hpp: about 0.1 dx / U, U = 1).
  auto discs = [](double xa, double xb) {
    return disc("a", xa, 0.5 + kOy, 0.12, 1.0, "u = -1.0\n") + disc("b", xb, 0.5 + kOy, 0.12, 1.0, "u = 1.0\n");
  };
  const Comparison c =
      compare(periodic_box("[initial]\nvelocity = \"zero\"\n" + discs(0.65 + kOx, 0.35 + kOx), 1e-2),
              periodic_box("[initial]\nvelocity = \"zero\"\n" + discs(0.15 + kOx, 0.85 + kOx), 1e-2), 0.5, 0.0, 100, 0.0015,
              1.0, 0.12);
  const auto& d = c.diff;
  report("collision", d);
  // they did meet: the smallest gap of the run (the last observable) below the contact
  // range, 2.5 dx
  std::printf("[periodic collision] smallest gap %.3f dx\n", c.lo.back() / kDx);
  EXPECT_LT(c.lo.back(), 2.5 * kDx);
  for (double x : d) EXPECT_LT(x, 1e-12);  // round-off, as for the soft disc (measured: at most 7e-14)
}
