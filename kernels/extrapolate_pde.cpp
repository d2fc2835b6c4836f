#include "kernels/extrapolate_pde.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "kernels/loop.hpp"

namespace refmap {

namespace {

// Box-local map codes (PdeWorkspace::id):
//   >= 0  index into PdeWorkspace::cells (fill cell if < nfill, else a q_n "extra")
//   -1    not visited (only possible for known cells)
//   -2    invalid: unknown cell outside the fill region
//  <= -3  known cell with frozen q_n entry k = -3 - code
constexpr int kUnvisited = -1, kInvalid = -2;

using Row = PdeWorkspace::Row;

/// Forward-Euler/Jacobi sweeps q_new[c] = d q[c] + ax q[ux] + ay q[uy] + b (both components)
/// until max |q_new - q| <= tol_abs or max_iter. On return q holds the latest iterate.
int jacobi(const std::vector<Row>& rows, std::vector<double>& q, std::vector<double>& q2,
           double tol_abs, int max_iter, int parallel_min, double& last_change) {
  const long n = long(rows.size());
  last_change = 0.0;
  if (n == 0 || max_iter <= 0) return 0;
  q2.resize(q.size());
  double* a = q.data();
  double* b = q2.data();
  const Row* R = rows.data();
  int it = 0;
  bool done = false;
  double chg = 0.0;
  constexpr int kMaxT = 64;
  const int nth = n >= parallel_min ? std::min(omp_get_max_threads(), kMaxT) : 1;
  // one sweep over [lo, hi): returns max |change|
  auto sweep = [R](const double* src, double* dst, long lo, long hi) {
    double m0 = 0.0, m1 = 0.0;
    for (long c = lo; c < hi; ++c) {
      const Row& r = R[c];
      const double x0 = src[2 * c], y0 = src[2 * c + 1];
      const double x1 = r.d * x0 + r.ax * src[2 * r.ux] + r.ay * src[2 * r.uy] + r.bx;
      const double y1 = r.d * y0 + r.ax * src[2 * r.ux + 1] + r.ay * src[2 * r.uy + 1] + r.by;
      dst[2 * c] = x1;
      dst[2 * c + 1] = y1;
      m0 = std::max(m0, std::fabs(x1 - x0));
      m1 = std::max(m1, std::fabs(y1 - y0));
    }
    return std::max(m0, m1);
  };
  if (nth == 1) {
    while (true) {
      chg = sweep(a, b, 0, n);
      ++it;
      std::swap(a, b);
      if (!(chg > tol_abs) || it >= max_iter) break;
    }
  } else {
    double part[kMaxT * 8];
    team_region(nth, [&](const Team& tm) {
      const int t = tm.t, T = tm.nt;
      const long lo = n * t / T, hi = n * (t + 1) / T;
      while (true) {
        part[8 * t] = sweep(a, b, lo, hi);
        tm.barrier();
        tm.single([&] {
          double mm = 0.0;
          for (int k = 0; k < T; ++k) mm = std::max(mm, part[8 * k]);
          chg = mm;
          ++it;
          std::swap(a, b);
          done = !(mm > tol_abs) || it >= max_iter;
        });
        if (done) break;
      }
    });
  }
  if (a != q.data()) q.swap(q2);
  last_change = chg;
  return it;
}

}  // namespace

ExtrapStats extrapolate_pde(View xi_x, View xi_y, View2<std::uint8_t> known, CView phi, int ni,
                            int nj, int ng, double dx, const PdeOptions& opt, PdeWorkspace* ws) {
  ExtrapStats st;
  if (ni + 2 * ng <= 0 || nj + 2 * ng <= 0) return st;
  PdeWorkspace local;
  PdeWorkspace& w = ws ? *ws : local;
  const int ilo = -ng, ihi = ni + ng - 1, jlo = -ng, jhi = nj + ng - 1;
  const double band = opt.band > 0.0 ? opt.band : 5.0 * dx;
  const double cfl = opt.cfl;
  const double dtau = cfl * dx;

  detail::known_extent(known, ni, nj, ng, w.ext);
  if (w.ext.empty()) return st;
  const int g = int(std::ceil(band / dx)) + 2;
  const int bi0 = std::max(ilo, w.ext.i0 - g), bi1 = std::min(ihi, w.ext.i1 + g);
  const int bj0 = std::max(jlo, w.ext.j0 - g), bj1 = std::min(jhi, w.ext.j1 + g);
  const int bw = bi1 - bi0 + 1, bh = bj1 - bj0 + 1;
  auto bidx = [&](int i, int j) { return (j - bj0) * bw + (i - bi0); };
  auto inbox = [&](int i, int j) { return i >= bi0 && i <= bi1 && j >= bj0 && j <= bj1; };

  // ---- fill region
  w.id.assign(std::size_t(bw) * std::size_t(bh), kUnvisited);
  w.cells.clear();
  for (int j = bj0; j <= bj1; ++j) {
    const std::uint8_t* kr = &known(0, j);
    const double* pr = &phi(0, j);
    int* idr = w.id.data() + std::ptrdiff_t(j - bj0) * bw - bi0;  // idr[i]: cell (i, j)
    for (int i = bi0; i <= bi1; ++i) {
      if (kr[i]) continue;
      if (pr[i] <= band) {
        idr[i] = int(w.cells.size());
        w.cells.push_back({i, j, 0.0, 0.0, -1, -1});
      } else {
        idr[i] = kInvalid;
      }
    }
  }
  const int nfill = int(w.cells.size());
  if (nfill == 0) return st;

  // unit normal from phi; returns 1 when the one-sided fallback was needed
  auto normal = [&](int i, int j, double& nx, double& ny) -> int {
    const double pc = phi(i, j);
    const bool l = i > ilo, r = i < ihi, b = j > jlo, t = j < jhi;
    double gx = l && r ? 0.5 * (phi(i + 1, j) - phi(i - 1, j))
              : r ? phi(i + 1, j) - pc : l ? pc - phi(i - 1, j) : 0.0;
    double gy = b && t ? 0.5 * (phi(i, j + 1) - phi(i, j - 1))
              : t ? phi(i, j + 1) - pc : b ? pc - phi(i, j - 1) : 0.0;
    const double tiny = 1e-8 * dx;
    int fb = 0;
    if (!(gx * gx + gy * gy > tiny * tiny)) {  // ridge/plateau: one-sided, towards lower phi
      fb = 1;
      constexpr double inf = std::numeric_limits<double>::infinity();
      const double L = l ? phi(i - 1, j) : inf, Rr = r ? phi(i + 1, j) : inf;
      const double B = b ? phi(i, j - 1) : inf, T = t ? phi(i, j + 1) : inf;
      gx = std::min(L, Rr) < pc ? (L <= Rr ? pc - L : -(pc - Rr)) : 0.0;
      gy = std::min(B, T) < pc ? (B <= T ? pc - B : -(pc - T)) : 0.0;
    }
    const double gn = std::sqrt(gx * gx + gy * gy);
    if (gn > 0.0) { nx = gx / gn; ny = gy / gn; } else { nx = 0.0; ny = 0.0; }
    return fb;
  };
  auto set_stencil = [&](PdeWorkspace::Cell& c) {
    st.fallbacks += normal(c.i, c.j, c.nx, c.ny);
    const int ix = c.nx > 0 ? c.i - 1 : c.i + 1, jy = c.ny > 0 ? c.j - 1 : c.j + 1;
    c.nbx = c.nx != 0.0 && inbox(ix, c.j) ? bidx(ix, c.j) : -1;
    c.nby = c.ny != 0.0 && inbox(c.i, jy) ? bidx(c.i, jy) : -1;
  };
  for (int c = 0; c < nfill; ++c) set_stencil(w.cells[std::size_t(c)]);

  // q_n = n . grad(xi) at a known cell, false if not computable
  auto isknown = [&](int i, int j) {
    return i >= ilo && i <= ihi && j >= jlo && j <= jhi && known(i, j) == 1;
  };
  const double inv2dx = 0.5 / dx, invdx = 1.0 / dx;
  auto deriv = [&](int i, int j, int di, int dj, double& dX, double& dY) -> bool {
    const bool m = isknown(i - di, j - dj), p = isknown(i + di, j + dj);
    if (m && p) {
      dX = (xi_x(i + di, j + dj) - xi_x(i - di, j - dj)) * inv2dx;
      dY = (xi_y(i + di, j + dj) - xi_y(i - di, j - dj)) * inv2dx;
    } else if (opt.qn_one_sided && p) {
      dX = (xi_x(i + di, j + dj) - xi_x(i, j)) * invdx;
      dY = (xi_y(i + di, j + dj) - xi_y(i, j)) * invdx;
    } else if (opt.qn_one_sided && m) {
      dX = (xi_x(i, j) - xi_x(i - di, j - dj)) * invdx;
      dY = (xi_y(i, j) - xi_y(i - di, j - dj)) * invdx;
    } else {
      return false;
    }
    return true;
  };
  auto qn_at = [&](int i, int j, double& qx, double& qy) -> bool {
    double nx, ny;
    normal(i, j, nx, ny);
    double xX = 0, yX = 0, xY = 0, yY = 0;
    if (nx != 0.0 && !deriv(i, j, 1, 0, xX, yX)) return false;
    if (ny != 0.0 && !deriv(i, j, 0, 1, xY, yY)) return false;
    qx = nx * xX + ny * xY;
    qy = nx * yX + ny * yY;
    return true;
  };

  // ---- stage 1 stencils: visit the upwind neighbours of every list cell; known cells
  // get a frozen q_n or, if it is not computable, join the list ("extras").
  w.frozen.clear();
  double s1 = 0.0;
  for (std::size_t c = 0; c < w.cells.size(); ++c) {
    const int nbs[2] = {w.cells[c].nbx, w.cells[c].nby};
    for (int nb : nbs) {
      if (nb < 0 || w.id[std::size_t(nb)] != kUnvisited) continue;
      const int i = bi0 + nb % bw, j = bj0 + nb / bw;  // a known cell
      double qx, qy;
      if (qn_at(i, j, qx, qy)) {
        w.id[std::size_t(nb)] = -3 - int(w.frozen.size() / 2);
        w.frozen.push_back(qx);
        w.frozen.push_back(qy);
        s1 = std::max(s1, std::max(std::fabs(qx), std::fabs(qy)));
      } else {
        w.id[std::size_t(nb)] = int(w.cells.size());
        PdeWorkspace::Cell e{i, j, 0.0, 0.0, -1, -1};
        set_stencil(e);
        w.cells.push_back(e);
      }
    }
  }
  const int n1 = int(w.cells.size());

  // reachability: a list cell is reachable if an upwind neighbour (non-zero coefficient)
  // is frozen or reachable
  auto reach_fix = [&](std::vector<std::uint8_t>& reach, int n, auto&& frozen_code,
                       auto&& list_code) {
    reach.assign(std::size_t(n), 0);
    for (bool changed = true; changed;) {
      changed = false;
      for (int c = 0; c < n; ++c) {
        if (reach[std::size_t(c)]) continue;
        const auto& cell = w.cells[std::size_t(c)];
        for (int nb : {cell.nbx, cell.nby}) {
          if (nb < 0) continue;
          const int code = w.id[std::size_t(nb)];
          if (frozen_code(code) || (list_code(code) && reach[std::size_t(code)])) {
            reach[std::size_t(c)] = 1;
            changed = true;
            break;
          }
        }
      }
    }
  };
  reach_fix(w.reach, n1, [](int code) { return code <= -3; },
            [&](int code) { return code >= 0 && code < n1; });

  // stage 1 rows
  w.rows.resize(std::size_t(n1));
  for (int c = 0; c < n1; ++c) {
    const auto& cell = w.cells[std::size_t(c)];
    Row r{c, c, 1.0, 0.0, 0.0, 0.0, 0.0};
    if (w.reach[std::size_t(c)]) {
      const double coef[2] = {cfl * std::fabs(cell.nx), cfl * std::fabs(cell.ny)};
      const int nbs[2] = {cell.nbx, cell.nby};
      for (int k = 0; k < 2; ++k) {
        if (coef[k] == 0.0) continue;
        r.d -= coef[k];
        const int code = nbs[k] >= 0 ? w.id[std::size_t(nbs[k])] : kInvalid;
        if (code >= 0 && w.reach[std::size_t(code)]) {
          (k == 0 ? r.ux : r.uy) = code;
          (k == 0 ? r.ax : r.ay) = coef[k];
        } else if (code <= -3) {
          const std::size_t f = std::size_t(-3 - code);
          r.bx += coef[k] * w.frozen[2 * f];
          r.by += coef[k] * w.frozen[2 * f + 1];
        } else {
          r.d += coef[k];  // dropped (no valid upwind data): zero derivative
        }
      }
    }
    w.rows[std::size_t(c)] = r;
  }
  w.q.assign(std::size_t(2 * n1), 0.0);
  double chg1 = 0.0;
  st.iterations_qn = jacobi(w.rows, w.q, w.q2, opt.tol * s1, opt.max_iter, opt.parallel_min, chg1);
  const bool conv1 = !(chg1 > opt.tol * s1);
  w.qn.assign(w.q.begin(), w.q.begin() + 2 * nfill);

  // ---- stage 2: xi in the fill cells reachable in stage 1; known cells are frozen
  double s2 = 0.0;
  w.rows.resize(std::size_t(nfill));
  for (int c = 0; c < nfill; ++c) {
    const auto& cell = w.cells[std::size_t(c)];
    Row r{c, c, 1.0, 0.0, 0.0, 0.0, 0.0};
    if (w.reach[std::size_t(c)]) {
      r.bx = dtau * w.qn[2 * std::size_t(c)];
      r.by = dtau * w.qn[2 * std::size_t(c) + 1];
      const double coef[2] = {cfl * std::fabs(cell.nx), cfl * std::fabs(cell.ny)};
      const int nbs[2] = {cell.nbx, cell.nby};
      for (int k = 0; k < 2; ++k) {
        if (coef[k] == 0.0) continue;
        r.d -= coef[k];
        const int code = nbs[k] >= 0 ? w.id[std::size_t(nbs[k])] : kInvalid;
        if (code >= 0 && code < nfill && w.reach[std::size_t(code)]) {
          (k == 0 ? r.ux : r.uy) = code;
          (k == 0 ? r.ax : r.ay) = coef[k];
        } else if (code <= -3 || code >= nfill) {  // known cell
          const int i = bi0 + nbs[k] % bw, j = bj0 + nbs[k] / bw;
          const double vx = xi_x(i, j), vy = xi_y(i, j);
          r.bx += coef[k] * vx;
          r.by += coef[k] * vy;
          s2 = std::max(s2, std::max(std::fabs(vx), std::fabs(vy)));
        } else {
          r.d += coef[k];
        }
      }
    }
    w.rows[std::size_t(c)] = r;
  }
  w.q.assign(std::size_t(2 * nfill), 0.0);
  if (opt.warm_start)
    for (int c = 0; c < nfill; ++c)
      if (w.reach[std::size_t(c)]) {
        const auto& cell = w.cells[std::size_t(c)];
        w.q[2 * std::size_t(c)] = xi_x(cell.i, cell.j);
        w.q[2 * std::size_t(c) + 1] = xi_y(cell.i, cell.j);
      }
  double chg2 = 0.0;
  st.iterations_xi = jacobi(w.rows, w.q, w.q2, opt.tol * s2, opt.max_iter, opt.parallel_min, chg2);
  const bool conv2 = !(chg2 > opt.tol * s2);
  st.iterations = st.iterations_qn + st.iterations_xi;
  st.converged = conv1 && conv2;
  st.final_change = s2 > 0.0 ? chg2 / s2 : chg2;

  for (int c = 0; c < nfill; ++c) {
    if (!w.reach[std::size_t(c)]) { ++st.unreached; continue; }
    const auto& cell = w.cells[std::size_t(c)];
    xi_x(cell.i, cell.j) = w.q[2 * std::size_t(c)];
    xi_y(cell.i, cell.j) = w.q[2 * std::size_t(c) + 1];
    known(cell.i, cell.j) = 1;
    ++st.cells_filled;
  }
  return st;
}

}  // namespace refmap
