#pragma once
// The variable-coefficient 5-point Poisson operator, written once. In cell-integrated form
// (kernels/multigrid.hpp; on the finest level L = dx^2 A, A the operator div(beta grad)
// of the projection's pressure Poisson equation, solver/pressure/poisson.hpp)
//
//     (L x)_P = sum_faces T_f (x_nb - x_P),
//
// with the four faces west, east, south, north of cell P. Every kernel that applies L
// (residuals, CG's q = L p) or relaxes it (Gauss-Seidel, Jacobi) calls these two
// functions, so all of them use the same operation order: a change here changes them all.
// Values, not pointers: the kernels read neighbours from different places (rows of a
// field, row buffers of the Jacobi sweep, wrapped indices in the tests).

namespace refmap {

/// (L x)_P from the face coefficients (tw, te, ts, tn), the neighbours and the centre.
inline double stencil5_apply(double tw, double te, double ts, double tn, double xw, double xe,
                             double xs, double xn, double xc) {
  return tw * (xw - xc) + te * (xe - xc) + ts * (xs - xc) + tn * (xn - xc);
}

/// The x_P that makes (f - L x)_P = 0 with the neighbours fixed (the Gauss-Seidel /
/// Jacobi target): (sum_f T_f x_nb - f) * id, id = 1 / sum_f T_f.
inline double stencil5_relax(double tw, double te, double ts, double tn, double xw, double xe,
                             double xs, double xn, double f, double id) {
  return (tw * xw + te * xe + ts * xs + tn * xn - f) * id;
}

}  // namespace refmap
