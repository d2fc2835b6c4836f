// Suspensions of soft particles in a shear cell (results/suspension.md):
//  - Placement.*: the random placement of [suspension] (solver/scene/suspension.hpp), expanded at
//    load into [[solid]] tables: the same seed gives the same particles bit for bit (and the
//    engine is the standard's), different seeds differ, the area fraction is the request's
//    within one particle's area, no two particles come closer than the gap (across the
//    periodic sides too) nor any closer to a wall, and a fraction the placement cannot reach
//    is an error naming the key and the fraction reached;
//  - ShearSuspension.*: a free, stiff soft disc at the centre of the shear cell: its dilute
//    coefficient, corrected for the walls, within 10 % of the 2-D Einstein value at 12.8 cells
//    per radius (not at 6.4), and a softer one a lower relative viscosity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "solver/components/wall_stress.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "solver/scene/suspension.hpp"
#include "test_helpers.hpp"

namespace refmap {
namespace {

/// The shear cell of bench/scenes/shear_suspension.toml: 2 x 1, walls at -1/2 and +1/2,
/// periodic along x, mu = rho = 1, started from the undisturbed shear, implicit viscosity.
std::string shear_cell(int nx, double t_end, const std::string& extra) {
  return "name = \"suspension\"\n[domain]\nlx = 2.0\nly = 1.0\n[grid]\nnx = " + std::to_string(nx) +
         "\nny = " + std::to_string(nx / 2) +
         "\n[fluid]\ndensity = 1.0\nviscosity = 1.0\n"
         "[boundary]\nleft = \"periodic\"\nright = \"periodic\"\n"
         "bottom = { type = \"moving_wall\", velocity = -0.5 }\ntop = { type = \"moving_wall\", velocity = 0.5 }\n"
         "[initial]\nvelocity = \"expression\"\nu_expr = \"y - 0.5\"\nv_expr = \"0\"\n"
         "[time]\nend = " + std::to_string(t_end) + "\nviscous = \"implicit\"\n[output]\nwall_stress = true\n" + extra;
}

std::string suspension(const std::string& keys, double radius = 0.1) {
  return shear_cell(64, 1.0, "[suspension]\nradius = " + std::to_string(radius) +
                                 "\nmu_s = 50.0\ndensity = 1.0\nviscosity = 1.0\n" + keys);
}

using refmap::testing::scene_error;

double solid_area(const SolidSpec& s) {
  return s.shape.kind == ShapeKind::Circle ? M_PI * s.shape.radius * s.shape.radius : M_PI * s.shape.a * s.shape.b;
}

double area_fraction(const Config& cfg) {
  double a = 0.0;
  for (const auto& s : cfg.solids) a += solid_area(s);
  return a / (cfg.grid.lx() * cfg.grid.ly());
}

/// The centre-to-centre distance by the nearest image along the periodic x (period 2).
double distance(const SolidSpec& p, const SolidSpec& q) {
  double dx = q.shape.cx - p.shape.cx;
  dx -= 2.0 * std::round(dx / 2.0);
  return std::hypot(dx, q.shape.cy - p.shape.cy);
}

TEST(Placement, GeneratorIsTheStandardOne) {
  // C++ [rand.predef]: the 10000th output of a default-constructed mt19937_64 is fixed, so the
  // placement's draws are the same with every standard library
  std::mt19937_64 rng;
  rng.discard(9999);
  const std::uint64_t draw = rng();
  EXPECT_EQ(draw, 9981545732273789042ULL);
  // its top 53 bits over 2^53: exact in double
  EXPECT_EQ(uniform01(draw), double(9981545732273789042ULL >> 11) / 9007199254740992.0);
  EXPECT_EQ(uniform01(0), 0.0);
  EXPECT_LT(uniform01(~0ULL), 1.0);
}

TEST(Placement, SameSeedGivesTheSameParticlesBitForBit) {
  const Config a = load_scene_string(suspension("area_fraction = 0.3\nseed = 7\n"), "a.toml");
  const Config b = load_scene_string(suspension("area_fraction = 0.3\nseed = 7\n"), "b.toml");
  ASSERT_EQ(a.solids.size(), b.solids.size());
  ASSERT_GT(a.solids.size(), 10u);
  for (std::size_t k = 0; k < a.solids.size(); ++k) {
    const ShapeParams &p = a.solids[k].shape, &q = b.solids[k].shape;
    EXPECT_EQ(std::memcmp(&p.cx, &q.cx, sizeof p.cx), 0);
    EXPECT_EQ(std::memcmp(&p.cy, &q.cy, sizeof p.cy), 0);
    EXPECT_EQ(std::memcmp(&p.radius, &q.radius, sizeof p.radius), 0);
    EXPECT_EQ(a.solids[k].name, "p" + std::to_string(k));
    EXPECT_EQ(a.solids[k].mu_s, 50.0);
    EXPECT_EQ(a.solids[k].velocity, SolidVelocity::Fluid);
  }
}

TEST(Placement, DifferentSeedsDiffer) {
  const Config a = load_scene_string(suspension("count = 10\nseed = 1\n"), "a.toml");
  const Config b = load_scene_string(suspension("count = 10\nseed = 2\n"), "b.toml");
  ASSERT_EQ(a.solids.size(), 10u);
  ASSERT_EQ(b.solids.size(), 10u);
  int same = 0;
  for (std::size_t k = 0; k < 10; ++k) same += a.solids[k].shape.cx == b.solids[k].shape.cx;
  EXPECT_EQ(same, 0);
}

TEST(Placement, AreaFractionWithinOneParticle) {
  const double cell = 2.0;  // the domain's area
  for (const double phi : {0.05, 0.2, 0.4}) {
    const Config c = load_scene_string(suspension("area_fraction = " + std::to_string(phi) + "\n"), "phi.toml");
    EXPECT_NEAR(area_fraction(c), phi, M_PI * 0.01 / cell) << "phi = " << phi;
  }
  // two sizes, half of each by number; and ellipses of the disc's area
  const Config two = load_scene_string(suspension("area_fraction = 0.3\nradius2 = 0.06\n"), "two.toml");
  EXPECT_NEAR(area_fraction(two), 0.3, M_PI * 0.01 / cell);
  int small = 0;
  for (const auto& s : two.solids) small += s.shape.radius == 0.06;
  EXPECT_NEAR(small, 0.5 * double(two.solids.size()), 0.5 + 1e-12);
  const Config ell = load_scene_string(suspension("area_fraction = 0.3\naspect = 2.0\n"), "ellipses.toml");
  EXPECT_NEAR(area_fraction(ell), 0.3, M_PI * 0.01 / cell);
  for (const auto& s : ell.solids) {
    EXPECT_EQ(s.shape.kind, ShapeKind::Ellipse);
    EXPECT_NEAR(s.shape.a / s.shape.b, 2.0, 1e-12);
  }
}

TEST(Placement, NoOverlapsAcrossThePeriodicSidesOrWithTheWalls) {
  const double gap = 0.1 * 0.1;  // suspension.gap (default 0.1) radii
  const Config c = load_scene_string(suspension("area_fraction = 0.4\nseed = 3\n"), "dense.toml");
  ASSERT_GT(c.solids.size(), 20u);
  int crossing = 0;
  for (std::size_t i = 0; i < c.solids.size(); ++i) {
    const ShapeParams& p = c.solids[i].shape;
    EXPECT_GE(p.cy - p.radius, gap * (1 - 1e-12));
    EXPECT_LE(p.cy + p.radius, 1.0 - gap * (1 - 1e-12));
    crossing += p.cx - p.radius < 0.0 || p.cx + p.radius > 2.0;
    for (std::size_t j = i + 1; j < c.solids.size(); ++j)
      EXPECT_GE(distance(c.solids[i], c.solids[j]), p.radius + c.solids[j].shape.radius + gap * (1 - 1e-12))
          << i << ", " << j;
  }
  EXPECT_GT(crossing, 0) << "this seed was picked for a particle across the periodic side";
}

TEST(Placement, EllipsesDoNotOverlap) {
  const Config c = load_scene_string(suspension("area_fraction = 0.3\naspect = 3.0\nseed = 5\n"), "ell.toml");
  ASSERT_GT(c.solids.size(), 10u);
  // 2000 points on each ellipse's boundary, none inside another ellipse (nearest image)
  for (const auto& sp : c.solids)
    for (const auto& sq : c.solids) {
      if (&sp == &sq) continue;
      const ShapeParams &p = sp.shape, &q = sq.shape;
      for (int k = 0; k < 2000; ++k) {
        const double t = 2 * M_PI * k / 2000, lx = p.a * std::cos(t), ly = p.b * std::sin(t);
        double x = p.cx + std::cos(p.angle) * lx - std::sin(p.angle) * ly - q.cx;
        const double y = p.cy + std::sin(p.angle) * lx + std::cos(p.angle) * ly - q.cy;
        x -= 2.0 * std::round(x / 2.0);
        const double X = std::cos(q.angle) * x + std::sin(q.angle) * y, Y = -std::sin(q.angle) * x + std::cos(q.angle) * y;
        ASSERT_GE((X / q.a) * (X / q.a) + (Y / q.b) * (Y / q.b), 1.0) << sp.name << " enters " << sq.name;
      }
    }
}

TEST(Placement, UnreachableFractionIsAnErrorNamingTheFractionReached) {
  const std::string msg = scene_error(suspension("area_fraction = 0.7\nattempts = 2000\n"));
  EXPECT_NE(msg.find("suspension.area_fraction"), std::string::npos) << msg;
  EXPECT_NE(msg.find("reached area fraction"), std::string::npos) << msg;
  // above the densest packing: the key's range
  EXPECT_NE(scene_error(suspension("area_fraction = 0.95\n")).find("suspension.area_fraction"), std::string::npos);
  // count and fraction together, or neither
  EXPECT_NE(scene_error(suspension("area_fraction = 0.2\ncount = 3\n")).find("give exactly one"), std::string::npos);
  EXPECT_NE(scene_error(suspension("")).find("give exactly one"), std::string::npos);
  // a particle wider than the gap between the walls
  EXPECT_NE(scene_error(suspension("count = 1\n", 0.6)).find("suspension.count"), std::string::npos);
}

TEST(Placement, ExplicitSolidOverlappingAParticleIsRefused) {
  // the particles are ordinary solids: the start check refuses an overlap with another solid
  const Config c = load_scene_string(suspension("count = 1\nseed = 1\n"), "one.toml");
  const ShapeParams& p = c.solids.at(0).shape;
  const std::string msg = scene_error(suspension("count = 1\nseed = 1\n") +
                                   "[[solid]]\nname = \"wall_disc\"\nshape = \"circle\"\ncenter = [" +
                                   std::to_string(p.cx) + ", " + std::to_string(p.cy) +
                                   "]\nradius = 0.05\nmu_s = 1.0\ndensity = 1.0\n");
  EXPECT_NE(msg.find("overlaps solid"), std::string::npos) << msg;
}

// ---- the dilute limit, with a free particle

/// eta_r of one free disc of radius 0.1 at the centre of the cell, averaged in time over the
/// last 40 % of a run to t_end (the stiff disc's shear waves ripple the wall stress);
/// transition: solids.transition, the blend's half-width in cells.
double eta_of_one_disc(double mu_s, int nx, double t_end, double transition = 3.0) {
  const Config cfg = load_scene_string(
      shear_cell(nx, t_end,
                 "[solids]\ntransition = " + std::to_string(transition) +
                     "\n[[solid]]\nname = \"disc\"\nshape = \"circle\"\ncenter = [1.0, 0.5]\nradius = 0.1\nmu_s = " +
                     std::to_string(mu_s) + "\ndensity = 1.0\nviscosity = 1.0\nvelocity = \"fluid\"\n"),
      "one_disc.toml");
  Simulation sim(cfg);
  const double t0 = 0.6 * cfg.t_end;
  double sum = 0.0, span = 0.0;
  std::vector<double> v;
  while (sim.time() < cfg.t_end - 1e-12) {
    const double before = sim.time();
    sim.step();
    if (sim.time() <= t0) continue;
    v.clear();
    if (const WallStress* w = sim.component<WallStress>()) w->values(sim, v);  // bottom, top, eta_r
    const double dt = sim.time() - std::max(before, t0);
    sum += v.at(2) * dt;
    span += dt;
  }
  return sum / span;
}

// One free stiff disc on the centre line (it stays there by symmetry), a/H = 0.1, L = 2H,
// Ca = 0.01: the dilute coefficient c = (eta_r - 1)/phi against the 2-D Einstein value 2
// (Brady 1984). Measured apart (results/suspension.md, "The dilute limit";
// results/suspension/dilute_fits.csv, bench/run_suspension_dilute.sh):
//  - the walls add k (a/H)^2 to c (H varied at fixed a and grid): 0.240 in this cell at 6.4
//    cells per radius, 0.205 at 12.8; the periodic images 0.001 (L = 2 against L = 4);
//  - the blend of eq. (3.5), half-width solids.transition = 3 cells, makes the particle stiff
//    beyond its radius: c falls with the grid, 2.586 / 2.420 / 2.274 at 6.4 / 12.8 / 25.6
//    cells per radius, and rises with the half-width at a fixed grid (2.28 at 1.5 cells, 2.85
//    at 4); the area the blend adds (0.7 % at 12.8 cells per radius) explains little of it.
// Corrected for the walls and images, c is 2.345 at 6.4 cells per radius (+17 %), 2.214 at
// 12.8 (+11 %) and 2.068 at 25.6 (+3 %). The test runs the two cheap grids and extrapolates
// to dx = 0 at first order (Richardson: 2 c(12.8) - c(6.4)), then subtracts the walls' 0.205:
// measured 2.05. The excess is not yet in its asymptotic range (the same extrapolation from
// 12.8 and 25.6 gives 1.92), so this 0.13 spread, and the walls' correction's own change with
// the grid (0.035 from 6.4 to 12.8), sit inside the 10 % tolerance asserted here.
// The runs stop at t = 0.5: c is steady to 1e-3 from t = 0.3 (the disturbance's diffusion
// across the gap, H^2 / (pi^2 nu) = 0.1, three times over).
TEST(ShearSuspension, StiffFreeDiscExtrapolatedCoefficientWithinTenPercentOfEinstein) {
  const double phi = M_PI * 0.01 / 2.0;
  const double walls = 0.205, images = 0.001;
  const double coarse = (eta_of_one_disc(50.0, 128, 0.5) - 1.0) / phi;  // 6.4 cells per radius
  const double fine = (eta_of_one_disc(50.0, 256, 0.5) - 1.0) / phi;    // 12.8
  const double extrapolated = 2.0 * fine - coarse;
  EXPECT_NEAR(extrapolated - walls - images, 2.0, 0.2) << "c = " << coarse << " and " << fine;
  // the excess is the blend's: it falls with dx (by 0.166 measured, t in [0.6, 1])
  EXPECT_GT(coarse - fine, 0.1) << "c = " << coarse << " at 6.4 cells per radius, " << fine << " at 12.8";
}

TEST(ShearSuspension, SofterDiscThinsTheSuspension) {
  const double stiff = eta_of_one_disc(50.0, 128, 1.0), soft = eta_of_one_disc(2.5, 128, 1.0);
  EXPECT_LT(soft, stiff);
}

}  // namespace
}  // namespace refmap
