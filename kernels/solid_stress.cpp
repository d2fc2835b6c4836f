#include "kernels/solid_stress.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void neo_hookean_stress(CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx, double mu_s,
                        double phi_max, View sxx, View sxy, View syy) {
  const double inv2 = 0.5 / dx;
  const double c = 2.0 * mu_s;
  parallel_rows(0, nj, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      if (!(phi(i, j) < phi_max)) {
        sxx(i, j) = sxy(i, j) = syy(i, j) = 0.0;
        continue;
      }
      const double gxx = (xi_x(i + 1, j) - xi_x(i - 1, j)) * inv2;
      const double gxy = (xi_x(i, j + 1) - xi_x(i, j - 1)) * inv2;
      const double gyx = (xi_y(i + 1, j) - xi_y(i - 1, j)) * inv2;
      const double gyy = (xi_y(i, j + 1) - xi_y(i, j - 1)) * inv2;
      const Sym2 b = left_cauchy_green(gxx, gxy, gyx, gyy);
      sxx(i, j) = c * (b.xx - 1.0);
      sxy(i, j) = c * b.xy;
      syy(i, j) = c * (b.yy - 1.0);
    }
  });
}

double blend_stress(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj, double dx,
                    double w_t, double mu_s, View gxx, View gxy, View gyy, int i0, int j0) {
  const double e = parallel_rows_sum(0, nj, [&](int j) {
    double en = 0.0;
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j);
      if (ph >= w_t) continue;
      const double s = 1.0 - smoothed_heaviside(ph, w_t);
      gxx(i0 + i, j0 + j) += s * sxx(i, j);
      gxy(i0 + i, j0 + j) += s * sxy(i, j);
      gyy(i0 + i, j0 + j) += s * syy(i, j);
      en += s * (sxx(i, j) + syy(i, j));
    }
    return en;
  });
  return mu_s > 0.0 ? 0.5 * e * dx * dx : 0.0;  // (1-H) mu_s (tr b - 2) = (1-H) tr(sigma)/2
}

void blend_stress_divergence(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj,
                             double dx, double w_t, View fx, View fy, int i0, int j0) {
  const double inv2 = 0.5 / dx;
  parallel_rows(0, nj, [&](int j) {
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
  parallel_rows(0, ny, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      fx(i, j) += (sxx(i + 1, j) - sxx(i - 1, j) + sxy(i, j + 1) - sxy(i, j - 1)) * inv2;
      fy(i, j) += (sxy(i + 1, j) - sxy(i - 1, j) + syy(i, j + 1) - syy(i, j - 1)) * inv2;
    }
  });
}

}  // namespace refmap
