#pragma once
// Fast marching reinitialisation of a level set (Jain & Mani 2017, section 3.3), with
// the improvements of Chopp (2001), "Some improvements of the fast marching method",
// SIAM J. Sci. Comput. 23, 230-244:
//
//  * initialisation near the front: every 2x2 quad of cell centres whose corner values
//    change sign gets the bicubic Hermite interpolant p(x, y) of phi (values, phi_x,
//    phi_y, phi_xy by central differences, one-sided at the window edge). For each
//    corner node x0 the closest point x* of {p = 0} is computed. Chopp's iteration is
//        x <- x + (x0 - x) - [(x0 - x).grad p(x) + p(x)] grad p(x) / |grad p(x)|^2
//    (linear convergence); its fixed point is the root of
//        G(x) = [p(x), (x - x0) x grad p(x)] = 0,
//    which is solved here by Newton's method (quadratic convergence, the Hessian of p
//    is cheap; the first Newton step from x0 is Chopp's step), the four corners of a quad
//    in lock-step SIMD lanes. If Newton fails (singular Jacobian, > 2 dx away, no
//    convergence) Chopp's iteration is tried, then |phi| / |grad phi| (counted in
//    FmmStats::newton_failures). The node's initial value is sign(phi(x0)) |x0 - x*|,
//    the minimum over the quads sharing the node. These nodes are Accepted.
//  * marching: a binary min-heap with back-pointers (decrease-key); the upwind Eikonal
//    quadratic uses the one-sided second-order difference (3 u_i - 4 u_{i-1} + u_{i-2}) /
//    (2 dx) where two Accepted points lie upwind in a direction (and u_{i-2} <= u_{i-1}),
//    first order otherwise; when the quadratic has no admissible root (negative
//    discriminant, or a root below an upwind value) it falls back to first order in both
//    directions, then to the best single direction.
//
// Both sides of the front are marched in one heap keyed on the unsigned distance: a cell
// only ever sees Accepted cells of its own side, except initialised cells across the
// front, whose signed value continues the distance function smoothly (that is what the
// second-order stencil wants). This is equivalent to marching phi > 0 and phi < 0
// separately.
//
// Accuracy (tests/test_fast_marching.cpp): second order; with a band of a fixed number
// of cells (e.g. 6 dx) the error even falls ~8x per refinement. Linear-interpolation
// initialisation (FmmInit::Linear) is first order.
//
// Sign convention: phi < 0 is inside (negative side); phi >= 0 is the positive side. The
// sign of every cell is preserved (a negative cell never becomes 0). Cells whose
// distance exceeds `band` are set to +band / -band.
//
// The window: only the front inside the window is seen, so the window should contain
// the solid plus the band (e.g. its bounding box + band + 2 cells). Where the front
// leaves the window, cells whose true closest point lies outside get the distance to
// the visible part of the front instead.
//
// Cost: O(ni nj) streaming passes (sign bits, quad search 8 quads at a time, final
// write) plus O(M log M) for the M cells marched inside the band. Nothing is allocated
// once the workspace has grown to the largest window it has seen.
#include <cstdint>
#include <vector>

#include "core/field.hpp"

namespace refmap {

struct FmmStats {
  int accepted_init = 0;  ///< nodes given their value by the initialisation near the front
  int marched = 0;        ///< nodes accepted by the march (|phi| <= band)
  int newton_failures = 0;///< closest-point iterations that fell back to |phi|/|grad phi|
};

enum class FmmInit : std::uint8_t {
  Chopp,   ///< bicubic interpolant + closest-point iteration (second order; the default)
  Linear,  ///< edge-crossing linear interpolation (first order; kept for comparison/tests)
};

struct FmmOptions {
  FmmInit init = FmmInit::Chopp;
  bool second_order = true;  ///< second-order upwind differences in the march
};

struct FmmHeapEntry {
  double key;  ///< tentative unsigned distance
  int cell;    ///< padded cell index
};

/// Reusable scratch memory of reinitialise_fmm (padded (ni+4) x (nj+4) arrays). Not
/// thread-safe: one per thread.
struct FmmWorkspace {
  /// Distance as seen from the positive / negative side: upos holds +d of Accepted
  /// cells with phi >= 0 and -d of initialised cells with phi < 0 (so the second-order
  /// stencil can reach across the front); uneg the mirror image; +inf elsewhere. Both
  /// are all +inf between calls (only the touched cells are reset).
  std::vector<double> upos, uneg;
  std::vector<std::uint8_t> state;  ///< sign / Trial / Accepted / padding bits
  std::vector<FmmHeapEntry> heap;   ///< binary min-heap of Trial cells keyed on distance
  std::vector<int> pos;             ///< back-pointer: position of a Trial cell in `heap`
  std::vector<int> init_cells;      ///< cells accepted by the initialisation
  std::vector<int> accepted;        ///< cells accepted by the march
  void reserve(int ncells);
};

/// Reinitialises `phi` (window-local: cells (i, j), 0 <= i < ni, 0 <= j < nj, of a view
/// with v(i,j) = p[j*stride + i]; ghost cells are neither read nor written) to the signed
/// distance to its zero level set, by fast marching in the band |phi| <= band. Cells
/// farther away get +-band with the sign of the input preserved. dx is the (uniform)
/// cell size; requires ni, nj >= 2. A window without a sign change becomes +-band.
FmmStats reinitialise_fmm(View phi, int ni, int nj, double dx, double band,
                          FmmWorkspace& ws, const FmmOptions& opt = {});

}  // namespace refmap
