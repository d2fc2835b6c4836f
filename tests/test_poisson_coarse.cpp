// Multigrid coarse operators (PoissonOptions::coarse_operator, solver/pressure/poisson_multigrid.cpp):
// "average" (restriction-weighted mean of beta) and "harmonic" (fine faces in series normal
// to the coarse face, strips in parallel) are both the rediscretised coarse 5-point operator
// when beta is constant, and "harmonic" is the exact series conductance across layers.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/pressure/poisson.hpp"
#include "solver/pressure/poisson_multigrid.hpp"
#include "tests/fixtures/poisson_problem.hpp"

namespace refmap {
namespace {

PoissonOptions with(MgCoarseOperator co) {
  PoissonOptions o;
  o.coarse_operator = co;
  o.coarse_cells = 4;  // every level down to the smallest
  return o;
}

// Constant beta on uniform and awkward grids (odd counts make 3-cell coarse cells; periodic
// directions wrap): both rules give the same coefficients on every level up to round-off.
TEST(PoissonCoarseOperator, HarmonicEqualsAverageForConstantBeta) {
  struct Case { int nx, ny; bool px, py; };
  for (const Case c : {Case{64, 64, false, false}, Case{37, 29, true, false}, Case{45, 23, false, true},
                       Case{33, 35, true, true}}) {
    const auto p = poisson_problem::disc_problem(c.nx, c.ny, 1.0 / c.nx, c.px, c.py, 1.0,
                                                 [](double, double) { return 0.0; });
    MultigridHierarchy a, h;
    a.setup(p.op(), with(MgCoarseOperator::Average));
    h.setup(p.op(), with(MgCoarseOperator::Harmonic));
    ASSERT_EQ(a.num_levels(), h.num_levels());
    ASSERT_GT(a.num_levels(), 2);
    for (int l = 1; l < a.num_levels(); ++l) {
      const auto& A = a.level(l);
      const auto& H = h.level(l);
      for (int j = 0; j < A.ny; ++j)
        for (int i = 0; i <= A.nx; ++i) EXPECT_NEAR(H.tx(i, j), A.tx(i, j), 1e-13) << l << " " << i << " " << j;
      for (int j = 0; j <= A.ny; ++j)
        for (int i = 0; i < A.nx; ++i) EXPECT_NEAR(H.ty(i, j), A.ty(i, j), 1e-13) << l << " " << i << " " << j;
    }
  }
}

// Layers in x (beta = b1 for x < 1/2, b2 beyond, the interface face carrying bi): the coarse
// x-face on the interface joins the centres of the coarse cells on either side, half a fine
// cell in b1, the interface face, half a fine cell in b2, so per fine row the resistance is
// 0.5/b1 + 1/bi + 0.5/b2, and the coarse face (two rows in parallel) has T = 2 / R.
TEST(PoissonCoarseOperator, HarmonicIsTheSeriesConductanceAcrossLayers) {
  const int n = 16;
  const double b1 = 1.0, b2 = 1e-3, bi = 2.0 / (1.0 / b1 + 1.0 / b2);
  auto p = poisson_problem::disc_problem(n, n, 1.0 / n, false, false, 1.0, [](double, double) { return 0.0; });
  for (int j = 0; j < n; ++j)
    for (int i = 1; i < n; ++i) p.beta_x(i, j) = i < n / 2 ? b1 : (i == n / 2 ? bi : b2);
  for (int j = 1; j < n; ++j)
    for (int i = 0; i < n; ++i) p.beta_y(i, j) = p.rho(i, j) = (i < n / 2 ? b1 : b2);
  MultigridHierarchy h;
  h.setup(p.op(), with(MgCoarseOperator::Harmonic));
  const auto& C = h.level(1);
  const double want = 2.0 / (0.5 / b1 + 1.0 / bi + 0.5 / b2);
  for (int J = 0; J < C.ny; ++J) {
    EXPECT_NEAR(C.tx(n / 4, J), want, 1e-14 * want);
    EXPECT_NEAR(C.tx(n / 4 - 1, J), b1, 1e-14);  // inside a layer: the plain coarse T
    EXPECT_NEAR(C.tx(n / 4 + 1, J), b2, 1e-17);
  }
}

}  // namespace
}  // namespace refmap
