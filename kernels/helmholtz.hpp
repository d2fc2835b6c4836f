#pragma once
// Operator assembly of the implicit velocity step (solver/model/implicit_step.hpp): for one
// velocity component w the Helmholtz-type problem
//
//     (rho/dt) d - d/dx(a_x m d_x d) - d/dy(a_y m d_y d) = f          (cell P)
//
// written in the form of the Poisson "sink" API (solver/pressure/poisson.hpp):
//
//     (1/dx^2) sum_f beta_f (d_nb - d_P) - c_P d_P = -f_P,
//     beta_f = a m_f on interior faces (m_f the mean of the two cells, as in
//     kernels/viscous.cpp), c = rho/dt plus the wall terms below.
//
// The compact normal part of the full stress div m (grad u + grad u^T): a_x = 2, a_y = 1
// for u (2 m u_xx + m u_yy), a_x = 1, a_y = 2 for v. The unknown d is the velocity change
// over the step, so every wall condition is homogeneous: a side on which the component is
// fixed (Dirichlet: ghost = -d, the wall value lies on the face, half a cell away) adds
// 2 a m_P / dx^2 to c_P of the cells next to it and keeps beta = 0 on its face; a side on
// which it is free (free-slip tangential: ghost = +d, zero flux) adds nothing. Each side is
// treated in one switch over its FaceKind (kernels/boundary_kind.hpp), so new kinds get a
// case here.
#include <array>

#include "core/field.hpp"
#include "kernels/boundary_kind.hpp"

namespace refmap {

/// Face coefficients beta_x = a_x m_f ((nx+1) x ny), beta_y = a_y m_f (nx x (ny+1));
/// 0 on wall faces; a periodic direction's faces 0 and n carry the same value. m needs
/// one ghost layer (periodic wrap where periodic).
void helmholtz_faces(CView m, View bx, View by, int nx, int ny, double ax, double ay,
                     const Sides& sides);

/// Sink c = rho/dt + the Dirichlet wall terms 2 a m_P / dx^2 on the sides where
/// `fixed[side]` (a Wall side on which the component is prescribed).
void helmholtz_sink(CView rho, CView m, View c, int nx, int ny, double dx, double dt, double ax,
                    double ay, const Sides& sides, const std::array<bool, 4>& fixed);

/// out = (1/dx^2) sum_f beta_f (x_nb - x_P) - c_P x_P (the operator of the sink API).
/// x needs one ghost layer: periodic wrap on periodic sides, any finite value on walls.
void helmholtz_apply(CView x, CView bx, CView by, CView c, View out, int nx, int ny, double dx);

// ---- upper-convected solid stress (time.solid_stress = "upper_convected") ---------------
// The stress increment over a step, tau = 2 mu_s dt (1 - H)(L b + b L^T) with L = grad d
// (docs/implicit.md), written with the cell tensor q = 2 mu_s dt (1 - H) b (summed over the
// solids; kernels/solid_stress.hpp, blend_rate_coefficients):
//     tau_xx = 2 (q_xx d_u,x + q_xy d_u,y)
//     tau_xy = q_xy d_u,x + q_yy d_u,y + q_xx d_v,x + q_xy d_v,y
//     tau_yy = 2 (q_xy d_v,x + q_yy d_v,y)
// and its force div tau in flux form (faces: q the mean of the two cells, normal
// derivatives compact, tangential ones the mean of the two cells' central differences,
// exactly as kernels/viscous.cpp; for q = eta I it is viscous_force with mu = eta).
// The compact part (the normal derivative of the same component: 2 q_xx on x faces and
// q_yy on y faces for u, q_xx and 2 q_yy for v) goes into the Helmholtz operator through
// the cell coefficients below; the rest (the "cross" terms) is evaluated at the latest
// iterate and moved to the right-hand side.

/// Face coefficients from cell coefficients: beta_x = mean of kx over the two cells,
/// beta_y = mean of ky; 0 on bounded sides' faces (as helmholtz_faces). kx, ky need one
/// ghost layer (periodic wrap where periodic).
void helmholtz_faces_cells(CView kx, CView ky, View bx, View by, int nx, int ny, const Sides& sides);

/// Sink c = rho/dt + 2 kx_P / dx^2 next to a fixed left/right side, 2 ky_P / dx^2 next to
/// a fixed bottom/top side (the Dirichlet wall of helmholtz_sink with a m -> k).
void helmholtz_sink_cells(CView rho, CView kx, CView ky, View c, int nx, int ny, double dx,
                          double dt, const Sides& sides, const std::array<bool, 4>& fixed);

/// fx, fy = div tau(du, dv) (full = true) or only its cross part (full = false: div tau
/// less the compact part that helmholtz_faces_cells carries). du, dv, q need one ghost
/// layer (corners too).
void rate_stress_force(CView du, CView dv, CView qxx, CView qxy, CView qyy, View fx, View fy,
                       int nx, int ny, double dx, bool full);

/// Periodic wrap of one ghost layer on the periodic directions; walls' ghosts set to 0.
void helmholtz_ghosts(View x, int nx, int ny, const Sides& sides);

}  // namespace refmap
