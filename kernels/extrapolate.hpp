#pragma once
// The one interface of the reference-map extrapolation methods (Extrapolator, made by
// make_extrapolator from the [solids] options; solver/model/extrapolation.hpp) and the shared types
// of their kernels:
//   extrapolate_lsq  (kernels/extrapolate_lsq.hpp) - Jain & Mani least-squares plane fits
//                    (Algorithm 2 of the paper, docs/references.md), the method of the paper;
//   extrapolate_pde  (kernels/extrapolate_pde.hpp) - Aslam (2004) linear PDE extrapolation,
//                    the RMT baseline it is compared with.
// Adding a method: a class deriving from Extrapolator in its own file and one line in
// make_extrapolator (solver/model/extrapolation.cpp) plus its name in solver/scene/option_names.cpp.
//
// Both work on one solid's WINDOW: window-local arrays of ni x nj cells with ng ghost layers,
// cell size dx. The kernels treat every cell (i, j) with -ng <= i < ni+ng, -ng <= j < nj+ng
// (ghosts included) as part of their domain; cells beyond that do not exist (unknown). Pass
// ng = 0 to keep the ghost layers out of both reading and filling.
//
// `known(i, j)` must be 0 or 1 on entry (1 = valid xi, Omega_S / flag1); on return it is 1
// for every cell the kernel filled. Values of xi in unknown cells are never read (they may be
// NaN), except by extrapolate_pde with PdeOptions::warm_start.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "core/field.hpp"

namespace refmap {

struct ExtrapStats {
  long cells_filled = 0;   ///< cells set known by this call
  long fallbacks = 0;      ///< LSQ: lower-order fits (collinear / < 3 known cells);
                           ///< PDE: cells whose normal needed the one-sided fallback
  int passes = 0;          ///< LSQ: passes that filled at least one cell
  int iterations = 0;      ///< PDE: pseudo-time iterations, both PDE solves together
  int iterations_qn = 0;   ///< PDE: iterations of the q_n = n.grad(xi) extension
  int iterations_xi = 0;   ///< PDE: iterations of the linear xi extrapolation
  long unreached = 0;      ///< PDE: fill-region cells with no upwind path to known data
                           ///< (left unknown); LSQ: 0
  bool converged = true;   ///< PDE: both solves met the tolerance within max_iter
  double final_change = 0.0;  ///< PDE: last max |change| of the xi solve / its scale
};

/// One extrapolation method with its options and its reusable workspace (so one instance
/// serves one solid at a time: not thread-safe).
class Extrapolator {
 public:
  virtual ~Extrapolator() = default;
  /// Fills xi_x, xi_y in the unknown cells of the band around the known ones (the window and
  /// known-mask conventions above) and sets known = 1 there. phi: the solid's level set on
  /// the window (negative inside), for methods that need it.
  virtual ExtrapStats extrapolate(View xi_x, View xi_y, View2<std::uint8_t> known, CView phi,
                                  int ni, int nj, int ng, double dx) = 0;
  /// The same where only the cells within `layers` of the known ones are needed (reachable by
  /// at most `layers` steps to an edge or corner neighbour: the stencil reach of the caller,
  /// e.g. the RK-4 stages of eq. (3.3), whose right-hand side reads one or two cells beyond
  /// Omega_S). A method that fills outward layer by layer (least squares: pass p fills layer
  /// p from the cells known before it) stops there, and those cells get the bits of a full
  /// call; the others fill their whole band (this default). Cells beyond keep their values
  /// and stay unknown.
  virtual ExtrapStats extrapolate_layers(View xi_x, View xi_y, View2<std::uint8_t> known, CView phi,
                                         int ni, int nj, int ng, double dx, int layers) {
    (void)layers;
    return extrapolate(xi_x, xi_y, known, phi, ni, nj, ng, dx);
  }
  /// How far from the known cells extrapolate_layers(..., layers) writes: `layers` for a
  /// method that stops there, -1 (anywhere in its band) for the others (this default).
  virtual int layers_written(int layers) const {
    (void)layers;
    return -1;
  }
};

namespace detail {

/// Bounding box of the cells with known != 0 over the kernel domain, plus per-row extents
/// (lo[j] > hi[j] for rows without known cells). Scans 8 bytes at a time.
struct KnownExtent {
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;  ///< inclusive; empty if i1 < i0
  std::vector<int> lo, hi;               ///< indexed j + ng, size nj + 2 ng
  bool empty() const { return i1 < i0; }
};

inline void known_extent(View2<const std::uint8_t> known, int ni, int nj, int ng,
                         KnownExtent& e) {
  const int w = ni + 2 * ng, h = nj + 2 * ng;
  e.lo.assign(std::size_t(std::max(h, 0)), 1 << 30);
  e.hi.assign(std::size_t(std::max(h, 0)), -(1 << 30));
  e.i0 = 1 << 30; e.i1 = -(1 << 30); e.j0 = 1 << 30; e.j1 = -(1 << 30);
  for (int jj = 0; jj < h; ++jj) {
    const std::uint8_t* row = &known(-ng, jj - ng);
    int first = -1, last = -1;
    int k = 0;
    for (; k + 8 <= w; k += 8) {          // first nonzero byte
      std::uint64_t v; std::memcpy(&v, row + k, 8);
      if (v) { first = k + __builtin_ctzll(v) / 8; break; }
    }
    if (first < 0) for (; k < w; ++k) if (row[k]) { first = k; break; }
    if (first < 0) continue;
    int t = w;
    for (; t - 8 >= first; t -= 8) {       // last nonzero byte
      std::uint64_t v; std::memcpy(&v, row + t - 8, 8);
      if (v) { last = t - 8 + (63 - __builtin_clzll(v)) / 8; break; }
    }
    if (last < 0) for (int q = t - 1; q >= first; --q) if (row[q]) { last = q; break; }
    e.lo[jj] = first - ng; e.hi[jj] = last - ng;
    e.i0 = std::min(e.i0, first - ng); e.i1 = std::max(e.i1, last - ng);
    e.j0 = std::min(e.j0, jj - ng); e.j1 = jj - ng;
  }
  if (e.j1 < e.j0) { e.i0 = 0; e.i1 = -1; e.j0 = 0; e.j1 = -1; }
}

}  // namespace detail
}  // namespace refmap
