#pragma once
// Velocity Verlet for the explicit elastic coupling (time.elastic_coupling = "verlet";
// docs/method.md, "Time step"). Algorithm 1 advects xi with the velocity of the step's start
// and then applies the whole force of the new xi's stress: for the solid that is symplectic
// Euler (drift, kick), and the velocity it stores runs half a step ahead of xi, so kinetic
// plus elastic energy is off by O(dt) and, with the adaptive step changing between steps, a
// loss accumulates. Velocity Verlet keeps the same single stress evaluation per step:
//
//   drift  xi^{n+1} = xi^n - dt w . grad xi^n,   w = u^n + dt/2 a^n
//   kick   u^{n+1}  = u^n + ... + dt/2 (F^n + F^{n+1}) / rho
//
// with F^n = F(xi^n) stored from the last step. The midpoint velocity w must be a
// projected (divergence-free) face field: a^n is taken from the last step's change of the
// projected face velocities, (u_f^n - u_f^{n-1}) / dt_{n-1}, whose stress part is
// P (F^{n-1} + F^n) / (2 rho); adding (F^n - F^{n-1}) / (2 rho) (averaged to the faces) makes
// that F^n / rho, so for the solid the drift is exactly Verlet's. The correction is not
// projected, but it is O(dt) and vanishes in an equilibrium (F^n = F^{n-1}).
#include "core/field.hpp"
#include "kernels/boundary_kind.hpp"

namespace refmap {

/// The drift's face velocities: w_f = u_f + cv (u_f - u_f,prev) + cf <d / rho>_f, with d the
/// cell field F^n - F^{n-1} (interior cells read; a periodic side wraps) and <.>_f the mean of
/// a face's two cells. cv = dt / (2 dt_prev), cf = dt / 4 (0 and 0 in a first step: w_f = u_f).
/// Non-periodic boundary faces take no force term (a wall's face velocity stays 0).
void verlet_drift_faces(CView uf, CView vf, CView ufp, CView vfp, CView dfx, CView dfy, CView rho, View wf,
                        View wv, int nx, int ny, double cv, double cf, Sides sides);

/// The kick: on entry fx holds the explicit viscous force vx plus the stress force F^{n+1};
/// leaves fx = vx + (F^n + F^{n+1}) / 2 with F^n = fp, then d = F^{n+1} - F^n and
/// fp = F^{n+1} (likewise y). Interior cells.
void verlet_kick(View fx, View fy, CView vx, CView vy, View fpx, View fpy, View dfx, View dfy, int nx, int ny);

}  // namespace refmap
