// Whole time steps of the solver (Google Benchmark). Thread count: OMP_NUM_THREADS.
//
//   WholeFluidStep/N   lid-driven cavity at Re = 1000 (scenes/lid_driven_cavity_re1000.toml:
//                      cfl 0.4, central advection, multigrid V-cycles to 1e-8) on N x N
//                      cells; dt = min(0.4 dx / U_lid, 0.9 rho dx^2 / (6 mu)): advective
//                      at N = 256, viscous-limited at N = 1024
//   WholeSolidStep/N   one soft disc in a decaying Taylor-Green vortex
//                      (scenes/disc_tgv.toml: LSQ extrapolation, conservative cell stress,
//                      multigrid to 1e-9) on N x N cells
//   ManyDiscsStep/M/N  the same flow with N soft discs of radius 0.2/sqrt(N) on a lattice
//                      on M x M cells (M = 512: the 16 and 64 discs of the scaling goals):
//                      the solids' phases run one solid per thread (kernels/loop.hpp,
//                      parallel_items)
//   Discs1000Step/1024 the 1000 soft discs of radius 0.01 at random places, contact on
//                      (bench/scenes/many_discs_1000.toml, the scene of bench/run_scaling.sh),
//                      against WholeSolidStep/1024 (one disc of radius 0.2, same grid)
//   IncrmtCircles42/128  the 42 spinning circles of the peer code IncRMT's multi-drop example
//                      (bench/scenes/incrmt_circles_42.toml, walls, contact) on 128 x 128:
//                      many small solids on a small grid, where per-solid threading and
//                      the cost of each parallel region matter most
//
// The scenes are inline TOML (load_scene_string) so the benchmark does not depend on the
// working directory. Each Simulation is built once per (scene, N) and kept across the
// repetitions (only one at a time, to bound memory); after construction it runs
// kWarmupSteps steps outside the timing, then dt is fixed to the stable time step of that
// state (Simulation::stable_dt()) and every timed iteration is one sim.step(dt), so the
// flow keeps evolving from one iteration to the next (the Poisson iteration count can vary
// slightly between repetitions).
//
// Counters: cells_per_s (N^2 per step), us_per_cell_step (wall microseconds per cell per
// step), poisson_iters (multigrid cycles of the last timed step), dt, threads.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"

namespace {

using namespace refmap;

constexpr int kWarmupSteps = 3;

const char* kCavityRe1000 = R"(
name = "bench_cavity_re1000"
[domain]
lx = 1.0
[grid]
nx = 128
ny = 128
[fluid]
density = 1.0
viscosity = 0.001
[boundary]
left = "no_slip"
right = "no_slip"
bottom = "no_slip"
top = { type = "moving_wall", velocity = 1.0 }
[initial]
velocity = "zero"
[time]
end = 120.0
cfl = 0.4
[solver]
advection = "central"
poisson = "multigrid"
tol = 1e-8
[output]
vtk = false
)";

const char* kDiscTgv = R"(
name = "bench_disc_tgv"
[domain]
lx = 1.0
[grid]
nx = 64
ny = 64
[fluid]
density = 1.0
viscosity = 0.001
[boundary]
left = "free_slip"
right = "free_slip"
bottom = "free_slip"
top = "free_slip"
[initial]
velocity = "taylor_green"
amplitude = 0.3141592653589793
wavenumber = 6.283185307179586
[time]
end = 4.0
cfl = 0.5
[solver]
poisson = "multigrid"
tol = 1e-9
[solids]
extrapolation = "lsq"
conservative = true
[[solid]]
name = "disc"
shape = "circle"
center = [0.5, 0.5]
radius = 0.2
mu_s = 0.5
density = 1.0
velocity = "fluid"
[output]
vtk = false
)";

/// bench/scenes/many_discs_<n>.toml (bench/scenes/make_many_discs.py) as inline TOML: the
/// disc_tgv flow with n discs of radius 0.2/sqrt(n) centred on a sqrt(n) x sqrt(n) lattice.
std::string many_discs_toml(int n) {
  int m = 1;
  while ((m + 1) * (m + 1) <= n) ++m;
  std::string t = kDiscTgv;
  t = t.substr(0, t.find("[[solid]]"));  // the flow without the disc
  const double r = 0.2 / m;
  char buf[256];
  for (int k = 0; k < m * m; ++k) {
    std::snprintf(buf, sizeof buf,
                  "[[solid]]\nname = \"disc%d\"\nshape = \"circle\"\ncenter = [%.6f, %.6f]\n"
                  "radius = %.10g\nmu_s = 0.5\ndensity = 1.0\nvelocity = \"fluid\"\n",
                  k, (k % m + 0.5) / m, (k / m + 0.5) / m, r);
    t += buf;
  }
  return t + "[output]\nvtk = false\n";
}

/// The one cached simulation (scene name + N), with its fixed time step.
struct Cached {
  std::string key;
  std::unique_ptr<Simulation> sim;
  double dt = 0.0;
};

Cached& cached(const char* toml, const std::string& scene, int n, bool from_file = false) {
  static Cached c;
  const std::string key = scene + "/" + std::to_string(n);
  if (c.key != key) {
    c.sim.reset();  // free the previous grid first
    const std::vector<std::string> sets = {"grid.nx=" + std::to_string(n),
                                           "grid.ny=" + std::to_string(n)};
    c.sim = std::make_unique<Simulation>(from_file ? load_scene(toml, sets)
                                                   : load_scene_string(toml, scene + ".toml", sets));
    for (int k = 0; k < kWarmupSteps; ++k) c.sim->step();
    c.dt = c.sim->stable_dt();
    c.key = key;
  }
  return c;
}

/// Times sim.step on the cached simulation of (toml, scene) at n x n cells.
void time_steps(benchmark::State& state, Cached& c, int n) {
  for (auto _ : state) {
    c.sim->step(c.dt);
    benchmark::ClobberMemory();
  }
  const double cells = double(n) * n * double(state.iterations());
  state.counters["cells_per_s"] = benchmark::Counter(cells, benchmark::Counter::kIsRate);
  // (cells * 1e-6 / s)^-1 = microseconds per cell-step
  state.counters["us_per_cell_step"] = benchmark::Counter(
      cells * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["threads"] = omp_get_max_threads();
}

void run_steps(benchmark::State& state, const char* toml, const std::string& scene) {
  const int n = int(state.range(0));
  Cached& c = cached(toml, scene, n);
  time_steps(state, c, n);
  state.counters["poisson_iters"] = c.sim->last_poisson_iterations();
  state.counters["dt"] = c.dt;
}

void BM_WholeFluidStep(benchmark::State& state) { run_steps(state, kCavityRe1000, "cavity"); }
void BM_WholeSolidStep(benchmark::State& state) { run_steps(state, kDiscTgv, "disc_tgv"); }
void BM_ManyDiscsStep(benchmark::State& state) {
  // range(0): the grid (n x n cells), range(1): the number of discs
  const int n = int(state.range(0)), discs = int(state.range(1));
  static std::string toml;
  toml = many_discs_toml(discs);
  Cached& c = cached(toml.c_str(), "many_discs_" + std::to_string(discs), n);
  time_steps(state, c, n);
  state.counters["solids"] = discs;
}

void BM_IncrmtCircles42(benchmark::State& state) {
  const int n = int(state.range(0));
  Cached& c = cached(REFMAP_SOURCE_DIR "/bench/scenes/incrmt_circles_42.toml", "incrmt_circles_42", n, true);
  time_steps(state, c, n);
  state.counters["solids"] = 42;
}

// 1000 soft discs of 10 cells' radius on 1024^2, contact on (results/performance.md, "Many solids"; the scene
// of bench/run_scaling.sh): against WholeSolidStep/1024 (one disc), the cost of many solids
void BM_Discs1000Step(benchmark::State& state) {
  const int n = int(state.range(0));
  Cached& c = cached(REFMAP_SOURCE_DIR "/bench/scenes/many_discs_1000.toml", "many_discs_1000", n, true);
  time_steps(state, c, n);
  state.counters["solids"] = 1000;
}

}  // namespace

BENCHMARK(BM_Discs1000Step)->Name("Discs1000Step")->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_IncrmtCircles42)->Name("IncrmtCircles42")->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WholeFluidStep)
    ->Name("WholeFluidStep")
    ->Arg(256)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_WholeSolidStep)
    ->Name("WholeSolidStep")
    ->Arg(256)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ManyDiscsStep)
    ->Name("ManyDiscsStep")
    ->Args({512, 16})
    ->Args({512, 64})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
