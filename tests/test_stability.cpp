// Where methods fail (issue 13; bench/stability.py maps the limits, results/README.md
// "Where methods fail"):
//  - FoldedMap: the health check that names a folded reference map (solver/health.cpp):
//    one cell of a disc's xi is folded by hand (det grad xi < 0 by the central differences
//    the stress kernel uses) and the message must name the solid and that global cell;
//    an unfolded disc passes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "solver/health.hpp"
#include "solver/scene.hpp"
#include "solver/simulation.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

const char* kDisc = R"(
name = "fold"
[domain]
lx = 1.0
[grid]
nx = 32
ny = 32
[fluid]
density = 1.0
viscosity = 0.01
[boundary]
left = "periodic"
right = "periodic"
bottom = "periodic"
top = "periodic"
[initial]
velocity = "zero"
[time]
end = 1.0
[[solid]]
name = "blob"
shape = "circle"
center = [0.5, 0.5]
radius = 0.15
mu_s = 1.0
density = 1.0
)";

}  // namespace

TEST(FoldedMap, UnfoldedDiscPasses) {
  Config cfg = load_scene_string(kDisc, "fold.toml");
  Simulation sim(cfg);
  EXPECT_EQ(check_reference_maps(sim), "");
  sim.step();
  EXPECT_EQ(check_reference_maps(sim), "");
  EXPECT_EQ(check_health(sim, 1e-3), "");
}

TEST(FoldedMap, MessageNamesSolidAndCell) {
  Config cfg = load_scene_string(kDisc, "fold.toml");
  Simulation sim(cfg);
  Solid& s = *sim.solids().at(0);
  const Grid& g = sim.grid();
  // the global cell of the disc's centre, (16, 16), is at x = y = 16.5 dx
  const int gi = 16, gj = 16;
  const int i = gi - s.i0(), j = gj - s.j0();
  ASSERT_LT(s.phi()(i, j), 0.0);
  // xi_x of the cell to the right set below its left neighbour's: d xi_x / dx < 0 at
  // (gi, gj) while d xi_y / dy = 1 and the cross terms stay 0, so det grad xi < 0 there
  // and nowhere else (the neighbours' central differences skip cell i + 1 or gain)
  Field& xx = s.xi_x_mut();
  xx(i + 1, j) = xx(i - 1, j) - g.dx;
  const std::string msg = check_reference_maps(sim);
  std::printf("[fold] %s\n", msg.c_str());
  EXPECT_NE(msg.find("reference map folded in solid 'blob'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cell (16, 16)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("det grad xi = -0.5"), std::string::npos) << msg;  // (-dx) / (2 dx) * 1
  EXPECT_NE(msg.find("1 cell folded"), std::string::npos) << msg;
  EXPECT_NE(msg.find("x = 0.515625, y = 0.515625"), std::string::npos) << msg;
  EXPECT_NE(msg.find("step 0, t = 0"), std::string::npos) << msg;
  EXPECT_EQ(check_health(sim, 1e-3), msg);  // part of the check after every step
}
