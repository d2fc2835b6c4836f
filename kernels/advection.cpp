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

// A face rule gives, for row j, the face flags (x faces i and i + 1, y faces j and j + 1) and
// the face value of q for a flag; the kernel below is written once for every rule.

/// The plain schemes: scheme S on every face (the flags are not read).
template <FluxScheme S>
struct EveryFace {
  struct Row {
    double x(int) const { return 0.0; }
    double bottom(int) const { return 0.0; }
    double top(int) const { return 0.0; }
    double operator()(double, double qmm, double qm, double qp, double qpp, double vel) const {
      return face_value<S>(qmm, qm, qp, qpp, vel);
    }
  };
  Row row(int) const { return {}; }
};

/// At a density jump: central, or Superbee on the faces flagged nonzero in lim_x / lim_y
/// (both values evaluated: no branch in the vectorised loop).
struct FlaggedFaces {
  CView lim_x, lim_y;
  struct Row {
    const double* lx;  // x faces of row j
    const double* lb;  // y faces of rows j (bottom) and j + 1 (top)
    const double* lt;
    double x(int i) const { return lx[i]; }
    double bottom(int i) const { return lb[i]; }
    double top(int i) const { return lt[i]; }
    double operator()(double flag, double qmm, double qm, double qp, double qpp, double vel) const {
      const double c = 0.5 * (qm + qp);
      const double l = face_value<FluxScheme::Superbee>(qmm, qm, qp, qpp, vel);
      return flag != 0.0 ? l : c;
    }
  };
  Row row(int j) const { return {&lim_x(0, j), &lim_y(0, j), &lim_y(0, j + 1)}; }
};

/// -div(q u) of two cell fields a, b by their face values under the face rule F.
template <class F>
void advect_rhs2_impl(CView a, CView b, CView uf, CView vf, View ra, View rb, int nx, int ny,
                      double dx, F rule) {
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
    const typename F::Row r = rule.row(j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      // x faces i (left) and i+1 (right), y faces j (bottom) and j+1 (top)
      const double ul = ufr[i], ur = ufr[i + 1];
      const double vb = vfb[i], vt = vft[i];
      const double ml = r.x(i), mr = r.x(i + 1), mb = r.bottom(i), mt = r.top(i);
      const double al = r(ml, a0[i - 2], a0[i - 1], a0[i], a0[i + 1], ul);
      const double ar = r(mr, a0[i - 1], a0[i], a0[i + 1], a0[i + 2], ur);
      const double ab = r(mb, am2[i], am1[i], a0[i], ap1[i], vb);
      const double at = r(mt, am1[i], a0[i], ap1[i], ap2[i], vt);
      const double bl = r(ml, b0[i - 2], b0[i - 1], b0[i], b0[i + 1], ul);
      const double br = r(mr, b0[i - 1], b0[i], b0[i + 1], b0[i + 2], ur);
      const double bb = r(mb, bm2[i], bm1[i], b0[i], bp1[i], vb);
      const double bt = r(mt, bm1[i], b0[i], bp1[i], bp2[i], vt);
      rar[i] = -(ur * ar - ul * al + vt * at - vb * ab) * inv;
      rbr[i] = -(ur * br - ul * bl + vt * bt - vb * bb) * inv;
    }
  });
}

}  // namespace

void advect_rhs2_hybrid(CView a, CView b, CView uf, CView vf, CView lim_x, CView lim_y, View ra,
                        View rb, int nx, int ny, double dx) {
  advect_rhs2_impl(a, b, uf, vf, ra, rb, nx, ny, dx, FlaggedFaces{lim_x, lim_y});
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
    advect_rhs2_impl(a, b, uf, vf, rhs_a, rhs_b, nx, ny, dx, EveryFace<FluxScheme::Central>{});
  else
    advect_rhs2_impl(a, b, uf, vf, rhs_a, rhs_b, nx, ny, dx, EveryFace<FluxScheme::Superbee>{});
}

}  // namespace refmap
