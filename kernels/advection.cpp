#include "kernels/advection.hpp"

#include "kernels/loop.hpp"

namespace refmap {

namespace {

template <FluxScheme S>
inline double face_value(double qmm, double qm, double qp, double qpp, double vel) {
  if constexpr (S == FluxScheme::Central) {
    return 0.5 * (qm + qp);
  } else {
    // pick the upwind stencil first (blends, no branch), then limit once
    const bool pos = vel >= 0.0;
    return superbee_face(pos ? qmm : qpp, pos ? qm : qp, pos ? qp : qm);
  }
}

template <FluxScheme S>
void advect_rhs2_impl(CView a, CView b, CView uf, CView vf, View ra, View rb, int nx, int ny,
                      double dx) {
  const double inv = 1.0 / dx;
  parallel_rows(0, ny, nx, [=](int j) {
    // restrict-qualified row pointers: the inner loop then vectorises (through the views
    // the compiler could not prove that the stores leave the loads' rows alone)
    const double* __restrict am2 = &a(0, j - 2);
    const double* __restrict am1 = &a(0, j - 1);
    const double* __restrict a0 = &a(0, j);
    const double* __restrict ap1 = &a(0, j + 1);
    const double* __restrict ap2 = &a(0, j + 2);
    const double* __restrict bm2 = &b(0, j - 2);
    const double* __restrict bm1 = &b(0, j - 1);
    const double* __restrict b0 = &b(0, j);
    const double* __restrict bp1 = &b(0, j + 1);
    const double* __restrict bp2 = &b(0, j + 2);
    const double* __restrict ufr = &uf(0, j);
    const double* __restrict vfb = &vf(0, j);
    const double* __restrict vft = &vf(0, j + 1);
    double* __restrict rar = &ra(0, j);
    double* __restrict rbr = &rb(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      // x faces i (left) and i+1 (right), y faces j (bottom) and j+1 (top)
      const double ul = ufr[i], ur = ufr[i + 1];
      const double vb = vfb[i], vt = vft[i];
      const double al = face_value<S>(a0[i - 2], a0[i - 1], a0[i], a0[i + 1], ul);
      const double ar = face_value<S>(a0[i - 1], a0[i], a0[i + 1], a0[i + 2], ur);
      const double ab = face_value<S>(am2[i], am1[i], a0[i], ap1[i], vb);
      const double at = face_value<S>(am1[i], a0[i], ap1[i], ap2[i], vt);
      const double bl = face_value<S>(b0[i - 2], b0[i - 1], b0[i], b0[i + 1], ul);
      const double br = face_value<S>(b0[i - 1], b0[i], b0[i + 1], b0[i + 2], ur);
      const double bb = face_value<S>(bm2[i], bm1[i], b0[i], bp1[i], vb);
      const double bt = face_value<S>(bm1[i], b0[i], bp1[i], bp2[i], vt);
      rar[i] = -(ur * ar - ul * al + vt * at - vb * ab) * inv;
      rbr[i] = -(ur * br - ul * bl + vt * bt - vb * bb) * inv;
    }
  });
}

}  // namespace

void advect_rhs2(CView a, CView b, CView uf, CView vf, View rhs_a, View rhs_b, int nx, int ny,
                 double dx, FluxScheme scheme) {
  if (scheme == FluxScheme::Central)
    advect_rhs2_impl<FluxScheme::Central>(a, b, uf, vf, rhs_a, rhs_b, nx, ny, dx);
  else
    advect_rhs2_impl<FluxScheme::Superbee>(a, b, uf, vf, rhs_a, rhs_b, nx, ny, dx);
}

}  // namespace refmap
