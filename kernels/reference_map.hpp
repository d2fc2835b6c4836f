#pragma once
// Reference-map advection, eq. (3.3): d xi/dt + H u . grad xi = 0 with H = 1 only inside
// the solid (phi < 0) and 0 elsewhere, so xi is transported only where it is valid and
// the extrapolated band is left for the extrapolation to overwrite.
//
// u . grad xi is written with the exactly divergence-free face velocities of the
// projection: u . grad q = div(u_f q) - q div(u_f) with central face values gives
//   [uf_{i+1/2} (q_{i+1} - q_i) + uf_{i-1/2} (q_i - q_{i-1})] / (2 dx) + (same in y),
// a second-order central scheme that is exact for affine q when u_f is the exact velocity
// of a rigid motion (the Zalesak test measures only the time-integration error).
// With XiFlux::Superbee or XiFlux::VanLeer the face values are limited upwind (Superbee as
// in kernels/advection.hpp, or van Leer's smooth limiter) in the same form,
// [ue (q_e - q_i) + uw (q_i - q_w)] / dx: still exact for affine q (r = 1 gives the central
// face value), first order at grid-scale oscillations, which they damp. They read two ghost
// layers of xi.
#include "core/field.hpp"

namespace refmap {

/// CellCentral: central differences of xi times the CELL velocity, k = -(u_c . grad_h) xi
/// (grad_h the central gradient of eq. 3.1): the transport the variational solid force
/// (kernels/variational_stress.hpp) pairs with exactly; reference_map_rhs_cell below.
enum class XiFlux { Central, Superbee, VanLeer, CellCentral };

/// k = -H u.grad(xi) for both components on a window (local (i, j) = global (i0+i, j0+j));
/// uf, vf are the global face-velocity views; one ghost layer of xi is read.
void reference_map_rhs(CView xi_x, CView xi_y, CView phi, CView uf, CView vf, int ni, int nj,
                       int i0, int j0, double dx, View kx, View ky, XiFlux flux = XiFlux::Central);

/// XiFlux::CellCentral: k = -H (u . grad_h) xi with the global cell velocity views u, v.
void reference_map_rhs_cell(CView xi_x, CView xi_y, CView phi, CView u, CView v, int ni, int nj, int i0, int j0,
                            double dx, View kx, View ky);

}  // namespace refmap
