// time.solid_picard_iterations (solver/model/solid_picard.cpp; docs/implicit.md, "The
// implicit step in xi"): the whole step repeated from a snapshot of the state at t^n with xi
// moved by the blend of u^n and the last pass's u^{n+1}.
//  - ThetaZeroRepeatsTheStepBitForBit: with theta = 0 and no defect correction every pass
//    recomputes the same step from the same state, so the result must be the plain step's
//    bits: the snapshot restores everything a step reads.
//  - the keys' errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "solver/model/simulation.hpp"
#include "solver/model/solid.hpp"
#include "solver/scene/scene.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

std::vector<std::string> semi_case() {
  // disc_tgv 32^2 at mu_s / rho_s = 100, P = 2 (past the explicit limit, P = 1)
  return {"grid.nx=32", "grid.ny=32", "time.end=100", "time.viscous=\"implicit\"",
          "time.solid_stress=\"semi_implicit\"", "solid.0.mu_s=100", "output.vtk=false",
          "time.dt_max=" + std::to_string(2.0 / 32.0 / std::sqrt(200.0))};
}

}  // namespace

TEST(SolidPicard, ThetaZeroRepeatsTheStepBitForBit) {
  Simulation a(load_scene(scene_path("disc_tgv.toml"), semi_case()));
  std::vector<std::string> sets = semi_case();
  for (const char* s : {"time.solid_picard_iterations=2", "time.solid_picard_theta=0", "time.solid_picard_defect=false"})
    sets.push_back(s);
  Simulation b(load_scene(scene_path("disc_tgv.toml"), sets));
  for (int n = 0; n < 5; ++n) {
    a.step();
    b.step();
  }
  const Grid& g = a.grid();
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      ASSERT_EQ(a.u()(i, j), b.u()(i, j)) << i << " " << j;
      ASSERT_EQ(a.v()(i, j), b.v()(i, j)) << i << " " << j;
    }
  const Solid &sa = *a.solids().at(0), &sb = *b.solids().at(0);
  ASSERT_EQ(sa.ni(), sb.ni());
  ASSERT_EQ(sa.nj(), sb.nj());
  for (int j = 0; j < sa.nj(); ++j)
    for (int i = 0; i < sa.ni(); ++i) ASSERT_EQ(sa.xi_x()(i, j), sb.xi_x()(i, j)) << i << " " << j;
  EXPECT_EQ(b.picard_change(), 0.0);  // the passes agree exactly
  EXPECT_GT(b.picard_cycles(), a.last_poisson_iterations());  // three passes' cycles
}

TEST(SolidPicard, KeysErrors) {
  const std::string base = "[domain]\nlx = 1\nly = 1\n[grid]\nnx = 16\nny = 16\n[fluid]\ndensity = 1\nviscosity = 0.01\n"
                           "[boundary]\nleft = \"no_slip\"\nright = \"no_slip\"\nbottom = \"no_slip\"\ntop = \"no_slip\"\n";
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 2\nsolid_stress = \"upper_convected\"\n")
                .find("time.solid_picard_iterations: is not offered with solid_stress = \"upper_convected\""),
            std::string::npos);
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 2\n")
                .find("time.solid_picard_defect: needs solid_stress = \"semi_implicit\""),
            std::string::npos);
  EXPECT_EQ(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 2\nsolid_picard_defect = false\n"), "");
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_theta = 1.5\n").find("time.solid_picard_theta"), std::string::npos);
}
