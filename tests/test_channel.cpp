// Inflow and outflow sides (docs/boundaries.md): plane Poiseuille flow in a channel of
// height H = 1 between no-slip walls, an inflow on the left and a zero-pressure outflow on
// the right, rho = 1, mu = 0.1, mean velocity U = 1 (Re = 10). The exact developed flow is
//     u = 6 U y (H - y) / H^2,  v = 0,  dp/dx = -12 mu U / H^2 = -1.2.
// 1. Parabolic inflow (scenes/channel_poiseuille.toml): the profile and the pressure
//    gradient on 8 and 16 cells across, against the exact ones. The tolerances come from
//    the grid convergence: the scheme is second order (the no-slip mirror ghost and the
//    midpoint flux of the inflow are O(dx^2) away from the parabola), so the error must fall
//    by at least 2.5x (order >= 1.3) from 8 to 16 cells and stay below the bound stated
//    at each assertion.
// 2. Start-up: a uniform inflow u = U; far downstream (x = 3.5 H, past the entrance length
//    of about (0.6 + 0.056 Re) H = 1.2 H) the profile is the developed parabola.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "solver/model/probes.hpp"
#include "solver/app/run.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/fixtures/scene_text.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

constexpr double kMu = 0.1, kU = 1.0, kH = 1.0;
double exact_u(double y) { return 6.0 * kU * y * (kH - y) / (kH * kH); }
constexpr double kDpDx = -12.0 * kMu * kU / (kH * kH);

struct ChannelResult {
  double profile_err;  ///< max |u - exact| over the cells of one column, over the peak 1.5 U
  double dpdx;         ///< least-squares slope of the centre-line pressure
};

/// u at the cells of the column nearest x, against the exact parabola.
double column_error(const Simulation& sim, const Grid& g, double x) {
  const Field u = sim.named_field("u");
  const int i = int((x - g.x0) / g.dx);
  double e = 0.0;
  for (int j = 0; j < g.ny; ++j) e = std::max(e, std::abs(u(i, j) - exact_u(g.yc(j))));
  return e / (1.5 * kU);
}

ChannelResult run_channel(int ny, const std::vector<std::string>& extra_sets, double x_profile) {
  // nx = 2 ny: the scene's 2 H long channel (the start-up case overrides lx and nx)
  std::vector<std::string> sets = {"grid.ny=" + std::to_string(ny), "grid.nx=" + std::to_string(2 * ny)};
  for (const auto& s : extra_sets) sets.push_back(s);
  Config cfg = load_scene(scene_path("channel_poiseuille.toml"), sets);
  cfg.write_vtk = false;
  Simulation sim(cfg);
  RunSummary r = run(sim, RunOptions::silent());
  EXPECT_FALSE(r.failed) << r.failure;
  const Grid& g = cfg.grid;
  ChannelResult res{};
  res.profile_err = column_error(sim, g, x_profile);
  // pressure slope over the middle of the channel (away from the inflow's first cell and
  // the outflow's half cell), least squares over the cells of the two rows nearest y = H/2
  const Field p = sim.named_field("p");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (int j : {g.ny / 2 - 1, g.ny / 2})
    for (int i = g.nx / 4; i < 3 * g.nx / 4; ++i) {
      const double x = g.xc(i);
      sx += x; sy += p(i, j); sxx += x * x; sxy += x * p(i, j);
      ++n;
    }
  res.dpdx = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  std::printf("[channel] ny = %d: %ld steps, t = %.3f, profile error %.3e (of 1.5 U), dp/dx = %.6f (exact %.6f, "
              "rel. error %.3e)\n",
              ny, sim.steps(), sim.time(), res.profile_err, res.dpdx, kDpDx, std::abs(res.dpdx / kDpDx - 1.0));
  return res;
}

}  // namespace

TEST(Channel, PoiseuilleProfileAndPressureDropConverge) {
  // started from the developed flow (the scene's ramp from rest would leave a diffusive
  // transient of the size of the fine grid's error at t = 5), run to t = 2
  const std::vector<std::string> developed = {
      "boundary.left={ type = \"inflow\", u = \"6 * y * (1 - y)\" }", "initial.velocity=\"expression\"",
      "initial.u_expr=\"6 * y * (1 - y)\"", "initial.v_expr=\"0\"", "time.end=2.0"};
  const ChannelResult c = run_channel(8, developed, 1.5);
  const ChannelResult f = run_channel(16, developed, 1.5);
  const double ec_p = std::abs(c.dpdx / kDpDx - 1.0), ef_p = std::abs(f.dpdx / kDpDx - 1.0);
  // second order: the error falls by 4 per halving; demand 2.5 (order 1.3) to leave room
  // for the not-quite-asymptotic coarse grid
  EXPECT_LT(f.profile_err, c.profile_err / 2.5);
  EXPECT_LT(ef_p, std::max(ec_p / 2.5, 1e-6));
  // the outflow's Dirichlet pressure through all three solvers (the sink): the same flow
  // to the solvers' tolerance
  for (const char* m : {"cg", "mgpcg"}) {
    std::vector<std::string> sets = developed;
    sets.push_back(std::string("solver.poisson=\"") + m + "\"");
    const ChannelResult o = run_channel(8, sets, 1.5);
    EXPECT_NEAR(o.dpdx, c.dpdx, 1e-6) << m;
    EXPECT_NEAR(o.profile_err, c.profile_err, 1e-6) << m;
  }
  // and the fine-grid errors within 4x the second-order estimate (dx/H)^2 = 1/256
  EXPECT_LT(f.profile_err, 4.0 / 256.0);
  EXPECT_LT(ef_p, 4.0 / 256.0);
}

TEST(Channel, UniformInflowDevelopsTheParabolaDownstream) {
  // a 4 H long channel, uniform inflow from rest
  const ChannelResult r = run_channel(16, {"domain.lx=4.0", "grid.nx=64", "boundary.left={ type = \"inflow\", u = 1 }",
                                           "initial.velocity=\"uniform\"", "initial.u=0"},
                                      3.5);
  // the developed profile's discretisation error on this grid (case 1: 3.2e-3 of the peak
  // at 16 cells across) plus what is left of the development: 1 % of the peak
  EXPECT_LT(r.profile_err, 0.01);
}

namespace {

/// The scene error message of a unit box with the given [boundary] lines ("" if it loads).
std::string boundary_error(const std::string& boundary) {
  try {
    load_scene_string(box_scene(16, boundary), "channel_test.toml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(Channel, SceneErrorsForBadInflowAndOutflow) {
  const std::string walls_tb = "bottom = \"no_slip\"\ntop = \"no_slip\"\n";
  // a valid channel loads and keeps its expressions
  {
    const Config c = load_scene_string(
        box_scene(16, "left = { type = \"inflow\", u = \"4*y*(1-y)*min(t, 1)\" }\nright = \"outflow\"\n" + walls_tb),
        "ok.toml");
    EXPECT_EQ(c.bc[Left].type, BcType::Inflow);
    EXPECT_EQ(c.bc[Right].type, BcType::Outflow);
    EXPECT_DOUBLE_EQ(c.bc[Left].inflow_u.eval(0.0, 0.5, 2.0), 1.0);
    EXPECT_DOUBLE_EQ(c.bc[Left].inflow_v.eval(0.0, 0.5, 2.0), 0.0);
  }
  // outflow only (two open sides, no inflow) is allowed
  EXPECT_EQ(boundary_error("left = \"outflow\"\nright = \"outflow\"\n" + walls_tb), "");
  EXPECT_TRUE(contains(boundary_error("left = { type = \"inflow\", u = 1 }\nright = \"no_slip\"\n" + walls_tb),
                       "needs an \"outflow\" side"));
  EXPECT_TRUE(contains(boundary_error("left = \"inflow\"\nright = \"outflow\"\n" + walls_tb), "needs its velocity"));
  EXPECT_TRUE(contains(boundary_error("left = { type = \"inflow\", v = 1 }\nright = \"outflow\"\n" + walls_tb),
                       "needs its normal velocity `u`"));
  EXPECT_TRUE(contains(boundary_error("left = { type = \"inflow\", u = \"y +\" }\nright = \"outflow\"\n" + walls_tb),
                       "invalid expression"));
  EXPECT_TRUE(contains(boundary_error("left = { type = \"inflow\", u = \"1/(y-y)\" }\nright = \"outflow\"\n" + walls_tb),
                       "must be finite along the whole side"));
  EXPECT_TRUE(contains(boundary_error("left = { type = \"no_slip\", u = 1 }\nright = \"outflow\"\n" + walls_tb),
                       "only an inflow takes u and v"));
  EXPECT_TRUE(contains(boundary_error("left = \"periodic\"\nright = \"outflow\"\n" + walls_tb),
                       "must be \"periodic\""));
}
