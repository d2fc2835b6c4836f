#pragma once
// Fast marching reinitialisation of a level set (Jain & Mani 2017, section 3.3), with
// the improvements of Chopp (2001), "Some improvements of the fast marching method",
// SIAM J. Sci. Comput. 23, 230-244:
//
//  * initialisation near the front: every 2x2 quad of cell centres whose corner values
//    change sign gets the bicubic Hermite interpolant p(x, y) of phi (values, phi_x,
//    phi_y, phi_xy by central differences, one-sided at the window edge). For each
//    corner node x0 the closest point of {p = 0} is found by the Newton-type iteration
//        x <- x + (x0 - x) - [(x0 - x).grad p(x) + p(x)] grad p(x) / |grad p(x)|^2
//    (falls back to |phi| / |grad phi| if it does not converge or wanders more than 2 dx
//    away). The node's initial value is sign(phi(x0)) |x0 - x*|, the minimum over the
//    quads sharing the node. These nodes are Accepted.
//  * marching: a binary min-heap with back-pointers (decrease-key); the upwind Eikonal
//    quadratic uses the one-sided second-order difference (3 u_i - 4 u_{i-1} + u_{i-2}) /
//    (2 dx) where two Accepted points lie upwind in a direction (and u_{i-2} <= u_{i-1}),
//    first order otherwise; when the quadratic has no admissible root it falls back to
//    first order, then to the best single direction.
//
// Both sides of the front are marched in one heap keyed on the unsigned distance: a cell
// only ever sees Accepted cells of its own side, except initialised cells across the
// front, whose signed value continues the distance function smoothly (that is what the
// second-order stencil wants). This is equivalent to marching phi > 0 and phi < 0
// separately.
//
// Sign convention: phi < 0 is inside (negative side); phi >= 0 is the positive side.
// Cells whose distance exceeds `band` are set to +band / -band (sign preserved).
//
// Cost: O(ni nj) for the scans (quad search, reset, final write) plus
// O(M log M) for the M cells marched inside the band. Nothing is allocated once the
// workspace has grown to the largest window it has seen.
#include <cstdint>
#include <vector>

#include "solver/field.hpp"

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

/// Reusable scratch memory of reinitialise_fmm. Not thread-safe: one per thread.
struct FmmWorkspace {
  std::vector<double> val;        ///< signed distance of Accepted / tentative of Trial cells
  std::vector<std::uint8_t> state;///< 0 Far, 1 Trial, 2 Accepted
  std::vector<int> heap;          ///< binary min-heap of cell indices keyed on |val|
  std::vector<int> pos;           ///< back-pointer: position of a Trial cell in `heap`
  std::vector<int> init_cells;    ///< cells accepted by the initialisation
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
