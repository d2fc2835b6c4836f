// Galerkin multigrid kernels; see multigrid9.hpp.
#include "kernels/multigrid9.hpp"

#include "kernels/loop.hpp"
#include "kernels/multigrid9_rows.hpp"

#include <algorithm>
#include <utility>

namespace refmap::mg {

using rows9::coarse_step;
using rows9::restrict_row;

namespace {

// stencil slots: k = (dj+1)*3 + (di+1)
constexpr int SW = 0, S = 1, SE = 2, W = 3, C = 4, E = 5, NW = 6, N = 7, NE = 8;

/// Index of i + d (d in {-1, 0, 1}) in a direction of n points: wrapped when periodic,
/// -1 outside a wall.
inline int step(int i, int d, int n, bool periodic) {
  const int k = i + d;
  if (k >= 0 && k < n) return k;
  if (!periodic) return -1;
  return k < 0 ? k + n : k - n;
}

/// The finest level's 5-point operator as a 9-point one (corners 0).
struct Five {
  static constexpr bool kFivePoint = true;  ///< corner coefficients are 0
  const Stencil& s;
  int nx, ny;
  bool px, py;
  explicit Five(const Stencil& st)
      : s(st), nx(st.nx), ny(st.ny), px(st.sides.periodic_x()), py(st.sides.periodic_y()) {}
  double coef(int k, int i, int j) const {
    switch (k) {
      case W: return s.tx(i, j);
      case E: return s.tx(i + 1, j);
      case S: return s.ty(i, j);
      case N: return s.ty(i, j + 1);
      case C: return -(s.tx(i, j) + s.tx(i + 1, j) + s.ty(i, j) + s.ty(i, j + 1) +
                       (s.c.p ? s.c(i, j) : 0.0));
      default: return 0.0;
    }
  }
  void coefs(int i, int j, double c[9]) const {
    const double w = s.tx(i, j), e = s.tx(i + 1, j), so = s.ty(i, j), no = s.ty(i, j + 1);
    c[SW] = c[SE] = c[NW] = c[NE] = 0.0;
    c[W] = w;
    c[E] = e;
    c[S] = so;
    c[N] = no;
    c[C] = -(w + e + so + no + (s.c.p ? s.c(i, j) : 0.0));
  }
};

struct Nine {
  static constexpr bool kFivePoint = false;
  const Stencil9& s;
  int nx, ny;
  bool px, py;
  explicit Nine(const Stencil9& st)
      : s(st), nx(st.nx), ny(st.ny), px(st.nbx->periodic), py(st.nby->periodic) {}
  double coef(int k, int i, int j) const { return s.coef(k, i, j); }
  void coefs(int i, int j, double c[9]) const {
    for (int k = 0; k < 9; ++k) c[k] = s.coef(k, i, j);
  }
};

/// Weight of fine point (i, j) on coarse point (i/2 + a, j/2 + b), a, b in {0, 1}.
inline double pweight(const Prolong9& P, int i, int j, int a, int b) {
  const int I = i >> 1, J = j >> 1;
  const bool oi = i & 1, oj = j & 1;
  if (!oi && !oj) return (a == 0 && b == 0) ? 1.0 : 0.0;
  if (oi && !oj) return b ? 0.0 : P.w(a ? 1 : 0, I, J);
  if (!oi && oj) return a ? 0.0 : P.w(b ? 3 : 2, I, J);
  return P.w(4 + a + 2 * b, I, J);
}

template <class Op>
void build_q(const Op& A, int ncx, int ncy, std::vector<double>& q) {
  const std::size_t nc = std::size_t(ncx) * std::size_t(ncy);
  q.resize(8 * nc);  // every entry is written below
  auto Q = [&](int k, int I, int J) -> double& { return q[std::size_t(k) * nc + std::size_t(I) + std::size_t(ncx) * J]; };
  // edge points: the operator collapsed across the line joining the two coarse points
  parallel_rows(0, ncy, 4 * ncx, [&](int J) {
    for (int I = 0; I < ncx; ++I) {
      int i = 2 * I + 1, j = 2 * J;
      Q(0, I, J) = Q(1, I, J) = Q(2, I, J) = Q(3, I, J) = 0.0;  // a point that does not exist
      if (i < A.nx && j < A.ny) {
        const double d = A.coef(C, i, j) + A.coef(S, i, j) + A.coef(N, i, j);
        if (d != 0.0) {
          Q(0, I, J) = -(A.coef(W, i, j) + A.coef(SW, i, j) + A.coef(NW, i, j)) / d;
          Q(1, I, J) = -(A.coef(E, i, j) + A.coef(SE, i, j) + A.coef(NE, i, j)) / d;
        }
      }
      i = 2 * I;
      j = 2 * J + 1;
      if (i < A.nx && j < A.ny) {
        const double d = A.coef(C, i, j) + A.coef(W, i, j) + A.coef(E, i, j);
        if (d != 0.0) {
          Q(2, I, J) = -(A.coef(S, i, j) + A.coef(SW, i, j) + A.coef(SE, i, j)) / d;
          Q(3, I, J) = -(A.coef(N, i, j) + A.coef(NW, i, j) + A.coef(NE, i, j)) / d;
        }
      }
    }
  });
  // centre points: their own equation, the 8 neighbours interpolated
  parallel_rows(0, ncy, 4 * ncx, [&](int J) {
    const int j = 2 * J + 1;
    for (int I = 0; I < ncx; ++I) Q(4, I, J) = Q(5, I, J) = Q(6, I, J) = Q(7, I, J) = 0.0;
    if (j >= A.ny) return;
    int J1 = coarse_step(J, 1, ncy, A.py);
    if (J1 < 0) J1 = J;  // past a wall: the coefficients towards it are 0
    for (int I = 0; I < ncx; ++I) {
      const int i = 2 * I + 1;
      if (i >= A.nx) continue;
      int I1 = coarse_step(I, 1, ncx, A.px);
      if (I1 < 0) I1 = I;
      const double d = A.coef(C, i, j);
      if (d == 0.0) continue;
      const double aS = A.coef(S, i, j), aN = A.coef(N, i, j), aW = A.coef(W, i, j),
                   aE = A.coef(E, i, j);
      Q(4, I, J) = -(A.coef(SW, i, j) + aS * Q(0, I, J) + aW * Q(2, I, J)) / d;
      Q(5, I, J) = -(A.coef(SE, i, j) + aS * Q(1, I, J) + aE * Q(2, I1, J)) / d;
      Q(6, I, J) = -(A.coef(NW, i, j) + aN * Q(0, I, J1) + aW * Q(3, I, J)) / d;
      Q(7, I, J) = -(A.coef(NE, i, j) + aN * Q(1, I, J1) + aE * Q(3, I1, J)) / d;
    }
  });
}

/// Position of the parents of fine index 2I + u (u in [-2, 2]) relative to I: fine 2I + u
/// has parents at floor(u / 2) + {0, 1}.
constexpr int kBase[5] = {-1, -1, 0, 0, 1};

template <class Op>
void rap(const Op& A, const Prolong9& P, std::vector<double>& ac) {
  const int ncx = P.ncx, ncy = P.ncy;
  const std::size_t nc = std::size_t(ncx) * std::size_t(ncy);
  ac.resize(9 * nc);  // every entry is written below
  // gather per coarse point (I, J): the column P e_IJ lives on fine points 2I-1..2I+1 x
  // 2J-1..2J+1; A widens it to the 5x5 window 2I-2..2I+2, whose points have their parents
  // within one coarse point of (I, J), so the product is 9-point. Parents are kept
  // relative to (I, J) (no wrap arithmetic: a periodic direction only wraps the loads).
  parallel_rows(0, ncy, 36 * ncx, [&](int J) {
    double w4[5][5][4];  // window point (u, v): weights on parents base + (a, b), a + 2b
    bool in[5][5];
    int jw[5];
    for (int v = 0; v < 5; ++v) {
      const int j = 2 * J + (v - 2);
      jw[v] = (j >= 0 && j < A.ny) ? j : (A.py ? (j < 0 ? j + A.ny : j - A.ny) : -1);
    }
    // window column u at fine index i (wrapped, or -1 outside a wall)
    auto fill_col = [&](int u, int i) {
      const int iw = (i >= 0 && i < A.nx) ? i : (A.px ? (i < 0 ? i + A.nx : i - A.nx) : -1);
      for (int v = 0; v < 5; ++v) {
        double* w = w4[u][v];
        in[u][v] = iw >= 0 && jw[v] >= 0;
        if (!in[u][v]) {
          w[0] = w[1] = w[2] = w[3] = 0.0;
          continue;
        }
        const int Ib = iw >> 1, Jb = jw[v] >> 1;
        const bool oi = iw & 1, oj = jw[v] & 1;
        if (!oi && !oj) {
          w[0] = 1.0; w[1] = w[2] = w[3] = 0.0;
        } else if (oi && !oj) {
          w[0] = P.w(0, Ib, Jb); w[1] = P.w(1, Ib, Jb); w[2] = w[3] = 0.0;
        } else if (!oi && oj) {
          w[0] = P.w(2, Ib, Jb); w[2] = P.w(3, Ib, Jb); w[1] = w[3] = 0.0;
        } else {
          for (int k = 0; k < 4; ++k) w[k] = P.w(4 + k, Ib, Jb);
        }
      }
    };
    for (int u = 0; u < 5; ++u) fill_col(u, u - 2);
    for (int I = 0; I < ncx; ++I) {
      if (I > 0) {  // slide the window by two fine columns
        for (int u = 0; u < 3; ++u)
          for (int v = 0; v < 5; ++v) {
            for (int k = 0; k < 4; ++k) w4[u][v][k] = w4[u + 2][v][k];
            in[u][v] = in[u + 2][v];
          }
        fill_col(3, 2 * I + 1);
        fill_col(4, 2 * I + 2);
      }
      double acc[4][4] = {};  // offsets -1..2 (the +2 column/row only ever gets zeros)
      // fully unrolled (the offsets then are constants and acc lives in registers)
#pragma GCC unroll 3
      for (int v = 1; v <= 3; ++v) {
#pragma GCC unroll 3
        for (int u = 1; u <= 3; ++u) {
          if (!in[u][v]) continue;
          // weight of this support point on (I, J) itself: parent (a, b) = -base
          const double p = w4[u][v][-kBase[u] + 2 * -kBase[v]];
          if (p == 0.0) continue;
          int i = 2 * I + (u - 2), j = 2 * J + (v - 2);
          if (i < 0) i += A.nx; else if (i >= A.nx) i -= A.nx;
          if (j < 0) j += A.ny; else if (j >= A.ny) j -= A.ny;
          double c9[9];
          A.coefs(i, j, c9);
#pragma GCC unroll 3
          for (int ej = -1; ej <= 1; ++ej) {
            const int v2 = v + ej;
#pragma GCC unroll 3
            for (int ei = -1; ei <= 1; ++ei) {
              if constexpr (Op::kFivePoint) {
                if (ei != 0 && ej != 0) continue;
              }
              const double av = c9[(ej + 1) * 3 + ei + 1];
              const int u2 = u + ei;
              const double pa = p * av;
              const double* t = w4[u2][v2];
              const int ox = kBase[u2] + 1, oy = kBase[v2] + 1;
              acc[oy][ox] += pa * t[0];
              acc[oy][ox + 1] += pa * t[1];
              acc[oy + 1][ox] += pa * t[2];
              acc[oy + 1][ox + 1] += pa * t[3];
            }
          }
        }
      }
      for (int oy = 0; oy < 3; ++oy)
        for (int ox = 0; ox < 3; ++ox)
          ac[std::size_t(oy * 3 + ox) * nc + std::size_t(I) + std::size_t(ncx) * J] = acc[oy][ox];
    }
  });
}

}  // namespace

void Neighbours1D::build(int n, bool per) {
  periodic = per;
  m.resize(n);
  p.resize(n);
  for (int i = 0; i < n; ++i) {
    const int a = step(i, -1, n, per), b = step(i, 1, n, per);
    m[i] = a < 0 ? i : a;  // a wall: the cell itself (its coefficient across the wall is 0)
    p[i] = b < 0 ? i : b;
  }
}

void five_to_nine(const Stencil& s, std::vector<double>& a) {
  const Five A(s);
  const std::size_t n = std::size_t(s.nx) * std::size_t(s.ny);
  a.assign(9 * n, 0.0);
  for (int k = 0; k < 9; ++k)
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) a[std::size_t(k) * n + std::size_t(i) + std::size_t(s.nx) * j] = A.coef(k, i, j);
}

void build_prolongation(const Stencil& fine, int ncx, int ncy, std::vector<double>& q) {
  build_q(Five(fine), ncx, ncy, q);
}
void build_prolongation(const Stencil9& fine, int ncx, int ncy, std::vector<double>& q) {
  build_q(Nine(fine), ncx, ncy, q);
}
void galerkin_product(const Stencil& fine, const Prolong9& P, std::vector<double>& ac) {
  rap(Five(fine), P, ac);
}
void galerkin_product(const Stencil9& fine, const Prolong9& P, std::vector<double>& ac) {
  rap(Nine(fine), P, ac);
}

namespace {
/// Gauss-Seidel update of the points i = ci, ci+2, ... of row j (every a_C != 0: checked
/// when the Galerkin levels are built). The first and last points take their neighbours
/// from the index tables (wrap or wall), the others directly, so that the inner loop has
/// no branches.
inline void relax_row(const Stencil9& s, View x, CView f, int j, int ci, double omega) {
  const std::size_t n = s.n();
  const int nx = s.nx;
  const int jm = s.nby->m[j], jp = s.nby->p[j];
  const double* a = s.a + std::size_t(nx) * j;
  const double* __restrict aSW = a + SW * n;
  const double* __restrict aS = a + S * n;
  const double* __restrict aSE = a + SE * n;
  const double* __restrict aW = a + W * n;
  const double* __restrict aC = a + C * n;
  const double* __restrict aE = a + E * n;
  const double* __restrict aNW = a + NW * n;
  const double* __restrict aN = a + N * n;
  const double* __restrict aNE = a + NE * n;
  double* __restrict xr = &x(0, j);
  const double* __restrict xs = &x(0, jm);
  const double* __restrict xn = &x(0, jp);
  const double* __restrict fr = &f(0, j);
  auto point = [&](int i, int l, int h) {
    const double off = aSW[i] * xs[l] + aS[i] * xs[i] + aSE[i] * xs[h] + aW[i] * xr[l] +
                       aE[i] * xr[h] + aNW[i] * xn[l] + aN[i] * xn[i] + aNE[i] * xn[h];
    const double v = (fr[i] - off) / aC[i];
    xr[i] += omega * (v - xr[i]);
  };
  int i = ci;
  if (i == 0) {
    point(0, s.nbx->m[0], s.nbx->p[0]);
    i = 2;
  }
  for (; i < nx - 1; i += 2) point(i, i - 1, i + 1);
  if (i == nx - 1) point(i, s.nbx->m[i], s.nbx->p[i]);
}
}  // namespace

void smooth9(const Stencil9& s, View x, CView f, int sweeps, bool reverse, double omega,
             double* res2) {
  const int ny = s.ny;
  // colours (ci, cj) = (c & 1, c >> 1) in the order 0, 1, 2, 3 (reverse: 3, 2, 1, 0)
  const bool pipelined = s.threads <= 1 && !s.nby->periodic;
  if (pipelined) {
    // one pass over memory for all sweeps, the same iterates as sweep after sweep, colour
    // by colour. Step k of a sweep relaxes row jf = c0 + 2k (both its colours), then row
    // jf - 1 of the other parity, whose neighbours jf - 2 and jf are then final for this
    // sweep (and row jf's neighbours jf +- 1 still old, as in the colour order). Sweep s
    // trails sweep s - 1 by two steps: its step k reads rows jf - 2 .. jf + 1, which
    // sweep s - 1 finished at its step k + 1.
    const int c0 = reverse ? 1 : 0;  // parity of the rows relaxed first
    const int a0 = reverse ? 1 : 0, a1 = 1 - a0;  // column parity order in a row
    const int steps = (ny + 2 - c0 + 1) / 2;  // jf = c0, c0 + 2, ... < ny + 2
    for (int t = 0; t < steps + 2 * (sweeps - 1); ++t) {
      for (int sw = 0; sw < sweeps; ++sw) {
        const int k = t - 2 * sw;
        if (k < 0 || k >= steps) continue;
        const int jf = c0 + 2 * k;
        if (jf < ny) {
          relax_row(s, x, f, jf, a0, omega);
          relax_row(s, x, f, jf, a1, omega);
        }
        const int js = jf - 1;
        if (js >= 0 && js < ny) {
          relax_row(s, x, f, js, a0, omega);
          relax_row(s, x, f, js, a1, omega);
        }
      }
    }
  } else {
    for (int sw = 0; sw < sweeps; ++sw)
      for (int cc = 0; cc < 4; ++cc) {
        const int col = reverse ? 3 - cc : cc;
        const int ci = col & 1, cj = col >> 1;
        parallel_rows_on(s.threads, 0, (ny - cj + 1) / 2,
                         [&](int r) { relax_row(s, x, f, cj + 2 * r, ci, omega); });
      }
  }
  if (res2) *res2 = residual9(s, x, f, View{});
}

double residual9(const Stencil9& s, CView x, CView f, View r) {
  const int nx = s.nx, ny = s.ny;
  const std::size_t n = s.n();
  const int* im = s.nbx->m.data();
  const int* ip = s.nbx->p.data();
  return parallel_rows_sum_on(s.threads, 0, ny, [&](int j) {
    const int jm = s.nby->m[j], jp = s.nby->p[j];
    const double* a = s.a + std::size_t(nx) * j;
    double acc = 0.0;
    for (int i = 0; i < nx; ++i) {
      const int l = im[i], h = ip[i];
      const double lx = a[SW * n + i] * x(l, jm) + a[S * n + i] * x(i, jm) +
                        a[SE * n + i] * x(h, jm) + a[W * n + i] * x(l, j) +
                        a[C * n + i] * x(i, j) + a[E * n + i] * x(h, j) +
                        a[NW * n + i] * x(l, jp) + a[N * n + i] * x(i, jp) +
                        a[NE * n + i] * x(h, jp);
      const double v = f(i, j) - lx;
      if (r.p) r(i, j) = v;
      acc += v * v;
    }
    return acc;
  });
}

void restrict9(const Prolong9& P, CView r, View fc, int threads) {
  const int nfy = P.nfy;
  parallel_rows_on(threads, 0, P.ncy, [&](int J) {
    const int j = 2 * J;
    const double* dn = (J > 0 || P.py) ? &r(0, j > 0 ? j - 1 : nfy - 1) : nullptr;
    const double* up = j + 1 < nfy ? &r(0, j + 1) : nullptr;
    restrict_row(P, J, dn, &r(0, j), up, fc);
  });
}

std::size_t scratch9_per_thread(int nxf) {
  // the fused passes' ring of 4 fine rows (multigrid.cpp); residual_restrict5 uses 3
  return 4 * rows9::row_slot(nxf);
}

void residual_restrict5(const Stencil& s, CView x, CView f, const Prolong9& P, View fc,
                        const Scratch& sc) {
  const int ncy = P.ncy, nfy = P.nfy;
  const int nt = std::max(1, std::min({s.threads, sc.nthreads, ncy}));
  const std::size_t W = rows9::row_slot(s.nx);
  // one chunk of coarse rows per thread; its first fine row below is computed twice
  parallel_rows_on(nt, 0, nt, [&](int t) {
    const int J0 = int(long(ncy) * t / nt), J1 = int(long(ncy) * (t + 1) / nt);
    double* rows[3] = {sc.thread(t), sc.thread(t) + W, sc.thread(t) + 2 * W};
    double* dn = rows[0];
    double* mid = rows[1];
    double* up = rows[2];
    bool have_dn = false;
    if (J0 > 0 || P.py) {
      residual_row(s, x, f, J0 > 0 ? 2 * J0 - 1 : nfy - 1, dn);
      have_dn = true;
    }
    for (int J = J0; J < J1; ++J) {
      const int j = 2 * J;
      residual_row(s, x, f, j, mid);
      const bool have_up = j + 1 < nfy;
      if (have_up) residual_row(s, x, f, j + 1, up);
      restrict_row(P, J, have_dn ? dn : nullptr, mid, have_up ? up : nullptr, fc);
      std::swap(dn, up);  // row 2J + 1 is the next coarse row's row below
      have_dn = have_up;
    }
  });
}

void prolong9_add(const Prolong9& P, CView xc, View xf, int threads) {
  parallel_rows_on(threads, 0, P.nfy, [&](int j) { rows9::prolong_row(P, xc, &xf(0, j), j); });
}

}  // namespace refmap::mg
