// Galerkin multigrid kernels; see multigrid9.hpp.
#include "kernels/multigrid9.hpp"

#include "kernels/loop.hpp"

namespace refmap::mg {

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
};

struct Nine {
  const Stencil9& s;
  int nx, ny;
  bool px, py;
  explicit Nine(const Stencil9& st)
      : s(st), nx(st.nx), ny(st.ny), px(st.nbx->periodic), py(st.nby->periodic) {}
  double coef(int k, int i, int j) const { return s.coef(k, i, j); }
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

/// Coarse index I + a (a in {0, 1}) in a direction of nc points: wrapped when periodic,
/// -1 past a wall.
inline int coarse_step(int I, int a, int nc, bool periodic) {
  const int K = I + a;
  if (K < nc) return K;
  return periodic ? K - nc : -1;
}

template <class Op>
void build_q(const Op& A, int ncx, int ncy, std::vector<double>& q) {
  const std::size_t nc = std::size_t(ncx) * std::size_t(ncy);
  q.assign(8 * nc, 0.0);
  auto Q = [&](int k, int I, int J) -> double& { return q[std::size_t(k) * nc + std::size_t(I) + std::size_t(ncx) * J]; };
  // edge points: the operator collapsed across the line joining the two coarse points
  parallel_rows(0, ncy, 4 * ncx, [&](int J) {
    for (int I = 0; I < ncx; ++I) {
      int i = 2 * I + 1, j = 2 * J;
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

template <class Op>
void rap(const Op& A, const Prolong9& P, std::vector<double>& ac) {
  const int ncx = P.ncx, ncy = P.ncy;
  const std::size_t nc = std::size_t(ncx) * std::size_t(ncy);
  ac.assign(9 * nc, 0.0);
  // gather per coarse point (I, J): the column P e_IJ lives on fine points 2I-1..2I+1 x
  // 2J-1..2J+1; A widens it by one, and every fine point there has its parents within
  // one coarse point of (I, J), so the product is 9-point
  parallel_rows(0, ncy, 36 * ncx, [&](int J) {
    for (int I = 0; I < ncx; ++I) {
      double acc[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      for (int dj = -1; dj <= 1; ++dj) {
        const int j = step(2 * J, dj, A.ny, A.py);
        if (j < 0) continue;
        for (int di = -1; di <= 1; ++di) {
          const int i = step(2 * I, di, A.nx, A.px);
          if (i < 0) continue;
          const double p = pweight(P, i, j, di < 0, dj < 0);
          if (p == 0.0) continue;
          for (int ej = -1; ej <= 1; ++ej) {
            const int j2 = step(j, ej, A.ny, A.py);
            if (j2 < 0) continue;
            for (int ei = -1; ei <= 1; ++ei) {
              const int i2 = step(i, ei, A.nx, A.px);
              if (i2 < 0) continue;
              const double av = A.coef((ej + 1) * 3 + ei + 1, i, j);
              if (av == 0.0) continue;
              const double pa = p * av;
              for (int b = 0; b < 2; ++b) {
                const int L = coarse_step(j2 >> 1, b, ncy, A.py);
                if (L < 0) continue;
                int oL = L - J;
                if (oL > 1) oL -= ncy;
                if (oL < -1) oL += ncy;
                for (int a = 0; a < 2; ++a) {
                  const int K = coarse_step(i2 >> 1, a, ncx, A.px);
                  if (K < 0) continue;
                  const double w = pweight(P, i2, j2, a, b);
                  if (w == 0.0) continue;
                  int oK = K - I;
                  if (oK > 1) oK -= ncx;
                  if (oK < -1) oK += ncx;
                  acc[(oL + 1) * 3 + oK + 1] += pa * w;
                }
              }
            }
          }
        }
      }
      for (int k = 0; k < 9; ++k) ac[std::size_t(k) * nc + std::size_t(I) + std::size_t(ncx) * J] = acc[k];
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

void smooth9(const Stencil9& s, View x, CView f, int sweeps, bool reverse, double omega,
             double* res2) {
  const int nx = s.nx, ny = s.ny;
  const std::size_t n = s.n();
  const int* im = s.nbx->m.data();
  const int* ip = s.nbx->p.data();
  for (int sw = 0; sw < sweeps; ++sw) {
    for (int cc = 0; cc < 4; ++cc) {
      const int col = reverse ? 3 - cc : cc;
      const int ci = col & 1, cj = col >> 1;
      parallel_rows_on(s.threads, 0, (ny - cj + 1) / 2, [&](int r) {
        const int j = cj + 2 * r;
        const int jm = s.nby->m[j], jp = s.nby->p[j];
        const double* a = s.a + std::size_t(nx) * j;
        for (int i = ci; i < nx; i += 2) {
          const double d = a[C * n + i];
          if (d == 0.0) continue;
          const int l = im[i], h = ip[i];
          const double off = a[SW * n + i] * x(l, jm) + a[S * n + i] * x(i, jm) +
                             a[SE * n + i] * x(h, jm) + a[W * n + i] * x(l, j) +
                             a[E * n + i] * x(h, j) + a[NW * n + i] * x(l, jp) +
                             a[N * n + i] * x(i, jp) + a[NE * n + i] * x(h, jp);
          const double xn = (f(i, j) - off) / d;
          x(i, j) += omega * (xn - x(i, j));
        }
      });
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
  parallel_rows_on(threads, 0, P.ncy, [&](int J) {
    for (int I = 0; I < P.ncx; ++I) {
      double acc = 0.0;
      for (int dj = -1; dj <= 1; ++dj) {
        const int j = step(2 * J, dj, P.nfy, P.py);
        if (j < 0) continue;
        for (int di = -1; di <= 1; ++di) {
          const int i = step(2 * I, di, P.nfx, P.px);
          if (i < 0) continue;
          const double w = pweight(P, i, j, di < 0, dj < 0);
          if (w != 0.0) acc += w * r(i, j);
        }
      }
      fc(I, J) = acc;
    }
  });
}

void prolong9_add(const Prolong9& P, CView xc, View xf, int threads) {
  parallel_rows_on(threads, 0, P.nfy, [&](int j) {
    const int J = j >> 1;
    const int J1 = coarse_step(J, 1, P.ncy, P.py);
    for (int i = 0; i < P.nfx; ++i) {
      const int I = i >> 1;
      double v = 0.0;
      if (!(i & 1) && !(j & 1)) {
        v = xc(I, J);
      } else {
        const int I1 = coarse_step(I, 1, P.ncx, P.px);
        for (int b = 0; b < 2; ++b) {
          const int L = b ? J1 : J;
          if (L < 0) continue;
          for (int a = 0; a < 2; ++a) {
            const int K = a ? I1 : I;
            if (K < 0) continue;
            const double w = pweight(P, i, j, a, b);
            if (w != 0.0) v += w * xc(K, L);
          }
        }
      }
      xf(i, j) += v;
    }
  });
}

}  // namespace refmap::mg
