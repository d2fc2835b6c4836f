#pragma once
// Actuated solids: a stress-free configuration that changes in time by a prescribed affine
// map A(t) of the reference configuration (a swimmer's muscles; `actuation` of a [[solid]],
// docs/actuation.md). Multiplicative split F = F_e A of the deformation gradient
// F = (grad xi)^{-1}: the stress is that of the elastic part F_e = F A^{-1}, so the solid
// relaxes towards its reference shape mapped by A. Since F A^{-1} = (A grad xi)^{-1}, the
// elastic left Cauchy-Green tensor is eq. (2.9)'s b evaluated for A grad xi:
//   b_e = F_e F_e^T = left_cauchy_green(A grad xi).
// det A = 1 keeps the incompressible solid's area (the pressure would take any other).
// The transform happens in one place, elastic_left_cauchy_green below, which every stress
// kernel (kernels/solid_stress.hpp) calls instead of left_cauchy_green; for a model that is
// not Actuated it is left_cauchy_green itself (same arithmetic, same bits).
#include "kernels/constitutive_kinematics.hpp"

namespace refmap {

/// A 2 x 2 matrix [[xx, xy], [yx, yy]] (the actuation map A, det A = 1).
struct Affine2 {
  double xx = 1.0, xy = 0.0, yx = 0.0, yy = 1.0;
};

/// Model M of the elastic part F_e = F A^{-1}: stress, strain, energy and wave modulus are
/// M's of b_e (the kernels pass b_e, from elastic_left_cauchy_green).
template <class M>
struct Actuated {
  M model;
  Affine2 a;
  Sym2 stress(const Sym2& b) const { return model.stress(b); }
  Sym2 strain(const Sym2& s) const { return model.strain(s); }
  double energy(const Sym2& b) const { return model.energy(b); }
  double wave_modulus(const Sym2& b) const { return model.wave_modulus(b); }
};

/// b of the elastic part of the deformation for model m from the gradient
/// g = [[dxi_x/dx, dxi_x/dy], [dxi_y/dx, dxi_y/dy]]: b itself for a plain model.
template <class M>
inline Sym2 elastic_left_cauchy_green(const M&, double gxx, double gxy, double gyx, double gyy) {
  return left_cauchy_green(gxx, gxy, gyx, gyy);
}

/// For an actuated model: b of A g.
template <class M>
inline Sym2 elastic_left_cauchy_green(const Actuated<M>& m, double gxx, double gxy, double gyx, double gyy) {
  const Affine2& a = m.a;
  return left_cauchy_green(a.xx * gxx + a.xy * gyx, a.xx * gxy + a.xy * gyy, a.yx * gxx + a.yy * gyx,
                           a.yx * gxy + a.yy * gyy);
}

}  // namespace refmap
