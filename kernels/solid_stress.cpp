#include "kernels/solid_stress.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void blend_stress_divergence(CView sxx, CView sxy, CView syy, CView phi, int ni, int nj,
                             double dx, double w_t, View fx, View fy, int i0, int j0) {
  const double inv2 = 0.5 / dx;
  parallel_rows(0, nj, ni, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j);
      if (ph >= w_t) continue;
      const double s = 1.0 - smoothed_heaviside(ph, w_t);
      fx(i0 + i, j0 + j) +=
          s * (sxx(i + 1, j) - sxx(i - 1, j) + sxy(i, j + 1) - sxy(i, j - 1)) * inv2;
      fy(i0 + i, j0 + j) +=
          s * (sxy(i + 1, j) - sxy(i - 1, j) + syy(i, j + 1) - syy(i, j - 1)) * inv2;
    }
  });
}

void add_stress_divergence(CView sxx, CView sxy, CView syy, View fx, View fy, int nx, int ny,
                           double dx) {
  const double inv2 = 0.5 / dx;
  parallel_rows(0, ny, nx, [=](int j) {
    // restrict-qualified row pointers so that the loop vectorises
    const double* __restrict xx = &sxx(0, j);
    const double* __restrict xys = &sxy(0, j - 1);
    const double* __restrict xyc = &sxy(0, j);
    const double* __restrict xyn = &sxy(0, j + 1);
    const double* __restrict yys = &syy(0, j - 1);
    const double* __restrict yyn = &syy(0, j + 1);
    double* __restrict fxr = &fx(0, j);
    double* __restrict fyr = &fy(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) {
      fxr[i] += (xx[i + 1] - xx[i - 1] + xyn[i] - xys[i]) * inv2;
      fyr[i] += (xyc[i + 1] - xyc[i - 1] + yyn[i] - yys[i]) * inv2;
    }
  });
}

}  // namespace refmap
