// FastMarching/<N>/<band>: reinitialisation of the level set of a disc of radius 0.15 N
// cells centred in an N x N grid (whole-grid window), band in cells. The input is a
// perturbed (non-distance) level set of the disc, re-copied before every call (the
// copy is excluded from the timing).
#include <benchmark/benchmark.h>

#include <cmath>

#include "kernels/fast_marching.hpp"
#include "core/field.hpp"

using namespace refmap;

static void BM_FastMarching(benchmark::State& state) {
  const int n = int(state.range(0));
  const double band_cells = double(state.range(1));
  const double dx = 1.0 / n, band = band_cells * dx;
  const double cx = 0.5, cy = 0.5, r = 0.15;
  Field src(n, n, 2), phi(n, n, 2);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
      src(i, j) = (std::hypot(x - cx, y - cy) - r) * (1.0 + 0.5 * (x - cx) * (x - cx));
    }
  FmmWorkspace ws;
  FmmStats st{};
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(src.raw(), src.raw() + src.raw_size(), phi.raw());
    state.ResumeTiming();
    st = reinitialise_fmm(phi.view(), n, n, dx, band, ws);
    benchmark::DoNotOptimize(phi.raw());
  }
  state.counters["init"] = st.accepted_init;
  state.counters["marched"] = st.marched;
  state.counters["ns_per_band_cell"] = benchmark::Counter(
      double(st.accepted_init + st.marched), benchmark::Counter::kIsIterationInvariantRate |
                                                 benchmark::Counter::kInvert);
}
BENCHMARK(BM_FastMarching)
    ->Name("FastMarching")
    ->ArgsProduct({{100, 200, 400, 800}, {6}})
    ->Unit(benchmark::kMicrosecond);

// The solver's typical call: a window around one solid (disc radius 15 cells, band 6,
// window = bbox + band + 2 cells).
static void BM_FastMarchingSolidWindow(benchmark::State& state) {
  const double rc = double(state.range(0));  // radius in cells
  const double band_cells = 6.0;
  const int n = int(2 * (rc + band_cells + 2));
  const double dx = 1.0, c = 0.5 * n;
  Field src(n, n, 2), phi(n, n, 2);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = i + 0.5, y = j + 0.5;
      src(i, j) = (std::hypot(x - c, y - c) - rc) * (1.0 + 0.01 * (x - c));
    }
  FmmWorkspace ws;
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(src.raw(), src.raw() + src.raw_size(), phi.raw());
    state.ResumeTiming();
    reinitialise_fmm(phi.view(), n, n, dx, band_cells * dx, ws);
    benchmark::DoNotOptimize(phi.raw());
  }
  state.counters["window"] = n;
}
BENCHMARK(BM_FastMarchingSolidWindow)->Name("FastMarchingSolidWindow")->Arg(15)->Unit(benchmark::kMicrosecond);
