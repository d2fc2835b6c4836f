#pragma once
// The two sums of a control-volume momentum balance over a rectangle of whole cells
// (docs/bodies.md, "Force from a control volume"; the bookkeeping per body is
// solver/components/control_volume_forces.hpp). For a control volume V with surface S (outer normal
// n), the momentum equation of the mixture (eq. 2.1 with the blended stress of eq. 3.6)
// integrated over V gives the force of the fluid on what lies inside as
//     F = oint_S [(-p I + mu (grad u + grad u^T) + sigma_s) n - rho u (u . n)] dS
//         - d/dt int_V w rho_f u dV - rho_f g int_V (1 - w) dV,
// w the fluid fraction (the fluid's part of the momentum: the solids' own inertia is left
// out). These kernels compute the surface sum (box_surface_force) and the volume sums
// (box_momentum); they know nothing of bodies.
#include <array>

#include "core/field.hpp"

namespace refmap {

/// Cells [i0, i1) x [j0, j1); its surface is the cell faces around it.
struct ControlBox {
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  bool empty() const { return i1 <= i0 || j1 <= j0; }
};

/// Where a box's cells and faces are: the grid's spacing and lower-left corner, the number
/// of interior cells, and the point torques are taken about.
struct BoxFrame {
  double dx = 1.0, x0 = 0.0, y0 = 0.0;
  int nx = 0, ny = 0;
  double xr = 0.0, yr = 0.0;
};

/// What the surface sum reads: cell-centred u, v, p, mu, rho with one ghost layer filled
/// (the tangential derivatives reach one cell past the box's corners); the face normal
/// velocities uf ((nx+1) x ny) and vf (nx x (ny+1)), exactly divergence-free, carry the
/// momentum flux; sxx, sxy, syy the blended solid stress (sxx.p == nullptr: none).
struct SurfaceFields {
  CView u, v, p, mu, rho, uf, vf, sxx, sxy, syy;
};

/// oint_S [(-p I + tau + sigma_s) n - rho u (u_f . n)] dS over the faces around the box
/// (x, y and the torque about (xr, yr)), tau = mu (grad u + grad u^T): on a face the normal
/// derivatives are the compact difference of the two cells, the tangential ones the mean
/// of their central differences, p, mu, rho u and sigma_s the mean of the two cells (sigma_s
/// the inner cell's on a face of the domain's boundary, where its ghosts are not filled).
std::array<double, 3> box_surface_force(const SurfaceFields& f, const ControlBox& b, const BoxFrame& fr);

/// Sums over the box's cells, w clamped to [0, 1]: {int w rho_w u, int w rho_w v,
/// int w rho_w r x u, int (1 - w), int (1 - w) r_x, int (1 - w) r_y} dV, r = x - (xr, yr).
std::array<double, 6> box_momentum(CView u, CView v, CView w, double rho_w, const ControlBox& b, const BoxFrame& fr);

}  // namespace refmap
