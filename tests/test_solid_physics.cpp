// Physics of the fluid-solid mixture:
//  - momentum: in a periodic box a moving neo-Hookean disc (rho_s = rho_f, so the
//    projection's 1/rho_f is constant) keeps the total momentum to round-off over 100
//    steps with the conservative form (divergence of the blended stress, the paper's
//    section 4.2 argument); the non-conservative form does not (printed, and asserted to
//    drift by many orders of magnitude more).
//  - the soft disc in a Taylor-Green vortex (the paper's Figs. 13-15): with the
//    conservative form the disc stretches and recoils while the total energy
//    (kinetic + elastic) stays below its start and the area within 0.5%; the
//    non-conservative form gains energy without bound and stretches the disc much further
//    (maximum aspect ratio from the second moments of the solid region).
//  - the finite-amplitude shear wave (scenes/shear_wave.toml, an exact solution of constant
//    energy): the explicit stress's energy error over four periods is first order in the
//    solid step; within 1 % at solid_cfl = 0.075 with either stress form, 5 % at the
//    default 0.5 (docs/stability.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "kernels/projection.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

const char* kPeriodicDisc = R"(
name = "periodic_disc"
[domain]
lx = 1.0
[grid]
nx = 48
ny = 48
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
end = 10.0
[solver]
tol = 1e-12
[[solid]]
name = "disc"
shape = "circle"
center = [0.5, 0.5]
radius = 0.2
mu_s = 5.0
density = 1.0
u = 0.5
v = -0.25
omega = 3.0
)";

double momentum_drift(bool conservative, const std::string& discretisation) {
  Config cfg = load_scene_string(kPeriodicDisc, "periodic_disc.toml",
                                 {std::string("solids.conservative=") + (conservative ? "true" : "false"),
                                  "solids.stress_discretisation=\"" + discretisation + "\""});
  Simulation sim(cfg);
  auto [mx0, my0] = sim.momentum();
  double drift = 0.0;
  for (int n = 0; n < 100; ++n) {
    sim.step();
    auto [mx, my] = sim.momentum();
    drift = std::max(drift, std::hypot(mx - mx0, my - my0));
  }
  const double scale = std::hypot(mx0, my0);
  std::printf("[momentum] %s/%s: |P0| = %.6e, max |P - P0| / |P0| over 100 steps = %.3e (t = %.3f)\n",
              conservative ? "conservative" : "non-conservative", discretisation.c_str(), scale,
              drift / scale, sim.time());
  return drift / scale;
}

struct DiscStats {
  double max_aspect = 1.0, max_area_dev = 0.0, max_energy_rise = 0.0, e0 = 0.0, max_total = 0.0;
};

// aspect ratio of the solid region from the eigenvalues of its second-moment tensor
double aspect_ratio(const Simulation& sim) {
  const Solid& s = *sim.solids().at(0);
  const Grid& g = sim.grid();
  double w = 0, mx = 0, my = 0;
  for (int pass = 0; pass < 2; ++pass) {
    double sxx = 0, sxy = 0, syy = 0;
    for (int j = 0; j < s.nj(); ++j)
      for (int i = 0; i < s.ni(); ++i) {
        const double f = std::clamp(0.5 - s.phi()(i, j) / g.dx, 0.0, 1.0);
        const double x = g.xc(s.i0() + i), y = g.yc(s.j0() + j);
        if (pass == 0) { w += f; mx += f * x; my += f * y; continue; }
        sxx += f * (x - mx) * (x - mx);
        sxy += f * (x - mx) * (y - my);
        syy += f * (y - my) * (y - my);
      }
    if (pass == 0) { mx /= w; my /= w; continue; }
    const double tr = sxx + syy, det = sxx * syy - sxy * sxy;
    const double d = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
    return std::sqrt((0.5 * tr + d) / (0.5 * tr - d));
  }
  return 1.0;
}

DiscStats run_disc_tgv(bool conservative, int n, double t_end) {
  Config cfg = load_scene(scene_path("disc_tgv.toml"),
                          {std::string("solids.conservative=") + (conservative ? "true" : "false"),
                           "grid.nx=" + std::to_string(n), "grid.ny=" + std::to_string(n),
                           "time.end=" + std::to_string(t_end)});
  Simulation sim(cfg);
  DiscStats st;
  const double a0 = sim.solids()[0]->diagnostics(sim.u(), sim.v()).area;
  st.e0 = sim.kinetic_energy();
  double running_min = st.e0, max_total = st.e0;
  while (sim.time() < cfg.t_end - 1e-12) {
    sim.step();
    const double total = sim.kinetic_energy() + sim.elastic_energy();
    if (!std::isfinite(total) || total > 1e3 * st.e0) {  // blown up: stop here
      max_total = std::isfinite(total) ? std::max(max_total, total) : 1e30;
      break;
    }
    max_total = std::max(max_total, total);
    // growth of the total energy above its running minimum, relative to the start
    st.max_energy_rise = std::max(st.max_energy_rise, (total - running_min) / st.e0);
    running_min = std::min(running_min, total);
    const double a = sim.solids()[0]->diagnostics(sim.u(), sim.v()).area;
    st.max_area_dev = std::max(st.max_area_dev, std::abs(a - a0) / a0);
    st.max_aspect = std::max(st.max_aspect, aspect_ratio(sim));
  }
  st.max_total = max_total;
  std::printf("[disc-tgv %s %d^2] t = %.3f steps %ld: max aspect %.3f, max area deviation %.3e, "
              "max total-energy rise %.3e of E0, max total / E0 %.3g\n",
              conservative ? "conservative" : "non-conservative", n, sim.time(), sim.steps(),
              st.max_aspect, st.max_area_dev, st.max_energy_rise, max_total / st.e0);
  return st;
}

/// The finite-amplitude shear wave of scenes/shear_wave.toml on 64^2 (64 cells per
/// wavelength) over four periods, t in [0, 4], with the solid limit binding (no fluid, no
/// viscosity, a slow flow): the largest |E / E0 - 1| over the steps of the
/// total energy E = kinetic + elastic, which is exactly constant (rho U0^2 / 4 per unit
/// area, docs/references.md#shear-wave-in-a-neo-hookean-solid).
double shear_wave_energy_deviation(const std::string& form, std::vector<std::string> extra = {}) {
  extra.insert(extra.end(), {"grid.nx=64", "grid.ny=64", "time.end=4", "solids.stress_discretisation=\"" + form + "\""});
  Config cfg = load_scene(scene_path("shear_wave.toml"), extra);
  Simulation sim(cfg);
  const double e0 = sim.kinetic_energy() + sim.elastic_energy();
  double dev = 0.0;
  while (sim.time() < cfg.t_end - 1e-12) {
    sim.step();
    dev = std::max(dev, std::abs((sim.kinetic_energy() + sim.elastic_energy()) / e0 - 1.0));
  }
  std::printf("[shear wave 64^2, %s stress, solid_cfl %g] %ld steps to t = %.4f: max |E / E0 - 1| = %.4f %%\n",
              form.c_str(), cfg.solid_opt.solid_cfl, sim.steps(), sim.time(), 100.0 * dev);
  return dev;
}

}  // namespace

TEST(ShearWaveEnergy, SymplecticEulerWithinOnePercentOnlyWellBelowTheDefaultStep) {
  // Algorithm 1's coupling (time.elastic_coupling = "symplectic_euler", the default before
  // Verlet): the explicit stress's energy error is first order in dt (measured): a swing within each
  // period (about +-2 % at solid_cfl 0.5) and a loss that accumulates (0.7 % a period). At
  // 64^2, max |E / E0 - 1| over t in [0, 4] measured (face / cell): solid_cfl 0.5 (the
  // default) 4.97 / 4.85 %; 0.35, 3.55 / 3.43 %; 0.25, 2.59 / 2.47 %; 0.15, 1.62 / 1.49 %;
  // 0.1, 1.13 / 1.00 %; 0.09, 1.03 / 0.90 %; 0.08, 0.94 / 0.80 %; 0.075, 0.89 / 0.75 %;
  // 0.0625, 0.77 / 0.62 %. The bound asked for, 1 % with either form, needs solid_cfl <= 0.085;
  // the default stays 0.5 because 0.075 fails two validation tests (ContactWall.
  // BounceUnderGravity: the stiff disc's rebound no longer leaves the contact range;
  // StabilityLimits.SpecificStressBlend...: more energy gain; docs/method.md, "Time step").
  const std::string se = "time.elastic_coupling=\"symplectic_euler\"";
  EXPECT_LT(shear_wave_energy_deviation("face", {se, "solids.solid_cfl=0.075"}), 0.01);
  EXPECT_LT(shear_wave_energy_deviation("cell", {se, "solids.solid_cfl=0.075"}), 0.01);
  // at the default step (6.7x fewer steps) five times the bound
  EXPECT_GT(shear_wave_energy_deviation("face", {se}), 0.04);
}

TEST(ShearWaveEnergy, VerletCouplingWithinOnePercentAtTheDefaultStep) {
  // time.elastic_coupling = "verlet" (kernels/verlet.hpp): the same stress evaluations per
  // step, second order in the energy. At the default solid_cfl 0.5, 64^2, t in [0, 4]:
  // max |E / E0 - 1| measured (face / cell) 0.19 / 0.054 % in the same 555 steps as Algorithm 1's
  // 4.97 / 4.85 % (results/shear_wave_energy.csv). The bounds keep the 1 % asked for with a
  // margin and still fail if the coupling fell back to first order (2 % at P = 0.2).
  // Verlet is the default coupling: the scene as shipped, no override
  EXPECT_LT(shear_wave_energy_deviation("face"), 0.0025);
  EXPECT_LT(shear_wave_energy_deviation("cell"), 0.001);
}

TEST(ElasticCoupling, VerletByDefaultWhereItAppliesRefusedWhereGivenAndNot) {
  // the default "verlet" acts with the explicit stress and face transport of xi; where it
  // cannot (an implicit solid stress, xi moved by cell velocities) the default falls back to
  // Algorithm 1, and the key given there is refused, naming it (exit 2)
  const std::vector<std::string> sets = {"grid.nx=32", "grid.ny=32"};
  EXPECT_TRUE(verlet_coupling(load_scene(scene_path("disc_tgv.toml"), sets)));
  for (const std::string& other : {std::string("time.solid_stress=\"semi_implicit\""),
                                   std::string("solids.xi_velocity=\"cell\"")}) {
    std::vector<std::string> s = sets;
    s.push_back(other);
    const Config c = load_scene(scene_path("disc_tgv.toml"), s);
    EXPECT_EQ(c.elastic_coupling, ElasticCoupling::SymplecticEuler) << other;
    EXPECT_FALSE(verlet_coupling(c)) << other;
    s.push_back("time.elastic_coupling=\"verlet\"");
    try {
      load_scene(scene_path("disc_tgv.toml"), s);
      ADD_FAILURE() << "verlet given with " << other << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("elastic_coupling"), std::string::npos) << e.what();
    }
  }
}

TEST(ElasticCoupling, ProjectedDriftCarriesXiWithADivergenceFreeVelocity) {
  // time.verlet_project_drift: the drift's stress correction (F^n - F^{n-1}) dt / (4 rho) is
  // projected with the pressure operator (solved to 1e-6 relative), so the face velocity that
  // carries xi is divergence-free; unprojected its divergence is that of the correction
  // (the soft disc of disc_tgv, 32^2, over 30 steps). The bound leaves two orders of
  // magnitude between the solve's tolerance and the max norm over the cells.
  auto max_div = [](bool project) {
    Config cfg = load_scene(scene_path("disc_tgv.toml"), {"grid.nx=32", "grid.ny=32",
                                                          std::string("time.verlet_project_drift=") +
                                                              (project ? "true" : "false")});
    Simulation sim(cfg);
    double d = 0.0;
    for (int n = 0; n < 30; ++n) {
      sim.step();
      d = std::max(d, max_abs_face_divergence(sim.drift_uf().cview(), sim.drift_vf().cview(), cfg.grid.nx,
                                              cfg.grid.ny, cfg.grid.dx));
    }
    return d;
  };
  const double off = max_div(false), on = max_div(true);
  std::printf("[disc_tgv 32^2, 30 steps] max |div w_f|: unprojected %.3e, projected %.3e\n", off, on);
  EXPECT_GT(off, 0.0);
  EXPECT_LT(on, 1e-4 * off);
  // only with the Verlet coupling (what it projects): refused with Algorithm 1's, naming the key
  try {
    load_scene(scene_path("disc_tgv.toml"),
               {"time.verlet_project_drift=true", "time.elastic_coupling=\"symplectic_euler\""});
    ADD_FAILURE() << "verlet_project_drift with symplectic_euler was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("verlet_project_drift"), std::string::npos) << e.what();
  }
}

TEST(SolidMomentum, ConservativeFormConservesMomentumToRoundOff) {
  const double face = momentum_drift(true, "face");
  const double cell = momentum_drift(true, "cell");
  EXPECT_LT(face, 1e-12);
  EXPECT_LT(cell, 1e-12);
  const double nonc = momentum_drift(false, "face");
  EXPECT_GT(nonc, 1e3 * std::max(face, 1e-16));
}

TEST(DiscTaylorGreen, ConservativeOscillatesNonConservativeRunsAway) {
  // 128^2, t in [0, 2]: the disc is stretched, recoils and stretches again.
  DiscStats c = run_disc_tgv(true, 128, 2.0);
  EXPECT_LT(c.max_area_dev, 5e-3);            // area within 0.5% of its start
  EXPECT_LE(c.max_total, c.e0 * (1 + 1e-12)); // total energy never exceeds its start
  // The total energy is not strictly monotone: it rises above its running minimum by
  // 3e-2 E0 at 64^2 and 1.7e-3 E0 at 128^2 (falling with dx); bound it at 128^2.
  EXPECT_LT(c.max_energy_rise, 5e-3);
  DiscStats n = run_disc_tgv(false, 128, 2.0);
  EXPECT_GT(n.max_total, 2.0 * c.e0);  // the non-conservative mixture creates energy
  EXPECT_GT(n.max_aspect, 1.5 * c.max_aspect);
}
