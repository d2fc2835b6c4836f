// Oscillatory Couette flow with an elastic layer (Sugiyama et al. 2011, test 1;
// docs/references.md#elastic-layer-couette-flow): start from rest, walls at y = +-1 moving with +-sin(pi t), solid
// |y| <= 0.5 with G = 5, fluid mu = 1. The u profile on y in [0, 1] at t = 4.8 must be
// within 2% of the wall speed (L-infinity over the 41 reference stations) of the start-up
// reference couette_elastic_startup.csv at 64 cells per unit length, and the error must fall
// when the grid is refined (32 -> 64 cells per unit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/model/probes.hpp"
#include "solver/app/run.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/fixtures/couette_layer.hpp"
#include "tests/quoted_results.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

double couette_error(int cells_per_unit) {
  Config cfg = couette_layer_scene(cells_per_unit);
  Simulation sim(cfg);
  RunSummary r = run(sim, RunOptions::silent());
  EXPECT_FALSE(r.failed) << r.failure;
  EXPECT_NEAR(sim.time(), 4.8, 1e-9);
  const double linf = couette_layer_linf(cfg, sim);
  std::printf("[couette] %d cells per unit: %ld steps, L-inf error at t = 4.8: %.4e (wall speed 1)\n",
              cells_per_unit, sim.steps(), linf);
  return linf;
}

}  // namespace

TEST(CouetteElastic, StartupProfileWithin2PercentAndConverging) {
  const double coarse = couette_error(32);
  const double fine = couette_error(64);
  EXPECT_LE(fine, 0.02);
  EXPECT_LT(fine, coarse);
  expect_quoted("CouetteElastic/linf_32", coarse);  // the numbers results/README.md quotes
  expect_quoted("CouetteElastic/linf_64", fine);
}
