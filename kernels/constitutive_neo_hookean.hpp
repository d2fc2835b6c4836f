#pragma once
// Incompressible neo-Hookean solid, the paper's law: sigma = 2 mu_s b - p I (eq. 2.9),
// energy density W = mu_s (I1 - 3), shear modulus G = 2 mu_s.
// Interface: see kernels/constitutive.hpp.
#include <cmath>

#include "kernels/constitutive_kinematics.hpp"

namespace refmap {

struct NeoHookean {
  double mu;      ///< the paper's mu_s
  double c;       ///< 2 mu_s
  double inv2mu;  ///< 1 / (2 mu_s) (0 for mu_s = 0)
  explicit NeoHookean(double mu_s) : mu(mu_s), c(2.0 * mu_s), inv2mu(mu_s > 0.0 ? 0.5 / mu_s : 0.0) {}

  /// Stored stress 2 mu_s (b - I): the constant isotropic 2 mu_s I of eq. (2.9) is a
  /// pressure and is absorbed into P (keeping it would only add -2 mu_s grad(1 - H), which
  /// the projection has to cancel).
  Sym2 stress(const Sym2& b) const { return {c * (b.xx - 1.0), c * b.xy, c * (b.yy - 1.0)}; }
  /// b back from the stored stress (the energy and the time step read it from there).
  Sym2 strain(const Sym2& s) const {
    return {1.0 + s.xx * inv2mu, s.xy * inv2mu, 1.0 + s.yy * inv2mu};
  }
  /// Isochoric energy density mu_s (tr b / sqrt(det b) - 2) >= 0; the plain mu_s (tr b - 2)
  /// went negative when the discrete xi drifted in volume (det b < 1).
  double energy(const Sym2& b) const { return mu * isochoric_i1_minus_3(b); }
  /// Tangent shear modulus for the shear-wave time-step bound: the neo-Hookean tangent
  /// stiffness along a principal direction grows with the stretch squared, 2 mu_s lambda_max(b).
  double wave_modulus(const Sym2& b) const { return c * max_stretch2(b); }
};

}  // namespace refmap
