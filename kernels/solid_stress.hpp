#pragma once
// Solid mechanics kernels of the reference map technique (Jain & Mani, sections 2-3):
//  - the smoothed Heaviside of eq. (3.5),
//  - the neo-Hookean Cauchy stress of eq. (2.9) from central differences of xi (eq. 3.1),
//  - blending into the mixture stress (eqs. 3.5-3.6) in the conservative form (divergence
//    of the blended stress) or the non-conservative one (blend of divergences),
//  - the divergence of a cell-centred stress tensor in flux form with face values the mean
//    of the two cells, so the sum over cells telescopes and momentum is conserved.
#include <cmath>

#include "solver/field.hpp"

namespace refmap {

/// Eq. (3.5): 0 for x <= -w, 1/2 [1 + x/w + sin(pi x / w)/pi] for |x| < w, 1 for x >= w.
/// H is 1 in the fluid (phi > 0) and 0 in the solid.
inline double smoothed_heaviside(double x, double w) {
  if (x <= -w) return 0.0;
  if (x >= w) return 1.0;
  return 0.5 * (1.0 + x / w + std::sin(M_PI * x / w) / M_PI);
}

struct Sym2 { double xx, xy, yy; };

/// Left Cauchy-Green tensor b = F F^T with F = (grad xi)^{-1}, i.e.
/// b = [(grad xi)^T (grad xi)]^{-1} (eq. 2.9), for the gradient
/// g = [[dxi_x/dx, dxi_x/dy], [dxi_y/dx, dxi_y/dy]].
inline Sym2 left_cauchy_green(double gxx, double gxy, double gyx, double gyy) {
  const double mxx = gxx * gxx + gyx * gyx;  // M = g^T g, b = M^{-1}
  const double mxy = gxx * gxy + gyx * gyy;
  const double myy = gxy * gxy + gyy * gyy;
  const double inv = 1.0 / (mxx * myy - mxy * mxy);  // det M = (det g)^2
  return {myy * inv, -mxy * inv, mxx * inv};
}

/// Neo-Hookean stress of one solid on its window (local arrays, one ghost layer of xi
/// used): sigma_s = 2 mu_s (b - I) for cells with phi < phi_max, 0 elsewhere. The constant
/// isotropic 2 mu_s I of eq. (2.9) is a pressure and is absorbed into P; keeping it would
/// only add -2 mu_s grad(1 - H), which the projection has to cancel. Gradients by central
/// differences, eq. (3.1).
void neo_hookean_stress(CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx, double mu_s,
                        double phi_max, View sxx, View sxy, View syy);

/// Conservative blending, eq. (3.6): S(i0+i, j0+j) += (1 - H(phi)) sigma_s(i, j) on the
/// window, H of half-width w_t. Returns the elastic energy
/// sum (1 - H) mu_s (tr b / sqrt(det b) - 2) dx^2, b = I + sigma_s / (2 mu_s): the isochoric
/// neo-Hookean energy (tr C - 3 with unit out-of-plane stretch when det b = 1, which the
/// continuous map keeps). It is >= 0; the plain mu_s (tr b - 2) went negative when the
/// discrete xi drifted in volume (det b < 1), an isotropic part the pressure takes.
double blend_stress(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj, double dx,
                    double w_t, double mu_s, View gxx, View gxy, View gyy, int i0, int j0);

/// Non-conservative blending (the form the paper shows failing, Fig. 14):
/// f(i0+i, j0+j) += (1 - H(phi)) div(sigma_s)(i, j). sigma_s ghosts must be valid.
void blend_stress_divergence(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj,
                             double dx, double w_t, View fx, View fy, int i0, int j0);

/// f += div S for a cell-centred symmetric tensor S (conservative form):
/// fx = (Sxx_{i+1} - Sxx_{i-1} + Sxy_{j+1} - Sxy_{j-1}) / (2 dx), likewise fy.
/// One ghost layer of S must be filled.
void add_stress_divergence(CView sxx, CView sxy, CView syy, View fx, View fy, int nx, int ny,
                           double dx);

}  // namespace refmap

namespace refmap {

/// Compact face-based divergence of the neo-Hookean stress of one solid (StressForm::Face,
/// `solids.stress_discretisation = "face"`; the default is StressForm::Cell, the paper's
/// cell-centred stress divided by add_stress_divergence above). On every face the gradient of xi is taken with the compact normal
/// difference and the average of the two cells' central tangential differences (as the
/// viscous stress in kernels/viscous.cpp), b and sigma_s = 2 mu_s (b - I) are evaluated
/// there, and f = div sigma by face differences. Unlike the divergence of the cell-centred
/// stress built from eq. (3.1) (a 2 dx-wide stencil that cannot see the odd-even mode,
/// which then rings undamped inside an inviscid solid), this couples neighbouring cells.
/// It is exact for affine xi like the cell form.
///   conservative:     sigma_f blended with (1 - H(phi_f)), phi_f the mean of the two
///                     cells, then differenced (divergence of the blended stress);
///   non-conservative: f_P = (1 - H(phi_P)) div(sigma_s) (blend of divergences).
/// Adds to the global fx, fy at (i0 + i, j0 + j) for window cells with phi < w_t + dx.
void add_face_stress_force(CView xi_x, CView xi_y, CView phi, int ni, int nj, double dx,
                           double mu_s, double w_t, bool conservative, View fx, View fy, int i0,
                           int j0);

}  // namespace refmap
