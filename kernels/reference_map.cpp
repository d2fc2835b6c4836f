#include "kernels/reference_map.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void reference_map_rhs(CView xi_x, CView xi_y, CView phi, CView uf, CView vf, int ni, int nj,
                       int i0, int j0, double dx, View kx, View ky) {
  const double s = -0.5 / dx;
  parallel_rows(0, nj, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      if (!(phi(i, j) < 0.0)) {  // H = 0 outside Omega_S, eq. (3.4)
        kx(i, j) = 0.0;
        ky(i, j) = 0.0;
        continue;
      }
      const double ue = uf(i0 + i + 1, j0 + j), uw = uf(i0 + i, j0 + j);
      const double vn = vf(i0 + i, j0 + j + 1), vs = vf(i0 + i, j0 + j);
      kx(i, j) = s * (ue * (xi_x(i + 1, j) - xi_x(i, j)) + uw * (xi_x(i, j) - xi_x(i - 1, j)) +
                      vn * (xi_x(i, j + 1) - xi_x(i, j)) + vs * (xi_x(i, j) - xi_x(i, j - 1)));
      ky(i, j) = s * (ue * (xi_y(i + 1, j) - xi_y(i, j)) + uw * (xi_y(i, j) - xi_y(i - 1, j)) +
                      vn * (xi_y(i, j + 1) - xi_y(i, j)) + vs * (xi_y(i, j) - xi_y(i, j - 1)));
    }
  });
}

}  // namespace refmap
