// Poisson solvers: multigrid (V/F, rbgs/jacobi), Jacobi-CG, MGPCG.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/stencil5.hpp"
#include "solver/pressure/poisson.hpp"
#include "solver/pressure/poisson_cg.hpp"
#include "solver/pressure/poisson_multigrid.hpp"
#include "tests/fixtures/fused_passes.hpp"
#include "tests/fixtures/poisson_problem.hpp"
#include "solver/scene/option_names.hpp"

namespace refmap {
namespace {

using poisson_problem::Problem;
constexpr double kPi = std::numbers::pi;

/// Options from the scene-file names (the tables below read better with names); an
/// unknown name is a bug of the test.
PoissonOptions options(const std::string& method, const std::string& cycle = "V",
                       const std::string& smoother = "rbgs") {
  PoissonOptions o;
  const auto m = parse_option<PoissonMethod>(method);
  const auto c = parse_option<MgCycle>(cycle);
  const auto s = parse_option<MgSmoother>(smoother);
  if (!m || !c || !s) throw std::logic_error("test: unknown Poisson option " + method + "/" + cycle + "/" + smoother);
  o.method = *m;
  o.cycle = *c;
  o.smoother = *s;
  return o;
}

struct Result {
  SolveStats st;
  Field x;
  double ref_res = 0.0;  // residual from the independent reference operator
};

Result solve(const Problem& p, const PoissonOptions& opt) {
  auto s = make_poisson_solver(opt);
  s->setup(p.op());
  Result r;
  r.x.resize(p.grid.nx, p.grid.ny);
  r.st = s->solve(p.rhs, r.x);
  r.ref_res = poisson_problem::reference_residual(p, r.x);
  return r;
}

double cos_cos(double x, double y) { return std::cos(kPi * x) * std::cos(kPi * y); }

double geometric_mean_factor(const std::vector<double>& h) {
  // mean reduction per cycle over cycles 2..n (the first cycle includes the start-up)
  if (h.size() < 3) return 0.0;
  const std::size_t n = h.size() - 2;
  return std::pow(h.back() / h[1], 1.0 / double(n));
}

double worst_factor(const std::vector<double>& h) {
  double w = 0.0;
  for (std::size_t k = 2; k < h.size(); ++k) w = std::max(w, h[k] / h[k - 1]);
  return w;
}

// ---------------------------------------------------------------------------------------
// The names are parsed once, by the scene loader (solver/scene/option_names.hpp); the factory
// takes enums and checks only the numeric options.
TEST(PoissonFactory, NamesRoundTripAndUnknownNamesAreRejected) {
  EXPECT_FALSE(parse_option<PoissonMethod>("sor"));
  EXPECT_FALSE(parse_option<MgCycle>("W"));
  EXPECT_FALSE(parse_option<MgSmoother>("sor"));
  EXPECT_FALSE(parse_option<MgCycle>("v"));  // names are case-sensitive
  for (PoissonMethod m : {PoissonMethod::Multigrid, PoissonMethod::Cg, PoissonMethod::Mgpcg})
    EXPECT_EQ(parse_option<PoissonMethod>(to_string(m)), m);
  for (MgCycle c : {MgCycle::V, MgCycle::F}) EXPECT_EQ(parse_option<MgCycle>(to_string(c)), c);
  for (MgSmoother s : {MgSmoother::Rbgs, MgSmoother::Jacobi}) EXPECT_EQ(parse_option<MgSmoother>(to_string(s)), s);
  for (const char* m : {"multigrid", "cg", "mgpcg"}) EXPECT_NE(make_poisson_solver(options(m)), nullptr);
  EXPECT_NE(make_poisson_solver(options("multigrid", "F", "jacobi")), nullptr);
  EXPECT_EQ(make_poisson_solver(options("multigrid", "F", "jacobi"))->name(), "multigrid(F-cycle, jacobi 2/2)");
  PoissonOptions bad = options("multigrid");
  bad.pre_smooth = bad.post_smooth = 0;
  EXPECT_THROW(make_poisson_solver(bad), std::invalid_argument);
}

TEST(PoissonFactory, RejectsBadShapes) {
  Problem p = poisson_problem::standard_problem(16, 1.0);
  auto s = make_poisson_solver(options("multigrid"));
  PoissonOperator op = p.op();
  op.beta_x = &p.beta_y;  // wrong size
  EXPECT_THROW(s->setup(op), std::invalid_argument);
  s->setup(p.op());
  Field x(15, 16), rhs(16, 16);
  EXPECT_THROW(s->solve(rhs, x), std::invalid_argument);
}

// 1. residual reduction per V-cycle on a constant-coefficient Neumann problem
TEST(PoissonMultigrid, VCycleConvergenceFactor) {
  Problem p = poisson_problem::standard_problem(256, 1.0);
  struct Case { const char* cycle; const char* smoother; int pre, post; double bound; };
  for (Case c : {Case{"V", "rbgs", 2, 2, 0.1}, Case{"V", "rbgs", 1, 1, 0.2}, Case{"F", "rbgs", 2, 2, 0.1},
                 Case{"V", "jacobi", 2, 2, 0.25}}) {
    PoissonOptions o = options("multigrid", c.cycle, c.smoother);
    o.pre_smooth = c.pre;
    o.post_smooth = c.post;
    o.record_history = true;
    o.tol = 1e-10;  // well above the round-off floor (~1e-12 relative at 256^2)
    o.max_iter = 30;
    Result r = solve(p, o);
    const double g = geometric_mean_factor(r.st.history), w = worst_factor(r.st.history);
    std::cout << "[ conv    ] 256^2 const " << c.cycle << "(" << c.pre << "," << c.post << ") "
              << c.smoother << ": mean factor " << g << ", worst " << w << ", " << r.st.iterations
              << " cycles to " << r.st.rel_residual << "\n";
    EXPECT_TRUE(r.st.converged);
    EXPECT_LE(g, c.bound);
    EXPECT_LE(w, 1.5 * c.bound);
  }
}

TEST(PoissonMultigrid, VCycleConvergenceFactorDensityRatio1000) {
  Problem p = poisson_problem::standard_problem(256, 1000.0);
  PoissonOptions o = options("multigrid");
  o.record_history = true;
  o.tol = 1e-10;
  o.max_iter = 100;
  Result r = solve(p, o);
  const double g = geometric_mean_factor(r.st.history);
  std::cout << "[ conv    ] 256^2 R=1000 V(2,2) rbgs: mean factor " << g << ", worst "
            << worst_factor(r.st.history) << "\n";
  EXPECT_TRUE(r.st.converged);
  EXPECT_LE(g, 0.5);
}

// 2. iterations to 1e-10 independent of the grid size
TEST(PoissonMultigrid, IterationsIndependentOfGridSize) {
  for (const char* cycle : {"V", "F"}) {
    std::vector<int> its;
    for (int n : {64, 128, 256, 512, 1024}) {
      Problem p = poisson_problem::standard_problem(n, 1.0);
      Result r = solve(p, options("multigrid", cycle));
      EXPECT_TRUE(r.st.converged) << n;
      EXPECT_LE(r.ref_res, 2e-10) << n;
      its.push_back(r.st.iterations);
      std::cout << "[ iters   ] " << cycle << "-cycle " << n << "^2: " << r.st.iterations
                << " cycles, rel residual " << r.st.rel_residual << "\n";
    }
    const auto [mn, mx] = std::minmax_element(its.begin(), its.end());
    EXPECT_LE(*mx - *mn, 2);
  }
}

// 3. density ratio 1000 across a smoothed circular interface
TEST(PoissonMultigrid, DensityRatio1000AllMethods) {
  Problem p = poisson_problem::standard_problem(256, 1000.0);
  struct Case { const char* method; const char* cycle; const char* smoother; int max_iter; };
  for (Case c : {Case{"multigrid", "V", "rbgs", 100}, Case{"multigrid", "F", "rbgs", 100},
                 Case{"multigrid", "V", "jacobi", 200}, Case{"mgpcg", "V", "rbgs", 100},
                 Case{"mgpcg", "V", "jacobi", 100}}) {
    PoissonOptions o = options(c.method, c.cycle, c.smoother);
    o.max_iter = c.max_iter;
    Result r = solve(p, o);
    std::cout << "[ R=1000  ] 256^2 " << c.method << " " << c.cycle << " " << c.smoother << ": "
              << r.st.iterations << " iterations, rel residual " << r.st.rel_residual
              << " (reference " << r.ref_res << ")\n";
    EXPECT_TRUE(r.st.converged) << c.method << c.cycle << c.smoother;
    EXPECT_LE(r.st.rel_residual, 1e-10);
    EXPECT_LE(r.ref_res, 2e-10);
    EXPECT_NEAR(poisson_problem::mean(r.x), 0.0, 1e-12);
  }
  // plain CG needs many iterations: smaller grid
  Problem q = poisson_problem::standard_problem(64, 1000.0);
  PoissonOptions o = options("cg");
  o.max_iter = 20000;
  Result r = solve(q, o);
  std::cout << "[ R=1000  ] 64^2 cg: " << r.st.iterations << " iterations, rel residual "
            << r.st.rel_residual << " (reference " << r.ref_res << ")\n";
  EXPECT_TRUE(r.st.converged);
  EXPECT_LE(r.ref_res, 2e-10);
}

// 4a. second-order accuracy against analytic solutions (continuous right-hand side)
double max_error(const Problem& p, const Field& x, const std::function<double(double, double)>& exact) {
  // compare zero-mean versions
  double me = 0.0;
  for (int j = 0; j < p.grid.ny; ++j)
    for (int i = 0; i < p.grid.nx; ++i) me += exact(p.grid.xc(i), p.grid.yc(j));
  me /= double(p.grid.cells());
  const double mx = poisson_problem::mean(x);
  double e = 0.0;
  for (int j = 0; j < p.grid.ny; ++j)
    for (int i = 0; i < p.grid.nx; ++i)
      e = std::max(e, std::abs((x(i, j) - mx) - (exact(p.grid.xc(i), p.grid.yc(j)) - me)));
  return e;
}

void check_second_order(bool px, bool py, const std::function<double(double, double)>& exact,
                        double lap_factor, const char* label) {
  std::vector<double> err;
  for (int n : {32, 64, 128, 256}) {
    Problem p = poisson_problem::disc_problem(n, n, 1.0 / n, px, py, 1.0, [&](double x, double y) {
      return lap_factor * exact(x, y);
    });
    for (const char* m : {"multigrid", "mgpcg"}) {
      Result r = solve(p, options(m));
      ASSERT_TRUE(r.st.converged) << label << " " << m << " " << n;
      if (std::string(m) == "multigrid") err.push_back(max_error(p, r.x, exact));
    }
  }
  for (std::size_t k = 1; k < err.size(); ++k) {
    const double ratio = err[k - 1] / err[k];
    std::cout << "[ order   ] " << label << " error " << err[k - 1] << " -> " << err[k]
              << " ratio " << ratio << "\n";
    EXPECT_GT(ratio, 3.6) << label;
    EXPECT_LT(ratio, 4.4) << label;
  }
  EXPECT_LT(err.back(), 1e-4) << label;
}

TEST(PoissonAccuracy, NeumannCosCosSecondOrder) {
  check_second_order(false, false, cos_cos, -2 * kPi * kPi, "neumann cos(pi x)cos(pi y)");
}

TEST(PoissonAccuracy, PeriodicSinSinSecondOrder) {
  check_second_order(true, true,
                     [](double x, double y) { return std::sin(2 * kPi * x) * std::sin(2 * kPi * y); },
                     -8 * kPi * kPi, "periodic sin(2 pi x)sin(2 pi y)");
}

TEST(PoissonAccuracy, MixedPeriodicXWallsYSecondOrder) {
  check_second_order(true, false,
                     [](double x, double y) { return std::sin(2 * kPi * x) * std::cos(kPi * y); },
                     -5 * kPi * kPi, "periodic-x/wall-y sin(2 pi x)cos(pi y)");
}

// 4b. discrete right-hand side: the solver must recover the field exactly
TEST(PoissonAccuracy, RecoversDiscreteSolutionVariableCoefficient) {
  for (auto [px, py] : {std::pair{false, false}, std::pair{true, false}, std::pair{true, true}}) {
    Problem p = poisson_problem::disc_problem(96, 80, 1.0 / 96, px, py, 100.0, cos_cos);
    Field exact(p.grid.nx, p.grid.ny);
    for (int j = 0; j < p.grid.ny; ++j)
      for (int i = 0; i < p.grid.nx; ++i)
        exact(i, j) = std::cos(3 * p.grid.xc(i)) * std::sin(2 * p.grid.yc(j) + 0.3) + 0.7;
    poisson_problem::apply_reference(p, exact, p.rhs);
    const double m = poisson_problem::mean(exact);
    double scale = 0.0;
    for (int j = 0; j < p.grid.ny; ++j)
      for (int i = 0; i < p.grid.nx; ++i) scale = std::max(scale, std::abs(exact(i, j) - m));
    for (const char* meth : {"multigrid", "mgpcg", "cg"}) {
      PoissonOptions o = options(meth);
      o.tol = 1e-12;
      o.max_iter = 5000;
      Result r = solve(p, o);
      ASSERT_TRUE(r.st.converged) << meth;
      double e = 0.0;
      for (int j = 0; j < p.grid.ny; ++j)
        for (int i = 0; i < p.grid.nx; ++i) e = std::max(e, std::abs(r.x(i, j) - (exact(i, j) - m)));
      EXPECT_LT(e / scale, 1e-8) << meth << " px=" << px << " py=" << py;
    }
  }
}

// 4c/5. non-square, non-power-of-two, odd sizes, mixed boundary conditions: every method
// converges to 1e-10 (checked with the reference operator too)
TEST(PoissonGrids, AllMethodsConvergeOnAwkwardGrids) {
  struct G { int nx, ny; bool px, py; double ratio; };
  const G grids[] = {
      {100, 60, false, false, 1000}, {129, 77, false, false, 1000}, {129, 129, false, false, 10},
      {37, 200, false, false, 1000}, {200, 37, false, false, 1},    {64, 48, true, false, 1000},
      {63, 50, true, false, 1000},   {65, 33, true, false, 1},      {37, 200, true, false, 100},
      {51, 77, false, true, 100},    {45, 45, true, true, 1000},    {7, 9, false, false, 10},
      {3, 50, true, false, 1},       {1000, 6, false, false, 1},    {17, 300, true, true, 10},
      {1, 1, false, false, 1},       {1, 40, false, true, 1},       {2, 3, true, true, 1},
      {5, 1500, false, false, 10},   // coarsest 2 x 750 = 1500 > 512 cells: sparse Cholesky
  };
  for (const G& g : grids) {
    const double dx = 1.0 / std::max(g.nx, g.ny);
    Problem p = poisson_problem::disc_problem(g.nx, g.ny, dx, g.px, g.py, g.ratio, [](double x, double y) {
      return std::cos(5 * x + 1) * std::sin(3 * y) + x;
    });
    struct M { const char* method; const char* cycle; const char* smoother; };
    for (M m : {M{"multigrid", "V", "rbgs"}, M{"multigrid", "F", "rbgs"}, M{"multigrid", "V", "jacobi"},
                M{"mgpcg", "V", "rbgs"}, M{"cg", "V", "rbgs"}}) {
      PoissonOptions o = options(m.method, m.cycle, m.smoother);
      o.max_iter = std::string(m.method) == "cg" ? 50000 : 200;
      Result r = solve(p, o);
      const std::string what = std::to_string(g.nx) + "x" + std::to_string(g.ny) +
                               (g.px ? " px" : "") + (g.py ? " py" : "") + " R=" +
                               std::to_string(int(g.ratio)) + " " + m.method + "/" + m.cycle +
                               "/" + m.smoother;
      EXPECT_TRUE(r.st.converged) << what << " residual " << r.st.rel_residual;
      EXPECT_LE(r.ref_res, 2e-10) << what;
      EXPECT_NEAR(poisson_problem::mean(r.x), 0.0, 1e-11) << what;
      if (std::string(m.method) != "cg")
        std::cout << "[ grids   ] " << what << ": " << r.st.iterations << " it\n";
    }
  }
}

// ---------------------------------------------------------------------------------------
TEST(PoissonSolvers, WarmStartAndZeroRhs) {
  Problem p = poisson_problem::standard_problem(128, 1000.0);
  for (const char* m : {"multigrid", "mgpcg", "cg"}) {
    PoissonOptions o = options(m);
    o.max_iter = 5000;
    auto s = make_poisson_solver(o);
    s->setup(p.op());
    Field x(p.grid.nx, p.grid.ny);
    const SolveStats a = s->solve(p.rhs, x);
    ASSERT_TRUE(a.converged) << m;
    const SolveStats b = s->solve(p.rhs, x);  // warm start from the solution
    EXPECT_EQ(b.iterations, 0) << m;
    EXPECT_LE(b.rel_residual, 1e-10) << m;
    // a constant added to the rhs does not change anything (projected away)
    Field rhs2 = p.rhs;
    for (int j = 0; j < p.grid.ny; ++j)
      for (int i = 0; i < p.grid.nx; ++i) rhs2(i, j) += 3.0;
    Field x2(p.grid.nx, p.grid.ny);
    const SolveStats c = s->solve(rhs2, x2);
    EXPECT_TRUE(c.converged);
    double d = 0.0;
    for (int j = 0; j < p.grid.ny; ++j)
      for (int i = 0; i < p.grid.nx; ++i) d = std::max(d, std::abs(x2(i, j) - x(i, j)));
    EXPECT_LT(d, 1e-7) << m;
    // zero rhs -> zero solution
    Field zero(p.grid.nx, p.grid.ny);
    const SolveStats z = s->solve(zero, x2);
    EXPECT_TRUE(z.converged);
    EXPECT_EQ(z.rel_residual, 0.0);
    EXPECT_EQ(x2(5, 7), 0.0);
  }
}

TEST(PoissonSolvers, SetupAgainWithNewCoefficients) {
  Problem a = poisson_problem::standard_problem(96, 1.0);
  Problem b = poisson_problem::standard_problem(96, 1000.0);
  for (const char* m : {"multigrid", "mgpcg"}) {
    auto s = make_poisson_solver(options(m));
    Field x(96, 96);
    s->setup(a.op());
    EXPECT_TRUE(s->solve(a.rhs, x).converged);
    s->setup(b.op());
    x.fill(0.0);
    const SolveStats st = s->solve(b.rhs, x);
    EXPECT_TRUE(st.converged) << m;
    EXPECT_LE(poisson_problem::reference_residual(b, x), 2e-10) << m;
  }
}

TEST(PoissonSolvers, SameIterationsOnOneAndTwoThreads) {
  const int saved = omp_get_max_threads();
  Problem p = poisson_problem::standard_problem(256, 1000.0);
  for (const char* m : {"multigrid", "mgpcg"}) {
    std::vector<double> res;
    std::vector<int> its;
    for (int t : {1, 2}) {
      omp_set_num_threads(t);
      Result r = solve(p, options(m));
      its.push_back(r.st.iterations);
      res.push_back(r.st.rel_residual);
    }
    EXPECT_EQ(its[0], its[1]) << m;
    EXPECT_NEAR(res[0], res[1], 1e-3 * res[0]) << m;
  }
  omp_set_num_threads(saved);
}

// The fused/pipelined red-black smoother (several sweeps in one pass, threads working on
// row chunks) must do exactly what plain sequential half-sweeps do.
TEST(PoissonKernels, RedBlackSmootherMatchesReference) {
  struct G { int nx, ny; bool px, py; };
  for (G g : {G{64, 64, false, false}, G{37, 53, true, false}, G{200, 130, false, false},
              G{201, 199, true, false}, G{40, 31, true, true}, G{120, 97, false, true}, G{16, 13, false, false}}) {
    Problem p = poisson_problem::disc_problem(g.nx, g.ny, 1.0 / g.nx, g.px, g.py, 100.0, cos_cos);
    MultigridHierarchy h;
    h.setup(p.op(), PoissonOptions{});
    const mg::Stencil s = h.stencil(0);
    Field x0(g.nx, g.ny, 1), f(g.nx, g.ny, 1);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        x0(i, j) = std::sin(0.3 * i * j + i);
        f(i, j) = std::cos(i + 2.0 * j);
      }
    mg::fill_ghosts(s, x0.view());
    auto X = [&](const Field& a, int i, int j) { return a((i + g.nx) % g.nx, (j + g.ny) % g.ny); };
    for (int sweeps : {1, 2, 3})
      for (bool black_first : {false, true}) {
        Field ref = x0;
        for (int sw = 0; sw < sweeps; ++sw)
          for (int half = 0; half < 2; ++half) {
            const int c = black_first ? 1 - half : half;
            const Field old = ref;
            for (int j = 0; j < g.ny; ++j)
              for (int i = 0; i < g.nx; ++i)
                if (((i + j) & 1) == c) {
                  const double g = stencil5_relax(s.tx(i, j), s.tx(i + 1, j), s.ty(i, j), s.ty(i, j + 1),
                                                  X(old, i - 1, j), X(old, i + 1, j), X(old, i, j - 1),
                                                  X(old, i, j + 1), f(i, j), s.invd(i, j));
                  ref(i, j) = old(i, j) + 1.25 * (g - old(i, j));
                }
          }
        for (int threads : {1, 2}) {
          Field x = x0;
          mg::Stencil st = s;
          st.threads = threads;
          mg::smooth_rbgs(st, x.view(), f.cview(), sweeps, black_first, 1.25);
          double d = 0.0;
          for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) d = std::max(d, std::abs(x(i, j) - ref(i, j)));
          if (g.px)
            for (int j = 0; j < g.ny; ++j)
              d = std::max({d, std::abs(x(-1, j) - ref(g.nx - 1, j)), std::abs(x(g.nx, j) - ref(0, j))});
          if (g.py)
            for (int i = 0; i < g.nx; ++i)
              d = std::max({d, std::abs(x(i, -1) - ref(i, g.ny - 1)), std::abs(x(i, g.ny) - ref(i, 0))});
          EXPECT_LT(d, 1e-13) << g.nx << "x" << g.ny << " px=" << g.px << " py=" << g.py
                              << " sweeps=" << sweeps << " black_first=" << black_first
                              << " threads=" << threads;
        }
      }
  }
}

// The fused passes of the V-cycle (pre-smoothing + residual restriction, prolongation +
// post-smoothing, walls in y: one pipelined pass each) must give exactly what the separate
// kernels give (same arithmetic per value, so bit for bit; checked to 1e-14 relative to
// allow for a different FMA contraction), on one and two threads, and fall back to the
// separate kernels for periodic y.
TEST(PoissonKernels, FusedPassesMatchSeparateKernels) {
  struct G { int nx, ny; bool px, py; };
  for (G g : {G{64, 64, false, false}, G{37, 53, true, false}, G{200, 130, false, false},
              G{201, 199, true, false}, G{40, 31, true, true}, G{120, 97, false, true},
              G{16, 13, false, false}, G{8, 128, true, false}}) {
    Problem p = poisson_problem::disc_problem(g.nx, g.ny, 1.0 / g.nx, g.px, g.py, 100.0, cos_cos);
    MultigridHierarchy h;
    h.setup(p.op(), PoissonOptions{});
    ASSERT_GE(h.num_levels(), 2);
    const auto& L0 = h.level(0);
    const auto& L1 = h.level(1);
    const mg::Stencil s = h.stencil(0);
    poisson_problem::FusedPassInputs in(g.nx, g.ny, L1.nx, L1.ny);
    Field& x0 = in.x0;
    const Field& f = in.f;
    Field& xc = in.xc;
    mg::fill_ghosts(s, x0.view());
    mg::fill_ghosts(h.stencil(1), xc.view());
    for (int sweeps : {1, 2, 3})
      for (bool black_first : {false, true}) {
        // separate kernels, one thread
        poisson_problem::FusedPassOutputs ref{x0, Field(L1.nx, L1.ny, 1), x0};
        mg::smooth_rbgs(s, ref.x.view(), f.cview(), sweeps, black_first, 1.25);
        mg::residual_restrict(s, ref.x.cview(), f.cview(), L0.trx, L0.try_, ref.fc.view(), h.scratch());
        mg::prolong_add(s, L0.trx, L0.try_, xc.cview(), ref.x2.view(), h.scratch());
        mg::smooth_rbgs(s, ref.x2.view(), f.cview(), sweeps, black_first, 1.25, &ref.r2);
        for (int threads : {1, 2}) {
          mg::Stencil st = s;
          st.threads = threads;
          poisson_problem::FusedPassOutputs got{x0, Field(L1.nx, L1.ny, 1), x0};
          mg::smooth_rbgs_restrict(st, got.x.view(), f.cview(), sweeps, black_first, 1.25, L0.trx,
                                   L0.try_, got.fc.view(), h.scratch());
          mg::prolong_smooth_rbgs(st, L0.trx, L0.try_, xc.cview(), got.x2.view(), f.cview(), sweeps,
                                  black_first, 1.25, h.scratch(), &got.r2);
          poisson_problem::expect_same_passes(got, ref, 1e-12,
                                              std::to_string(g.nx) + "x" + std::to_string(g.ny) +
                                                  " px=" + std::to_string(g.px) + " py=" + std::to_string(g.py) +
                                                  " sweeps=" + std::to_string(sweeps) +
                                                  " black_first=" + std::to_string(black_first) +
                                                  " threads=" + std::to_string(threads));
        }
      }
  }
}

// The V-cycle used by mgpcg must be a symmetric negative-definite linear operator.
TEST(PoissonMultigrid, VCyclePreconditionerIsSymmetric) {
  struct G { int nx, ny; bool px, py; double ratio; const char* smoother; };
  for (G g : {G{64, 64, false, false, 1000, "rbgs"}, G{45, 37, true, false, 100, "rbgs"},
              G{33, 41, true, true, 10, "rbgs"}, G{50, 70, false, false, 1000, "jacobi"},
              G{47, 29, true, true, 1, "jacobi"}}) {
    Problem p = poisson_problem::disc_problem(g.nx, g.ny, 1.0 / g.nx, g.px, g.py, g.ratio, cos_cos);
    MultigridHierarchy h;
    h.setup(p.op(), options("mgpcg", "V", g.smoother), /*symmetric=*/true);
    Field a(g.nx, g.ny, 1), b(g.nx, g.ny, 1), va(g.nx, g.ny, 1), vb(g.nx, g.ny, 1);
    double sa = 0, sb = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        a(i, j) = std::sin(1.3 * i + 0.7 * j * j) ;
        b(i, j) = std::cos(0.37 * i * j + 2.1 * i);
        sa += a(i, j);
        sb += b(i, j);
      }
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        a(i, j) -= sa / (g.nx * g.ny);
        b(i, j) -= sb / (g.nx * g.ny);
      }
    h.precondition(a.cview(), va.view());
    h.precondition(b.cview(), vb.view());
    double ab = 0, ba = 0, aa = 0, norm = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        ab += va(i, j) * b(i, j);
        ba += a(i, j) * vb(i, j);
        aa += va(i, j) * a(i, j);
        norm += std::abs(va(i, j) * b(i, j));
      }
    EXPECT_NEAR(ab, ba, 1e-11 * norm) << g.nx << "x" << g.ny;
    EXPECT_LT(aa, 0.0);
  }
}

}  // namespace
}  // namespace refmap
