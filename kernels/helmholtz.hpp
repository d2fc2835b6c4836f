#pragma once
// Operator assembly of the implicit velocity step (solver/implicit_step.hpp): for one
// velocity component w the Helmholtz-type problem
//
//     (rho/dt) d - d/dx(a_x m d_x d) - d/dy(a_y m d_y d) = f          (cell P)
//
// written in the form of the Poisson "sink" API (solver/poisson.hpp):
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

/// Periodic wrap of one ghost layer on the periodic directions; walls' ghosts set to 0.
void helmholtz_ghosts(View x, int nx, int ny, const Sides& sides);

}  // namespace refmap
