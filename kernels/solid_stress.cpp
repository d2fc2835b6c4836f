#include "kernels/solid_stress.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void neo_hookean_stress(CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx, double mu_s,
                        double phi_max, View sxx, View sxy, View syy) {
  const double inv2 = 0.5 / dx;
  const double c = 2.0 * mu_s;
  parallel_rows(0, nj, ni, [=](int j) {
    // restrict-qualified row pointers and a select instead of a branch, so that the loop
    // vectorises; cells with phi >= phi_max are computed too (from whatever xi holds there,
    // possibly stale) and then discarded by the select
    const double* __restrict xs = &xi_x(0, j - 1);
    const double* __restrict xc = &xi_x(0, j);
    const double* __restrict xn = &xi_x(0, j + 1);
    const double* __restrict ys = &xi_y(0, j - 1);
    const double* __restrict yc = &xi_y(0, j);
    const double* __restrict yn = &xi_y(0, j + 1);
    const double* __restrict ph = &phi(0, j);
    double* __restrict oxx = &sxx(0, j);
    double* __restrict oxy = &sxy(0, j);
    double* __restrict oyy = &syy(0, j);
#pragma omp simd
    for (int i = 0; i < ni; ++i) {
      const double gxx = (xc[i + 1] - xc[i - 1]) * inv2;
      const double gxy = (xn[i] - xs[i]) * inv2;
      const double gyx = (yc[i + 1] - yc[i - 1]) * inv2;
      const double gyy = (yn[i] - ys[i]) * inv2;
      const Sym2 b = left_cauchy_green(gxx, gxy, gyx, gyy);
      const bool in = ph[i] < phi_max;  // false for NaN phi too
      oxx[i] = in ? c * (b.xx - 1.0) : 0.0;
      oxy[i] = in ? c * b.xy : 0.0;
      oyy[i] = in ? c * (b.yy - 1.0) : 0.0;
    }
  });
}

double blend_stress(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj, double dx,
                    double w_t, double mu_s, View gxx, View gxy, View gyy, int i0, int j0) {
  const double inv2mu = mu_s > 0.0 ? 0.5 / mu_s : 0.0;
  const double e = parallel_rows_sum(0, nj, ni, [&](int j) {
    double en = 0.0;
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j);
      if (ph >= w_t) continue;
      const double s = 1.0 - smoothed_heaviside(ph, w_t);
      gxx(i0 + i, j0 + j) += s * sxx(i, j);
      gxy(i0 + i, j0 + j) += s * sxy(i, j);
      gyy(i0 + i, j0 + j) += s * syy(i, j);
      // isochoric strain energy mu_s (tr b / sqrt(det b) - 2) >= 0: equal to mu_s (tr b - 2)
      // when det b = 1 (incompressible), and blind to the volume drift of the discrete xi,
      // whose isotropic stress is taken by the pressure
      const double bxx = 1.0 + sxx(i, j) * inv2mu, byy = 1.0 + syy(i, j) * inv2mu;
      const double bxy = sxy(i, j) * inv2mu, det = bxx * byy - bxy * bxy;
      en += s * (det > 0.0 ? (bxx + byy) / std::sqrt(det) - 2.0 : bxx + byy - 2.0);
    }
    return en;
  });
  return mu_s > 0.0 ? mu_s * e * dx * dx : 0.0;
}

void blend_stress_divergence(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj,
                             double dx, double w_t, View fx, View fy, int i0, int j0) {
  const double inv2 = 0.5 / dx;
  parallel_rows(0, nj, ni, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j);
      if (ph >= w_t) continue;
      const double s = 1.0 - smoothed_heaviside(ph, w_t);
      fx(i0 + i, j0 + j) +=
          s * (sxx(i + 1, j) - sxx(i - 1, j) + sxy(i, j + 1) - sxy(i, j - 1)) * inv2;
      fy(i0 + i, j0 + j) +=
          s * (sxy(i + 1, j) - sxy(i - 1, j) + syy(i, j + 1) - syy(i, j - 1)) * inv2;
    }
  });
}

void add_stress_divergence(CView sxx, CView sxy, CView syy, View fx, View fy, int nx, int ny,
                           double dx) {
  const double inv2 = 0.5 / dx;
  parallel_rows(0, ny, nx, [=](int j) {
    // restrict-qualified row pointers so that the loop vectorises
    const double* __restrict xx = &sxx(0, j);
    const double* __restrict xys = &sxy(0, j - 1);
    const double* __restrict xyc = &sxy(0, j);
    const double* __restrict xyn = &sxy(0, j + 1);
    const double* __restrict yys = &syy(0, j - 1);
    const double* __restrict yyn = &syy(0, j + 1);
    double* __restrict fxr = &fx(0, j);
    double* __restrict fyr = &fy(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      fxr[i] += (xx[i + 1] - xx[i - 1] + xyn[i] - xys[i]) * inv2;
      fyr[i] += (xyc[i + 1] - xyc[i - 1] + yyn[i] - yys[i]) * inv2;
    }
  });
}

}  // namespace refmap

namespace refmap {

namespace {

/// sigma_s - (pressure-free, rest-free) at the x-face between cells (i-1, j) and (i, j):
/// returns (sigma_xx, sigma_xy) — the x-momentum and y-momentum fluxes through it.
inline void x_face_flux(CView xx, CView xy, int i, int j, double inv, double& fxx, double& fxy,
                        double c) {
  const double gxx = (xx(i, j) - xx(i - 1, j)) * inv;
  const double gyx = (xy(i, j) - xy(i - 1, j)) * inv;
  const double gxy = 0.25 * (xx(i, j + 1) - xx(i, j - 1) + xx(i - 1, j + 1) - xx(i - 1, j - 1)) * inv;
  const double gyy = 0.25 * (xy(i, j + 1) - xy(i, j - 1) + xy(i - 1, j + 1) - xy(i - 1, j - 1)) * inv;
  const Sym2 b = left_cauchy_green(gxx, gxy, gyx, gyy);
  fxx = c * (b.xx - 1.0);
  fxy = c * b.xy;
}

/// Same at the y-face between (i, j-1) and (i, j): returns (sigma_xy, sigma_yy).
inline void y_face_flux(CView xx, CView xy, int i, int j, double inv, double& fyx, double& fyy,
                        double c) {
  const double gxy = (xx(i, j) - xx(i, j - 1)) * inv;
  const double gyy = (xy(i, j) - xy(i, j - 1)) * inv;
  const double gxx = 0.25 * (xx(i + 1, j) - xx(i - 1, j) + xx(i + 1, j - 1) - xx(i - 1, j - 1)) * inv;
  const double gyx = 0.25 * (xy(i + 1, j) - xy(i - 1, j) + xy(i + 1, j - 1) - xy(i - 1, j - 1)) * inv;
  const Sym2 b = left_cauchy_green(gxx, gxy, gyx, gyy);
  fyx = c * b.xy;
  fyy = c * (b.yy - 1.0);
}

}  // namespace

void add_face_stress_force(CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx,
                           double mu_s, double w_t, bool conservative, View fx, View fy, int i0,
                           int j0) {
  const double inv = 1.0 / dx;
  const double c = 2.0 * mu_s;
  const double cut = w_t + 2.0 * dx;  // (1 - H) vanishes beyond w_t; margin for the faces
  parallel_rows(0, nj, ni, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j);
      if (!(ph < cut)) continue;
      double w_l = 1.0, w_r = 1.0, w_b = 1.0, w_t_ = 1.0, w_c = 1.0;
      if (conservative) {
        w_l = 1.0 - smoothed_heaviside(0.5 * (phi(i - 1, j) + ph), w_t);
        w_r = 1.0 - smoothed_heaviside(0.5 * (phi(i + 1, j) + ph), w_t);
        w_b = 1.0 - smoothed_heaviside(0.5 * (phi(i, j - 1) + ph), w_t);
        w_t_ = 1.0 - smoothed_heaviside(0.5 * (phi(i, j + 1) + ph), w_t);
        if (w_l == 0.0 && w_r == 0.0 && w_b == 0.0 && w_t_ == 0.0) continue;
      } else {
        w_c = 1.0 - smoothed_heaviside(ph, w_t);
        if (w_c == 0.0) continue;
      }
      // a face with zero weight is not evaluated: xi beyond the band may be stale
      double lxx = 0, lxy = 0, rxx = 0, rxy = 0, bxy = 0, byy = 0, txy = 0, tyy = 0;
      if (w_l != 0.0) x_face_flux(xi_x, xi_y, i, j, inv, lxx, lxy, c);
      if (w_r != 0.0) x_face_flux(xi_x, xi_y, i + 1, j, inv, rxx, rxy, c);
      if (w_b != 0.0) y_face_flux(xi_x, xi_y, i, j, inv, bxy, byy, c);
      if (w_t_ != 0.0) y_face_flux(xi_x, xi_y, i, j + 1, inv, txy, tyy, c);
      const double ax = (w_r * rxx - w_l * lxx + w_t_ * txy - w_b * bxy) * inv;
      const double ay = (w_r * rxy - w_l * lxy + w_t_ * tyy - w_b * byy) * inv;
      fx(i0 + i, j0 + j) += w_c * ax;
      fy(i0 + i, j0 + j) += w_c * ay;
    }
  });
}

}  // namespace refmap
