#pragma once
// Variational (energy-consistent) solid force of one reference-map solid
// (`solids.stress_discretisation = "variational"`, docs/implicit.md, "The variational force").
//
// The semi-discrete stored energy of a solid is
//     E_h(xi) = sum_c w_c W(A_c) dx^2,   A_c = (grad_h xi)_c (central differences, eq. 3.1),
// with w_c = 1 - H(phi_c + s) (eq. 3.5, shifted inward by s). In a cell whose xi is advected,
// xi_k' = -A_k u_k (eq. 3.3), so dE_h/dt = sum_k g_k . xi_k' with g_k = dE_h / dxi_k, and the
// force density
//     f_k = A_k^T g_k / dx^2 = -A_k^T (div_h P)_k,      P_c = w_c dW/dA (A_c)
// does exactly the work -dE_h/dt on the velocity (sum_k f_k . u_k dx^2 = -dE_h/dt): no force
// without stored energy behind it. For that every g_k must sit on an advected cell, i.e. no
// cell with w_c > 0 may difference into an extrapolated neighbour: s >= w_T + dx (then
// w_c > 0 only where phi_c < -dx). With b = A^-1 A^-T and the stored stress sigma(b) (the
// Kirchhoff stress less a constant isotropic part, kernels/constitutive.hpp),
//     dW/dA = -A^-T sigma(b)
// is exact for the energy W(b) + 2 mu_s ln det A of neo-Hookean (equal to W where det A = 1;
// d tr b = -2 (A^-T b) : dA). In the continuum -A^T div(-A^-T sigma) = div sigma + grad W',
// the stress divergence up to a gradient, which the pressure takes: the form is consistent.
#include <cmath>

#include "kernels/constitutive.hpp"
#include "kernels/loop.hpp"
#include "kernels/solid_stress.hpp"
#include "core/field.hpp"

namespace refmap {

/// P = w dW/dA = -w A^-T sigma(b) on the window cells (interior, ghosts untouched) with
/// w = 1 - H(phi + shift) > 0 (0 elsewhere), (pxx, pxy, pyx, pyy) = P_{m j}, m the component
/// of xi, j the direction of the derivative. Returns sum w W(b) dx^2 (the model's energy).
template <ConstitutiveModel M>
double variational_stress_tensor(const M& model, CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx,
                                 double w_t, double shift, View pxx, View pxy, View pyx, View pyy) {
  const double inv2 = 0.5 / dx;
  const double e = parallel_rows_sum(0, nj, ni, [&](int j) {
    double en = 0.0;
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j) + shift;
      if (!(ph < w_t)) {
        pxx(i, j) = pxy(i, j) = pyx(i, j) = pyy(i, j) = 0.0;
        continue;
      }
      const double w = 1.0 - smoothed_heaviside(ph, w_t);
      const double a = (xi_x(i + 1, j) - xi_x(i - 1, j)) * inv2;  // d xi_x / dx
      const double b = (xi_x(i, j + 1) - xi_x(i, j - 1)) * inv2;  // d xi_x / dy
      const double c = (xi_y(i + 1, j) - xi_y(i - 1, j)) * inv2;  // d xi_y / dx
      const double d = (xi_y(i, j + 1) - xi_y(i, j - 1)) * inv2;  // d xi_y / dy
      const Sym2 bb = elastic_left_cauchy_green(model, a, b, c, d);
      const Sym2 s = model.stress(bb);
      // A^-T = [[d, -c], [-b, a]] / det A
      const double k = -w / (a * d - b * c);
      pxx(i, j) = k * (d * s.xx - c * s.xy);
      pxy(i, j) = k * (d * s.xy - c * s.yy);
      pyx(i, j) = k * (-b * s.xx + a * s.xy);
      pyy(i, j) = k * (-b * s.xy + a * s.yy);
      en += w * model.energy(bb);
    }
    return en;
  });
  return e * dx * dx;
}

/// f(i0+i, j0+j) += -A^T div_h P on the window cells where div_h P is not zero (one ghost
/// layer of P must be zero or valid).
inline void add_variational_force(CView xi_x, CView xi_y, CView pxx, CView pxy, CView pyx, CView pyy, int ni,
                                  int nj, double dx, View fx, View fy, int i0, int j0) {
  const double inv2 = 0.5 / dx;
  parallel_rows(0, nj, ni, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      // (div_h P)_m = d P_mx / dx + d P_my / dy, central as the transpose of eq. (3.1)'s
      const double dvx = (pxx(i + 1, j) - pxx(i - 1, j) + pxy(i, j + 1) - pxy(i, j - 1)) * inv2;
      const double dvy = (pyx(i + 1, j) - pyx(i - 1, j) + pyy(i, j + 1) - pyy(i, j - 1)) * inv2;
      if (dvx == 0.0 && dvy == 0.0) continue;
      const double a = (xi_x(i + 1, j) - xi_x(i - 1, j)) * inv2;
      const double b = (xi_x(i, j + 1) - xi_x(i, j - 1)) * inv2;
      const double c = (xi_y(i + 1, j) - xi_y(i - 1, j)) * inv2;
      const double d = (xi_y(i, j + 1) - xi_y(i, j - 1)) * inv2;
      fx(i0 + i, j0 + j) -= a * dvx + c * dvy;
      fy(i0 + i, j0 + j) -= b * dvx + d * dvy;
    }
  });
}

}  // namespace refmap
