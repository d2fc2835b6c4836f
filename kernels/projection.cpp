#include "kernels/projection.hpp"

#include <cmath>

#include "kernels/loop.hpp"

namespace refmap {

void face_beta(CView rho, View bx, View by, int nx, int ny, Sides sides) {
  parallel_rows(0, ny, nx, [&](int j) {
    const double* __restrict r = &rho(0, j);
    double* __restrict b = &bx(0, j);
#pragma omp simd
    for (int i = 1; i < nx; ++i) b[i] = 2.0 / (r[i - 1] + r[i]);
    switch (sides[Left]) {
      case FaceKind::Wall:
      case FaceKind::Inflow: bx(0, j) = 0.0; break;
      case FaceKind::Periodic:
      case FaceKind::Outflow: bx(0, j) = 2.0 / (rho(-1, j) + rho(0, j)); break;  // even ghost: 1/rho_P
    }
    switch (sides[Right]) {
      case FaceKind::Wall:
      case FaceKind::Inflow: bx(nx, j) = 0.0; break;
      case FaceKind::Periodic: bx(nx, j) = bx(0, j); break;  // face nx is face 0
      case FaceKind::Outflow: bx(nx, j) = 2.0 / (rho(nx - 1, j) + rho(nx, j)); break;
    }
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    int jj = j;  // the face row computed
    if (j == 0 || j == ny) {
      switch (sides[j == 0 ? Bottom : Top]) {
        case FaceKind::Wall:
        case FaceKind::Inflow:
          for (int i = 0; i < nx; ++i) by(i, j) = 0.0;
          return;
        case FaceKind::Periodic: jj = 0; break;  // face ny repeats face 0
        case FaceKind::Outflow: break;            // from the even ghost row: 1/rho_P
      }
    }
    const double* __restrict rs = &rho(0, jj - 1);
    const double* __restrict rn = &rho(0, jj);
    double* __restrict b = &by(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) b[i] = 2.0 / (rs[i] + rn[i]);
  });
}

void face_accel(CView p, CView bx, CView by, View gx_f, View gy_f, int nx, int ny, double dx,
                double gx, double gy, double rho_ref, Sides sides) {
  const double inv = 1.0 / dx;
  parallel_rows(0, ny, nx, [&](int j) {
    {
      const double* __restrict br = &bx(0, j);
      const double* __restrict pr = &p(0, j);
      double* __restrict g = &gx_f(0, j);
#pragma omp simd
      for (int i = 1; i < nx; ++i) {
        const double b = br[i];
        g[i] = b * (pr[i] - pr[i - 1]) * inv - gx * (1.0 - rho_ref * b);
      }
    }
    // Inflow: the face velocity is prescribed (not corrected), but the adjacent cell's
    // velocity correction (eq. 5.7, the mean of its two faces) must still feel the
    // pressure gradient: it is extrapolated from the first interior face (a 0 there would
    // halve the correction of the cell and bias a developed inflow). Outflow: p = 0 on the
    // face, half a cell from the cell centre.
    switch (sides[Left]) {
      case FaceKind::Wall: gx_f(0, j) = 0.0; break;
      case FaceKind::Periodic: {
        const double b = bx(0, j);
        gx_f(0, j) = b * (p(0, j) - p(-1, j)) * inv - gx * (1.0 - rho_ref * b);
        break;
      }
      case FaceKind::Inflow: gx_f(0, j) = gx_f(1, j); break;
      case FaceKind::Outflow: {
        const double b = bx(0, j);
        gx_f(0, j) = b * 2.0 * p(0, j) * inv - gx * (1.0 - rho_ref * b);
        break;
      }
    }
    switch (sides[Right]) {
      case FaceKind::Wall: gx_f(nx, j) = 0.0; break;
      case FaceKind::Periodic: gx_f(nx, j) = gx_f(0, j); break;  // face nx is face 0
      case FaceKind::Inflow: gx_f(nx, j) = gx_f(nx - 1, j); break;
      case FaceKind::Outflow: {
        const double b = bx(nx, j);
        gx_f(nx, j) = -b * 2.0 * p(nx - 1, j) * inv - gx * (1.0 - rho_ref * b);
        break;
      }
    }
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    int jj = j;  // the face row computed
    if (j == 0 || j == ny) {
      switch (sides[j == 0 ? Bottom : Top]) {
        case FaceKind::Wall:
          for (int i = 0; i < nx; ++i) gy_f(i, j) = 0.0;
          return;
        case FaceKind::Periodic: jj = 0; break;  // face ny repeats face 0
        case FaceKind::Inflow: return;             // copied from the adjacent row below
        case FaceKind::Outflow: {                  // p = 0 on the face
          const double s = j == 0 ? 2.0 : -2.0;
          const int jc = j == 0 ? 0 : ny - 1;
          for (int i = 0; i < nx; ++i) {
            const double b = by(i, j);
            gy_f(i, j) = s * b * p(i, jc) * inv - gy * (1.0 - rho_ref * b);
          }
          return;
        }
      }
    }
    const double* __restrict br = &by(0, jj);
    const double* __restrict pn = &p(0, jj);
    const double* __restrict ps = &p(0, jj - 1);
    double* __restrict g = &gy_f(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      const double b = br[i];
      g[i] = b * (pn[i] - ps[i]) * inv - gy * (1.0 - rho_ref * b);
    }
  });
  // an inflow row: the pressure gradient of the first interior row (see the x faces)
  for (int j : {0, ny}) {
    switch (sides[j == 0 ? Bottom : Top]) {
      case FaceKind::Wall:
      case FaceKind::Periodic:
      case FaceKind::Outflow: break;
      case FaceKind::Inflow: {
        const int src = j == 0 ? 1 : ny - 1;
        for (int i = 0; i < nx; ++i) gy_f(i, j) = gy_f(i, src);
        break;
      }
    }
  }
}

void predict_face_velocity(CView u, CView v, CView gx_f, CView gy_f, View uf, View vf, int nx,
                           int ny, double dt, Sides sides) {
  parallel_rows(0, ny, nx, [&](int j) {
    {
      const double* __restrict ur = &u(0, j);
      const double* __restrict g = &gx_f(0, j);
      double* __restrict f = &uf(0, j);
#pragma omp simd
      for (int i = 1; i < nx; ++i) f[i] = 0.5 * (ur[i - 1] + ur[i]) - dt * g[i];
    }
    // inflow: the ghost makes the mean the prescribed velocity (solver/model/boundary.hpp);
    // outflow: the ghost is the cell's (zero normal derivative), corrected by the gradient
    switch (sides[Left]) {
      case FaceKind::Wall: uf(0, j) = 0.0; break;
      case FaceKind::Periodic:
      case FaceKind::Outflow: uf(0, j) = 0.5 * (u(-1, j) + u(0, j)) - dt * gx_f(0, j); break;
      case FaceKind::Inflow: uf(0, j) = 0.5 * (u(-1, j) + u(0, j)); break;
    }
    switch (sides[Right]) {
      case FaceKind::Wall: uf(nx, j) = 0.0; break;
      case FaceKind::Periodic: uf(nx, j) = uf(0, j); break;  // face nx is face 0
      case FaceKind::Outflow: uf(nx, j) = 0.5 * (u(nx - 1, j) + u(nx, j)) - dt * gx_f(nx, j); break;
      case FaceKind::Inflow: uf(nx, j) = 0.5 * (u(nx - 1, j) + u(nx, j)); break;
    }
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    int jj = j;  // the face row computed
    if (j == 0 || j == ny) {
      switch (sides[j == 0 ? Bottom : Top]) {
        case FaceKind::Wall:
          for (int i = 0; i < nx; ++i) vf(i, j) = 0.0;
          return;
        case FaceKind::Periodic: jj = 0; break;  // face ny repeats face 0
        case FaceKind::Outflow: break;           // from the ghost row and the face gradient
        case FaceKind::Inflow:
          for (int i = 0; i < nx; ++i) vf(i, j) = 0.5 * (v(i, j - 1) + v(i, j));
          return;
      }
    }
    const double* __restrict vs = &v(0, jj - 1);
    const double* __restrict vn = &v(0, jj);
    const double* __restrict g = &gy_f(0, jj);
    double* __restrict f = &vf(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) f[i] = 0.5 * (vs[i] + vn[i]) - dt * g[i];
  });
}

void face_divergence(CView uf, CView vf, View out, int nx, int ny, double dx, double scale) {
  const double s = scale / dx;
  parallel_rows(0, ny, nx, [&](int j) {
    const double* ul = &uf(0, j);
    const double* vb = &vf(0, j);
    const double* vt = &vf(0, j + 1);
    double* o = &out(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) o[i] = s * (ul[i + 1] - ul[i] + vt[i] - vb[i]);
  });
}

double max_abs_face_divergence(CView uf, CView vf, int nx, int ny, double dx) {
  const double s = 1.0 / dx;
  return parallel_rows_max(0, ny, nx, [&](int j) {
    double m = 0.0;
    for (int i = 0; i < nx; ++i) {
      const double d = std::abs(s * (uf(i + 1, j) - uf(i, j) + vf(i, j + 1) - vf(i, j)));
      // NaN must propagate so a blown-up run is noticed
      if (!(d <= m)) m = d;
    }
    return m;
  });
}

void correct_face_velocity(View uf, View vf, CView dp, CView bx, CView by, int nx, int ny,
                           double dx, double dt, Sides sides) {
  const double c = dt / dx;
  parallel_rows(0, ny, nx, [&](int j) {
    {
      const double* __restrict b = &bx(0, j);
      const double* __restrict d = &dp(0, j);
      double* __restrict f = &uf(0, j);
#pragma omp simd
      for (int i = 1; i < nx; ++i) f[i] -= c * b[i] * (d[i] - d[i - 1]);
    }
    switch (sides[Left]) {
      case FaceKind::Wall:
      case FaceKind::Inflow: break;  // no normal velocity to correct / prescribed
      case FaceKind::Periodic: uf(0, j) = uf(0, j) - c * bx(0, j) * (dp(0, j) - dp(-1, j)); break;
      case FaceKind::Outflow: uf(0, j) -= c * bx(0, j) * 2.0 * dp(0, j); break;  // dp = 0 on the face
    }
    switch (sides[Right]) {
      case FaceKind::Wall:
      case FaceKind::Inflow: break;
      case FaceKind::Periodic: uf(nx, j) = uf(0, j); break;  // face nx is face 0
      case FaceKind::Outflow: uf(nx, j) += c * bx(nx, j) * 2.0 * dp(nx - 1, j); break;
    }
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    if (j == 0 || j == ny) {
      switch (sides[j == 0 ? Bottom : Top]) {
        case FaceKind::Wall:
        case FaceKind::Inflow: return;
        case FaceKind::Periodic:
          if (j == ny) return;  // copied from face row 0 below
          break;
        case FaceKind::Outflow: {  // dp = 0 on the face
          const double s = j == 0 ? 2.0 : -2.0;
          const int jc = j == 0 ? 0 : ny - 1;
          for (int i = 0; i < nx; ++i) vf(i, j) -= c * by(i, j) * s * dp(i, jc);
          return;
        }
      }
    }
    const double* __restrict b = &by(0, j);
    const double* __restrict dn = &dp(0, j);
    const double* __restrict ds = &dp(0, j - 1);
    double* __restrict f = &vf(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) f[i] -= c * b[i] * (dn[i] - ds[i]);
  });
  switch (sides[Top]) {
    case FaceKind::Wall:
    case FaceKind::Inflow:
    case FaceKind::Outflow: break;
    case FaceKind::Periodic:
      for (int i = 0; i < nx; ++i) vf(i, ny) = vf(i, 0);
      break;
  }
}

void correct_cell_velocity(View u, View v, CView gx_f, CView gy_f, int nx, int ny, double dt) {
  const double c = 0.5 * dt;
  parallel_rows(0, ny, nx, [&](int j) {
    double* ur = &u(0, j);
    double* vr = &v(0, j);
    const double* gx = &gx_f(0, j);
    const double* gb = &gy_f(0, j);
    const double* gt = &gy_f(0, j + 1);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      ur[i] -= c * (gx[i] + gx[i + 1]);
      vr[i] -= c * (gb[i] + gt[i]);
    }
  });
}

}  // namespace refmap
