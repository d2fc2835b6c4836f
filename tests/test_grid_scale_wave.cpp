// The solid's restoring force for its shortest wave, with xi carried by the face velocities
// (solids.xi_velocity = "face", the default) or by the cell velocities ("cell";
// kernels/reference_map.hpp, docs/reference_map.md "Which velocity carries xi").
//
// A periodic box of inviscid neo-Hookean solid (scenes/shear_wave.toml, 32^2, mu_s = 1/2,
// rho = 1) starts at rest in its reference state with the velocity's odd-even mode along x,
// u = u0 (-1)^i, v = 0. Its face velocities (u_W + u_P) / 2 are zero, so the projection never
// sees it (no face divergence), and the momentum is not advected. With "cell" the mode
// strains xi (d_i' = u_i) and the compact face stress restores it: for small amplitude,
// sigma_xx = 2 mu_s (b_xx - 1) = 4 mu_s d_x' (b = F F^T, F = 1 / (1 - d_x')), so
// rho d_i'' = 4 mu_s (d_{i+1} - 2 d_i + d_{i-1}) / dx^2 and the odd-even mode has
// omega^2 = 16 mu_s / (rho dx^2). The step (xi first, with the velocity of the step's start,
// then the velocity from the new stress) is symplectic Euler, whose discrete rotation angle per
// step phi obeys cos(phi) = 1 - (omega dt)^2 / 2, and from d = 0, u = u0 gives u^n = -u0 exactly
// at n phi = pi. With dt = 2 sin(pi / (2 N)) / omega that is step N. With "face" the mode strains
// nothing and keeps its velocity: the solid has no restoring force for it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

std::string g17(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

/// The odd-even mode's amplitude sum u (-1)^i / (n^2 u0) after `steps` steps.
double odd_even_amplitude_after(const std::string& xi_velocity, int steps, double dt, double u0) {
  Config cfg = load_scene(scene_path("shear_wave.toml"),
                          {"grid.nx=32", "grid.ny=32", "solids.xi_velocity=\"" + xi_velocity + "\"",
                           // (-1)^i at the cell centres x = (i + 1/2) / 32
                           "initial.u_expr=\"" + g17(u0) + " * cos(32 * pi * x - pi / 2)\"",
                           "initial.v_expr=\"0\"", "time.dt=" + g17(dt), "time.end=1"});
  Simulation sim(cfg);
  for (int k = 0; k < steps; ++k) sim.step();
  const Field& u = sim.u();
  const int n = cfg.grid.nx;
  double a = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a += u(i, j) * (i % 2 == 0 ? 1.0 : -1.0);
  a /= double(n) * n * u0;
  std::printf("[odd-even velocity mode, xi_velocity %s] %d steps of %.6g: amplitude %.6f of its start\n",
              xi_velocity.c_str(), steps, dt, a);
  return a;
}

}  // namespace

TEST(GridScaleWave, CellVelocityRestoresTheOddEvenModeFaceVelocityDoesNot) {
  const double mu_s = 0.5, rho = 1.0, dx = 1.0 / 32;
  const double omega = 4.0 * std::sqrt(mu_s / rho) / dx;  // 90.5 rad/s
  const int n_half = 20;                                    // steps per half period
  const double dt = 2.0 * std::sin(M_PI / (2.0 * n_half)) / omega;
  // small amplitude: the displacement u0 / omega = 1e-6 dx, so the nonlinear part of b is
  // ~1e-6 of the linear one; the tolerance 1e-4 leaves room for the limited xi face values
  // (van Leer's harmonic mean differs from the central value at second order in the mode)
  const double u0 = 1e-4 * dx * omega * 1e-2;
  EXPECT_NEAR(odd_even_amplitude_after("cell", n_half, dt, u0), -1.0, 1e-4);   // reversed: u^N = -u0
  EXPECT_NEAR(odd_even_amplitude_after("face", n_half, dt, u0), 1.0, 1e-12);   // untouched
}

// [[solid]] grid_viscosity = c adds c dx rho_s c_s, c_s = sqrt(2 mu_s / rho_s), to the solid's
// Kelvin-Voigt viscosity (solver/scene/scene.cpp): FSI2's flag (mu_s = 2.5e5 set here, the
// benchmark's shear modulus) at the bound c = 0.4 (the peer code's level) gets
// 0.4 * 0.005 * 1e4 * sqrt(5e5 / 1e4) = 141.42 Pa s on top of the 300 of the scene, half that
// grid part at dx = 0.0025; a rigid body refuses the key.
TEST(GridScaleWave, GridViscosityIsCDxRhoCs) {
  Config a = load_scene(scene_path("turek_hron_fsi2.toml"), {"solid.1.grid_viscosity=0.4", "solid.1.mu_s=2.5e5"});
  EXPECT_NEAR(a.solids.at(1).viscosity, 300.0 + 0.4 * 0.005 * std::sqrt(1e4 * 5e5), 1e-9);
  Config b = load_scene(scene_path("turek_hron_fsi2.toml"),
                        {"solid.1.grid_viscosity=0.4", "solid.1.viscosity=0", "grid.nx=1000", "grid.ny=164",
                         "time.dt=1.25e-4", "solid.1.mu_s=2.5e5"});
  EXPECT_NEAR(b.solids.at(1).viscosity, 0.4 * 0.0025 * std::sqrt(1e4 * 5e5), 1e-9);
  EXPECT_THROW(load_scene(scene_path("turek_hron_fsi2.toml"), {"solid.0.grid_viscosity=0.4"}), std::exception);
}
