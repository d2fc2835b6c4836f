// Zalesak slotted disk, the paper's Table 2: one full rigid rotation of the reference map
// on 100 x 100 with extrapolation into a 5 dx band every step. The exact final field is
// the initial one (xi = x), so E = RMS over the disk's cells of (xi_final - x) measures
// extrapolation + advection error. Jain & Mani report 6.72e-9 / 7.34e-9 for least
// squares and 8.32e-4 / 4.67e-4 for the PDE approach (norm not stated); the goal is
// <= 1e-8 with least squares. The PDE baseline's error is printed beside it and
// asserted to be worse than least squares (the paper's finding).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/app/run.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/quoted_results.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

struct XiError { double ex, ey; long fallbacks; };

XiError rotate(const std::string& method, const std::string& xi_advection = "vanleer") {
  Config cfg = load_scene(scene_path("zalesak.toml"), {"solids.extrapolation=\"" + method + "\"",
                                                       "solids.xi_advection=\"" + xi_advection + "\""});
  Simulation sim(cfg);
  const Solid& s0 = *sim.solids().at(0);
  // cells of the initial disk (global indices), phi0 < 0
  std::vector<std::pair<int, int>> cells;
  for (int j = 0; j < cfg.grid.ny; ++j)
    for (int i = 0; i < cfg.grid.nx; ++i)
      if (s0.shape().phi0(cfg.grid.xc(i), cfg.grid.yc(j)) < 0.0) cells.emplace_back(i, j);
  RunSummary r = run(sim, RunOptions::silent());
  EXPECT_FALSE(r.failed) << r.failure;
  EXPECT_NEAR(sim.time(), 1.0, 1e-12);
  const Solid& s = *sim.solids().at(0);
  double sx = 0, sy = 0;
  for (auto [i, j] : cells) {
    const double dx = s.xi_x()(i - s.i0(), j - s.j0()) - cfg.grid.xc(i);
    const double dy = s.xi_y()(i - s.i0(), j - s.j0()) - cfg.grid.yc(j);
    sx += dx * dx;
    sy += dy * dy;
  }
  XiError e{std::sqrt(sx / cells.size()), std::sqrt(sy / cells.size()),
            s.extrapolation_counters().fallbacks};
  std::printf("[zalesak %s, %s xi fluxes] %zu disk cells, %ld steps: E_xi_x = %.3e, E_xi_y = %.3e, fallbacks %ld\n",
              method.c_str(), xi_advection.c_str(), cells.size(), sim.steps(), e.ex, e.ey, e.fallbacks);
  return e;
}

}  // namespace

TEST(Zalesak, LeastSquaresErrorBelow1e8AndBetterThanPde) {
  XiError lsq = rotate("lsq");
  EXPECT_LE(lsq.ex, 1e-8);
  EXPECT_LE(lsq.ey, 1e-8);
  XiError pde = rotate("pde");
  std::printf("[zalesak] paper (Table 2): LSQ 6.72e-9 / 7.34e-9, PDE 8.32e-4 / 4.67e-4\n");
  EXPECT_GT(pde.ex, lsq.ex);
  EXPECT_GT(pde.ey, lsq.ey);
  // results/README.md quotes the PDE errors (truncation level); the least-squares ones sit at
  // round-off, which differs with the machine's floating point, so the page gives their bound
  expect_quoted("Zalesak.Pde/ex", pde.ex);
  expect_quoted("Zalesak.Pde/ey", pde.ey);
}

// The paper's central fluxes for xi: the rotation is affine, so they are exact too and the
// least-squares error must stay at round-off level (the van Leer default is tested above).
TEST(Zalesak, LeastSquaresWithCentralXiFluxesErrorBelow1e8) {
  XiError lsq = rotate("lsq", "central");
  EXPECT_LE(lsq.ex, 1e-8);
  EXPECT_LE(lsq.ey, 1e-8);
}
