#include "kernels/viscous.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void viscous_force(CView u, CView v, CView mu, View fx, View fy, int nx, int ny, double dx) {
  const double inv = 1.0 / dx;
  const double inv2 = inv * inv;
  parallel_rows(0, ny, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      // face viscosities
      const double mw = 0.5 * (mu(i - 1, j) + mu(i, j)), me = 0.5 * (mu(i, j) + mu(i + 1, j));
      const double ms = 0.5 * (mu(i, j - 1) + mu(i, j)), mn = 0.5 * (mu(i, j) + mu(i, j + 1));
      // x-momentum: d/dx(2 mu u_x) + d/dy(mu (u_y + v_x))
      const double txx_e = 2.0 * me * (u(i + 1, j) - u(i, j));
      const double txx_w = 2.0 * mw * (u(i, j) - u(i - 1, j));
      const double vx_n = 0.25 * (v(i + 1, j + 1) - v(i - 1, j + 1) + v(i + 1, j) - v(i - 1, j));
      const double vx_s = 0.25 * (v(i + 1, j) - v(i - 1, j) + v(i + 1, j - 1) - v(i - 1, j - 1));
      const double txy_n = mn * (u(i, j + 1) - u(i, j) + vx_n);
      const double txy_s = ms * (u(i, j) - u(i, j - 1) + vx_s);
      fx(i, j) = (txx_e - txx_w + txy_n - txy_s) * inv2;
      // y-momentum: d/dx(mu (v_x + u_y)) + d/dy(2 mu v_y)
      const double uy_e = 0.25 * (u(i + 1, j + 1) - u(i + 1, j - 1) + u(i, j + 1) - u(i, j - 1));
      const double uy_w = 0.25 * (u(i, j + 1) - u(i, j - 1) + u(i - 1, j + 1) - u(i - 1, j - 1));
      const double tyx_e = me * (v(i + 1, j) - v(i, j) + uy_e);
      const double tyx_w = mw * (v(i, j) - v(i - 1, j) + uy_w);
      const double tyy_n = 2.0 * mn * (v(i, j + 1) - v(i, j));
      const double tyy_s = 2.0 * ms * (v(i, j) - v(i, j - 1));
      fy(i, j) = (tyx_e - tyx_w + tyy_n - tyy_s) * inv2;
    }
  });
}

void apply_force(View u, View v, CView fx, CView fy, CView rho, double dt, int nx, int ny) {
  parallel_rows(0, ny, [&](int j) {
    double* ur = &u(0, j);
    double* vr = &v(0, j);
    const double *a = &fx(0, j), *b = &fy(0, j), *r = &rho(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      const double s = dt / r[i];
      ur[i] += s * a[i];
      vr[i] += s * b[i];
    }
  });
}

}  // namespace refmap
