#pragma once
// Aslam (2004) PDE extrapolation, linear variant, per component of the reference map: the
// RMT baseline (Valkov et al. 2015) that the least-squares method is compared with
// (docs/references.md, "Methods cited in the code").
//
//   n = grad(phi)/|grad(phi)|   (central differences; one-sided at the domain edge)
//   (1) q_n = n . grad(xi) at known cells: central differences where both stencil cells are
//       known, else one-sided (PdeOptions::qn_one_sided), else q_n is "not computable" there
//       and the cell joins the q_n fill region;
//   (2) extend q_n:  dq/dtau + n . grad(q) = 0               (frozen where computed)
//   (3) fill xi:     dxi/dtau + n . grad(xi) - q_n = 0        (frozen where known)
// First-order upwind differences (the upwind neighbour of n_x > 0 is i-1), forward Euler,
// dtau = cfl dx, Jacobi updates (double buffer: deterministic, OpenMP over the cell list).
// Fill region: cells with known == 0 and phi <= band. Only the fill cells (and the known
// cells they depend on) are visited: the stencils are assembled once per call into a compact
// list, each pseudo-time iteration is one sweep over that list.
//
// Convergence: a solve stops at the first iteration with
//     max over its cells and both components |q^{k+1} - q^k| <= tol * S,
// S = the largest |value| among the frozen cells that feed the solve (|xi| of the known
// cells next to the band for (3), |q_n| for (2)); equivalently the steady-state residual
// |n.grad q - source| <= tol S / dtau. Default tol = 1e-8: the converged-vs-stopped
// difference is ~tol S (measured: 0.7-0.8 tol S), i.e. <= 1e-6 on the [0,100]^2 Zalesak
// problem, far below the PDE's own discretisation error there (paper: 8e-4; this code on
// an affine field: rms 5e-3 of the unit-square scale). Cost: ~4 iterations per PDE per decade
// of tol (disc r = 15 cells, band 5: 44+44 iterations at 1e-8, 52+52 at 1e-10, 36+36 at 1e-6).
//
// Cells of the fill region with no upwind path to known data (e.g. a pocket cut off by
// cells outside the band, or a cell where grad(phi) vanishes on every side) are left unknown
// and counted in ExtrapStats::unreached. Degenerate central gradients of phi fall back to a
// one-sided gradient (counted in ExtrapStats::fallbacks).
//
// Cells considered: the bounding box of the known cells grown by ceil(band/dx) + 2 cells
// (phi must be distance-like: a cell with phi <= band lies within band of a known cell).
#include <cstdint>
#include <vector>

#include "kernels/extrapolate.hpp"

namespace refmap {

struct PdeOptions {
  double band = 0.0;      ///< fill cells with phi <= band (length units); <= 0: 5 dx
  double cfl = 0.5;       ///< dtau = cfl dx (stable for cfl (|n_x| + |n_y|) <= 1)
  double tol = 1e-8;      ///< relative max-change tolerance (see above)
  int max_iter = 5000;    ///< per PDE solve
  bool qn_one_sided = true;  ///< false: q_n only from central differences (Basilisk-style)
  bool warm_start = false;   ///< true: the current xi values in the fill region (must be
                             ///< finite) are the initial guess of solve (3); false: 0
  int parallel_min = 2048;   ///< fewer list cells than this: one thread (a sweep is
                             ///< ~3 ns/cell; two barriers per iteration)
};

/// Reusable scratch space. Not thread-safe: one workspace per concurrent call.
struct PdeWorkspace {
  struct Cell { int i, j; double nx, ny; int nbx, nby; };  // nb*: box index or -1
  struct Row { int ux, uy; double d, ax, ay, bx, by; };
  detail::KnownExtent ext;
  std::vector<int> id;          // box-local map, see extrapolate_pde.cpp
  std::vector<Cell> cells;      // fill cells [0, nfill) then q_n extras (known cells)
  std::vector<double> frozen;   // frozen q_n values, 2 per entry
  std::vector<std::uint8_t> reach, reach2;
  std::vector<Row> rows;
  std::vector<double> q, q2, qn;
};

/// Fills xi_x, xi_y in the fill region (see above and kernels/extrapolate.hpp for the
/// window conventions) and sets known = 1 there. phi: level set on the whole window
/// (negative inside the solid), same indexing as xi.
ExtrapStats extrapolate_pde(View xi_x, View xi_y, View2<std::uint8_t> known, CView phi, int ni,
                            int nj, int ng, double dx, const PdeOptions& opt = {},
                            PdeWorkspace* ws = nullptr);

/// extrapolate_pde behind the Extrapolator interface, with its options and workspace. The
/// band is given in cells (PdeOptions::band = band_cells dx at each call).
class PdeExtrapolator final : public Extrapolator {
 public:
  PdeExtrapolator(const PdeOptions& opt, double band_cells) : opt_(opt), band_cells_(band_cells) {}
  ExtrapStats extrapolate(View xi_x, View xi_y, View2<std::uint8_t> known, CView phi, int ni,
                          int nj, int ng, double dx) override {
    opt_.band = band_cells_ * dx;
    return extrapolate_pde(xi_x, xi_y, known, phi, ni, nj, ng, dx, opt_, &ws_);
  }

 private:
  PdeOptions opt_;
  double band_cells_;
  PdeWorkspace ws_;
};

}  // namespace refmap
