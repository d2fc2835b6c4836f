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

// central value, or the Superbee one where lim != 0 (both evaluated: no branch)
inline double hybrid_value(double qmm, double qm, double qp, double qpp, double vel, double lim) {
  const double c = 0.5 * (qm + qp);
  const double l = face_value<FluxScheme::Superbee>(qmm, qm, qp, qpp, vel);
  return lim != 0.0 ? l : c;
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

void advect_rhs2_hybrid(CView a, CView b, CView uf, CView vf, CView lim_x, CView lim_y, View ra,
                        View rb, int nx, int ny, double dx) {
  const double inv = 1.0 / dx;
  parallel_rows(0, ny, nx, [=](int j) {
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
    const double* __restrict lx = &lim_x(0, j);
    const double* __restrict lb = &lim_y(0, j);
    const double* __restrict lt = &lim_y(0, j + 1);
    double* __restrict rar = &ra(0, j);
    double* __restrict rbr = &rb(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      const double ul = ufr[i], ur = ufr[i + 1];
      const double vb = vfb[i], vt = vft[i];
      const double ml = lx[i], mr = lx[i + 1], mb = lb[i], mt = lt[i];
      const double al = hybrid_value(a0[i - 2], a0[i - 1], a0[i], a0[i + 1], ul, ml);
      const double ar = hybrid_value(a0[i - 1], a0[i], a0[i + 1], a0[i + 2], ur, mr);
      const double ab = hybrid_value(am2[i], am1[i], a0[i], ap1[i], vb, mb);
      const double at = hybrid_value(am1[i], a0[i], ap1[i], ap2[i], vt, mt);
      const double bl = hybrid_value(b0[i - 2], b0[i - 1], b0[i], b0[i + 1], ul, ml);
      const double br = hybrid_value(b0[i - 1], b0[i], b0[i + 1], b0[i + 2], ur, mr);
      const double bb = hybrid_value(bm2[i], bm1[i], b0[i], bp1[i], vb, mb);
      const double bt = hybrid_value(bm1[i], b0[i], bp1[i], bp2[i], vt, mt);
      rar[i] = -(ur * ar - ul * al + vt * at - vb * ab) * inv;
      rbr[i] = -(ur * br - ul * bl + vt * bt - vb * bb) * inv;
    }
  });
}

void flag_density_jump_faces(CView rho0, CView rho1, View lim_x, View lim_y, int nx, int ny) {
  // a face is flagged when its stencil's density is not one value, at either time
  auto varies = [](double r0, double r1, double r2, double r3) {
    return r0 != r1 || r1 != r2 || r2 != r3;
  };
  parallel_rows(0, ny + 1, nx, [=](int j) {
    if (j < ny)
      for (int i = 0; i <= nx; ++i)
        lim_x(i, j) = varies(rho0(i - 2, j), rho0(i - 1, j), rho0(i, j), rho0(i + 1, j)) ||
                              varies(rho1(i - 2, j), rho1(i - 1, j), rho1(i, j), rho1(i + 1, j))
                          ? 1.0
                          : 0.0;
    for (int i = 0; i < nx; ++i)
      lim_y(i, j) = varies(rho0(i, j - 2), rho0(i, j - 1), rho0(i, j), rho0(i, j + 1)) ||
                            varies(rho1(i, j - 2), rho1(i, j - 1), rho1(i, j), rho1(i, j + 1))
                        ? 1.0
                        : 0.0;
  });
}

void advect_rhs2(CView a, CView b, CView uf, CView vf, View rhs_a, View rhs_b, int nx, int ny,
                 double dx, FluxScheme scheme) {
  if (scheme == FluxScheme::Central)
    advect_rhs2_impl<FluxScheme::Central>(a, b, uf, vf, rhs_a, rhs_b, nx, ny, dx);
  else
    advect_rhs2_impl<FluxScheme::Superbee>(a, b, uf, vf, rhs_a, rhs_b, nx, ny, dx);
}

}  // namespace refmap
