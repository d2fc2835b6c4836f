#pragma once
// The one loop driver of the stencil kernels: rows of the grid are split statically
// across OpenMP threads, each kernel body is a plain inner loop over i that the
// compiler vectorises. Performance policy (schedule, which loop is parallel) lives here.
#include <omp.h>

namespace refmap {

/// Calls f(j) for j in [j0, j1), rows distributed over the OpenMP team.
template <class F>
inline void parallel_rows(int j0, int j1, F&& f) {
#pragma omp parallel for schedule(static)
  for (int j = j0; j < j1; ++j) f(j);
}

/// Same, reducing the maximum of f(j).
template <class F>
inline double parallel_rows_max(int j0, int j1, F&& f) {
  double m = 0.0;
#pragma omp parallel for schedule(static) reduction(max : m)
  for (int j = j0; j < j1; ++j) {
    const double r = f(j);
    m = r > m ? r : m;
  }
  return m;
}

/// Same, reducing the sum of f(j).
template <class F>
inline double parallel_rows_sum(int j0, int j1, F&& f) {
  double s = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : s)
  for (int j = j0; j < j1; ++j) s += f(j);
  return s;
}

}  // namespace refmap
