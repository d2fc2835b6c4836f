#pragma once
// Solid windows across periodic sides (docs/reference_map.md, "Periodic sides").
//
// A solid's window (solver/model/solid.hpp) lives in UNWRAPPED index space: window cell (i, j) is
// cell (i0 + i, j0 + j) of the periodic continuation of the grid, centred at
// (x0 + (i0 + i + 1/2) dx, y0 + (j0 + j + 1/2) dx) even where i0 + i is outside [0, nx).
// The reference map, the level set, the markers and the solid's centroid are therefore
// continuous as the solid crosses a seam -- nothing is shifted by the period, and a solid
// carried once around a periodic box ends with its centroid one period further on. Only
// the reads and writes of the GLOBAL fields (velocity, density, stress, force) wrap: the
// window cell maps to the grid cell ((i0 + i) mod nx, (j0 + j) mod ny). A window is never
// wider than the period (Solid::fit_window), so no two of its cells map to the same one.
//
// In a non-periodic direction, and for a window inside the grid, every mapping below is
// the identity: the scenes whose solids never reach a periodic side run the same
// arithmetic as before.
#include <algorithm>

#include "core/field.hpp"

namespace refmap {

/// The global cell of an unwrapped index: modulo the grid's size in a periodic direction.
struct PeriodicWrap {
  int nx = 0, ny = 0;
  bool px = false, py = false;  ///< x, y periodic

  static int mod(int k, int n) {
    if (unsigned(k) < unsigned(n)) return k;  // the common case: inside the grid
    k %= n;
    return k < 0 ? k + n : k;
  }
  int i(int gi) const { return px ? mod(gi, nx) : gi; }
  int j(int gj) const { return py ? mod(gj, ny) : gj; }
};

/// A rectangle of a window that maps onto the grid without crossing a seam: window cells
/// (li + i, lj + j) are grid cells (gi + i, gj + j) for 0 <= i < ni, 0 <= j < nj.
struct WindowPiece {
  int li, lj, gi, gj, ni, nj;
};

/// Calls f(WindowPiece) for the pieces of the window [i0, i0 + ni) x [j0, j0 + nj): the whole
/// window at (i0, j0) when it does not cross a periodic side, else split at the seams (at
/// most two pieces per direction). A kernel that writes to global fields at (i0 + i, j0 + j)
/// runs on each piece with its window views shifted by (li, lj) (shifted_view below): its
/// stencils still read the window's own neighbours across the cut.
template <class F>
void for_each_piece(const PeriodicWrap& w, int i0, int j0, int ni, int nj, F&& f) {
  // the runs [l, l + m) of one direction, with their first grid index
  auto split = [](int a0, int len, int n, bool periodic, auto&& g) {
    if (!periodic || (a0 >= 0 && a0 + len <= n)) {
      g(0, a0, len);
      return;
    }
    for (int l = 0; l < len;) {
      const int ga = PeriodicWrap::mod(a0 + l, n);
      const int m = std::min(len - l, n - ga);
      g(l, ga, m);
      l += m;
    }
  };
  split(j0, nj, w.ny, w.py, [&](int lj, int gj, int mj) {
    split(i0, ni, w.nx, w.px, [&](int li, int gi, int mi) { f(WindowPiece{li, lj, gi, gj, mi, mj}); });
  });
}

/// A view of the same array whose (0, 0) is element (i, j) of v.
template <class T>
View2<T> shifted_view(View2<T> v, int i, int j) {
  return {&v(i, j), v.stride};
}

}  // namespace refmap
