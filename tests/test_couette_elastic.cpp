// Oscillatory Couette flow with an elastic layer (Sugiyama et al. 2011, test 1;
// BENCHMARKS.md section 3): start from rest, walls at y = +-1 moving with +-sin(pi t), solid
// |y| <= 0.5 with G = 5, fluid mu = 1. The u profile on y in [0, 1] at t = 4.8 must be
// within 2% of the wall speed (L-infinity over the 41 reference stations) of the start-up
// reference couette_elastic_startup.csv at 64 cells per unit length, and the error must fall
// when the grid is refined (32 -> 64 cells per unit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/probes.hpp"
#include "solver/run.hpp"
#include "solver/scene.hpp"
#include "solver/simulation.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

double couette_error(int cells_per_unit) {
  // nx = 8 columns always (the flow is one-dimensional); lx follows dx
  const double dx = 1.0 / cells_per_unit;
  Config cfg = load_scene(scene_path("couette_elastic.toml"),
                          {"grid.ny=" + std::to_string(2 * cells_per_unit),
                           "domain.lx=" + std::to_string(8 * dx), "domain.ly=2.0"});
  Simulation sim(cfg);
  RunSummary r = run(sim, RunOptions::silent());
  EXPECT_FALSE(r.failed) << r.failure;
  EXPECT_NEAR(sim.time(), 4.8, 1e-9);
  Csv ref = read_csv(data_path("couette_elastic_startup.csv"));
  auto ys = ref.column("y");
  auto us = ref.column("u_t4.8");
  Field u = sim.named_field("u");
  double linf = 0.0;
  for (size_t k = 0; k < ys.size(); ++k)
    linf = std::max(linf, std::abs(sample_bilinear(cfg.grid, u, 4 * dx, ys[k]) - us[k]));
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
}
