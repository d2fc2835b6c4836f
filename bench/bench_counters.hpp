#pragma once
// Counters shared by the stencil-kernel benchmarks (bench_fluid.cpp, bench_poisson.cpp) and
// the machine-limit benchmarks (bench_machine.cpp), so that bench/summarise.py can put every
// kernel on the same roofline as the measured STREAM bandwidth and FMA peak.
//
//   cells_per_s     cells processed per second of wall time
//   GB/s            bytes_per_cell * cells_per_s * 1e-9 (the per-cell traffic model stated
//                   in each benchmark file: every array read or written once per cell, 8 B,
//                   write-allocate NOT counted; the STREAM benchmarks use the same convention)
//   GFlop/s         flops_per_cell * cells_per_s * 1e-9 (flops counted from the source;
//                   an FMA counts as 2)
//   bytes_per_cell, flops_per_cell   the model figures themselves (iteration invariant), so
//                   the arithmetic intensity flops/byte can be read from the JSON
//   threads         omp_get_max_threads()
#include <benchmark/benchmark.h>
#include <omp.h>

namespace refmap::bench {

inline void set_kernel_counters(benchmark::State& state, double cells_per_iter,
                                double bytes_per_cell, double flops_per_cell) {
  const double cells = cells_per_iter * double(state.iterations());
  state.counters["cells_per_s"] = benchmark::Counter(cells, benchmark::Counter::kIsRate);
  state.counters["GB/s"] =
      benchmark::Counter(cells * bytes_per_cell * 1e-9, benchmark::Counter::kIsRate);
  state.counters["GFlop/s"] =
      benchmark::Counter(cells * flops_per_cell * 1e-9, benchmark::Counter::kIsRate);
  state.counters["bytes_per_cell"] = bytes_per_cell;
  state.counters["flops_per_cell"] = flops_per_cell;
  state.counters["threads"] = omp_get_max_threads();
}

}  // namespace refmap::bench
