#pragma once
// Kinematics shared by the constitutive models (kernels/constitutive.hpp): the left
// Cauchy-Green tensor b of eq. (2.9) from the reference-map gradient, and its invariants.
// Plane strain: b is the in-plane 2 x 2 block, the out-of-plane stretch is 1.
#include <cmath>

namespace refmap {

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

/// Largest eigenvalue of b: the largest principal stretch squared.
inline double max_stretch2(const Sym2& b) {
  const double m = 0.5 * (b.xx + b.yy);
  const double d = std::sqrt(0.25 * (b.xx - b.yy) * (b.xx - b.yy) + b.xy * b.xy);
  return m + d;
}

/// tr b / sqrt(det b) - 2: the isochoric in-plane invariant, I1 - 3 of an incompressible
/// plane-strain deformation (det b = 1, out-of-plane stretch 1), >= 0. Blind to the volume
/// drift of the discrete xi (det b != 1), whose isotropic stress the pressure takes; for
/// det b <= 0 (a folded map) it falls back to tr b - 2.
inline double isochoric_i1_minus_3(const Sym2& b) {
  const double det = b.xx * b.yy - b.xy * b.xy;
  return det > 0.0 ? (b.xx + b.yy) / std::sqrt(det) - 2.0 : b.xx + b.yy - 2.0;
}

}  // namespace refmap
