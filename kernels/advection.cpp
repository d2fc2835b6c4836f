#include "kernels/advection.hpp"

#include "kernels/loop.hpp"

namespace refmap {

namespace {

template <FluxScheme S>
inline double face_value(double qmm, double qm, double qp, double qpp, double vel) {
  if constexpr (S == FluxScheme::Central) {
    return 0.5 * (qm + qp);
  } else {
    return vel >= 0.0 ? superbee_face(qmm, qm, qp) : superbee_face(qpp, qp, qm);
  }
}

template <FluxScheme S>
void advect_rhs2_impl(CView a, CView b, CView uf, CView vf, View ra, View rb, int nx, int ny,
                      double dx) {
  const double inv = 1.0 / dx;
  parallel_rows(0, ny, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      // x faces i (left) and i+1 (right)
      const double ul = uf(i, j), ur = uf(i + 1, j);
      const double vb = vf(i, j), vt = vf(i, j + 1);
      const double al = face_value<S>(a(i - 2, j), a(i - 1, j), a(i, j), a(i + 1, j), ul);
      const double ar = face_value<S>(a(i - 1, j), a(i, j), a(i + 1, j), a(i + 2, j), ur);
      const double ab = face_value<S>(a(i, j - 2), a(i, j - 1), a(i, j), a(i, j + 1), vb);
      const double at = face_value<S>(a(i, j - 1), a(i, j), a(i, j + 1), a(i, j + 2), vt);
      const double bl = face_value<S>(b(i - 2, j), b(i - 1, j), b(i, j), b(i + 1, j), ul);
      const double br = face_value<S>(b(i - 1, j), b(i, j), b(i + 1, j), b(i + 2, j), ur);
      const double bb = face_value<S>(b(i, j - 2), b(i, j - 1), b(i, j), b(i, j + 1), vb);
      const double bt = face_value<S>(b(i, j - 1), b(i, j), b(i, j + 1), b(i, j + 2), vt);
      ra(i, j) = -(ur * ar - ul * al + vt * at - vb * ab) * inv;
      rb(i, j) = -(ur * br - ul * bl + vt * bt - vb * bb) * inv;
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

void axpy_interior(CView q, CView k, double c, View out, int nx, int ny) {
  parallel_rows(0, ny, [&](int j) {
    const double* qr = &q(0, j);
    const double* kr = &k(0, j);
    double* o = &out(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) o[i] = qr[i] + c * kr[i];
  });
}

void rk4_combine(View q, CView k1, CView k2, CView k3, CView k4, double dt, int nx, int ny) {
  const double c = dt / 6.0;
  parallel_rows(0, ny, [&](int j) {
    double* qr = &q(0, j);
    const double *a = &k1(0, j), *b = &k2(0, j), *d = &k3(0, j), *e = &k4(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) qr[i] += c * (a[i] + 2.0 * b[i] + 2.0 * d[i] + e[i]);
  });
}

}  // namespace refmap
