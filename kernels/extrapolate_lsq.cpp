#include "kernels/extrapolate_lsq.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#ifdef __BMI2__
#include <immintrin.h>
#endif

#include "kernels/loop.hpp"

namespace refmap {

namespace {

constexpr int kR = 5;  // max |di|, |dj| of the largest stencil, di^2 + dj^2 <= 32 (radius 4 sqrt(2))

struct Domain { int ilo, ihi, jlo, jhi; };  // inclusive

/// The fit stencil, offsets di^2 + dj^2 <= radius2 (2 <= radius2 <= 32): per row
/// r = dj + kR its half-width floor(sqrt(radius2 - dj^2)) (-1: empty row) and the bit mask
/// of that row in the 11-bit pattern of the fast path (bit di + 5).
struct Stencil {
  int half[2 * kR + 1];
  unsigned mask[2 * kR + 1];
  explicit Stencil(int radius2) {
    for (int r = 0; r <= 2 * kR; ++r) {
      const int dj = r - kR, rest = radius2 - dj * dj;
      int m = -1;
      while ((m + 1) * (m + 1) <= rest) ++m;  // floor(sqrt(rest)), -1 when rest < 0
      half[r] = m;
      mask[r] = m < 0 ? 0u : ((1u << (2 * m + 1)) - 1u) << (5 - m);
    }
  }
};

/// Plane fit at (i, j) over known cells (known == 1) in the fit stencil, clipped to
/// the domain. Writes the extrapolated values; returns true when a lower-order fallback was
/// used. General (scalar) path: stencils crossing the domain edge and degenerate fits.
bool fit_cell_general(int i, int j, CView xx, CView xy, View2<const std::uint8_t> kn,
                     const Domain& d, const Stencil& sten, double& ox, double& oy) {
  const int dj0 = std::max(-kR, d.jlo - j), dj1 = std::min(kR, d.jhi - j);
  std::int64_t n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  double fx = 0, fxX = 0, fxY = 0, fy = 0, fyX = 0, fyY = 0;
  for (int dj = dj0; dj <= dj1; ++dj) {
    const int m = sten.half[dj + kR];
    if (m < 0) continue;
    const int a = std::max(-m, d.ilo - i), b = std::min(m, d.ihi - i);
    const std::uint8_t* kr = &kn(i, j + dj);
    const double* xr = &xx(i, j + dj);
    const double* yr = &xy(i, j + dj);
    int r0 = 0, r1 = 0, r2 = 0;
    double vx0 = 0, vx1 = 0, vy0 = 0, vy1 = 0;
    for (int di = a; di <= b; ++di) {
      const bool w = kr[di] == 1;
      const double vx = w ? xr[di] : 0.0;  // select, never multiply: unknowns may be NaN
      const double vy = w ? yr[di] : 0.0;
      const int wi = w;
      r0 += wi; r1 += wi * di; r2 += wi * di * di;
      vx0 += vx; vx1 += vx * di;
      vy0 += vy; vy1 += vy * di;
    }
    n += r0; sx += r1; sxx += r2;
    sy += std::int64_t(dj) * r0; sxy += std::int64_t(dj) * r1; syy += std::int64_t(dj * dj) * r0;
    fx += vx0; fxX += vx1; fxY += dj * vx0;
    fy += vy0; fyX += vy1; fyY += dj * vy0;
  }
  // normal matrix M = [n sx sy; sx sxx sxy; sy sxy syy], unknowns (c, a, b); c = row 0 of
  // adj(M) . rhs / det(M). All integer, exact.
  const std::int64_t c00 = sxx * syy - sxy * sxy;
  const std::int64_t c01 = sy * sxy - sx * syy;
  const std::int64_t c02 = sx * sxy - sxx * sy;
  const std::int64_t det = n * c00 + sx * c01 + sy * c02;
  if (det > 0) {
    const double inv = 1.0 / double(det);
    const double a0 = double(c00), a1 = double(c01), a2 = double(c02);
    ox = (a0 * fx + a1 * fxX + a2 * fxY) * inv;
    oy = (a0 * fy + a1 * fyX + a2 * fyY) * inv;
    return false;
  }
  // Fallbacks. Collinear known cells: the centred scatter matrix has rank 1; its non-zero
  // column is along the line. Fit xi = alpha + beta t, t = dir . (X, Y); target is t = 0.
  if (n <= 0) { ox = 0.0; oy = 0.0; return true; }  // unreachable for a real candidate
  const std::int64_t cxx = n * sxx - sx * sx, cyy = n * syy - sy * sy, cxy = n * sxy - sx * sy;
  if (cxx == 0 && cyy == 0) {  // one distinct point
    ox = fx / double(n); oy = fy / double(n);
    return true;
  }
  const double tx = double(cxx >= cyy ? cxx : cxy), ty = double(cxx >= cyy ? cxy : cyy);
  const double s = 1.0 / std::max(std::fabs(tx), std::fabs(ty));
  const double ux = tx * s, uy = ty * s;
  const double st = ux * double(sx) + uy * double(sy);
  const double stt = ux * ux * double(sxx) + 2.0 * ux * uy * double(sxy) + uy * uy * double(syy);
  const double den = double(n) * stt - st * st;
  if (!(den > 0.0)) { ox = fx / double(n); oy = fy / double(n); return true; }
  const double stx = ux * fxX + uy * fxY, sty = ux * fyX + uy * fyY;
  const double bx = (double(n) * stx - st * fx) / den;
  const double by = (double(n) * sty - st * fy) / den;
  ox = (fx - bx * st) / double(n);
  oy = (fy - by * st) / double(n);
  return true;
}


// ---- fast path (stencil entirely inside the domain) ------------------------------------
// Geometry: per stencil row, the 11-bit pattern of known cells at di = -5..5 (bit di + 5)
// is packed from the mask bytes (bit 0 of each byte: 1 = known, 0 = unknown, 2 = pending);
// count, sum di and sum di^2 of a pattern come from tables. Values: with the normal-matrix
// cofactors (c00, c01, c02) the fit is c = sum_k (c00 + c01 X_k + c02 Y_k) xi_k / det, one
// weighted sum per component over 3 groups of 4 lanes with the unknown lanes masked out.

// Packed per-pattern moments: bits 0-15 count, 16-31 (sum di) + 16, 32-47 sum di^2, so one
// 64-bit add accumulates all three (fields never overflow into each other, see fit_cell_fast)
struct PatTable { std::uint64_t v[2048]; };
constexpr PatTable make_pat_table() {
  PatTable t{};
  for (int p = 0; p < 2048; ++p) {
    int c = 0, a = 16, b = 0;  // a: biased sum of di, in [1, 31]
    for (int bit = 0; bit < 11; ++bit)
      if (p >> bit & 1) { c += 1; a += bit - 5; b += (bit - 5) * (bit - 5); }
    t.v[p] = std::uint64_t(c) | std::uint64_t(a) << 16 | std::uint64_t(b) << 32;
  }
  return t;
}
constexpr PatTable kPat = make_pat_table();

/// bit 0 of 8 consecutive bytes -> 8-bit pattern (byte k -> bit k)
inline unsigned pack8(const std::uint8_t* p) {
  std::uint64_t x;
  std::memcpy(&x, p, 8);
#ifdef __BMI2__
  return unsigned(_pext_u64(x, 0x0101010101010101ULL));
#else
  return unsigned(((x & 0x0101010101010101ULL) * 0x0102040810204080ULL) >> 56);
#endif
}

typedef double v4d __attribute__((vector_size(32)));
typedef long long v4i __attribute__((vector_size(32)));
// lane groups of a stencil row, loaded at i - 5 + off: di = -5..-2, -1..2, 2..5 (the
// repeated di = 2 lane of the last group gets a bit that is never set)
constexpr int kOff[3] = {0, 4, 7};
const v4i kBits[3] = {{1 << 0, 1 << 1, 1 << 2, 1 << 3},
                      {1 << 4, 1 << 5, 1 << 6, 1 << 7},
                      {1 << 15, 1 << 8, 1 << 9, 1 << 10}};
const v4d kX[3] = {{-5, -4, -3, -2}, {-1, 0, 1, 2}, {2, 3, 4, 5}};

[[gnu::always_inline]] inline bool fit_cell_fast(int i, int j, CView xx, CView xy,
                                                View2<const std::uint8_t> kn, const Domain& d,
                                                const Stencil& sten, double& ox, double& oy) {
  unsigned pat[2 * kR + 1];
  // A = sum T, B = sum r T, C = sum r^2 T over rows r = dj + 5 = 0..10 (T = kPat entry).
  // Field bounds: A: count <= 101, sum(di+16) <= 341, sum di^2 <= 1210; B <= 10 A;
  // C: only its count field is used (<= 100*101); higher fields may overflow upwards only.
  std::uint64_t A = 0, B = 0, C = 0;
  const std::uint8_t* kr = &kn(i, j - kR);
  for (int r = 0; r <= 2 * kR; ++r, kr += kn.stride) {
    const unsigned p = (pack8(kr - 5) | pack8(kr - 2) << 3) & sten.mask[r];
    pat[r] = p;
    const std::uint64_t t = kPat.v[p];
    A += t;
    B += std::uint64_t(r) * t;
    C += std::uint64_t(r * r) * t;
  }
  constexpr std::uint64_t F = 0xffff;
  const int n = int(A & F);
  const int sx = int(A >> 16 & F) - 16 * 11;
  const int sxx = int(A >> 32 & F);
  const int sy = int(B & F) - 5 * n;                          // sum (dj+5) c = sy + 5 n
  const int sxy = int(B >> 16 & F) - 16 * 55 - 5 * sx;        // sum r (s1+16)
  const int syy = int(C & F) - 10 * sy - 25 * n;              // sum (dj+5)^2 c
  const std::int64_t c00 = std::int64_t(sxx) * syy - std::int64_t(sxy) * sxy;
  const std::int64_t c01 = std::int64_t(sy) * sxy - std::int64_t(sx) * syy;
  const std::int64_t c02 = std::int64_t(sx) * sxy - std::int64_t(sxx) * sy;
  const std::int64_t det = n * c00 + sx * c01 + sy * c02;
  if (det <= 0) return fit_cell_general(i, j, xx, xy, kn, d, sten, ox, oy);
  const double a0 = double(c00), a1 = double(c01), a2 = double(c02);
  v4d ax[3] = {}, ay[3] = {};
  v4d wx[3];
  for (int g = 0; g < 3; ++g) wx[g] = a0 + a1 * kX[g];
  for (int r = 0; r <= 2 * kR; ++r) {
    const unsigned p = pat[r];
    if (!p) continue;
    const int dj = r - kR;
    const double* xr = &xx(i - 5, j + dj);
    const double* yr = &xy(i - 5, j + dj);
    const v4i pv = {p, p, p, p};
    const double wy = a2 * dj;
    for (int g = 0; g < 3; ++g) {
      const v4i m = (pv & kBits[g]) != 0;
      v4d vx, vy;
      std::memcpy(&vx, xr + kOff[g], sizeof vx);
      std::memcpy(&vy, yr + kOff[g], sizeof vy);
      vx = (v4d)((v4i)vx & m);  // unknown lanes -> +0.0 (never arithmetic on them)
      vy = (v4d)((v4i)vy & m);
      const v4d w = wx[g] + wy;
      ax[g] += w * vx;
      ay[g] += w * vy;
    }
  }
  const v4d sxv = ax[0] + ax[1] + ax[2], syv = ay[0] + ay[1] + ay[2];
  const double inv = 1.0 / double(det);
  ox = ((sxv[0] + sxv[1]) + (sxv[2] + sxv[3])) * inv;
  oy = ((syv[0] + syv[1]) + (syv[2] + syv[3])) * inv;
  return false;
}

[[gnu::always_inline]] inline bool fit_cell(int i, int j, CView xx, CView xy,
                                           View2<const std::uint8_t> kn, const Domain& d,
                                           const Stencil& sten, double& ox, double& oy) {
  if (i - kR >= d.ilo && i + kR <= d.ihi && j - kR >= d.jlo && j + kR <= d.jhi)
    return fit_cell_fast(i, j, xx, xy, kn, d, sten, ox, oy);
  return fit_cell_general(i, j, xx, xy, kn, d, sten, ox, oy);
}

}  // namespace

ExtrapStats extrapolate_lsq(View xi_x, View xi_y, View2<std::uint8_t> known, int ni, int nj,
                            int ng, double /*dx*/, const LsqOptions& opt, LsqWorkspace* ws) {
  ExtrapStats st;
  if (opt.passes <= 0 || ni + 2 * ng <= 0 || nj + 2 * ng <= 0) return st;
  LsqWorkspace local;
  LsqWorkspace& w = ws ? *ws : local;
  const Domain d{-ng, ni + ng - 1, -ng, nj + ng - 1};
  const Stencil stencil(std::clamp(opt.radius2, 2, 32));
  const View2<const std::uint8_t> tgt = opt.target;
  const bool has_tgt = tgt.p != nullptr;
  auto allowed = [&](int i, int j) { return !has_tgt || tgt(i, j) != 0; };

  // ---- pass-1 candidates: scan only rows/columns next to known cells
  detail::known_extent(known, ni, nj, ng, w.ext);
  if (w.ext.empty()) return st;
  w.cand.clear();
  {
    const auto& e = w.ext;
    const int jb = std::max(d.jlo, e.j0 - 1), je = std::min(d.jhi, e.j1 + 1);
    for (int j = jb; j <= je; ++j) {
      int lo = 1 << 30, hi = -(1 << 30);
      for (int jj = std::max(d.jlo, j - 1); jj <= std::min(d.jhi, j + 1); ++jj) {
        lo = std::min(lo, e.lo[jj + ng]); hi = std::max(hi, e.hi[jj + ng]);
      }
      if (hi < lo) continue;
      const int ib = std::max(d.ilo, lo - 1), ie = std::min(d.ihi, hi + 1);
      const std::uint8_t* rm = j > d.jlo ? &known(0, j - 1) : nullptr;
      const std::uint8_t* r0 = &known(0, j);
      const std::uint8_t* rp = j < d.jhi ? &known(0, j + 1) : nullptr;
      for (int i = ib; i <= ie; ++i) {
        if (r0[i]) continue;
        const int a = std::max(d.ilo, i - 1), b = std::min(d.ihi, i + 1);
        int any = 0;
        for (int q = a; q <= b; ++q) any |= r0[q] | (rm ? rm[q] : 0) | (rp ? rp[q] : 0);
        if (any && allowed(i, j)) w.cand.push_back({i, j});
      }
    }
    for (const auto& c : w.cand) known(c.i, c.j) = 2;  // pending: not yet known
  }

  const View2<const std::uint8_t> kc = known;
  const CView cx = xi_x, cy = xi_y;
  const long pmin = opt.parallel_min >= 0 ? opt.parallel_min : kLsqParallelMin;
  for (int pass = 0; pass < opt.passes; ++pass) {
    const long n = long(w.cand.size());
    if (n == 0) break;
    w.val.resize(std::size_t(2 * n));
    const LsqWorkspace::Cell* cand = w.cand.data();
    double* val = w.val.data();
    const long nfb = parallel_items_count(n >= pmin ? omp_get_max_threads() : 1, n, [&](long c) {
      return long(fit_cell(cand[c].i, cand[c].j, cx, cy, kc, d, stencil, val[2 * c], val[2 * c + 1]));
    });
    for (long c = 0; c < n; ++c) {
      const int i = cand[c].i, j = cand[c].j;
      xi_x(i, j) = val[2 * c];
      xi_y(i, j) = val[2 * c + 1];
      known(i, j) = 1;
    }
    st.cells_filled += n;
    st.fallbacks += nfb;
    st.passes += 1;
    if (pass + 1 == opt.passes) break;
    // ---- next pass: unknown (allowed) neighbours of the cells just filled
    w.next.clear();
    for (long c = 0; c < n; ++c) {
      const int i = cand[c].i, j = cand[c].j;
      for (int jj = std::max(d.jlo, j - 1); jj <= std::min(d.jhi, j + 1); ++jj)
        for (int ii = std::max(d.ilo, i - 1); ii <= std::min(d.ihi, i + 1); ++ii) {
          std::uint8_t& k = known(ii, jj);
          if (k == 0 && allowed(ii, jj)) { k = 2; w.next.push_back({ii, jj}); }
        }
    }
    w.cand.swap(w.next);
  }
  return st;
}

}  // namespace refmap
