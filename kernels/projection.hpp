#pragma once
// The approximate projection of Algorithm 1, steps 5-9 (eqs. 5.3-5.7), on a collocated
// grid. Face quantities: x faces (nx+1) x ny (face i = left face of cell i), y faces
// nx x (ny+1). A boundary face is treated by the kind of its side
// (kernels/boundary_kind.hpp): a wall (normal velocity 0, beta 0, no pressure-gradient/
// body-force imbalance), periodic (computed from the wrapped ghost cells; face n repeats
// face 0), inflow (velocity from the ghost fill, beta 0, G_f extrapolated from the first
// interior face) or outflow (p = 0 on the face, beta = 1/rho_P, velocity from the ghost).
#include "kernels/boundary_kind.hpp"
#include "core/field.hpp"

namespace refmap {

/// beta = 1/rho_f on faces, rho_f the arithmetic mean of the two cells (ghosts of rho
/// filled); 0 on wall faces.
void face_beta(CView rho, View bx, View by, int nx, int ny, Sides sides);

/// Face "acceleration" G_f = beta_f (grad P)_f - F_f / rho_f with the balanced-force body
/// force F_f = (rho_f - rho_ref) g (step 5), i.e. F_f/rho_f = g (1 - rho_ref beta_f);
/// 0 on wall faces. p ghosts filled.
void face_accel(CView p, CView bx, CView by, View gx_f, View gy_f, int nx, int ny, double dx,
                double gx, double gy, double rho_ref, Sides sides);

/// Rhie-Chow-like face velocity, eq. (5.3): u_f = <u>_{P->f} - dt G_f (0 on walls).
void predict_face_velocity(CView u, CView v, CView gx_f, CView gy_f, View uf, View vf, int nx,
                           int ny, double dt, Sides sides);

/// out = scale * div(u_f) per cell: scale * [uf(i+1)-uf(i) + vf(j+1)-vf(j)] / dx.
void face_divergence(CView uf, CView vf, View out, int nx, int ny, double dx, double scale);

/// max over cells of |div u_f|.
double max_abs_face_divergence(CView uf, CView vf, int nx, int ny, double dx);

/// Eq. (5.6): u_f -= dt beta_f (grad dP)_f on every non-wall face (dp ghosts filled).
void correct_face_velocity(View uf, View vf, CView dp, CView bx, CView by, int nx, int ny,
                           double dx, double dt, Sides sides);

/// Eq. (5.7): u_P -= dt <G_f>_{f->P}, the average of the cell's two faces per direction.
void correct_cell_velocity(View u, View v, CView gx_f, CView gy_f, int nx, int ny, double dt);

}  // namespace refmap
