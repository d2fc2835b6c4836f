#include "kernels/viscous.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void viscous_force(CView u, CView v, CView mu, View fx, View fy, int nx, int ny, double dx) {
  const double inv = 1.0 / dx;
  const double inv2 = inv * inv;
  parallel_rows(0, ny, nx, [=](int j) {
    // restrict-qualified row pointers so that the loop vectorises
    const double* __restrict us = &u(0, j - 1);
    const double* __restrict uc = &u(0, j);
    const double* __restrict un = &u(0, j + 1);
    const double* __restrict vs = &v(0, j - 1);
    const double* __restrict vc = &v(0, j);
    const double* __restrict vn = &v(0, j + 1);
    const double* __restrict ms_ = &mu(0, j - 1);
    const double* __restrict mc = &mu(0, j);
    const double* __restrict mn_ = &mu(0, j + 1);
    double* __restrict fxr = &fx(0, j);
    double* __restrict fyr = &fy(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      // face viscosities
      const double mw = 0.5 * (mc[i - 1] + mc[i]), me = 0.5 * (mc[i] + mc[i + 1]);
      const double ms = 0.5 * (ms_[i] + mc[i]), mn = 0.5 * (mc[i] + mn_[i]);
      // x-momentum: d/dx(2 mu u_x) + d/dy(mu (u_y + v_x))
      const double txx_e = 2.0 * me * (uc[i + 1] - uc[i]);
      const double txx_w = 2.0 * mw * (uc[i] - uc[i - 1]);
      const double vx_n = 0.25 * (vn[i + 1] - vn[i - 1] + vc[i + 1] - vc[i - 1]);
      const double vx_s = 0.25 * (vc[i + 1] - vc[i - 1] + vs[i + 1] - vs[i - 1]);
      const double txy_n = mn * (un[i] - uc[i] + vx_n);
      const double txy_s = ms * (uc[i] - us[i] + vx_s);
      fxr[i] = (txx_e - txx_w + txy_n - txy_s) * inv2;
      // y-momentum: d/dx(mu (v_x + u_y)) + d/dy(2 mu v_y)
      const double uy_e = 0.25 * (un[i + 1] - us[i + 1] + un[i] - us[i]);
      const double uy_w = 0.25 * (un[i] - us[i] + un[i - 1] - us[i - 1]);
      const double tyx_e = me * (vc[i + 1] - vc[i] + uy_e);
      const double tyx_w = mw * (vc[i] - vc[i - 1] + uy_w);
      const double tyy_n = 2.0 * mn * (vn[i] - vc[i]);
      const double tyy_s = 2.0 * ms * (vc[i] - vs[i]);
      fyr[i] = (tyx_e - tyx_w + tyy_n - tyy_s) * inv2;
    }
  });
}

void apply_force(View u, View v, CView fx, CView fy, CView rho, double dt, int nx, int ny) {
  parallel_rows(0, ny, nx, [&](int j) {
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
