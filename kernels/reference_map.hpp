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
// With XiFlux::Superbee, XiFlux::VanLeer or XiFlux::Minmod the face values are limited upwind
// (Superbee as in kernels/advection.hpp, van Leer's smooth limiter, or minmod, the most
// dissipative of the second-order TVD limiters: Sweby 1984) in the same form,
// [ue (q_e - q_i) + uw (q_i - q_w)] / dx: still exact for affine q (r = 1 gives the central
// face value), first order at grid-scale oscillations, which they damp. They read two ghost
// layers of xi.
//
// Which velocity carries xi (XiVelocity, `solids.xi_velocity`): the face velocities
// (default), or the cell-centred velocity u_P that the solid stress accelerates, with the
// same face values of xi: u.grad q = u_P [(q_e - q_i) + (q_i - q_w)] / dx + (same in y).
// Why the cell velocity: the solid's force acts on u_P, but u_f = (u_P + u_E) / 2 - dt G_f
// (eq. 5.3) averages it, so with face velocities the displacement rate xi sees is
// (u_W + 2 u_P + u_E) / 4 - the cell velocity filtered by cos^2(k dx / 2) - and the compact
// face stress then restores a wave of k dx = theta with omega = c sin(theta) / dx instead of
// 2 c sin(theta / 2) / dx: no restoring force at all for the odd-even mode of the velocity
// along its own direction (which the projection does not see either), and phase speeds
// below a fluid's speed past the solid for waves of a few cells (docs/reference_map.md,
// "Which velocity carries xi"). With u_P every mode of the velocity strains xi. Both are
// exact for affine xi under a rigid motion sampled at the cells; u_P is only
// approximately divergence-free (Algorithm 1 step 9), and on the Turek & Hron flag (a 10:1
// density jump) that divergence compresses xi until the map folds, far sooner than the
// face form's wave grows: an experiment that failed (results/fsi.md, "The grid-scale wave
// along the flag").
#include "core/field.hpp"

namespace refmap {

enum class XiFlux { Central, Superbee, VanLeer, Minmod };
enum class XiVelocity { Face, Cell };

/// How far from a cell of Omega_S (phi < 0) reference_map_rhs reads xi, in cells along a grid
/// direction: the central increments read the four neighbours, the limited ones one cell
/// further (q_{i+2} and q_{i-1} for the face between i and i + 1). The RK-4 stages need the
/// extrapolated band only this far (Solid::advect).
constexpr int reference_map_rhs_reach(XiFlux flux) { return flux == XiFlux::Central ? 1 : 2; }

/// k = -H u.grad(xi) for both components on a window (local (i, j) = global (i0+i, j0+j));
/// uf, vf are the global face-velocity views; one ghost layer of xi is read.
void reference_map_rhs(CView xi_x, CView xi_y, CView phi, CView uf, CView vf, int ni, int nj,
                       int i0, int j0, double dx, View kx, View ky, XiFlux flux = XiFlux::Central);

/// The same carried by the cell-centred velocity (u, v) (XiVelocity::Cell): the global cell
/// views, read at (i0 + i, j0 + j) for both faces of a direction.
void reference_map_rhs_cell(CView xi_x, CView xi_y, CView phi, CView u, CView v, int ni, int nj,
                            int i0, int j0, double dx, View kx, View ky, XiFlux flux = XiFlux::Central);

}  // namespace refmap
