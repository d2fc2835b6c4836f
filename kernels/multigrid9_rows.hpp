#pragma once
// Row kernels of the Galerkin transfers (kernels/multigrid9.hpp): the prolongation of one
// fine row and the restriction to one coarse row. Shared by the separate kernels
// (multigrid9.cpp) and the fused smoothing passes of the finest level (multigrid.cpp), so
// both do the same arithmetic per value.
#include <cstddef>

#include "kernels/multigrid9.hpp"

namespace refmap::mg::rows9 {

/// Doubles of one fine row's slot in a thread's scratch (nx rounded up to a multiple of 8):
/// the rows residual_restrict5 and the fused passes keep (scratch9_per_thread).
inline std::size_t row_slot(int nx) { return (std::size_t(nx) + 7) / 8 * 8; }

/// Coarse index I + a (a in {0, 1}) in a direction of nc points: wrapped when periodic,
/// -1 past a wall.
inline int coarse_step(int I, int a, int nc, bool periodic) {
  const int K = I + a;
  if (K < nc) return K;
  return periodic ? K - nc : -1;
}

/// Fine row j of xf += P xc: xr points at xf(0, j).
inline void prolong_row(const Prolong9& P, CView xc, double* xr, int j) {
  const int ncx = P.ncx, ncy = P.ncy, nfx = P.nfx;
  const int J = j >> 1;
  int J1 = coarse_step(J, 1, ncy, P.py);
  if (J1 < 0) J1 = J;  // past a wall: the weights towards it are 0
  auto I1 = [&](int I) { return I + 1 < ncx ? I + 1 : (P.px ? 0 : I); };
  if (!(j & 1)) {
    for (int I = 0; I < ncx; ++I) {
      const double c0 = xc(I, J);
      xr[2 * I] += c0;
      if (2 * I + 1 < nfx) xr[2 * I + 1] += P.w(0, I, J) * c0 + P.w(1, I, J) * xc(I1(I), J);
    }
  } else {
    for (int I = 0; I < ncx; ++I) {
      const int Ir = I1(I);
      const double c00 = xc(I, J), c01 = xc(I, J1);
      xr[2 * I] += P.w(2, I, J) * c00 + P.w(3, I, J) * c01;
      if (2 * I + 1 < nfx)
        xr[2 * I + 1] += P.w(4, I, J) * c00 + P.w(5, I, J) * xc(Ir, J) + P.w(6, I, J) * c01 +
                         P.w(7, I, J) * xc(Ir, J1);
    }
  }
}

/// Coarse row J of P^T r from the fine rows 2J - 1 (dn), 2J (mid), 2J + 1 (up); a null
/// pointer for a row beyond a wall. fc(I, J) = sum over the fine points whose
/// interpolation uses (I, J): (2I, 2J) injected, (2I +- 1, 2J) and (2I, 2J +- 1) edge
/// weights, (2I +- 1, 2J +- 1) middle weights (blocks I - 1 and J - 1 for the points
/// left of 2I and below 2J).
inline void restrict_row(const Prolong9& P, int J, const double* dn, const double* mid,
                         const double* up, View fc) {
  const int ncx = P.ncx, ncy = P.ncy, nfx = P.nfx;
  const int Jd = J > 0 ? J - 1 : ncy - 1;  // block below (periodic wrap)
  for (int I = 0; I < ncx; ++I) {
    const int i = 2 * I;
    const bool has_rt = i + 1 < nfx;
    const bool has_lt = I > 0 || P.px;
    const int Il = I > 0 ? I - 1 : ncx - 1;
    const int il = i > 0 ? i - 1 : nfx - 1;
    double v = mid[i];
    if (has_rt) v += P.w(0, I, J) * mid[i + 1];
    if (has_lt) v += P.w(1, Il, J) * mid[il];
    if (up) {
      v += P.w(2, I, J) * up[i];
      if (has_rt) v += P.w(4, I, J) * up[i + 1];
      if (has_lt) v += P.w(5, Il, J) * up[il];
    }
    if (dn) {
      v += P.w(3, I, Jd) * dn[i];
      if (has_rt) v += P.w(6, I, Jd) * dn[i + 1];
      if (has_lt) v += P.w(7, Il, Jd) * dn[il];
    }
    fc(I, J) = v;
  }
}

}  // namespace refmap::mg::rows9
