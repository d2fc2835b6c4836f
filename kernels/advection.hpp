#pragma once
// Advection of a cell-centred quantity q by face-normal velocities (flux form):
//     rhs = -div(u_f q) = -[ (uf q)_{i+1/2} - (uf q)_{i-1/2} + (vf q)_{j+1/2} - (vf q)_{j-1/2} ] / dx
// Used for momentum rho*u in eq. (5.1) (RK-4 stages) and, by the solids, for the
// reference map. Face values of q are second-order central or Superbee-limited upwind.
#include "core/field.hpp"

namespace refmap {

enum class FluxScheme { Central, Superbee };

/// Superbee limiter psi(r) = max(0, min(2r, 1), min(r, 2)).
inline double superbee(double r) {
  const double a = 2.0 * r < 1.0 ? 2.0 * r : 1.0;
  const double b = r < 2.0 ? r : 2.0;
  const double m = a > b ? a : b;
  return m > 0.0 ? m : 0.0;
}

/// Limited face value between upwind cell qu (with its own upwind neighbour quu) and
/// downwind cell qd: q_f = qu + 0.5 psi(r) (qd - qu), r = (qu - quu) / (qd - qu).
/// Evaluated without the division and without branches (so the loops vectorise): with
/// d = qd - qu, s = sign(d) and e = s (qu - quu), psi(r) d = s max(0, min(2e, |d|), min(e, 2|d|))
/// (both minima are <= 0 when e <= 0, and the expression is 0 when d = 0).
inline double superbee_face(double quu, double qu, double qd) {
  const double d = qd - qu;
  const double s = __builtin_copysign(1.0, d);
  const double ad = s * d;
  const double e = s * (qu - quu);
  const double m1 = 2.0 * e < ad ? 2.0 * e : ad;
  const double m2 = e < 2.0 * ad ? e : 2.0 * ad;
  double m = m1 > m2 ? m1 : m2;
  m = m > 0.0 ? m : 0.0;
  return qu + 0.5 * s * m;
}

/// rhs_a = -div(u_f a), rhs_b = -div(u_f b) for two quantities sharing the face
/// velocities (the two momentum components). q ghosts (two layers) must be filled.
/// uf: (nx+1) x ny, vf: nx x (ny+1).
void advect_rhs2(CView a, CView b, CView uf, CView vf, View rhs_a, View rhs_b, int nx, int ny,
                 double dx, FluxScheme scheme);

/// As advect_rhs2 with central face values, except on the faces flagged nonzero in
/// (lim_x, lim_y) (same shapes as uf, vf), which take the Superbee-limited value: the
/// momentum at a density jump (flag_density_jump_faces), where the central flux of rho*u
/// carries the heavy side's momentum into light cells undamped.
void advect_rhs2_hybrid(CView a, CView b, CView uf, CView vf, CView lim_x, CView lim_y, View rhs_a,
                        View rhs_b, int nx, int ny, double dx);

/// lim = 1 on the faces whose four-cell flux stencil (two cells each side) sees a density
/// difference in rho0 or rho1, else 0. rho ghosts (two layers) must be filled.
void flag_density_jump_faces(CView rho0, CView rho1, View lim_x, View lim_y, int nx, int ny);

}  // namespace refmap
