// Poisson solver benchmarks (Google Benchmark). Thread count: OMP_NUM_THREADS.
//
//   PoissonSmoother/N         one red-black Gauss-Seidel sweep on the finest level (one pass)
//   PoissonSmootherTwoSweeps/N  two RB-GS sweeps pipelined into one pass (walls in y);
//                             counters per sweep (cells_per_s counts 2 n^2 per call)
//   PoissonSmootherJacobi/N   one weighted-Jacobi sweep
//   PoissonResidual/N         r = f - L x (stored) + ||r||^2
//   PoissonRestrict/N         fused residual + P^T restriction to the next level
//   PoissonProlong/N          x_f += P x_c
//   PoissonVCycle/N/R         one V(2,2) cycle (all levels), density ratio R
//   PoissonSolve/<m>/N/R      the standard study problem (bench/poisson_problem.hpp) solved
//                             from x = 0 to 1e-8 relative residual, m in {V, F, cg, mgpcg}
//
// Counters: cells_per_s = finest cells processed per second (per sweep / cycle / solve);
// GB/s = bytes_per_cell * cells_per_s with bytes_per_cell the compulsory DRAM traffic of the
// kernel under the assumption that the neighbouring rows stay in cache (one read of every
// input array and one write of every output array per cell, write-allocate not counted,
// face arrays counted as one value per cell):
//   RB-GS sweep   reads x, f, tx, ty, invd, writes x             = 6 x 8 = 48 B/cell
//                 (two pipelined sweeps: the same 48 B/cell for both = 24 B/cell/sweep)
//   Jacobi sweep  same arrays                                    = 48 B/cell
//   residual      reads x, f, tx, ty, writes r                   = 5 x 8 = 40 B/cell
//   restrict      reads x, f, tx, ty, writes coarse f (1/4)      = 34 B/cell
//   prolong       reads and writes x_f, reads coarse x (1/4)     = 18 B/cell
//   V-cycle       V(2,2) as the solver runs it: 2 pre-sweeps in one pass (48), restrict
//                 (34), prolong (18), 2 post-sweeps in one pass with the convergence
//                 residual fused (48), x 4/3 for the coarser levels: 148 * 4/3 ~ 200 B/cell
//                 (an estimate; the periodic-y path needs one pass per sweep)
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <memory>
#include <string>

#include "bench/poisson_problem.hpp"
#include "kernels/multigrid.hpp"
#include "solver/poisson.hpp"
#include "solver/poisson_multigrid.hpp"

namespace {

using namespace refmap;

void set_counters(benchmark::State& state, double cells_per_iter, double bytes_per_cell) {
  const double cells = cells_per_iter * double(state.iterations());
  state.counters["cells_per_s"] = benchmark::Counter(cells, benchmark::Counter::kIsRate);
  state.counters["GB/s"] =
      benchmark::Counter(cells * bytes_per_cell * 1e-9, benchmark::Counter::kIsRate);
}

struct KernelSetup {
  poisson_problem::Problem p;
  MultigridHierarchy h;
  Field x, f;
  explicit KernelSetup(int n, double ratio = 1.0) : p(poisson_problem::standard_problem(n, ratio)) {
    h.setup(p.op(), PoissonOptions{});
    x.resize(n, n, 1);
    f.resize(n, n, 1);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        x(i, j) = std::sin(0.1 * i) * std::cos(0.07 * j);
        f(i, j) = p.rhs(i, j) * p.grid.dx * p.grid.dx;
      }
    mg::fill_ghosts(h.stencil(0), x.view());
  }
};

void BM_Smoother(benchmark::State& state) {
  const int n = int(state.range(0));
  KernelSetup k(n);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    mg::smooth_rbgs(s, k.x.view(), k.f.cview(), 1, false, 1.25);
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 48);
}

void BM_Smoother2(benchmark::State& state) {  // two sweeps fused into one pass
  const int n = int(state.range(0));
  KernelSetup k(n);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    mg::smooth_rbgs(s, k.x.view(), k.f.cview(), 2, false, 1.25);
    benchmark::ClobberMemory();
  }
  set_counters(state, 2.0 * n * n, 24);  // per sweep: one pass (48 B/cell) for two sweeps
}

void BM_SmootherJacobi(benchmark::State& state) {
  const int n = int(state.range(0));
  KernelSetup k(n);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    mg::smooth_jacobi(s, k.x.view(), k.f.cview(), 1, 0.8, k.h.scratch());
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 48);
}

void BM_Residual(benchmark::State& state) {
  const int n = int(state.range(0));
  KernelSetup k(n);
  Field r(n, n, 1);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(mg::residual(s, k.x.cview(), k.f.cview(), r.view()));
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 40);
}

void BM_Restrict(benchmark::State& state) {
  const int n = int(state.range(0));
  KernelSetup k(n);
  const auto& L0 = k.h.level(0);
  Field fc(k.h.level(1).nx, k.h.level(1).ny, 1);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    mg::residual_restrict(s, k.x.cview(), k.f.cview(), L0.trx, L0.try_, fc.view(), k.h.scratch());
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 34);
}

void BM_Prolong(benchmark::State& state) {
  const int n = int(state.range(0));
  KernelSetup k(n);
  const auto& L0 = k.h.level(0);
  Field xc(k.h.level(1).nx, k.h.level(1).ny, 1);
  xc.fill(1e-3);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    mg::prolong_add(s, L0.trx, L0.try_, xc.cview(), k.x.view(), k.h.scratch());
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 18);
}

void BM_VCycle(benchmark::State& state) {
  const int n = int(state.range(0));
  const double ratio = double(state.range(1));
  poisson_problem::Problem p = poisson_problem::standard_problem(n, ratio);
  MultigridHierarchy h;
  h.setup(p.op(), PoissonOptions{});
  Field x(n, n, 1), f(n, n, 1);
  const mg::Stencil s = h.stencil(0);
  const double mean = poisson_problem::mean(p.rhs);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) f(i, j) = (p.rhs(i, j) - mean) * p.grid.dx * p.grid.dx;
  double r0 = std::sqrt(mg::residual(s, x.cview(), f.cview(), View{}));
  double r = r0;
  int cycles = 0;
  for (auto _ : state) {
    double r2 = 0.0;
    h.cycle(x.view(), f.cview(), false, &r2);  // with the solver's convergence residual
    r = std::sqrt(r2);
    ++cycles;
    if (r < 1e-9 * r0) {  // keep measuring real work: restart before the round-off floor
      state.PauseTiming();
      x.fill(0.0);
      r0 = std::sqrt(mg::residual(s, x.cview(), f.cview(), View{}));
      state.ResumeTiming();
    }
  }
  state.counters["levels"] = h.num_levels();
  set_counters(state, double(n) * n, 200);
}

void BM_Solve(benchmark::State& state, std::string method) {
  const int n = int(state.range(0));
  const double ratio = double(state.range(1));
  poisson_problem::Problem p = poisson_problem::standard_problem(n, ratio);
  PoissonOptions o;
  o.tol = 1e-8;
  o.max_iter = 100000;
  if (method == "V" || method == "F") {
    o.method = "multigrid";
    o.cycle = method;
  } else {
    o.method = method;
  }
  auto solver = make_poisson_solver(o);
  solver->setup(p.op());
  Field x(n, n);
  SolveStats st;
  for (auto _ : state) {
    state.PauseTiming();
    x.fill(0.0);
    state.ResumeTiming();
    st = solver->solve(p.rhs, x);
  }
  if (!st.converged) state.SkipWithError("did not converge");
  state.counters["iterations"] = st.iterations;
  state.counters["rel_residual"] = st.rel_residual;
  state.counters["threads"] = omp_get_max_threads();
  state.counters["cells_per_s"] =
      benchmark::Counter(double(n) * n * double(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_Smoother)->Name("PoissonSmoother")->Arg(256)->Arg(1024)->UseRealTime();
BENCHMARK(BM_Smoother2)->Name("PoissonSmootherTwoSweeps")->Arg(256)->Arg(1024)->UseRealTime();
BENCHMARK(BM_SmootherJacobi)->Name("PoissonSmootherJacobi")->Arg(256)->Arg(1024)->UseRealTime();
BENCHMARK(BM_Residual)->Name("PoissonResidual")->Arg(256)->Arg(1024)->UseRealTime();
BENCHMARK(BM_Restrict)->Name("PoissonRestrict")->Arg(256)->Arg(1024)->UseRealTime();
BENCHMARK(BM_Prolong)->Name("PoissonProlong")->Arg(256)->Arg(1024)->UseRealTime();
BENCHMARK(BM_VCycle)
    ->Name("PoissonVCycle")
    ->Args({256, 1})
    ->Args({256, 1000})
    ->Args({1024, 1})
    ->Args({1024, 1000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

const int registered = [] {
  for (const char* m : {"V", "F", "mgpcg", "cg"})
    for (int n : {256, 1024})
      for (int ratio : {1, 10, 1000})
        benchmark::RegisterBenchmark(("PoissonSolve/" + std::string(m)).c_str(), BM_Solve, std::string(m))
            ->Args({n, ratio})
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
  return 0;
}();

}  // namespace
