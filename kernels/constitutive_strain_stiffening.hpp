#pragma once
// Strain-stiffening incompressible solid in plane strain (a two-term I1 model):
//   W = c1 (I1 - 3) + c3 (I1 - 3)^2,  I1 = tr b + 1 (out-of-plane stretch 1),
//   sigma = 2 W1 b - p I,  W1 = dW/dI1 = c1 + 2 c3 (I1 - 3),
// c1 = mu_s of the scene; c3 = 0 is the neo-Hookean solid. Simple shear of amount g:
// sigma_xy = 2 (c1 + 2 c3 g^2) g, sigma_xx - sigma_yy = 2 (c1 + 2 c3 g^2) g^2.
// Interface: see kernels/constitutive.hpp.
// Stability (disc_tgv, mu_s = 0.5, 64^2): c3 = 0.5 and 1 decay like the neo-Hookean disc;
// c3 = 2 gains energy and blows up near t = 0.7-1.2 with the "cell" stress discretisation,
// whatever the solid time step (solid_cfl 0.5, 0.2, 0.15), but decays with "face". The
// stiffening law seems to pump the odd-even mode that the 2 dx-wide cell stencil leaves
// undamped (kernels/solid_stress.hpp); not investigated further.
#include <algorithm>
#include <cmath>

#include "kernels/constitutive_kinematics.hpp"

namespace refmap {

struct StrainStiffening {
  double c1, c3;
  StrainStiffening(double c1_, double c3_) : c1(c1_), c3(c3_) {}

  /// W1 at x = I1 - 3 = tr b - 2. An incompressible plane strain has tr b >= 2; the
  /// discrete xi drifts in volume (det b < 1 allows tr b < 2), where the unclamped W1 would
  /// drop below c1 and, for tr b - 2 < -c1 / (2 c3), turn negative (a negative stiffness).
  /// Such cells get the neo-Hookean W1 = c1.
  double w1(double x) const { return c1 + 2.0 * c3 * std::max(0.0, x); }
  /// Stored stress 2 W1 (b - I): sigma minus the isotropic 2 W1 I, which the pressure
  /// takes; zero at rest.
  Sym2 stress(const Sym2& b) const {
    const double k = 2.0 * w1(b.xx + b.yy - 2.0);
    return {k * (b.xx - 1.0), k * b.xy, k * (b.yy - 1.0)};
  }
  /// b back from the stored stress s = 2 W1 (b - I): with x = tr b - 2, tr s = 2 W1 x has
  /// the sign of x; for x > 0, tr s = 2 (c1 + 2 c3 x) x gives the root with W1 > 0,
  /// x = tr s / (c1 + sqrt(c1^2 + 4 c3 tr s)) (cancellation-free), else x = tr s / (2 c1).
  Sym2 strain(const Sym2& s) const {
    const double t = s.xx + s.yy;
    const double x = t > 0.0 ? t / (c1 + std::sqrt(c1 * c1 + 4.0 * c3 * t)) : t / (2.0 * c1);
    const double inv = 0.5 / w1(x);
    return {1.0 + s.xx * inv, s.xy * inv, 1.0 + s.yy * inv};
  }
  /// Energy density with the isochoric invariant (as the neo-Hookean diagnostic): x =
  /// tr b / sqrt(det b) - 2 = I1 - 3 for det b = 1, W = c1 x + c3 x^2.
  double energy(const Sym2& b) const {
    const double x = isochoric_i1_minus_3(b);
    return c1 * x + c3 * x * x;
  }
  /// Tangent shear modulus rho c^2 bound over in-plane shear waves of the pre-strained
  /// incompressible solid (Ogden's incremental moduli of W(I1) in principal axes:
  /// A_1212 = 2 W1 l1^2, A_2121 = 2 W1 l2^2, 2 beta = 2 W1 (l1^2 + l2^2) + 4 W11 (l1^2 - l2^2)^2,
  /// rho c^2 = A_1212 cos^4 + 2 beta cos^2 sin^2 + A_2121 sin^4 <= max(a, (a + beta) / 2),
  /// a = 2 W1 lambda_max(b), W11 = 2 c3). c3 = 0 gives the neo-Hookean 2 mu_s lambda_max(b).
  double wave_modulus(const Sym2& b) const {
    const double tr = b.xx + b.yy, det = b.xx * b.yy - b.xy * b.xy;
    const double W1 = w1(tr - 2.0);  // W11 = 2 c3 (an upper bound where W1 is clamped)
    const double a = 2.0 * W1 * max_stretch2(b);
    const double beta = W1 * tr + 4.0 * c3 * std::max(0.0, tr * tr - 4.0 * det);
    return std::max(a, 0.5 * (a + beta));
  }
};

}  // namespace refmap
