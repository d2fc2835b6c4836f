// Decaying Taylor-Green vortex on [0, 2pi]^2, periodic (docs/references.md#taylor-green-vortex):
//   u = sin x cos y e^{-2 nu t}, v = -cos x sin y e^{-2 nu t}.
// Spatial convergence 32^2 -> 64^2 -> 128^2 with dt proportional to dx^2 (so the
// first-order splitting error of the explicit viscous step falls at the same rate and
// the observed ratio measures the spatial order): the RMS velocity error must fall by at
// least 3.5 per doubling. The projected face velocities must be divergence-free to
// round-off after every step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/quoted_results.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

struct TgResult {
  double err;        // RMS of |u - u_exact| over cells at t_end
  double max_div;    // max over steps of max |div u_f| * dx / U
};

TgResult run_tg(int n, const std::string& advection) {
  const double dx = 2.0 * M_PI / n;
  const double dt = 0.5 * dx * dx;  // Courant number 0.1 at 32^2, 0.025 at 128^2
  Config cfg = load_scene(scene_path("taylor_green.toml"),
                          {"grid.nx=" + std::to_string(n), "grid.ny=" + std::to_string(n),
                           "time.dt=" + std::to_string(dt), "solver.advection=\"" + advection + "\""});
  Simulation sim(cfg);
  TgResult r{0.0, 0.0};
  r.max_div = sim.max_face_divergence() * cfg.grid.dx;
  while (sim.time() < cfg.t_end - 1e-12) {
    sim.step(std::min(dt, cfg.t_end - sim.time()));
    r.max_div = std::max(r.max_div, sim.max_face_divergence() * cfg.grid.dx);
  }
  const double decay = std::exp(-2.0 * cfg.mu_f / cfg.rho_f * sim.time());
  double s = 0.0;
  const Grid& g = cfg.grid;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.xc(i), y = g.yc(j);
      const double du = sim.u()(i, j) - std::sin(x) * std::cos(y) * decay;
      const double dv = sim.v()(i, j) + std::cos(x) * std::sin(y) * decay;
      s += du * du + dv * dv;
    }
  r.err = std::sqrt(s / g.cells());
  std::printf("[taylor-green %s] n = %d steps = %ld  rms error %.4e  max |div u_f| dx %.2e\n",
              advection.c_str(), n, sim.steps(), r.err, r.max_div);
  return r;
}

}  // namespace

TEST(TaylorGreen, SecondOrderCentral) {
  TgResult a = run_tg(32, "central"), b = run_tg(64, "central"), c = run_tg(128, "central");
  std::printf("[taylor-green central] ratios %.3f %.3f\n", a.err / b.err, b.err / c.err);
  EXPECT_GE(a.err / b.err, 3.5);
  EXPECT_GE(b.err / c.err, 3.5);
  expect_quoted("TaylorGreen.SecondOrderCentral/ratio_32_64", a.err / b.err);  // as results/README.md quotes
  expect_quoted("TaylorGreen.SecondOrderCentral/ratio_64_128", b.err / c.err);
  for (const TgResult& r : {a, b, c}) EXPECT_LT(r.max_div, 1e-11);
}
