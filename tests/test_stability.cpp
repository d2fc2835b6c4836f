// Where methods fail (bench/stability.py maps the limits, results/stability.md
// "Where methods fail"):
//  - FoldedMap: the health check that names a folded reference map (solver/model/health.cpp):
//    one cell of a disc's xi is folded by hand (det grad xi < 0 by the central differences
//    the stress kernel uses) and the message must name the solid and that global cell;
//    an unfolded disc passes.
//  - StabilityLimits: runs each side of the limits the study measured (below), for the
//    sweeps a (solid time step; explicit and the semi-implicit solid stress), b
//    (deformation), c (density ratio), d (contact with a wall and between two discs) and e
//    (resolution).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <string>

#include "solver/model/health.hpp"
#include "solver/app/run.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/test_helpers.hpp"
#include "tests/fixtures/scene_text.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

const std::string kDisc = refmap::testing::box_scene(32, refmap::testing::kPeriodic,
                                                    refmap::testing::disc_toml("blob", 0.5, 0.5, 0.15));

}  // namespace

TEST(FoldedMap, UnfoldedDiscPasses) {
  Config cfg = load_scene_string(kDisc, "fold.toml");
  Simulation sim(cfg);
  EXPECT_EQ(check_reference_maps(sim), "");
  sim.step();
  EXPECT_EQ(check_reference_maps(sim), "");
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
}

// ---------------------------------------------------------------------------------------
// StabilityLimits: one configuration of each sweep of bench/stability.py at about 0.8 of
// the limit it measured (results/stability_limits.csv), which must stay stable and
// accurate, and one well past it, which must stop with its cause or be classified
// inaccurate by the study's own rule: area drift (or error) over 1 %, or a total energy
// (kinetic + elastic) more than 1 % above its start in these viscous runs.

namespace {

struct Outcome {
  bool failed = false;
  std::string failure;
  double area_drift = 0.0;   ///< max |A - A0| / A0 over the rows of diagnostics.csv
  double area_error = 0.0;   ///< max |A - pi R^2| / (pi R^2)
  double energy_rise = 0.0;  ///< max E / E0 - 1, E = kinetic + elastic + contact energy
  double min_gap = 1e30;     ///< min over rows of the gap to a wall or solid, in cells
  double poisson_residual = 0.0;  ///< max over the steps of the pressure solve's residual
  double t_end = 0.0;        ///< time of the last row
  double e_end = 0.0;        ///< total energy (kinetic + elastic) of the last row
  double e_start = 0.0;      ///< total energy (kinetic + elastic) of the first row
};

/// The study's "stable" class (bench/stability.py): the run completes, the area drifts by
/// at most 1 % and the total energy never rises more than 1 % above its start.
void expect_stable(const Outcome& o) {
  EXPECT_FALSE(o.failed) << o.failure;
  EXPECT_LE(o.area_drift, 0.01);
  EXPECT_LE(o.energy_rise, 0.01);
}

Outcome run_disc_tgv(const std::string& tag, std::vector<std::string> sets, const char* scene = "disc_tgv.toml") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("refmap_test_stability_" + tag);
  fs::remove_all(dir);
  sets.push_back("output.vtk=false");
  Config cfg = load_scene(scene_path(scene), sets);
  Simulation sim(cfg);
  RunOptions ro;
  ro.out_dir = dir.string();
  ro.quiet = true;
  ro.progress = false;
  const RunSummary sum = run(sim, ro);
  Outcome o;
  o.failed = sum.failed;
  o.failure = sum.failure;
  const Csv d = read_csv((dir / "diagnostics.csv").string());
  const Csv s0 = read_csv((dir / "solids.csv").string()).where("solid", 0);  // a row per row of d
  const auto area = s0.column("area"), e = d.column("total_energy"), ec = d.column("contact_energy");
  const auto gw = s0.column("gap_wall"), gs = s0.column("gap_solid");
  const auto res = d.column("poisson_residual");
  const double exact = M_PI * 0.2 * 0.2, dx = sim.grid().dx;
  for (size_t k = 0; k < area.size(); ++k) {
    o.area_drift = std::max(o.area_drift, std::abs(area[k] - area[0]) / area[0]);
    o.area_error = std::max(o.area_error, std::abs(area[k] - exact) / exact);
    o.energy_rise = std::max(o.energy_rise, (e[k] + ec[k]) / (e[0] + ec[0]) - 1.0);
    o.min_gap = std::min({o.min_gap, gw[k] / dx, gs[k] / dx});
    if (k > 0) o.poisson_residual = std::max(o.poisson_residual, res[k]);
  }
  o.t_end = d.column("time").back();
  o.e_end = e.back();
  o.e_start = e.front();
  std::printf("[stability] %s: %s, area drift %.3g, area error %.3g, energy rise %.3g, min gap %.3g dx, "
              "Poisson residual %.3g, t_end %.6g, E_end %.6g %s\n", tag.c_str(), o.failed ? "stopped" : "completed",
              o.area_drift, o.area_error, o.energy_rise, o.min_gap, o.poisson_residual, o.t_end, o.e_end,
              o.failure.c_str());
  fs::remove_all(dir);
  return o;
}

std::vector<std::string> solid_cfl_case(const char* xi, double mu, double p) {
  return {"grid.nx=32", "grid.ny=32", "time.end=100", "time.max_steps=400", "solids.xi_advection=\"" + std::string(xi) + "\"",
          "solid.0.mu_s=" + std::to_string(mu), "solids.solid_cfl=" + std::to_string(p)};
}

std::vector<std::string> amplitude_case(double factor, bool conservative = true) {
  char a[64];
  std::snprintf(a, sizeof a, "initial.amplitude=%.17g", 0.3141592653589793 * factor);
  return {"grid.nx=64", "grid.ny=64", "time.end=2.0", a,
          std::string("solids.conservative=") + (conservative ? "true" : "false")};
}

}  // namespace

// sweep a: limit P = 1 at mu_s / rho_s = 100 (cell stress, conservative form)
TEST(StabilityLimits, SolidTimeStepBelowLimitIsStable) {
  const Outcome o = run_disc_tgv("cfl_0.8", solid_cfl_case("vanleer", 100.0, 0.8));
  expect_stable(o);
}

TEST(StabilityLimits, SolidTimeStepFarPastLimitFails) {
  // van Leer xi fluxes: the energy grows by orders of magnitude but the run survives 400 steps
  const Outcome vl = run_disc_tgv("cfl_8_vanleer", solid_cfl_case("vanleer", 100.0, 8.0));
  EXPECT_TRUE(vl.failed || vl.energy_rise > 1.0) << vl.energy_rise;
  // central xi fluxes (the paper's): the energy jumps a thousandfold in one step as the map
  // folds, and the run stops (the kinetic-energy check reports it before the fold check)
  const Outcome c = run_disc_tgv("cfl_8_central", solid_cfl_case("central", 100.0, 8.0));
  ASSERT_TRUE(c.failed);
  EXPECT_TRUE(c.failure.find("kinetic energy grew") != std::string::npos ||
              c.failure.find("reference map folded in solid 'disc'") != std::string::npos)
      << c.failure;
}

// sweep a, the semi-implicit solid stress (time.solid_stress = "semi_implicit", k = 0.5,
// with time.viscous = "implicit"; docs/implicit.md): it has no solid time-step limit of its
// own, so the study imposes P through time.dt_max = P dx / sqrt(2 mu_s / rho_s). On this
// disc in a fluid it does not lift the explicit limit: at mu_s / rho_s = 100 the largest
// stable P is 1 as for the explicit cell stress; P = 2 gains 7 % energy, from P = 4 the map
// folds (every k tried, 0.1 to 4).
namespace {
std::vector<std::string> semi_implicit_case(double mu, double p) {
  char dt[64];
  std::snprintf(dt, sizeof dt, "time.dt_max=%.17g", p / 32.0 / std::sqrt(2.0 * mu));
  return {"grid.nx=32", "grid.ny=32", "time.end=100", "time.max_steps=400", "time.viscous=\"implicit\"",
          "time.solid_stress=\"semi_implicit\"", "time.solid_implicit_k=0.5", "solid.0.mu_s=" + std::to_string(mu),
          dt};
}
}  // namespace

TEST(StabilityLimits, SemiImplicitBelowLimitIsStableAndAccurate) {
  // the study's run (400 steps) ends at t = 0.707; to t = 0.7 it is 396 steps
  std::vector<std::string> sets = semi_implicit_case(100.0, 0.8);
  sets.push_back("time.end=0.7");
  const Outcome o = run_disc_tgv("semi_0.8", sets);
  expect_stable(o);
  // accuracy: the total energy (kinetic + elastic; the two swap many times over the run, the
  // disc's wave period is about 0.015) at t = 0.7 against the explicit run at P = 0.1
  // (3198 steps). Both schemes are first order in dt and err on opposite sides: measured at
  // P = 0.8, 0.4, 0.2, 0.1 the semi-implicit energy is 13, 9, 6, 1.5 % below the reference
  // (its implicit term damps), the explicit one 12, 3, -1.4 % above it. 15 % bounds the
  // semi-implicit error at P = 0.8; a change that makes the splitting inconsistent (an
  // error that does not shrink with dt) or damps more moves it past this.
  std::vector<std::string> ref = solid_cfl_case("vanleer", 100.0, 0.1);
  ref.push_back("time.end=0.7");
  ref.push_back("time.max_steps=0");
  const Outcome ex = run_disc_tgv("semi_0.8_reference", ref);
  ASSERT_FALSE(ex.failed) << ex.failure;
  ASSERT_NEAR(o.t_end, 0.7, 1e-12);
  ASSERT_NEAR(ex.t_end, 0.7, 1e-12);
  EXPECT_LT(o.e_end, ex.e_end);  // the implicit term only removes energy
  EXPECT_NEAR(o.e_end, ex.e_end, 0.15 * ex.e_end);
}

TEST(StabilityLimits, SemiImplicitFarPastLimitFails) {
  // P = 4 (4x the limit): the map folds at t = 1.75 after 285 steps (exit 3)
  const Outcome o = run_disc_tgv("semi_4", semi_implicit_case(100.0, 4.0));
  EXPECT_TRUE(o.failed || o.energy_rise > 0.01 || o.area_drift > 0.01) << o.energy_rise;
  if (o.failed) {
    EXPECT_TRUE(o.failure.find("reference map folded in solid 'disc'") != std::string::npos ||
                o.failure.find("kinetic energy grew") != std::string::npos)
        << o.failure;
  }
}

// The same P = 4 with the implicit coefficient reaching 2 cells further into the fluid
// (time.solid_implicit_reach = 2, docs/implicit.md): the fold above is gone. The run is not
// "stable" by the study's 1 % rule: the first steps raise the total energy by ~40 % (the
// disc starts with the vortex's velocity inside it, and xi is advected with that velocity
// over the whole large step before the stress acts), after which it only falls. Measured:
// rise 0.40 at step 3, E(end) / E0 = 0.09 at t = 3.5, area drift 0.12 %.
TEST(StabilityLimits, SemiImplicitReachKeepsTheDiscBounded) {
  std::vector<std::string> sets = semi_implicit_case(100.0, 4.0);
  sets.push_back("time.solid_implicit_reach=2");
  const Outcome o = run_disc_tgv("semi_4_reach2", sets);
  ASSERT_FALSE(o.failed) << o.failure;
  EXPECT_LE(o.area_drift, 0.01);
  EXPECT_LT(o.energy_rise, 0.6);   // the start-up transient only (without reach: x 1e4)
  EXPECT_LT(o.e_end, 0.3 * o.e_start);  // and then dissipated by the fluid
}

// The reach adds implicit damping where the explicit stress has none (an O(dt^2) term per
// step), so it costs accuracy at moderate steps and must vanish as dt -> 0: the total energy
// at t = 0.7 against the explicit run at P = 0.1, measured 32.8 / 17.6 / 7.7 % low at
// P = 0.8 / 0.4 / 0.2 (reach 0: 13.2 / 8.6 / 6.1 %). Asserted: first-order convergence
// (the error at least 1.5x smaller per halving) and within 10 % at P = 0.2.
TEST(StabilityLimits, SemiImplicitReachConvergesToExplicit) {
  auto energy_at_07 = [](const std::string& tag, std::vector<std::string> sets) {
    sets.push_back("time.end=0.7");
    sets.push_back("time.max_steps=0");
    const Outcome o = run_disc_tgv(tag, sets);
    EXPECT_FALSE(o.failed) << o.failure;
    EXPECT_NEAR(o.t_end, 0.7, 1e-12);
    return o.e_end;
  };
  const double ref = energy_at_07("reach_reference", solid_cfl_case("vanleer", 100.0, 0.1));
  std::vector<double> err;
  for (double p : {0.4, 0.2}) {
    std::vector<std::string> sets = semi_implicit_case(100.0, p);
    sets.push_back("time.solid_implicit_reach=2");
    err.push_back((ref - energy_at_07("reach_" + std::to_string(p), sets)) / ref);
  }
  EXPECT_GT(err[1], 0.0);  // the implicit terms only remove energy
  EXPECT_LT(err[1], 0.10);
  EXPECT_GT(err[0] / err[1], 1.5);
}

// sweep b: limit amplitude = 1 A0 for lsq 2.83 (64^2, to t = 2)
// The variational solid force (solids.stress_discretisation = "variational",
// kernels/variational_stress.hpp; docs/implicit.md, "The variational force"; numbers in
// results/implicit_variational.csv, `python3 bench/variational_study.py`): with the
// semi-implicit splitting it keeps the stiff disc (mu_s / rho_s = 1e5, 64^2, 400 steps) bounded
// at P = 8, where the same splitting on the paper's cell stress blows up (exit 3 after 350
// steps, energy x 5e6). Measured with k = 0.25: largest total energy 1.16 E0 (a start-up rise,
// then it only falls: e_end 0.59 E0), area drift 0.056 %. The 1 % energy bound asked for is NOT
// met (the start-up rise); the bounds below sit between the measured values and a failure.
namespace {
std::vector<std::string> variational_case(double mu, double p, double k, bool variational) {
  char dt[64];
  std::snprintf(dt, sizeof dt, "time.dt_max=%.17g", p / 64.0 / std::sqrt(2.0 * mu));
  std::vector<std::string> s{"grid.nx=64", "grid.ny=64", "time.end=100", "time.max_steps=400",
                             "time.viscous=\"implicit\"", "time.solid_stress=\"semi_implicit\"",
                             "time.solid_implicit_k=" + std::to_string(k), "solid.0.mu_s=" + std::to_string(mu), dt};
  if (variational) s.push_back("solids.stress_discretisation=\"variational\"");
  return s;
}
}  // namespace

TEST(StabilityLimits, VariationalForceKeepsStiffDiscBoundedPastTheCellLimit) {
  const Outcome v = run_disc_tgv("variational_1e5_P8", variational_case(1e5, 8.0, 0.25, true));
  ASSERT_FALSE(v.failed) << v.failure;
  EXPECT_LE(v.area_drift, 0.005);  // measured 0.00056
  EXPECT_LT(v.energy_rise, 0.3);   // measured 0.16 (the cell stress below: x 5e6)
  EXPECT_LT(v.e_end, 0.8 * v.e_start);  // measured 0.59: after the start-up rise it only falls
  const Outcome c = run_disc_tgv("cell_1e5_P8", variational_case(1e5, 8.0, 0.5, false));
  EXPECT_TRUE(c.failed || c.energy_rise > 1e3) << c.energy_rise;
}

// What keeps the variational force from being the answer: at small steps it GAINS energy
// (a semi-discrete defect, not a time-step limit: the explicit variational run at P = 0.5
// ends at 16 E0 (mu_s / rho_s = 100) and 624 E0 (1e5) after 400 steps, the cell stress at
// 0.88 and 0.90). Semi-implicit, k = 0.5, mu_s / rho_s = 1e5, P = 0.5: measured 3.7 E0 at the
// end. A fix of the defect makes this test fail: then replace it by the stable bound.
TEST(StabilityLimits, VariationalForceGainsEnergyAtSmallSteps) {
  const Outcome v = run_disc_tgv("variational_1e5_P0.5", variational_case(1e5, 0.5, 0.5, true));
  EXPECT_FALSE(v.failed) << v.failure;
  EXPECT_GT(v.energy_rise, 1.0);  // measured 2.7
}

// The small-step gain above is the transport's: with xi moved by the cell velocity through
// the same central gradient the force uses (solids.xi_velocity = "cell" with xi_advection = "central", the exact
// pairing of the energy identity) the explicit variational run is stable by the study's rule.
// Measured (mu_s / rho_s = 100, 64^2, P = 0.5, 400 steps): largest energy 1.000 E0 (it only
// falls, to 0.89 E0), area drift 0.57 % (the cell velocity is not discretely divergence-free).
TEST(StabilityLimits, VariationalForceWithCellTransportIsStableAtSmallSteps) {
  const Outcome o = run_disc_tgv("variational_cell_P0.5",
                                 {"grid.nx=64", "grid.ny=64", "time.end=100", "time.max_steps=400",
                                  "solid.0.mu_s=100", "solids.solid_cfl=0.5",
                                  "solids.stress_discretisation=\"variational\"",
                                  "solids.xi_velocity=\"cell\"", "solids.xi_advection=\"central\""});
  expect_stable(o);
  EXPECT_LT(o.e_end, 0.95 * o.e_start);  // measured 0.89; the face transport: 16 E0
}

// The fixed-point iteration of the whole step with xi moved by the midpoint velocity
// (time.solid_picard_iterations = 2, theta = 1/2, the defect correction through the eta
// operator; solver/model/solid_picard.cpp, docs/implicit.md "The implicit step in xi";
// numbers in results/implicit_picard.csv, `python3 bench/picard_study.py`). disc_tgv 64^2,
// mu_s / rho_s = 100. Below its limit (P = 2, where the semi-implicit step alone ends at
// 14 E0) it is bounded and only loses energy (measured over 512 steps: largest energy
// 1.000 E0, area drift 0.05 %; but 52 % of KE(0) off the explicit run: it damps); at P = 4
// the energy first falls (0.50 E0 at step 120) and then grows (3.9 E0 at step 267).
namespace {
std::vector<std::string> picard_case(double p, int steps) {
  char dt[64];
  std::snprintf(dt, sizeof dt, "time.dt_max=%.17g", p / 64.0 / std::sqrt(200.0));
  return {"grid.nx=64", "grid.ny=64", "time.end=100", "time.max_steps=" + std::to_string(steps),
          "time.viscous=\"implicit\"", "time.solid_stress=\"semi_implicit\"", "solid.0.mu_s=100",
          "time.solid_picard_iterations=2", "time.solid_picard_theta=0.5", dt};
}
}  // namespace

TEST(StabilityLimits, PicardStepBelowLimitIsBounded) {
  const Outcome o = run_disc_tgv("picard_P2", picard_case(2.0, 256));
  expect_stable(o);
  EXPECT_LT(o.e_end, 0.8 * o.e_start);  // it damps (explicit at P = 0.5: 0.92 E0 at t = 1.13)
}

// The same iteration with the preconditioner's eta reaching 2 cells further into the fluid
// (time.solid_implicit_reach = 2: in the defect form it changes the iteration, not its fixed
// point) converges better (last-pass change 0.17 % at the median step against 0.8 .. 2.5 %)
// and stays bounded at P = 8: measured over 128 steps, largest energy 1.000 E0 (it only
// falls, to 0.34 E0), area drift 0.023 %.
TEST(StabilityLimits, PicardStepWithReachPreconditionerIsBoundedAtP8) {
  std::vector<std::string> sets = picard_case(8.0, 128);
  sets.push_back("time.solid_implicit_reach=2");
  const Outcome o = run_disc_tgv("picard_r2_P8", sets);
  expect_stable(o);
  EXPECT_LT(o.e_end, 0.5 * o.e_start);  // measured 0.34: it damps (explicit at P = 0.5: 0.92)
}

TEST(StabilityLimits, PicardStepPastLimitGrows) {
  const Outcome o = run_disc_tgv("picard_P4", picard_case(4.0, 270));
  EXPECT_TRUE(o.failed || o.energy_rise > 0.5) << o.energy_rise;  // measured 2.9 (3.9 E0)
}

TEST(StabilityLimits, DeformationBelowLimitIsStable) {
  const Outcome o = run_disc_tgv("amp_0.8", amplitude_case(0.8));
  expect_stable(o);
}

TEST(StabilityLimits, DeformationFarPastLimitFails) {
  // the map folds or the energy blows up first, depending on the step sequence (with the
  // contact spring's limit in every step the map folded at t = 0.2025; since that limit
  // applies only near contact, the blow-up is caught first, at t = 0.2028)
  const Outcome o = run_disc_tgv("amp_8", amplitude_case(8.0));
  ASSERT_TRUE(o.failed);
  EXPECT_TRUE(o.failure.find("reference map folded in solid 'disc'") != std::string::npos ||
              o.failure.find("the solution is blowing up") != std::string::npos)
      << o.failure;
}

// the paper's Fig. 14: the non-conservative form fails already at the scene's amplitude
TEST(StabilityLimits, NonConservativeFailsAtSceneAmplitude) {
  const Outcome o = run_disc_tgv("amp_1_noncons", amplitude_case(1.0, false));
  EXPECT_TRUE(o.failed || o.energy_rise > 0.01 || o.area_drift > 0.01) << o.energy_rise;
}

// sweep e: accurate (area error <= 1 % at t = 2) from R/dx = 12 on; R/dx = 4 is not
TEST(StabilityLimits, ResolutionAtLimitIsAccurate) {
  const Outcome o = run_disc_tgv("res_16", {"grid.nx=80", "grid.ny=80", "time.end=2.0"});
  EXPECT_FALSE(o.failed) << o.failure;
  EXPECT_LE(o.area_error, 0.01);
}

TEST(StabilityLimits, ResolutionFarBelowLimitIsInaccurate) {
  const Outcome o = run_disc_tgv("res_4", {"grid.nx=20", "grid.ny=20", "time.end=2.0"});
  EXPECT_TRUE(o.failed || o.area_error > 0.01) << o.area_error;
}

// sweep c: the density ratio rho_s / rho_f at mu_s / rho_s = 0.5 (48^2, to t = 1, multigrid,
// no gravity), with the limited momentum flux at the density jump (solver.density_jump_flux
// = "superbee", the default): stable and accurate from 0.3 to 3; 10 gains 6 % energy, 100
// 28 % (the elastic coupling, docs/density_ratio.md), 1000 blows up; 0.1 and below drift in
// area (0.01: 2.5 %), 1e-3 folds
namespace {
std::vector<std::string> density_case(double ratio) {
  return {"grid.nx=48", "grid.ny=48", "time.end=1.0", "solid.0.density=" + std::to_string(ratio),
          "solid.0.mu_s=" + std::to_string(0.5 * ratio)};
}
}  // namespace

TEST(StabilityLimits, DensityRatioBelowLimitIsStable) {
  const Outcome o = run_disc_tgv("rho_2.4", density_case(2.4));  // 0.8 of the limit 3
  expect_stable(o);
  EXPECT_LE(o.poisson_residual, 1e-9);  // the scene's solver.tol: the multigrid converged every step
  const Outcome light = run_disc_tgv("rho_0.4", density_case(0.4));  // inside the light limit 0.3 (drift 0.8 %)
  EXPECT_FALSE(light.failed) << light.failure;
  EXPECT_LE(light.area_drift, 0.01);
  EXPECT_LE(light.energy_rise, 0.01);
}

TEST(StabilityLimits, DensityRatioFarPastLimitFails) {
  const Outcome heavy = run_disc_tgv("rho_1000", density_case(1000.0));
  ASSERT_TRUE(heavy.failed);
  EXPECT_GT(heavy.energy_rise, 1e3);  // a blow-up, whichever check names it first (folded map at t = 0.74)
  EXPECT_TRUE(heavy.failure.find("time step collapsed") != std::string::npos ||
              heavy.failure.find("kinetic energy grew") != std::string::npos ||
              heavy.failure.find("reference map folded") != std::string::npos)
      << heavy.failure;
  const Outcome ten = run_disc_tgv("rho_10", density_case(10.0));  // past the limit 3: inaccurate
  EXPECT_GT(ten.energy_rise, 0.01);
  const Outcome light = run_disc_tgv("rho_0.01", density_case(0.01));
  EXPECT_TRUE(light.failed || light.area_drift > 0.01) << light.area_drift;
}

// The limited momentum flux at the density jump against the central one it replaces, at
// ratio 100 (48^2, t = 1): with central fluxes the advection feeds energy into the light
// cells next to the disc until the run blows up (time step collapse at t = 0.61, kinetic
// energy 3e11); with the limited flux the run completes. What is left, +28 % at 48^2, is the
// elastic coupling's gain (docs/density_ratio.md: the sub-step budget puts it in the stress
// work against the stored elastic energy, not the transport); the bound 0.5 is twice that
// margin and many orders below the blow-up, so it catches the transport instability coming
// back without asserting the unsolved part.
TEST(StabilityLimits, DensityJumpFluxKeepsHeavyDiscBounded) {
  const Outcome limited = run_disc_tgv("rho_100_limited", density_case(100.0));
  EXPECT_FALSE(limited.failed) << limited.failure;
  EXPECT_LT(limited.energy_rise, 0.5);
  EXPECT_LE(limited.area_drift, 0.01);
  auto sets = density_case(100.0);
  sets.push_back("solver.density_jump_flux=\"same\"");
  const Outcome central = run_disc_tgv("rho_100_central", sets);
  EXPECT_TRUE(central.failed);
  EXPECT_GT(central.energy_rise, 1e3);
}

// The specific stress blend (solids.stress_blend = "specific": the stress weighted by
// (1 - H) rho_b / rho_s, docs/density_ratio.md) against the gain above. Measured (48^2,
// t = 1): energy rise at ratio 30 +17.8 % (volume) -> +0.2 %, at 100 +34 % -> +3.4 %; ratio
// 1000 completes (+43 %; volume: folds at t = 0.74); with g = 1 ratio 100 completes with
// 0.69 % area drift (volume: blows up); at ratio 1 it is the volume blend, bit for bit.
TEST(StabilityLimits, SpecificStressBlendRemovesMostOfTheHeavyDiscsGain) {
  auto specific = [](std::vector<std::string> sets) {
    sets.push_back("solids.stress_blend=\"specific\"");
    return sets;
  };
  const Outcome vol30 = run_disc_tgv("rho_30_volume", density_case(30.0));
  const Outcome spec30 = run_disc_tgv("rho_30_specific", specific(density_case(30.0)));
  EXPECT_GT(vol30.energy_rise, 0.1);
  ASSERT_FALSE(spec30.failed) << spec30.failure;
  EXPECT_LE(spec30.energy_rise, 0.01);
  EXPECT_LE(spec30.area_drift, 0.01);
  const Outcome spec1000 = run_disc_tgv("rho_1000_specific", specific(density_case(1000.0)));
  EXPECT_FALSE(spec1000.failed) << spec1000.failure;
  EXPECT_LT(spec1000.energy_rise, 0.6);
  auto g100 = specific(density_case(100.0));
  g100.push_back("gravity.g=[0.0, -1.0]");
  const Outcome spec_g100 = run_disc_tgv("rho_100_g_specific", g100);
  EXPECT_FALSE(spec_g100.failed) << spec_g100.failure;
  EXPECT_LE(spec_g100.area_drift, 0.01);
  const Outcome vol1 = run_disc_tgv("rho_1_volume", density_case(1.0));
  const Outcome spec1 = run_disc_tgv("rho_1_specific", specific(density_case(1.0)));
  EXPECT_EQ(vol1.e_end, spec1.e_end);
  EXPECT_EQ(vol1.area_drift, spec1.area_drift);
}

// sweep d: contact, scenes/wall_microgravity.toml (48^2, to t = 0.5) with the contact
// strength held at the scene's (velocity_scale 1.5): the disc stays off the wall (gap > 0)
// up to the impact speed V = 2 and overlaps it from V = 3 (gap -0.37 dx; V = 4: -1.25 dx)
namespace {
std::vector<std::string> impact_case(double v, double stiffness = 20.0) {
  return {"grid.nx=48", "grid.ny=48", "time.end=0.5", "contact.velocity_scale=1.5",
          "solid.0.v=" + std::to_string(-v), "contact.stiffness=" + std::to_string(stiffness)};
}
}  // namespace

TEST(StabilityLimits, ImpactBelowLimitKeepsAGap) {
  const Outcome o = run_disc_tgv("impact_1.6", impact_case(1.6), "wall_microgravity.toml");  // 0.8 of V = 2
  expect_stable(o);
  EXPECT_GT(o.min_gap, 0.0);
}

TEST(StabilityLimits, ImpactFarPastLimitOverlaps) {
  const Outcome o = run_disc_tgv("impact_4", impact_case(4.0), "wall_microgravity.toml");
  EXPECT_TRUE(o.failed || o.min_gap < 0.0 || o.area_drift > 0.01) << o.min_gap;
}

// ... and at V = 3 the contact stiffness (the strength still for U = 1.5) keeps a gap from
// 40 on (gap 0.42 dx; 2000: 1.8 dx, stable too, with 8 times the steps); 20 and below overlap
TEST(StabilityLimits, ContactStiffnessAboveLimitKeepsAGap) {
  const Outcome o = run_disc_tgv("stiff_50", impact_case(3.0, 50.0), "wall_microgravity.toml");  // limit / 0.8
  expect_stable(o);
  EXPECT_GT(o.min_gap, 0.0);
}

TEST(StabilityLimits, ContactStiffnessFarBelowLimitOverlaps) {
  const Outcome o = run_disc_tgv("stiff_1", impact_case(3.0, 1.0), "wall_microgravity.toml");
  EXPECT_TRUE(o.failed || o.min_gap < 0.0 || o.area_drift > 0.01) << o.min_gap;
}

// ... and two such discs launched head-on at each other at V each (the scene's disc moved to
// (0.3, 0.5), a copy at (0.7, 0.5), gap 0.1; to t = 0.3): the discs never overlap each other
// (gap_solid >= 0.69 dx at every speed and stiffness swept), but the impact squeezes their
// area, by 0.78 % at V = 3, 0.98 % at V = 4 (the limit) and 1.6 % at V = 6 and 8; from V = 8
// the rebounding discs also cross the side walls (gap_wall -1.2 dx at t = 0.27)
namespace {
std::vector<std::string> pair_case(double v) {
  return {"grid.nx=48", "grid.ny=48", "time.end=0.3", "contact.velocity_scale=1.5", "solid.0.center=[0.3, 0.5]",
          "solid.0.v=0.0", "solid.0.u=" + std::to_string(v), "solid.1.name=\"disc2\"", "solid.1.shape=\"circle\"",
          "solid.1.center=[0.7, 0.5]", "solid.1.radius=0.15", "solid.1.mu_s=100.0", "solid.1.density=2.0",
          "solid.1.viscosity=0.0", "solid.1.u=" + std::to_string(-v), "solid.1.v=0.0"};
}
}  // namespace

TEST(StabilityLimits, SolidPairBelowLimitKeepsAGap) {
  // 0.75 of V = 4 (at 0.8, V = 3.2, the drift is already 0.99 %: it grows with V up to the limit)
  const Outcome o = run_disc_tgv("pair_3", pair_case(3.0), "wall_microgravity.toml");
  expect_stable(o);
  EXPECT_GT(o.min_gap, 0.0);
}

TEST(StabilityLimits, SolidPairFarPastLimitFails) {
  const Outcome o = run_disc_tgv("pair_8", pair_case(8.0), "wall_microgravity.toml");
  EXPECT_TRUE(o.failed || o.min_gap < 0.0 || o.area_drift > 0.01) << o.area_drift;
}

// time.solid_implicit_cfl: the implicit solid stress's own cap P on dt <= P dx sqrt(rho_s /
// G) (none by default). With the reach the disc in disc_tgv stays bounded to P ~ 8
// (results/implicit.md, "The reach"); the cap at 8 makes that a rule: at mu_s = 1e5 the
// first step is the capped one, 5.6e-4, not the vortex's advective 0.050 (89x larger).
TEST(StabilityLimits, ImplicitSolidCflCapsTheStep) {
  const double mu = 1e5, dx = 1.0 / 32;
  std::vector<std::string> sets = semi_implicit_case(mu, 1e3);  // dt_max far above
  sets.push_back("time.solid_implicit_reach=2");
  sets.push_back("time.solid_implicit_cfl=8");
  sets.push_back("time.max_steps=1");
  sets.push_back("output.vtk=false");
  Config cfg = load_scene(scene_path("disc_tgv.toml"), sets);
  Simulation sim(cfg);
  const double dt = sim.step();
  EXPECT_DOUBLE_EQ(dt, 8.0 * dx / std::sqrt(2.0 * mu / 1.0));
}
