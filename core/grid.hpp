#pragma once
// The one fixed Cartesian grid of refmap: nx x ny square cells (dx = dy), cell-centred,
// with `ng` ghost layers on every side. Cell (i, j) has its centre at
// (x0 + (i + 1/2) dx, y0 + (j + 1/2) dx); i in [0, nx), j in [0, ny).
#include <cstddef>

namespace refmap {

struct Grid {
  int nx = 0, ny = 0;       ///< interior cells in x and y
  double dx = 1.0;          ///< cell size (dx = dy)
  double x0 = 0.0, y0 = 0.0;///< lower-left corner of the domain
  static constexpr int ng = 2;  ///< ghost layers (Superbee and the stress stencils need two)

  double lx() const { return nx * dx; }
  double ly() const { return ny * dx; }
  double xc(int i) const { return x0 + (i + 0.5) * dx; }  ///< x of a cell centre
  double yc(int j) const { return y0 + (j + 0.5) * dx; }  ///< y of a cell centre
  double xf(int i) const { return x0 + i * dx; }          ///< x of x-face i (left face of cell i)
  double yf(int j) const { return y0 + j * dx; }          ///< y of y-face j (bottom face of cell j)
  std::size_t cells() const { return std::size_t(nx) * std::size_t(ny); }
};

}  // namespace refmap
