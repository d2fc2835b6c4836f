// Poisson solver benchmarks (Google Benchmark). Thread count: OMP_NUM_THREADS.
// Grids N x N, N = 128, 256, 512, 1024, 2048 (the problem of tests/fixtures/poisson_problem.hpp).
//
//   PoissonSmoother/N         one red-black Gauss-Seidel sweep on the finest level (one pass)
//   PoissonSmootherTwoSweeps/N  two RB-GS sweeps pipelined into one pass (walls in y);
//                             counters per sweep (cells_per_s counts 2 n^2 per call)
//   PoissonSmootherJacobi/N   one weighted-Jacobi sweep
//   PoissonResidual/N         r = f - L x (stored) + ||r||^2
//   PoissonRestrict/N         fused residual + P^T restriction to the next level
//   PoissonProlong/N          x_f += P x_c
//   PoissonVCycle/N/R         one V(2,2) cycle (all levels), density ratio R
//   PoissonSolve/<m>/N/R      the pressure solver study: the standard problem
//                             standard_problem(N, R) (tests/fixtures/poisson_problem.hpp) solved from
//                             x = 0 to a relative residual ||r||_2 / ||rhs||_2 <= 1e-8 (rhs
//                             projected to zero mean), m in {V, F, cg, mgpcg}: multigrid
//                             V(2,2) / F(2,2) cycles, Jacobi-preconditioned CG, CG
//                             preconditioned by one V-cycle. N = 128 ... 2048, R = 1, 10,
//                             1000; plain CG only up to N = 512 (its iteration count grows
//                             like N, so 1024^2 and 2048^2 would dominate the run time).
//                             The time is the whole solve (setup of the hierarchy excluded).
//   PoissonContrast/<m>/<co>/N/R  the same solve for m in {V, F, mgpcg} with coarse
//                             operator co in {average, harmonic, galerkin} (solver.coarse_operator),
//                             N = 256 ... 2048 ("harmonic" only up to 512), R = 1, 1000
//                             (bench/run_poisson_contrast.sh -> results/poisson_contrast.csv)
//
// Kernel counters (bench/bench_counters.hpp): cells_per_s = finest cells processed per
// second (per sweep / cycle); GB/s = bytes_per_cell * cells_per_s; GFlop/s =
// flops_per_cell * cells_per_s. bytes_per_cell is the compulsory DRAM traffic of the
// kernel under the assumption that the neighbouring rows stay in cache (one read of every
// input array and one write of every output array per cell, 8 B each, write-allocate not
// counted, face arrays counted as one value per cell). flops_per_cell counts add, sub and
// mul from the source loops in kernels/multigrid.cpp (an FMA counts as 2):
//   RB-GS sweep   reads x, f, tx, ty, invd, writes x             = 6 x 8 = 48 B/cell
//                 (two pipelined sweeps: the same 48 B/cell for both = 24 B/cell/sweep)
//                 g = (4 mul + 3 add + 1 sub) * invd (1 mul); x += omega (g - x)
//                 (sub, mul, add)                                = 12 flop/cell
//   Jacobi sweep  same arrays, same arithmetic                    = 48 B, 12 flop/cell
//   residual      reads x, f, tx, ty, writes r                   = 5 x 8 = 40 B/cell
//                 4 differences, 4 mul, 3 add, 1 sub, r^2 sum (2) = 14 flop/cell
//   restrict      reads x, f, tx, ty, writes coarse f (1/4)      = 34 B/cell
//                 residual 12, x-restriction (2 add, 2 mul, 1 add per coarse value, half
//                 a value per fine cell) 2.5, y-restriction (4 fine rows x (mul, add) per
//                 coarse cell, a quarter per fine cell) 2          = 16.5 flop/cell
//   prolong       reads and writes x_f, reads coarse x (1/4)     = 18 B/cell
//                 y-interpolation (2 mul, 1 add per coarse value, half per fine cell) 1.5,
//                 x-interpolation 0.75 t (0.5) + (mul, add, add) 3 = 5 flop/cell
//   V-cycle       V(2,2) as the solver runs it (walls in y): one pass for the 2 pre-sweeps
//                 with the residual restriction fused (48 B + coarse f 2 B; 24 + 16.5 flop),
//                 one pass for the prolongation and the 2 post-sweeps with the convergence
//                 residual fused (coarse x 2 B + 48 B; 5 + 24 + 14 flop), x 4/3 for the
//                 coarser levels: 100 * 4/3 ~ 133 B/cell, 83.5 * 4/3 ~ 111 flop/cell
//                 (an estimate; the periodic-y path needs one pass per sweep and separate
//                 restriction and prolongation passes, 200 B/cell)
//
// Solver counters (PoissonSolve): iterations (cycles / CG steps), rel_residual (the
// solver's final ||r||_2 / ||rhs||_2), ref_residual (the same measured independently by
// poisson_problem::reference_residual after the timed loop), conv_factor =
// rel_residual^(1/iterations) (mean residual reduction per cycle / CG step, from 1 at
// x = 0), ns_per_unknown = wall time of one solve / N^2 (flat in N for an optimal solver),
// cells_per_s, threads.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "bench/bench_counters.hpp"
#include "kernels/multigrid.hpp"
#include "solver/pressure/poisson.hpp"
#include "solver/scene/option_names.hpp"
#include "solver/pressure/poisson_multigrid.hpp"
#include "tests/fixtures/poisson_problem.hpp"

namespace {

using namespace refmap;

void set_counters(benchmark::State& state, double cells_per_iter, double bytes_per_cell,
                  double flops_per_cell) {
  bench::set_kernel_counters(state, cells_per_iter, bytes_per_cell, flops_per_cell);
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
  set_counters(state, double(n) * n, 48, 12);
}

void BM_Smoother2(benchmark::State& state) {  // two sweeps fused into one pass
  const int n = int(state.range(0));
  KernelSetup k(n);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    mg::smooth_rbgs(s, k.x.view(), k.f.cview(), 2, false, 1.25);
    benchmark::ClobberMemory();
  }
  set_counters(state, 2.0 * n * n, 24, 12);  // per sweep: one pass (48 B/cell) for two sweeps
}

void BM_SmootherJacobi(benchmark::State& state) {
  const int n = int(state.range(0));
  KernelSetup k(n);
  const mg::Stencil s = k.h.stencil(0);
  for (auto _ : state) {
    mg::smooth_jacobi(s, k.x.view(), k.f.cview(), 1, 0.8, k.h.scratch());
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 48, 12);
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
  set_counters(state, double(n) * n, 40, 14);
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
  set_counters(state, double(n) * n, 34, 16.5);
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
  set_counters(state, double(n) * n, 18, 5);
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
  set_counters(state, double(n) * n, 133, 111);
}

/// The problem and solver of the last PoissonSolve case, kept across repetitions and
/// across the four methods of one (N, R) (only one at a time, to bound memory).
struct SolveCache {
  int n = 0;
  double ratio = 0;
  std::unique_ptr<poisson_problem::Problem> p;
  std::string method;
  std::unique_ptr<PoissonSolver> solver;
};

SolveCache& solve_case(const std::string& method, int n, double ratio,
                       const std::string& coarse = "") {
  static SolveCache c;
  if (!c.p || c.n != n || c.ratio != ratio) {
    c.solver.reset();
    c.p.reset();
    c.p = std::make_unique<poisson_problem::Problem>(poisson_problem::standard_problem(n, ratio));
    c.n = n;
    c.ratio = ratio;
    c.method.clear();
  }
  if (!c.solver || c.method != method + "/" + coarse) {
    PoissonOptions o;
    o.tol = 1e-8;
    o.max_iter = 100000;
    // "V" / "F": multigrid with that cycle; else a method name (solver/scene/option_names.hpp)
    if (const auto cycle = parse_option<MgCycle>(method)) {
      o.method = PoissonMethod::Multigrid;
      o.cycle = *cycle;
    } else if (const auto m = parse_option<PoissonMethod>(method)) {
      o.method = *m;
    } else {
      throw std::invalid_argument("bench_poisson: unknown method " + method);
    }
    c.solver.reset();
    if (!coarse.empty()) {
      const auto co = parse_option<MgCoarseOperator>(coarse);
      if (!co) throw std::invalid_argument("bench_poisson: unknown coarse operator " + coarse);
      o.coarse_operator = *co;
    }
    c.solver = make_poisson_solver(o);
    c.solver->setup(c.p->op());
    c.method = method + "/" + coarse;
  }
  return c;
}

void BM_Solve(benchmark::State& state, std::string method, std::string coarse = "") {
  const int n = int(state.range(0));
  const double ratio = double(state.range(1));
  SolveCache& c = solve_case(method, n, ratio, coarse);
  Field x(n, n);
  SolveStats st;
  for (auto _ : state) {
    state.PauseTiming();
    x.fill(0.0);
    state.ResumeTiming();
    st = c.solver->solve(c.p->rhs, x);
  }
  if (!st.converged) state.SkipWithError("did not converge");
  const double cells = double(n) * n * double(state.iterations());
  state.counters["iterations"] = st.iterations;
  state.counters["rel_residual"] = st.rel_residual;
  state.counters["ref_residual"] = poisson_problem::reference_residual(*c.p, x);
  state.counters["conv_factor"] =
      st.iterations > 0 && st.rel_residual > 0 ? std::pow(st.rel_residual, 1.0 / st.iterations)
                                               : 0.0;
  state.counters["ns_per_unknown"] = benchmark::Counter(
      cells * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cells_per_s"] = benchmark::Counter(cells, benchmark::Counter::kIsRate);
  state.counters["threads"] = omp_get_max_threads();
}

/// MultigridSolver::setup alone (the hierarchy's coefficients; called every time step when
/// beta changes) for each coarse operator: what "galerkin" adds per step.
void BM_Setup(benchmark::State& state, std::string coarse) {
  const int n = int(state.range(0));
  const double ratio = double(state.range(1));
  const auto p = poisson_problem::standard_problem(n, ratio);
  PoissonOptions o;
  o.coarse_operator = *parse_option<MgCoarseOperator>(coarse);
  auto solver = make_poisson_solver(o);
  solver->setup(p.op());  // storage allocated once, as in a run
  for (auto _ : state) solver->setup(p.op());
  state.counters["ns_per_unknown"] = benchmark::Counter(
      double(n) * n * double(state.iterations()) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void grids(benchmark::internal::Benchmark* b) {
  for (int n : {128, 256, 512, 1024, 2048}) b->Arg(n);
  b->UseRealTime();
}

BENCHMARK(BM_Smoother)->Name("PoissonSmoother")->Apply(grids);
BENCHMARK(BM_Smoother2)->Name("PoissonSmootherTwoSweeps")->Apply(grids);
BENCHMARK(BM_SmootherJacobi)->Name("PoissonSmootherJacobi")->Apply(grids);
BENCHMARK(BM_Residual)->Name("PoissonResidual")->Apply(grids);
BENCHMARK(BM_Restrict)->Name("PoissonRestrict")->Apply(grids);
BENCHMARK(BM_Prolong)->Name("PoissonProlong")->Apply(grids);
BENCHMARK(BM_VCycle)
    ->Name("PoissonVCycle")
    ->ArgsProduct({{128, 256, 512, 1024, 2048}, {1, 1000}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

constexpr int kCgMaxN = 512;  // plain CG: O(N) iterations, only up to 512^2

const int registered = [] {
  // (N, R) outer so the cached problem is shared by the four methods
  for (int n : {128, 256, 512, 1024, 2048})
    for (int ratio : {1, 10, 1000})
      for (const char* m : {"V", "F", "mgpcg", "cg"}) {
        if (std::string(m) == "cg" && n > kCgMaxN) continue;
        benchmark::RegisterBenchmark(("PoissonSolve/" + std::string(m)).c_str(), BM_Solve,
                                     std::string(m), std::string())
            ->Args({n, ratio})
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
  // the density-contrast study (bench/run_poisson_contrast.sh): V-cycles and MGPCG with
  // each coarse operator (PoissonOptions::coarse_operator), ratio 1 and 1000
  for (int n : {256, 512, 1024, 2048})
    for (int ratio : {1, 1000})
      for (const char* m : {"V", "F", "mgpcg"})
        for (const char* co : {"average", "harmonic", "galerkin"}) {
          // "harmonic" needs hundreds of cycles at ratio 1000 from 1024^2 on: small grids only
          if (std::string(co) == "harmonic" && n > 512) continue;
          benchmark::RegisterBenchmark(
              ("PoissonContrast/" + std::string(m) + "/" + co).c_str(), BM_Solve, std::string(m),
              std::string(co))
              ->Args({n, ratio})
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime();
        }
  for (const char* co : {"average", "galerkin"})
    benchmark::RegisterBenchmark(("PoissonContrastSetup/" + std::string(co)).c_str(), BM_Setup, std::string(co))
        ->ArgsProduct({{256, 512, 1024, 2048}, {1000}})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  return 0;
}();

}  // namespace
