#include "kernels/verlet.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void verlet_drift_faces(CView uf, CView vf, CView ufp, CView vfp, CView dfx, CView dfy, CView rho, View wf,
                        View wv, int nx, int ny, double cv, double cf, Sides sides) {
  const double h = 0.5 * cf;  // cf times the mean of two cells
  const bool px = sides.periodic_x(), py = sides.periodic_y();
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i <= nx; ++i) {
      double a = 0.0;
      if (i > 0 && i < nx) a = dfx(i - 1, j) / rho(i - 1, j) + dfx(i, j) / rho(i, j);
      else if (px) a = dfx(nx - 1, j) / rho(nx - 1, j) + dfx(0, j) / rho(0, j);  // face 0 = face nx
      wf(i, j) = uf(i, j) + cv * (uf(i, j) - ufp(i, j)) + h * a;
    }
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    const bool inner = j > 0 && j < ny;
    if (!inner && !py) {
      for (int i = 0; i < nx; ++i) wv(i, j) = vf(i, j) + cv * (vf(i, j) - vfp(i, j));
      return;
    }
    const int js = inner ? j - 1 : ny - 1, jn = inner ? j : 0;
    for (int i = 0; i < nx; ++i)
      wv(i, j) = vf(i, j) + cv * (vf(i, j) - vfp(i, j)) + h * (dfy(i, js) / rho(i, js) + dfy(i, jn) / rho(i, jn));
  });
}

void verlet_kick(View fx, View fy, CView vx, CView vy, View fpx, View fpy, View dfx, View dfy, int nx, int ny) {
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      const double ax = fx(i, j) - vx(i, j), ay = fy(i, j) - vy(i, j);  // F^{n+1}
      fx(i, j) = vx(i, j) + 0.5 * (fpx(i, j) + ax);
      fy(i, j) = vy(i, j) + 0.5 * (fpy(i, j) + ay);
      dfx(i, j) = ax - fpx(i, j);
      dfy(i, j) = ay - fpy(i, j);
      fpx(i, j) = ax;
      fpy(i, j) = ay;
    }
  });
}

}  // namespace refmap
