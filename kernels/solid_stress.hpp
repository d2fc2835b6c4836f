#pragma once
// Solid mechanics kernels of the reference map technique (Jain & Mani, sections 2-3):
//  - the smoothed Heaviside of eq. (3.5),
//  - the Cauchy stress of a constitutive model (kernels/constitutive.hpp; the paper's
//    neo-Hookean eq. 2.9 by default) from central differences of xi (eq. 3.1),
//  - blending into the mixture stress (eqs. 3.5-3.6) in the conservative form (divergence
//    of the blended stress) or the non-conservative one (blend of divergences),
//  - the divergence of a cell-centred stress tensor in flux form with face values the mean
//    of the two cells, so the sum over cells telescopes and momentum is conserved.
// The kernels that evaluate the model are templates on it (defined below), so the model's
// inline functions stay inside the vectorised loops.
#include <algorithm>
#include <cmath>

#include "kernels/constitutive.hpp"
#include "kernels/loop.hpp"
#include "core/field.hpp"

namespace refmap {

/// Eq. (3.5): 0 for x <= -w, 1/2 [1 + x/w + sin(pi x / w)/pi] for |x| < w, 1 for x >= w.
/// H is 1 in the fluid (phi > 0) and 0 in the solid.
inline double smoothed_heaviside(double x, double w) {
  if (x <= -w) return 0.0;
  if (x >= w) return 1.0;
  return 0.5 * (1.0 + x / w + std::sin(M_PI * x / w) / M_PI);
}

/// Stress of one solid on its window (local arrays, one ghost layer of xi used):
/// sigma_s = model.stress(b) (e.g. 2 mu_s (b - I)) for cells with phi < phi_max, 0
/// elsewhere. Gradients by central differences, eq. (3.1).
template <ConstitutiveModel M>
void cell_stress(const M& model, CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx,
                 double phi_max, View sxx, View sxy, View syy);

/// Conservative blending, eq. (3.6): S(i0+i, j0+j) += w sigma_s(i, j) on the window, with
/// w = 1 - H(phi) (H of half-width w_t), or, for light_ratio = rho_f / rho_s < 1
/// (solids.stress_blend = "specific"), w = (1 - H) rho_b / rho_s = (1 - H)(1 - H + H
/// light_ratio). Returns the elastic energy sum w W(b) dx^2, b read back from the stored
/// stress (model.strain), W the model's (isochoric) energy density.
template <ConstitutiveModel M>
double blend_stress(const M& model, CView sxx, CView sxy, CView syy, CView phi, int ni, int nj,
                    double dx, double w_t, View gxx, View gxy, View gyy, int i0, int j0,
                    double light_ratio = 1.0);

/// Largest tangent shear modulus model.wave_modulus(b) over the cells with phi < phi_max
/// (b read back from the stored stress), at least its value at rest: the time-step bound.
template <ConstitutiveModel M>
double max_wave_modulus(const M& model, CView sxx, CView sxy, CView syy, CView phi, int ni,
                        int nj, double phi_max);

/// Cell tensor of the upper-convected implicit step (time.solid_stress = "upper_convected",
/// kernels/helmholtz.hpp, docs/implicit.md): q(i0+i, j0+j) += scale G0 (1 - H(phi)) b on
/// the cells with phi < w_t, b read back from the stored stress (model.strain) and G0 the
/// model's tangent modulus at rest (2 mu_s for neo-Hookean, whose stress 2 mu_s (b - I)
/// changes by exactly 2 mu_s db). Blended with 1 - H(phi - reach) (eq. 3.6 for reach = 0,
/// the stress's blend; reach > 0, a length, extends it into the fluid: docs/implicit.md).
template <ConstitutiveModel M>
void blend_rate_coefficients(const M& model, CView sxx, CView sxy, CView syy, CView phi, int ni,
                             int nj, double w_t, double reach, double scale, View qxx, View qxy,
                             View qyy, int i0, int j0) {
  const double g0 = scale * model.wave_modulus({1.0, 0.0, 1.0});
  parallel_rows(0, nj, ni, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j) - reach;
      if (!(ph < w_t)) continue;
      const double s = g0 * (1.0 - smoothed_heaviside(ph, w_t));
      const Sym2 b = model.strain({sxx(i, j), sxy(i, j), syy(i, j)});
      qxx(i0 + i, j0 + j) += s * b.xx;
      qxy(i0 + i, j0 + j) += s * b.xy;
      qyy(i0 + i, j0 + j) += s * b.yy;
    }
  });
}

/// Non-conservative blending (the form the paper shows failing, Fig. 14):
/// f(i0+i, j0+j) += (1 - H(phi)) div(sigma_s)(i, j). sigma_s ghosts must be valid.
void blend_stress_divergence(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj,
                             double dx, double w_t, View fx, View fy, int i0, int j0);

/// f += div S for a cell-centred symmetric tensor S (conservative form):
/// fx = (Sxx_{i+1} - Sxx_{i-1} + Sxy_{j+1} - Sxy_{j-1}) / (2 dx), likewise fy.
/// One ghost layer of S must be filled.
void add_stress_divergence(CView sxx, CView sxy, CView syy, View fx, View fy, int nx, int ny,
                           double dx);

/// Compact face-based divergence of the solid stress of one solid (StressForm::Face,
/// `solids.stress_discretisation = "face"`; the default is StressForm::Cell, the paper's
/// cell-centred stress divided by add_stress_divergence above). On every face the gradient
/// of xi is taken with the compact normal difference and the average of the two cells' central tangential differences (as the
/// viscous stress in kernels/viscous.cpp), b and sigma_s = model.stress(b) are evaluated
/// there, and f = div sigma by face differences. Unlike the divergence of the cell-centred
/// stress built from eq. (3.1) (a 2 dx-wide stencil that cannot see the odd-even mode,
/// which then rings undamped inside an inviscid solid), this couples neighbouring cells.
/// It is exact for affine xi like the cell form.
///   conservative:     sigma_f blended with (1 - H(phi_f)), phi_f the mean of the two
///                     cells, then differenced (divergence of the blended stress);
///   non-conservative: f_P = (1 - H(phi_P)) div(sigma_s) (blend of divergences).
/// Adds to the global fx, fy at (i0 + i, j0 + j) for window cells with phi < w_t + dx.
template <ConstitutiveModel M>
void add_face_stress_force(const M& model, CView xi_x, CView xi_y, CView phi, int ni, int nj,
                           double dx, double w_t, bool conservative, View fx, View fy, int i0,
                           int j0);

// ---- definitions -------------------------------------------------------------------------

template <ConstitutiveModel M>
void cell_stress(const M& model, CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx,
                 double phi_max, View sxx, View sxy, View syy) {
  const double inv2 = 0.5 / dx;
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
    const M m = model;  // a local copy: its constants stay in registers and the loop vectorises
#pragma omp simd
    for (int i = 0; i < ni; ++i) {
      const double gxx = (xc[i + 1] - xc[i - 1]) * inv2;
      const double gxy = (xn[i] - xs[i]) * inv2;
      const double gyx = (yc[i + 1] - yc[i - 1]) * inv2;
      const double gyy = (yn[i] - ys[i]) * inv2;
      const Sym2 s = m.stress(elastic_left_cauchy_green(m, gxx, gxy, gyx, gyy));
      const bool in = ph[i] < phi_max;  // false for NaN phi too
      oxx[i] = in ? s.xx : 0.0;
      oxy[i] = in ? s.xy : 0.0;
      oyy[i] = in ? s.yy : 0.0;
    }
  });
}

template <ConstitutiveModel M>
double blend_stress(const M& model, CView sxx, CView sxy, CView syy, CView phi, int ni, int nj,
                    double dx, double w_t, View gxx, View gxy, View gyy, int i0, int j0,
                    double light_ratio) {
  const bool specific = light_ratio < 1.0;
  const double e = parallel_rows_sum(0, nj, ni, [&](int j) {
    double en = 0.0;
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j);
      if (ph >= w_t) continue;
      double s = 1.0 - smoothed_heaviside(ph, w_t);
      if (specific) s *= s + (1.0 - s) * light_ratio;  // rho_b / rho_s
      gxx(i0 + i, j0 + j) += s * sxx(i, j);
      gxy(i0 + i, j0 + j) += s * sxy(i, j);
      gyy(i0 + i, j0 + j) += s * syy(i, j);
      en += s * model.energy(model.strain({sxx(i, j), sxy(i, j), syy(i, j)}));
    }
    return en;
  });
  return e * dx * dx;
}

template <ConstitutiveModel M>
double max_wave_modulus(const M& model, CView sxx, CView sxy, CView syy, CView phi, int ni,
                        int nj, double phi_max) {
  double g = model.wave_modulus({1.0, 0.0, 1.0});
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      if (!(phi(i, j) < phi_max)) continue;
      g = std::max(g, model.wave_modulus(model.strain({sxx(i, j), sxy(i, j), syy(i, j)})));
    }
  return g;
}

namespace detail {

/// sigma_s - (pressure-free, rest-free) at the x-face between cells (i-1, j) and (i, j):
/// returns (sigma_xx, sigma_xy) — the x-momentum and y-momentum fluxes through it.
template <ConstitutiveModel M>
inline void x_face_flux(const M& model, CView xx, CView xy, int i, int j, double inv,
                        double& fxx, double& fxy) {
  const double gxx = (xx(i, j) - xx(i - 1, j)) * inv;
  const double gyx = (xy(i, j) - xy(i - 1, j)) * inv;
  const double gxy = 0.25 * (xx(i, j + 1) - xx(i, j - 1) + xx(i - 1, j + 1) - xx(i - 1, j - 1)) * inv;
  const double gyy = 0.25 * (xy(i, j + 1) - xy(i, j - 1) + xy(i - 1, j + 1) - xy(i - 1, j - 1)) * inv;
  const Sym2 s = model.stress(elastic_left_cauchy_green(model, gxx, gxy, gyx, gyy));
  fxx = s.xx;
  fxy = s.xy;
}

/// Same at the y-face between (i, j-1) and (i, j): returns (sigma_xy, sigma_yy).
template <ConstitutiveModel M>
inline void y_face_flux(const M& model, CView xx, CView xy, int i, int j, double inv,
                        double& fyx, double& fyy) {
  const double gxy = (xx(i, j) - xx(i, j - 1)) * inv;
  const double gyy = (xy(i, j) - xy(i, j - 1)) * inv;
  const double gxx = 0.25 * (xx(i + 1, j) - xx(i - 1, j) + xx(i + 1, j - 1) - xx(i - 1, j - 1)) * inv;
  const double gyx = 0.25 * (xy(i + 1, j) - xy(i - 1, j) + xy(i + 1, j - 1) - xy(i - 1, j - 1)) * inv;
  const Sym2 s = model.stress(elastic_left_cauchy_green(model, gxx, gxy, gyx, gyy));
  fyx = s.xy;
  fyy = s.yy;
}

}  // namespace detail

template <ConstitutiveModel M>
void add_face_stress_force(const M& model, CView xi_x, CView xi_y, CView phi, int ni, int nj,
                           double dx, double w_t, bool conservative, View fx, View fy, int i0,
                           int j0) {
  const double inv = 1.0 / dx;
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
      if (w_l != 0.0) detail::x_face_flux(model, xi_x, xi_y, i, j, inv, lxx, lxy);
      if (w_r != 0.0) detail::x_face_flux(model, xi_x, xi_y, i + 1, j, inv, rxx, rxy);
      if (w_b != 0.0) detail::y_face_flux(model, xi_x, xi_y, i, j, inv, bxy, byy);
      if (w_t_ != 0.0) detail::y_face_flux(model, xi_x, xi_y, i, j + 1, inv, txy, tyy);
      const double ax = (w_r * rxx - w_l * lxx + w_t_ * txy - w_b * bxy) * inv;
      const double ay = (w_r * rxy - w_l * lxy + w_t_ * tyy - w_b * byy) * inv;
      fx(i0 + i, j0 + j) += w_c * ax;
      fy(i0 + i, j0 + j) += w_c * ay;
    }
  });
}

}  // namespace refmap
