// The Galerkin coarse operator of the multigrid (solver.coarse_operator = "galerkin",
// solver/pressure/multigrid_galerkin.hpp, kernels/multigrid9.hpp): its coarse stencil against the
// analytic Galerkin stencil of the 5-point Laplacian, its convergence factor at density
// ratio 1000, and solves of manufactured problems (with and without the sink term).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/pressure/poisson.hpp"
#include "solver/pressure/poisson_multigrid.hpp"
#include "solver/scene/scene.hpp"
#include "tests/fixtures/fused_passes.hpp"
#include "tests/fixtures/poisson_problem.hpp"
#include "tests/fixtures/scene_text.hpp"

namespace refmap {
namespace {

PoissonOptions galerkin_opts() {
  PoissonOptions o;
  o.coarse_operator = MgCoarseOperator::Galerkin;
  o.coarse_cells = 4;  // every level down to the smallest
  return o;
}

// Constant beta = 1: the fine operator (cell-integrated) is the 5-point L = Lx (x) I + I (x) Ly
// with Lx = [1 -2 1]. Its operator-dependent prolongation is then bilinear: an edge point
// gets -a_W / (a_C + a_S + a_N) = 1 / (4 - 2) = 1/2 from each side, a middle point
// (1/2 + 1/2) / 4 = 1/4 from each diagonal coarse point: P = Px (x) Py with Px = [1/2 1 1/2].
// In 1-D, Px^T Lx Px = [1/2 -1 1/2] (L P e_I is -1 at fine 2I and 1/2 at 2I +- 2) and the
// "mass" Px^T Px = [1/4 3/2 1/4], so P^T L P = [1/2 -1 1/2] (x) [1/4 3/2 1/4] + sym.:
// corners 1/2*1/4 + 1/4*1/2 = 1/4, edges 1/2*3/2 - 1*1/4 = 1/2, centre -1*3/2*2 = -3
// (the known 9-point Galerkin stencil of full weighting / bilinear interpolation, times
// 4 h^2 / h^2 for the unscaled R = P^T). Exact in binary floating point up to round-off.
TEST(PoissonGalerkin, CoarseStencilOfTheLaplacian) {
  struct Case { int n; bool periodic; };
  for (const Case c : {Case{33, false}, Case{32, true}}) {
    const auto p = poisson_problem::disc_problem(c.n, c.n, 1.0 / c.n, c.periodic, c.periodic, 1.0,
                                                 [](double, double) { return 0.0; });
    MultigridHierarchy h;
    h.setup(p.op(), galerkin_opts());
    const GalerkinLevels* g = h.galerkin();
    ASSERT_NE(g, nullptr);
    ASSERT_GT(g->num_levels(), 2);
    const mg::Stencil9 s = g->stencil(1);
    EXPECT_EQ(s.nx, c.periodic ? 16 : 17);
    const double want[9] = {0.25, 0.5, 0.25, 0.5, -3.0, 0.5, 0.25, 0.5, 0.25};
    const int lo = c.periodic ? 0 : 1, hi = c.periodic ? s.nx : s.nx - 1;  // walls: interior only
    for (int J = lo; J < hi; ++J)
      for (int I = lo; I < hi; ++I)
        for (int k = 0; k < 9; ++k) EXPECT_NEAR(s.coef(k, I, J), want[k], 1e-14) << I << " " << J << " " << k;
    // every level: constants are in the null space (rows sum to 0) and the operator is
    // symmetric (a_k(P) equals the opposite coefficient of the neighbour it points at)
    for (int l = 1; l < g->num_levels(); ++l) {
      const mg::Stencil9 t = g->stencil(l);
      for (int J = 0; J < t.ny; ++J)
        for (int I = 0; I < t.nx; ++I) {
          double sum = 0.0;
          for (int k = 0; k < 9; ++k) sum += t.coef(k, I, J);
          EXPECT_NEAR(sum, 0.0, 1e-13) << l << " " << I << " " << J;
          const int E = t.nbx->p[I], N = t.nby->p[J];
          if (E != I) { EXPECT_NEAR(t.coef(5, I, J), t.coef(3, E, J), 1e-13); }
          if (N != J) { EXPECT_NEAR(t.coef(7, I, J), t.coef(1, I, N), 1e-13); }
          if (E != I && N != J) { EXPECT_NEAR(t.coef(8, I, J), t.coef(0, E, N), 1e-13); }
        }
    }
  }
}

// The one-pass pipelined four-colour sweeps (one thread, walls in y) compute the same
// iterates as the colour-by-colour sweeps of the threaded path, bit for bit (the order of
// the updates that read each other is the same), forward and reversed, odd and even counts.
TEST(PoissonGalerkin, PipelinedSmootherEqualsColourOrder) {
  for (int n : {37, 40}) {
    const auto p = poisson_problem::standard_problem(n, 1000.0);
    MultigridHierarchy h;
    h.setup(p.op(), galerkin_opts());
    mg::Stencil9 s = h.galerkin()->stencil(1);
    Field f(s.nx, s.ny, 1), x1(s.nx, s.ny, 1), x2(s.nx, s.ny, 1);
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        f(i, j) = std::sin(0.7 * i + 1.3 * j);
        x1(i, j) = x2(i, j) = std::cos(0.4 * i - 0.9 * j);
      }
    for (bool rev : {false, true}) {
      s.threads = 1;
      mg::smooth9(s, x1.view(), f.cview(), 3, rev, 1.0);
      s.threads = 2;  // the colour-by-colour path
      mg::smooth9(s, x2.view(), f.cview(), 3, rev, 1.0);
      for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i) ASSERT_EQ(x1(i, j), x2(i, j)) << n << " " << rev << " " << i << " " << j;
    }
  }
}

// The finest level's fused passes of the Galerkin cycle (smoothing + residual restriction,
// prolongation + smoothing; walls in y: one pipelined pass each, kernels/multigrid9.hpp)
// give what the separate kernels give, bit for bit up to FMA contraction (1e-14 relative),
// on one and two threads, with and without the sink, and fall back to the separate kernels
// for periodic y. A fused pass that restricts a wrong row or skips one at a thread's chunk
// boundary is off by O(1).
TEST(PoissonGalerkin, FusedFinestPassesMatchSeparateKernels) {
  struct G { int nx, ny; bool px, py, sink; };
  for (G g : {G{64, 64, false, false, false}, G{38, 53, true, false, false}, G{201, 199, false, false, true},
              G{130, 120, true, false, true}, G{40, 32, true, true, false}, G{16, 13, false, false, false}}) {
    const auto p = poisson_problem::disc_problem(g.nx, g.ny, 1.0 / g.nx, g.px, g.py, 100.0,
                                                 [](double x, double y) { return std::cos(3 * x) * std::cos(2 * y); });
    PoissonOperator op = p.op();
    Field sink(g.nx, g.ny);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) sink(i, j) = 50.0 + 10.0 * std::sin(0.1 * i * j);
    if (g.sink) op.sink = &sink;
    MultigridHierarchy h;
    h.setup(op, galerkin_opts());
    const GalerkinLevels* gl = h.galerkin();
    ASSERT_NE(gl, nullptr);
    ASSERT_GE(gl->num_levels(), 2);
    const mg::Stencil s = h.stencil(0);
    ASSERT_EQ(s.c.p != nullptr, g.sink);
    const mg::Prolong9 P = gl->prolongation(0);
    poisson_problem::FusedPassInputs in(g.nx, g.ny, P.ncx, P.ncy);
    Field& x0 = in.x0;
    const Field& f = in.f;
    Field& xc = in.xc;
    mg::fill_ghosts(s, x0.view());
    std::vector<double> buf(2 * mg::scratch9_per_thread(g.nx));
    const mg::Scratch sc{buf.data(), mg::scratch9_per_thread(g.nx), 2};
    for (int sweeps : {1, 2})
      for (bool black_first : {false, true}) {
        mg::Stencil s1 = s;
        s1.threads = 1;
        // separate kernels, one thread
        poisson_problem::FusedPassOutputs ref{x0, Field(P.ncx, P.ncy, 1), x0};
        mg::smooth_rbgs(s1, ref.x.view(), f.cview(), sweeps, black_first, 1.2);
        mg::residual_restrict5(s1, ref.x.cview(), f.cview(), P, ref.fc.view(), sc);
        mg::prolong9_add(P, xc.cview(), ref.x2.view(), 1);
        mg::fill_ghosts(s1, ref.x2.view());
        mg::smooth_rbgs(s1, ref.x2.view(), f.cview(), sweeps, black_first, 1.2, &ref.r2);
        for (int threads : {1, 2}) {
          mg::Stencil st = s;
          st.threads = threads;
          poisson_problem::FusedPassOutputs got{x0, Field(P.ncx, P.ncy, 1), x0};
          mg::smooth_rbgs_restrict9(st, got.x.view(), f.cview(), sweeps, black_first, 1.2, P, got.fc.view(), sc);
          mg::prolong9_smooth_rbgs(st, P, xc.cview(), got.x2.view(), f.cview(), sweeps, black_first, 1.2, sc,
                                   &got.r2);
          poisson_problem::expect_same_passes(got, ref, 1e-13,
                                              std::to_string(g.nx) + "x" + std::to_string(g.ny) + " sweeps " +
                                                  std::to_string(sweeps) + " threads " + std::to_string(threads));
        }
      }
  }
}

double v_cycle_factor(const poisson_problem::Problem& p, MgCoarseOperator co, int& cycles) {
  PoissonOptions o;
  o.coarse_operator = co;
  o.tol = 1e-8;
  o.max_iter = 100;
  o.record_history = true;
  auto s = make_poisson_solver(o);
  s->setup(p.op());
  Field x(p.grid.nx, p.grid.ny);
  const SolveStats st = s->solve(p.rhs, x);
  cycles = st.iterations;
  EXPECT_TRUE(st.converged);
  EXPECT_LT(poisson_problem::reference_residual(p, x), 1e-7);
  // mean factor per cycle over the whole solve
  return std::pow(st.history.back() / st.history.front(), 1.0 / st.iterations);
}

// Density ratio 1000 (the standard disc problem, 128^2), mean factor per V(2,2)-cycle to
// 1e-8: the default rediscretised coarse operator 0.145 (10 cycles), Galerkin 0.034
// (6 cycles; 0.024 and 5 cycles at ratio 1), measured. Bound 0.1: the rate of a V-cycle
// that keeps ratio 1000 within ~1.3x of the ratio-1 cycle count here (1e-8 in <= 8
// cycles), which the default misses by 1.5x.
TEST(PoissonGalerkin, ConvergenceFactorAtDensityRatio1000) {
  const auto p1000 = poisson_problem::standard_problem(128, 1000.0);
  const auto p1 = poisson_problem::standard_problem(128, 1.0);
  int ca = 0, cg = 0, c1 = 0;
  const double fa = v_cycle_factor(p1000, MgCoarseOperator::Average, ca);
  const double fg = v_cycle_factor(p1000, MgCoarseOperator::Galerkin, cg);
  const double f1 = v_cycle_factor(p1, MgCoarseOperator::Galerkin, c1);
  std::cout << "[ galerkin ] 128^2 R=1000: average " << ca << " cycles, factor " << fa
            << "; galerkin " << cg << " cycles, factor " << fg << "; galerkin R=1: " << c1
            << " cycles, factor " << f1 << "\n";
  EXPECT_GT(fa, 0.1);
  EXPECT_LT(fg, 0.1);
  EXPECT_LT(f1, 0.1);
  EXPECT_LE(double(cg), 1.3 * c1);  // the goal: within 1.3x of the ratio-1 count (results/multigrid.md)
}

// Manufactured solutions: x* = cos(2 pi x) cos(pi y) (+ periodic-friendly), rhs = A x*
// computed independently (poisson_problem::apply_reference, plus - c x* with a sink); the
// solver at tol 1e-10 must return x* (up to the mean without a sink) to 1e-7 of its
// amplitude (the discrete problem is solved exactly; the error is the residual 1e-10
// times the inverse operator's norm, ~ (1/pi^2) * R for the ratio R = 1000 disc).
TEST(PoissonGalerkin, SolvesManufacturedProblems) {
  const double pi = std::numbers::pi;
  struct Case { int nx, ny; bool px, py; double sink; PoissonMethod m; MgCycle cyc; };
  for (const Case c : {Case{96, 80, false, false, 0.0, PoissonMethod::Multigrid, MgCycle::V},
                       Case{64, 64, true, false, 0.0, PoissonMethod::Mgpcg, MgCycle::V},
                       Case{75, 64, false, true, 0.0, PoissonMethod::Multigrid, MgCycle::F},
                       Case{64, 48, true, true, 50.0, PoissonMethod::Multigrid, MgCycle::V}}) {
    auto p = poisson_problem::disc_problem(c.nx, c.ny, 1.0 / c.nx, c.px, c.py, 1000.0,
                                           [](double, double) { return 0.0; });
    Field xs(c.nx, c.ny), sink(c.nx, c.ny);
    for (int j = 0; j < c.ny; ++j)
      for (int i = 0; i < c.nx; ++i)
        xs(i, j) = std::cos(2 * pi * p.grid.xc(i)) * std::cos(2 * pi * p.grid.yc(j) * c.nx / c.ny);
    sink.fill(c.sink);
    Field ax;
    poisson_problem::apply_reference(p, xs, ax);
    for (int j = 0; j < c.ny; ++j)
      for (int i = 0; i < c.nx; ++i) p.rhs(i, j) = ax(i, j) - c.sink * xs(i, j);
    PoissonOperator op = p.op();
    if (c.sink > 0) op.sink = &sink;
    PoissonOptions o;
    o.coarse_operator = MgCoarseOperator::Galerkin;
    o.method = c.m;
    o.cycle = c.cyc;
    o.tol = 1e-10;
    o.max_iter = 60;
    auto s = make_poisson_solver(o);
    s->setup(op);
    Field x(c.nx, c.ny);
    const SolveStats st = s->solve(p.rhs, x);
    EXPECT_TRUE(st.converged) << c.nx << "x" << c.ny << " " << st.iterations << " " << st.rel_residual;
    const double shift = c.sink > 0 ? 0.0 : poisson_problem::mean(xs) - poisson_problem::mean(x);
    double err = 0.0;
    for (int j = 0; j < c.ny; ++j)
      for (int i = 0; i < c.nx; ++i) err = std::max(err, std::abs(x(i, j) + shift - xs(i, j)));
    EXPECT_LT(err, 1e-7) << c.nx << "x" << c.ny << " periodic " << c.px << c.py << " sink " << c.sink;
    EXPECT_LT(st.iterations, 20) << c.nx << "x" << c.ny;
  }
}

// The scene key: "galerkin" is read into the enum, a misspelt value is an error that names
// the key; the Jacobi smoother with "galerkin" is refused when the solver is set up.
TEST(PoissonGalerkin, SceneKey) {
  using testing::box_scene;
  using testing::kWalls;
  const Config c = load_scene_string(box_scene(16, kWalls, "[solver]\ncoarse_operator = \"galerkin\"\n"), "g");
  EXPECT_EQ(c.poisson.coarse_operator, MgCoarseOperator::Galerkin);
  try {
    load_scene_string(box_scene(16, kWalls, "[solver]\ncoarse_operator = \"galerkn\"\n"), "g");
    ADD_FAILURE() << "no error for a bad coarse_operator";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("coarse_operator"), std::string::npos) << e.what();
  }
  PoissonOptions o = galerkin_opts();
  o.smoother = MgSmoother::Jacobi;
  const auto p = poisson_problem::standard_problem(16, 1.0);
  auto s = make_poisson_solver(o);
  EXPECT_THROW(s->setup(p.op()), std::invalid_argument);
}

}  // namespace
}  // namespace refmap
