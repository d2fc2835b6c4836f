// The wall shear stress and the relative viscosity of a shear cell (solver/components/wall_stress.hpp):
//  - plane Couette flow between walls at -U/2 and +U/2, periodic along x, started from rest:
//    the discrete linear profile is exact, so once the start-up has decayed (e^{-pi^2 nu t /
//    H^2}: 2e-5 at t = 1.1) both walls carry mu gamma and eta_r = 1;
//  - a rigid disc free to turn, pinned at the centre of the cell, raises eta_r: in the dilute
//    limit of two-dimensional Stokes flow eta_r = 1 + 2 phi (the 2-D Einstein coefficient,
//    Brady 1984), phi the area fraction. At a/H = 0.1 (phi = 0.0157) and 6.4 cells per
//    radius (128 x 64 on 2 x 1) the measured coefficient (eta_r - 1)/phi is 2.07; it includes
//    the walls' confinement, which grows as (a/H)^2 (fitted on three radii, so on 6.4, 9.6
//    and 12.8 cells per radius: about +0.18 here, so about 1.89 unconfined:
//    results/shear_cell.csv, bench/run_shear_cell.sh; a free disc with H varied at a fixed
//    grid gives +0.24 at 6.4 cells per radius, results/suspension.md). The test asks the
//    coefficient within 10 % of 2, as results/suspension.md asks of the dilute limit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "solver/components/wall_stress.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {
namespace {

std::string shear_cell(int nx, double t_end, const std::string& solids) {
  return "name = \"shear_cell\"\n[domain]\nlx = 2.0\nly = 1.0\n[grid]\nnx = " + std::to_string(nx) +
         "\nny = " + std::to_string(nx / 2) +
         "\n[fluid]\ndensity = 1.0\nviscosity = 1.0\n"
         "[boundary]\nleft = \"periodic\"\nright = \"periodic\"\n"
         "bottom = { type = \"moving_wall\", velocity = -0.5 }\ntop = { type = \"moving_wall\", velocity = 0.5 }\n"
         "[time]\nend = " + std::to_string(t_end) + "\n[output]\nwall_stress = true\n" + solids;
}

/// The last three diagnostics columns (bottom, top, eta_r) at the end of the run.
std::vector<double> run_to_end(const Config& cfg) {
  Simulation sim(cfg);
  while (sim.time() < cfg.t_end - 1e-12) sim.step();
  std::vector<double> v;  // the wall stress component's columns (a scene with solids also has contact's)
  if (const WallStress* w = sim.component<WallStress>()) w->values(sim, v);
  return v;
}

TEST(WallStress, CouetteFlowHasRelativeViscosityOne) {
  const auto v = run_to_end(load_scene_string(shear_cell(32, 1.1, ""), "couette.toml"));
  ASSERT_EQ(v.size(), 3u);
  // mu gamma = 1 * (0.5 - (-0.5)) / 1 on both walls
  EXPECT_NEAR(v[0], 1.0, 1e-4);
  EXPECT_NEAR(v[1], 1.0, 1e-4);
  EXPECT_NEAR(v[2], 1.0, 1e-4);
}

TEST(WallStress, NeedsWallsAtTheBottomAndTop) {
  std::string text = shear_cell(32, 1.0, "");
  text.replace(text.find("bottom = {"), text.find('\n', text.find("bottom = {")) - text.find("bottom = {"),
               "bottom = \"periodic\"");
  text.replace(text.find("top = {"), text.find('\n', text.find("top = {")) - text.find("top = {"), "top = \"periodic\"");
  EXPECT_THROW(load_scene_string(text, "no_walls.toml"), SceneError);
}

TEST(ShearCell, PinnedDiscGivesTheEinsteinCoefficient) {
  const double a = 0.1, phi = M_PI * a * a / 2.0;
  const auto v = run_to_end(load_scene_string(
      shear_cell(128, 1.0,
                 "[[solid]]\nname = \"disc\"\nshape = \"circle\"\ncenter = [1.0, 0.5]\nradius = 0.1\n"
                 "density = 1.0\nmotion = \"pinned\"\n"),
      "pinned_disc.toml"));
  ASSERT_EQ(v.size(), 3u);
  const double coefficient = (v[2] - 1.0) / phi;
  EXPECT_NEAR(coefficient, 2.0, 0.2) << "eta_r = " << v[2];
}

}  // namespace
}  // namespace refmap
