// Simulation::set_stage_probe, which the energy budget of bench/energy_budget/ reads
// (docs/implicit.md, "Why the splitting fails at the interface"): the probe sees the split
// step's intermediate velocities u* and u** and the stress and viscosity the step used,
// and it does not change the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kernels/solid_stress.hpp"
#include "kernels/viscous.hpp"
#include "solver/model/boundary.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {
namespace {

// Algorithm 1's coupling (the default Verlet coupling kicks with the mean of two steps' forces:
// u** = u* + dt (f_v + (f_s^n + f_s^{n+1}) / 2) / rho, kernels/verlet.hpp)
const std::vector<std::string> kSets = {"grid.nx=32", "grid.ny=32", "output.vtk=false",
                                        "time.elastic_coupling=\"symplectic_euler\""};

Config disc_tgv() { return load_scene(std::string(REFMAP_SOURCE_DIR) + "/scenes/disc_tgv.toml", kSets); }

TEST(StageProbe, SeesTheExplicitStressStep) {
  // explicit step, eq. (5.2): u** = u* + dt (f_v + f_s) / rho, f_v = div mu (grad u* +
  // grad u*^T) (kernels/viscous.cpp), f_s = div of the blended stress (eq. 3.6). The probe's
  // fields must reproduce that change: the same operations in the same order, so the only
  // difference allowed is round-off of the sum (1e-12 of the largest change).
  Simulation sim(disc_tgv());
  const Grid& g = sim.grid();
  Field us, vs;
  double worst = 0.0, scale = 0.0;
  int probes = 0;
  sim.set_stage_probe([&](Simulation::Stage st, double dt) {
    if (st == Simulation::Stage::Advected) {
      us = sim.u();
      vs = sim.v();
      sim.apply_velocity_bc(us, vs, sim.time() + dt);
      ++probes;
      return;
    }
    Field S[3] = {sim.solid_stress_xx(), sim.solid_stress_xy(), sim.solid_stress_yy()};
    for (Field& s : S) fill_scalar_ghosts(s, sim.config().bc);
    Field fx(g.nx, g.ny, Grid::ng), fy(g.nx, g.ny, Grid::ng);
    viscous_force(us.view(), vs.view(), sim.viscosity().view(), fx.view(), fy.view(), g.nx, g.ny, g.dx);
    add_stress_divergence(S[0].view(), S[1].view(), S[2].view(), fx.view(), fy.view(), g.nx, g.ny, g.dx);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double rho = sim.rho()(i, j);
        const double du = sim.u()(i, j) - us(i, j), dv = sim.v()(i, j) - vs(i, j);
        scale = std::max({scale, std::abs(du), std::abs(dv)});
        worst = std::max({worst, std::abs(du - dt * fx(i, j) / rho), std::abs(dv - dt * fy(i, j) / rho)});
      }
    ++probes;
  });
  for (int n = 0; n < 3; ++n) sim.step();
  EXPECT_EQ(probes, 6);
  ASSERT_GT(scale, 0.0);
  EXPECT_LE(worst, 1e-12 * scale) << "largest change " << scale;
}

TEST(StageProbe, DoesNotChangeTheRun) {
  // a probe that only reads: the state after the steps has the same bits as without it
  Simulation a(disc_tgv()), b(disc_tgv());
  double seen = 0.0;
  b.set_stage_probe([&](Simulation::Stage, double) { seen += b.u()(5, 5); });
  for (int n = 0; n < 3; ++n) {
    a.step();
    b.step();
  }
  EXPECT_NE(seen, 0.0);
  for (int j = 0; j < a.grid().ny; ++j)
    for (int i = 0; i < a.grid().nx; ++i) {
      ASSERT_EQ(a.u()(i, j), b.u()(i, j));
      ASSERT_EQ(a.v()(i, j), b.v()(i, j));
    }
  EXPECT_EQ(a.elastic_energy(), b.elastic_energy());
}

}  // namespace
}  // namespace refmap
