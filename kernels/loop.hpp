#pragma once
// The one threading layer of refmap: every parallel loop, team region and reduction of
// the solver goes through this file, so the performance policy (which loops run on more
// than one thread, schedule, team size) and the reduction order live in one place.
//
//  * Row loops: rows of the grid are split statically across OpenMP threads; each kernel
//    body is a plain inner loop over i that the compiler vectorises.
//  * Work threshold: a loop over fewer than min_parallel_cells() cells (kMinParallelCells;
//    kMinParallelCellsPassive when waiting threads sleep) runs on the calling
//    thread as a plain loop, without a parallel region: on small grids (the 8 x 128 elastic
//    Couette layer, small solid windows, coarse multigrid levels) fork/join and barriers
//    cost more than the loop. (Not even an `if (false)` region: libgomp still builds a
//    team of one for it: measured ~2 us per call, as much as an axpy over 128^2 cells.)
//  * Deterministic reductions: a sum over rows stores one partial per row, f(j), and adds
//    the partials serially in row order, so the result has the same bits for any number
//    of threads (an OpenMP reduction clause combines per-thread partial sums in an order
//    that depends on the team size). On one thread this is the order of `s += f(j)`.
//  * Team regions: one persistent parallel region whose threads own contiguous row chunks
//    and synchronise with barriers (the multigrid's fused smoothing passes: one fork/join
//    per pass instead of one per sweep).
//  * Item loops (parallel_items): independent items of very different sizes (the solids:
//    each advects, extrapolates and reinitialises its own window) are spread over the
//    threads one item at a time, largest first, in ONE parallel region; inside it every
//    row loop, sum, item count and team region of this file runs as a plain serial loop
//    (omp_in_parallel()), so an item computes the same bits as on one thread.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <string>
#include <cstddef>
#include <exception>
#include <numeric>
#include <utility>
#include <vector>

namespace refmap {

/// Cells of work below which a loop runs on one thread. Measured on the 2-core VM (AMD
/// EPYC, shared, min of 15 repeats; default wait policy): 2 threads beat 1 from ~9k cells
/// for a 5-point residual norm (~10 flop/cell) and from ~40k for an axpy (bandwidth
/// bound, ~2 us fork/join); with OMP_WAIT_POLICY=PASSIVE (a sleeping partner must be
/// woken, ~10-20 us) only from ~250k. 16384 (128^2) sits between the two kernel kinds and
/// keeps the former multigrid per-level threshold.
inline constexpr std::size_t kMinParallelCells = 16384;
/// The same when waiting threads sleep (OMP_WAIT_POLICY=passive, the user's choice; refmap
/// keeps libgomp's spinning default and shrinks its team beside busy processes instead,
/// solver/app/thread_governor.hpp): every region then wakes its partner (~10-20 us), so small
/// grids (two_solids_tgv's 128^2) ran slower on 2 threads than on 1 (results/threads.md,
/// "Threads across solids"); 256^2 and larger grids keep their row threading.
inline constexpr std::size_t kMinParallelCellsPassive = 65536;

/// True when OMP_WAIT_POLICY says passive (read once).
inline bool passive_wait() {
  static const bool p = [] {
    const char* e = std::getenv("OMP_WAIT_POLICY");
    if (!e) return false;
    std::string v(e);
    for (char& c : v) c = char(std::tolower(static_cast<unsigned char>(c)));
    return v.find("passive") != std::string::npos;
  }();
  return p;
}

/// The work threshold of the wait policy in effect: kMinParallelCells or
/// kMinParallelCellsPassive.
inline std::size_t min_parallel_cells() { return passive_wait() ? kMinParallelCellsPassive : kMinParallelCells; }

/// Team size for a loop over `rows` rows holding `cells` cells in all: 1 below
/// min_parallel_cells() or inside a parallel region (no nested teams), never more threads
/// than rows.
inline int loop_threads(std::size_t cells, int rows) {
  if (cells < min_parallel_cells() || rows < 2 || omp_in_parallel()) return 1;
  return std::max(1, std::min(omp_get_max_threads(), rows));
}

/// Team size for a caller that has already decided to want `want` threads (e.g. a
/// multigrid level's Stencil::threads): never more threads than rows, at least 1.
inline int team_size(int want, int rows) { return std::max(1, std::min(want, rows)); }

/// True inside a parallel region with more than one thread (e.g. a parallel_items region):
/// the loops of this file then run on the calling thread (no nested teams).
inline bool in_parallel_region() { return omp_in_parallel() != 0; }

/// Per-row partial sums of a reduction (on the stack for up to 2048 values).
class RowPartials {
 public:
  explicit RowPartials(std::size_t n) : p_(small_) {
    if (n > kSmall) {
      big_.resize(n);
      p_ = big_.data();
    }
  }
  RowPartials(const RowPartials&) = delete;
  RowPartials& operator=(const RowPartials&) = delete;
  double* data() { return p_; }
  double& operator[](std::size_t k) { return p_[k]; }
  /// Serial sum of values [0, n) with stride `stride` starting at `first`, in order.
  double sum(std::size_t n, std::size_t first = 0, std::size_t stride = 1) const {
    double s = 0.0;
    for (std::size_t k = 0; k < n; ++k) s += p_[first + k * stride];
    return s;
  }

 private:
  static constexpr std::size_t kSmall = 2048;
  double small_[kSmall];
  std::vector<double> big_;
  double* p_;
};

/// Calls f(j) for j in [j0, j1) on a team of (at most) nt threads; nt <= 1: on the
/// calling thread, no parallel region.
template <class F>
inline void parallel_rows_on(int nt, int j0, int j1, F&& f) {
  nt = std::min(nt, j1 - j0);
  if (nt <= 1 || in_parallel_region()) {
    for (int j = j0; j < j1; ++j) f(j);
    return;
  }
#pragma omp parallel for schedule(static) num_threads(nt)
  for (int j = j0; j < j1; ++j) f(j);
}

/// Calls f(j) for j in [j0, j1), rows of row_len cells distributed over the OpenMP team
/// (serially below kMinParallelCells).
template <class F>
inline void parallel_rows(int j0, int j1, int row_len, F&& f) {
  parallel_rows_on(loop_threads(std::size_t(std::max(0, j1 - j0)) * std::size_t(std::max(0, row_len)), j1 - j0),
                   j0, j1, std::forward<F>(f));
}


/// Sets n values from p to v, in blocks of `block` values over the team (serially below
/// the work threshold): the whole-field resets of a step (blended density and viscosity,
/// the contact force) are full passes over memory that one thread cannot saturate.
template <class T>
inline void parallel_fill(T* p, std::size_t n, T v, std::size_t block = 4096) {
  const int nb = int((n + block - 1) / block);
  parallel_rows(0, nb, int(block), [=](int b) {
    const std::size_t a = std::size_t(b) * block, e = std::min(n, a + block);
    std::fill(p + a, p + e, v);
  });
}

/// N sums over rows at once: f(j) returns std::array<double, N> of row j's partials;
/// result k is sum_j f(j)[k] added in row order (same bits for any team size).
template <int N, class F>
inline std::array<double, N> parallel_rows_sums_on(int nt, int j0, int j1, F&& f) {
  std::array<double, N> s{};
  const int n = j1 - j0;
  nt = std::min(nt, n);
  if (nt <= 1 || in_parallel_region()) {  // the same order as the partials below, without storing them
    for (int j = j0; j < j1; ++j) {
      const std::array<double, N> a = f(j);
      for (int k = 0; k < N; ++k) s[k] += a[k];
    }
    return s;
  }
  RowPartials part(std::size_t(n) * N);
  double* pp = part.data();
#pragma omp parallel for schedule(static) num_threads(nt)
  for (int j = j0; j < j1; ++j) {
    const std::array<double, N> a = f(j);
    for (int k = 0; k < N; ++k) pp[std::size_t(j - j0) * N + k] = a[k];
  }
  for (int k = 0; k < N; ++k) s[k] = part.sum(std::size_t(n), std::size_t(k), N);
  return s;
}

/// Sum of f(j) over [j0, j1) on a team of (at most) nt threads, added in row order.
template <class F>
inline double parallel_rows_sum_on(int nt, int j0, int j1, F&& f) {
  return parallel_rows_sums_on<1>(nt, j0, j1, [&](int j) { return std::array<double, 1>{f(j)}; })[0];
}

/// Sum of f(j) over rows of row_len cells, added in row order (deterministic).
template <class F>
inline double parallel_rows_sum(int j0, int j1, int row_len, F&& f) {
  return parallel_rows_sum_on(
      loop_threads(std::size_t(std::max(0, j1 - j0)) * std::size_t(std::max(0, row_len)), j1 - j0), j0, j1,
      std::forward<F>(f));
}

/// Maximum of f(j) (and 0) over rows of row_len cells (order-independent).
template <class F>
inline double parallel_rows_max(int j0, int j1, int row_len, F&& f) {
  double m = 0.0;
  const int nt =
      loop_threads(std::size_t(std::max(0, j1 - j0)) * std::size_t(std::max(0, row_len)), j1 - j0);
  if (nt <= 1) {
    for (int j = j0; j < j1; ++j) {
      const double r = f(j);
      m = r > m ? r : m;
    }
    return m;
  }
#pragma omp parallel for schedule(static) reduction(max : m) num_threads(nt)
  for (int j = j0; j < j1; ++j) {
    const double r = f(j);
    m = r > m ? r : m;
  }
  return m;
}

/// Sum of the integer f(c) over items [0, n) (e.g. cells of a list) on (at most) nt
/// threads; integer sums do not depend on the order.
template <class F>
inline long parallel_items_count(int nt, long n, F&& f) {
  long s = 0;
  if (nt <= 1 || in_parallel_region()) {
    for (long c = 0; c < n; ++c) s += f(c);
    return s;
  }
#pragma omp parallel for schedule(static) reduction(+ : s) num_threads(nt)
  for (long c = 0; c < n; ++c) s += f(c);
  return s;
}

// ---- item loops -----------------------------------------------------------------------

/// Calls f(k) for every item k in [0, n), each item on one thread; work(k) estimates item
/// k's cost in cells of a simple row loop (the unit of kMinParallelCells; e.g. a solid's
/// window cells times the relative cost of one of them):
///  * serially in index order (each item's own row loops may then use the team) when
///    there is one thread, fewer than 2 items, less than kMinParallelCells of work in
///    all, or when already inside a parallel region;
///  * otherwise an item holding more than an even share of the work (one large solid
///    among small ones) runs first on the calling thread with its row loops threaded, and
///    the others run in one parallel region, dynamic schedule, largest first (so a
///    large item does not start last and leave the other threads idle).
/// The items must be independent (each writes only its own state). An exception thrown by
/// an item is rethrown after all items ran; of several, the one of the lowest index (the
/// one a serial loop would have thrown).
template <class W, class F>
inline void parallel_items(int n, W&& work, F&& f) {
  const int nt = in_parallel_region() ? 1 : omp_get_max_threads();
  std::vector<std::size_t> w(std::size_t(std::max(0, n)));
  std::size_t total = 0;
  for (int k = 0; k < n; ++k) total += (w[std::size_t(k)] = std::size_t(work(k)));
  if (nt <= 1 || n < 2 || total < min_parallel_cells()) {
    for (int k = 0; k < n; ++k) f(k);
    return;
  }
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return w[std::size_t(a)] > w[std::size_t(b)]; });
  std::vector<std::exception_ptr> err(static_cast<std::size_t>(n));
  auto run = [&](int k) {
    try {
      f(k);
    } catch (...) {
      err[std::size_t(k)] = std::current_exception();
    }
  };
  int first = 0;  // dominant items: row-threaded, one after another
  while (first < n && w[std::size_t(order[std::size_t(first)])] * std::size_t(nt) > total) run(order[std::size_t(first++)]);
  std::size_t rest = 0;
  for (int r = first; r < n; ++r) rest += w[std::size_t(order[std::size_t(r)])];
  if (n - first < 2 || rest < min_parallel_cells()) {
    for (int r = first; r < n; ++r) run(order[std::size_t(r)]);
  } else {
    const int team = std::min(nt, n - first);
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
    for (int r = first; r < n; ++r) run(order[std::size_t(r)]);
  }
  for (const std::exception_ptr& e : err)
    if (e) std::rethrow_exception(e);
}

// ---- team regions ----------------------------------------------------------------------

/// Thread t of a team region of nt threads.
struct Team {
  int t = 0, nt = 1;
  /// First row of chunk k when n rows are split into nt contiguous chunks.
  int chunk_lo(int n, int k) const { return int((long long)n * k / nt); }
  /// This thread's rows [first, second) of n.
  std::pair<int, int> rows(int n) const { return {chunk_lo(n, t), chunk_lo(n, t + 1)}; }
  bool first() const { return t == 0; }
  bool last() const { return t == nt - 1; }
  /// Every thread of the team waits here (a team of one never enters OpenMP, so a
  /// serial team inside some other parallel region does not bind to that region).
  void barrier() const {
    if (nt > 1) {
#pragma omp barrier
    }
  }
  /// One thread runs g, the others wait for it (barrier at the end).
  template <class G>
  void single(G&& g) const {
    if (nt <= 1) {
      g();
      return;
    }
#pragma omp single
    g();
  }
};

/// Runs f(Team) on every thread of one parallel region of nt threads (nt <= 1: f(Team{0,
/// 1}) on the calling thread, no parallel region; its barriers are then no-ops). For
/// fused passes that synchronise internally: one fork/join for the whole pass.
template <class F>
inline void team_region(int nt, F&& f) {
  if (nt <= 1 || in_parallel_region()) {
    f(Team{});
    return;
  }
#pragma omp parallel num_threads(nt)
  {
    const Team tm{omp_get_thread_num(), omp_get_num_threads()};
    f(tm);
  }
}

}  // namespace refmap
