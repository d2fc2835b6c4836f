// Machine limits measured by the harness itself (Google Benchmark), the roof of the
// roofline in results/roofline.png. Thread count: OMP_NUM_THREADS (1 and 2 both work; every
// loop is an OpenMP loop or region over all threads).
//
//   MachineStreamCopy/<MiB>   c[i] = a[i]             over arrays of <MiB> MiB each
//   MachineStreamTriad/<MiB>  a[i] = b[i] + s * c[i]  over three arrays of <MiB> MiB each
//   MachineFmaPeak            double-precision FMA throughput: every thread runs kChains
//                             independent FMA chains x <- x * a + b held in vector registers
//                             (AVX-512 / AVX2+FMA intrinsics as -march=native allows, scalar
//                             std::fma otherwise)
//
// The arrays are 128 MiB each (16 Mi doubles): 2 x 128 MiB (Copy) and 3 x 128 MiB (Triad)
// are 8 and 12 times a 32 MiB L3 (the AMD EPYC these VMs ran on) and 5 and 8 times the
// 48 MiB L3 of the Intel Xeon they also run on, so the loops run from DRAM. They are
// allocated once (64-byte aligned) and first touched in parallel with the same static
// schedule as the timed loops.
//
// Byte counting (the STREAM convention, the same as the kernel benchmarks): each array read
// or written counts once, 8 B per element; the write-allocate read of the destination line
// is NOT counted:
//   Copy   read a, write c             = 16 B/element   (24 B with write-allocate)
//   Triad  read b, c, write a          = 24 B/element   (32 B with write-allocate)
// GB/s uses those figures; GB/s_with_wa adds the write-allocate read, which is what the
// hardware moves when the stores are ordinary (cached) stores. The timed loops are plain
// element loops compiled without loop-pattern replacement (no memcpy call, so no
// non-temporal stores from the C library): the destination IS write-allocated, and the true
// DRAM traffic is the GB/s_with_wa figure. Triad counts 2 flops per element (mul + add,
// which the compiler may contract into one FMA).
//
// Counters: GB/s, GB/s_with_wa, GFlop/s (Triad, FmaPeak), bytes_per_cell, flops_per_cell
// (per element for the STREAM loops), threads.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__AVX512F__) || defined(__FMA__)
#include <immintrin.h>
#endif

namespace {

constexpr std::size_t kMiB = 1024 * 1024;

/// Three arrays of `elems` doubles each, kept across benchmark runs (allocation and first
/// touch are not timed).
struct Arrays {
  std::size_t n = 0;
  double *a = nullptr, *b = nullptr, *c = nullptr;
  void ensure(std::size_t elems) {
    if (elems == n) return;
    std::free(a);
    std::free(b);
    std::free(c);
    const std::size_t bytes = (elems * sizeof(double) + 63) / 64 * 64;
    a = static_cast<double*>(std::aligned_alloc(64, bytes));
    b = static_cast<double*>(std::aligned_alloc(64, bytes));
    c = static_cast<double*>(std::aligned_alloc(64, bytes));
    if (!a || !b || !c) throw std::bad_alloc();
    n = elems;
    const long ne = long(elems);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < ne; ++i) {
      a[i] = 1.0;
      b[i] = 2.0;
      c[i] = 0.5;
    }
  }
  ~Arrays() {
    std::free(a);
    std::free(b);
    std::free(c);
  }
};

Arrays& arrays() {
  static Arrays s;
  return s;
}

// Plain loops: no replacement by memcpy/memset (which could use non-temporal stores and
// change what is measured).
__attribute__((noinline, optimize("no-tree-loop-distribute-patterns"))) void stream_copy(
    const double* __restrict a, double* __restrict c, long n) {
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) c[i] = a[i];
}

__attribute__((noinline, optimize("no-tree-loop-distribute-patterns"))) void stream_triad(
    double* __restrict a, const double* __restrict b, const double* __restrict c, double s,
    long n) {
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
}

void stream_counters(benchmark::State& state, double elems, double bytes, double bytes_wa,
                     double flops) {
  const double e = elems * double(state.iterations());
  state.counters["GB/s"] = benchmark::Counter(e * bytes * 1e-9, benchmark::Counter::kIsRate);
  state.counters["GB/s_with_wa"] =
      benchmark::Counter(e * bytes_wa * 1e-9, benchmark::Counter::kIsRate);
  if (flops > 0)
    state.counters["GFlop/s"] = benchmark::Counter(e * flops * 1e-9, benchmark::Counter::kIsRate);
  state.counters["bytes_per_cell"] = bytes;
  state.counters["flops_per_cell"] = flops;
  state.counters["threads"] = omp_get_max_threads();
}

void BM_StreamCopy(benchmark::State& state) {
  const std::size_t n = std::size_t(state.range(0)) * kMiB / sizeof(double);
  Arrays& A = arrays();
  A.ensure(n);
  for (auto _ : state) {
    stream_copy(A.a, A.c, long(n));
    benchmark::ClobberMemory();
  }
  stream_counters(state, double(n), 16, 24, 0);
}

void BM_StreamTriad(benchmark::State& state) {
  const std::size_t n = std::size_t(state.range(0)) * kMiB / sizeof(double);
  Arrays& A = arrays();
  A.ensure(n);
  for (auto _ : state) {
    stream_triad(A.a, A.b, A.c, 3.0, long(n));
    benchmark::ClobberMemory();
  }
  stream_counters(state, double(n), 24, 32, 2);
}

// ---- FMA peak ----------------------------------------------------------------------------
// kChains independent dependency chains: with an FMA latency of 4 cycles and 2 FMA pipes
// at least 8 are needed to keep both pipes busy; 12 leave a margin and, with the two
// constants, still fit the 16 vector registers of AVX2 (AVX-512 has 32).
constexpr int kChains = 12;
constexpr long kRounds = 1 << 16;  // FMAs per chain per call

#if defined(__AVX512F__)
constexpr int kWidth = 8;
using Vec = __m512d;
inline Vec vset(double v) { return _mm512_set1_pd(v); }
inline Vec vfma(Vec x, Vec a, Vec b) { return _mm512_fmadd_pd(x, a, b); }
inline double vsum(Vec x) {  // (not _mm512_reduce_add_pd: GCC 12 warns inside it)
  alignas(64) double t[8];
  _mm512_store_pd(t, x);
  return t[0] + t[1] + t[2] + t[3] + t[4] + t[5] + t[6] + t[7];
}
constexpr const char* kIsa = "avx512";
#elif defined(__FMA__)
constexpr int kWidth = 4;
using Vec = __m256d;
inline Vec vset(double v) { return _mm256_set1_pd(v); }
inline Vec vfma(Vec x, Vec a, Vec b) { return _mm256_fmadd_pd(x, a, b); }
inline double vsum(Vec x) {
  alignas(32) double t[4];
  _mm256_store_pd(t, x);
  return t[0] + t[1] + t[2] + t[3];
}
constexpr const char* kIsa = "avx2-fma";
#else
constexpr int kWidth = 1;
using Vec = double;
inline Vec vset(double v) { return v; }
inline Vec vfma(Vec x, Vec a, Vec b) { return std::fma(x, a, b); }
inline double vsum(Vec x) { return x; }
constexpr const char* kIsa = "scalar";
#endif

/// x <- x * a + b on kChains registers, kRounds times; returns the sum (keeps it live).
/// a < 1 and b = 1 - a: every chain converges to 1, no overflow or denormals.
__attribute__((noinline)) double fma_chains(double seed) {
  const Vec a = vset(0.999999), b = vset(1.0 - 0.999999);
  Vec x[kChains];
#pragma GCC unroll 12
  for (int k = 0; k < kChains; ++k) x[k] = vset(seed + 0.01 * k);
  for (long r = 0; r < kRounds; ++r) {
#pragma GCC unroll 12
    for (int k = 0; k < kChains; ++k) x[k] = vfma(x[k], a, b);
  }
  double s = 0.0;
#pragma GCC unroll 12
  for (int k = 0; k < kChains; ++k) s += vsum(x[k]);
  return s;
}

void BM_FmaPeak(benchmark::State& state) {
  int nthreads = 1;
  for (auto _ : state) {
    double total = 0.0;
#pragma omp parallel reduction(+ : total)
    {
#pragma omp single
      nthreads = omp_get_num_threads();
      total += fma_chains(0.5 + 0.001 * omp_get_thread_num());
    }
    benchmark::DoNotOptimize(total);
  }
  const double flops_per_call = 2.0 * kChains * kWidth * double(kRounds) * nthreads;
  state.counters["GFlop/s"] = benchmark::Counter(flops_per_call * double(state.iterations()) * 1e-9,
                                                 benchmark::Counter::kIsRate);
  state.counters["vector_width"] = kWidth;
  state.counters["chains"] = kChains;
  state.counters["threads"] = omp_get_max_threads();
  state.SetLabel(kIsa);
}

}  // namespace

BENCHMARK(BM_StreamCopy)->Name("MachineStreamCopy")->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StreamTriad)->Name("MachineStreamTriad")->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FmaPeak)->Name("MachineFmaPeak")->Unit(benchmark::kMicrosecond)->UseRealTime();
