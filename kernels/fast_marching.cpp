// Fast marching reinitialisation with Chopp's (2001) bicubic initialisation.
// See fast_marching.hpp for the method.
#include "kernels/fast_marching.hpp"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace refmap {

namespace {

// state bits of a (padded) cell
constexpr std::uint8_t kTrial = 1;
constexpr std::uint8_t kAcc = 2;
constexpr std::uint8_t kNeg = 4;     // input phi < 0
constexpr std::uint8_t kBorder = 8;  // padding around the window: never Trial/Accepted
constexpr int kPad = 2;              // padding width (the second-order stencil reaches 2)
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTinyDistance = 1e-300;

using HeapEntry = FmmHeapEntry;

/// Binary min-heap on |distance| with back-pointers for decrease-key. The storage is
/// the workspace's vectors (capacity kept between calls).
class MinHeap {
 public:
  MinHeap(std::vector<HeapEntry>& h, std::vector<int>& pos) : h_(h), pos_(pos) { h_.clear(); }
  bool empty() const { return h_.empty(); }
  const HeapEntry& top() const { return h_.front(); }
  void push(int cell, double key) {
    h_.push_back({key, cell});
    sift_up(int(h_.size()) - 1);
  }
  void decrease(int cell, double key) {
    int p = pos_[cell];
    h_[p].key = key;
    sift_up(p);
  }
  void pop() {
    const int n = int(h_.size()) - 1;
    const HeapEntry e = h_[n];
    h_.pop_back();
    if (n == 0) return;
    int p = 0;
    for (;;) {
      int c = 2 * p + 1;
      if (c >= n) break;
      if (c + 1 < n && h_[c + 1].key < h_[c].key) ++c;
      if (!(h_[c].key < e.key)) break;
      h_[p] = h_[c];
      pos_[h_[p].cell] = p;
      p = c;
    }
    h_[p] = e;
    pos_[e.cell] = p;
  }

 private:
  void sift_up(int p) {
    HeapEntry e = h_[p];
    while (p > 0) {
      int parent = (p - 1) >> 1;
      if (!(e.key < h_[parent].key)) break;
      h_[p] = h_[parent];
      pos_[h_[p].cell] = p;
      p = parent;
    }
    h_[p] = e;
    pos_[e.cell] = p;
  }
  std::vector<HeapEntry>& h_;
  std::vector<int>& pos_;
};

/// Bicubic Hermite interpolant on the unit square (local coordinates s, t in cells):
/// p(s, t) = sum_{m,n} a[m][n] s^m t^n.
struct Bicubic {
  double a[4][4];

  // F = [[f00, f01, ft00, ft01], [f10, f11, ft10, ft11],
  //      [fs00, fs01, fst00, fst01], [fs10, fs11, fst10, fst11]],  a = A F A^T
  void build(const double F[4][4]) {
    static constexpr double A[4][4] = {
        {1, 0, 0, 0}, {0, 0, 1, 0}, {-3, 3, -2, -1}, {2, -2, 1, 1}};
    double T[4][4];
    for (int m = 0; m < 4; ++m)
      for (int n = 0; n < 4; ++n) {
        double s = 0;
        for (int k = 0; k < 4; ++k) s += A[m][k] * F[k][n];
        T[m][n] = s;
      }
    for (int m = 0; m < 4; ++m)
      for (int n = 0; n < 4; ++n) {
        double s = 0;
        for (int k = 0; k < 4; ++k) s += T[m][k] * A[n][k];
        a[m][n] = s;
      }
  }

  void eval(double s, double t, double& p, double& ps, double& pt) const {
    double c[4], d[4];
    for (int m = 0; m < 4; ++m) {
      c[m] = a[m][0] + t * (a[m][1] + t * (a[m][2] + t * a[m][3]));
      d[m] = a[m][1] + t * (2.0 * a[m][2] + 3.0 * t * a[m][3]);
    }
    p = c[0] + s * (c[1] + s * (c[2] + s * c[3]));
    ps = c[1] + s * (2.0 * c[2] + 3.0 * s * c[3]);
    pt = d[0] + s * (d[1] + s * (d[2] + s * d[3]));
  }
};

constexpr double kWander2 = 4.0;  // the closest point must lie within 2 cells of the node

/// Chopp's iteration x <- x0 - [(x0 - x).grad p + p] grad p / |grad p|^2 (the projection
/// of x0 onto the zero line of p linearised at x); converges linearly at a rate of about
/// distance x curvature. Returns the distance in cells, or -1 on failure.
double closest_distance_simple(const Bicubic& b, double s0, double t0) {
  constexpr int kMaxIter = 100;
  double s = s0, t = t0;
  for (int it = 0; it < kMaxIter; ++it) {
    double p, gs, gt;
    b.eval(s, t, p, gs, gt);
    const double g2 = gs * gs + gt * gt;
    if (!(g2 > 1e-24)) return -1.0;
    const double rs = s0 - s, rt = t0 - t;
    const double k = (rs * gs + rt * gt + p) / g2;
    const double ds = rs - k * gs, dt = rt - k * gt;
    s += ds;
    t += dt;
    const double es = s - s0, et = t - t0;
    const double dist2 = es * es + et * et;
    if (!(dist2 <= kWander2)) return -1.0;
    if (ds * ds + dt * dt < 1e-24) return std::sqrt(dist2);
  }
  return -1.0;
}

/// Newton's method on G(x) = [p(x), (x - x0) x grad p(x)] = 0 (on the zero set, with
/// x - x0 parallel to the normal): the same fixed point as Chopp's iteration, but
/// quadratically convergent; its first step, from x = x0, is Chopp's step. Run for the
/// four corners of a quad at once: four independent iterations in lock-step (so they
/// overlap in the pipeline / SIMD lanes). Corner c is (s0, t0) = (c >> 1, c & 1).
/// d[c] = distance in cells, or -1 on failure.
/// True when the sign bits of r0[0..8] and r1[0..8] are all equal (quads 0..7 of the
/// row pair do not straddle the front).
inline bool uniform8(const std::uint8_t* r0, const std::uint8_t* r1) {
  std::uint64_t x, y, z, w;
  std::memcpy(&x, r0, 8);
  std::memcpy(&y, r0 + 1, 8);
  std::memcpy(&z, r1, 8);
  std::memcpy(&w, r1 + 1, 8);
  constexpr std::uint64_t kMask = 0x0101010101010101ull * kNeg;
  return (((x ^ y) | (x ^ z) | (x ^ w)) & kMask) == 0;
}

using v4d = double __attribute__((vector_size(32)));     // GCC/Clang vector extensions
using v4m = long long __attribute__((vector_size(32)));  // lane masks (0 / -1)

void closest_distance_newton4(const Bicubic& b, double d[4]) {
  constexpr int kMaxIter = 12;
  const v4d s0 = {0.0, 0.0, 1.0, 1.0}, t0 = {0.0, 1.0, 0.0, 1.0};
  v4d s = s0, t = t0;
  v4m run = {-1, -1, -1, -1}, ok = {0, 0, 0, 0};
  const auto& a = b.a;
  for (int it = 0; it < kMaxIter; ++it) {
    // c_m(t), c_m'(t), c_m''(t), then p and its derivatives in s
    const v4d c0 = a[0][0] + t * (a[0][1] + t * (a[0][2] + t * a[0][3]));
    const v4d c1 = a[1][0] + t * (a[1][1] + t * (a[1][2] + t * a[1][3]));
    const v4d c2 = a[2][0] + t * (a[2][1] + t * (a[2][2] + t * a[2][3]));
    const v4d c3 = a[3][0] + t * (a[3][1] + t * (a[3][2] + t * a[3][3]));
    const v4d d0 = a[0][1] + t * (2.0 * a[0][2] + 3.0 * a[0][3] * t);
    const v4d d1 = a[1][1] + t * (2.0 * a[1][2] + 3.0 * a[1][3] * t);
    const v4d d2 = a[2][1] + t * (2.0 * a[2][2] + 3.0 * a[2][3] * t);
    const v4d d3 = a[3][1] + t * (2.0 * a[3][2] + 3.0 * a[3][3] * t);
    const v4d e0 = 2.0 * a[0][2] + 6.0 * a[0][3] * t;
    const v4d e1 = 2.0 * a[1][2] + 6.0 * a[1][3] * t;
    const v4d e2 = 2.0 * a[2][2] + 6.0 * a[2][3] * t;
    const v4d e3 = 2.0 * a[3][2] + 6.0 * a[3][3] * t;
    const v4d p = c0 + s * (c1 + s * (c2 + s * c3));
    const v4d ps = c1 + s * (2.0 * c2 + 3.0 * s * c3);
    const v4d pss = 2.0 * c2 + 6.0 * s * c3;
    const v4d pt = d0 + s * (d1 + s * (d2 + s * d3));
    const v4d pst = d1 + s * (2.0 * d2 + 3.0 * s * d3);
    const v4d ptt = e0 + s * (e1 + s * (e2 + s * e3));
    const v4d rs = s - s0, rt = t - t0;
    const v4d g2 = rs * pt - rt * ps;
    const v4d j21 = pt + rs * pst - rt * pss;
    const v4d j22 = rs * ptt - ps - rt * pst;
    const v4d det = ps * j22 - pt * j21;
    const v4d gg = ps * ps + pt * pt;
    const v4d inv = 1.0 / det;
    const v4d ds = (pt * g2 - p * j22) * inv;
    const v4d dt = (j21 * p - ps * g2) * inv;
    const v4d sn = s + ds, tn = t + dt;
    const v4d es = sn - s0, et = tn - t0;
    // NaNs fail the "good" comparisons
    const v4m good = (det * det > 1e-24 * gg * gg) & (gg > 1e-24) & (es * es + et * et <= kWander2);
    const v4m conv = ds * ds + dt * dt < 1e-16;  // |step| < 1e-8 cells: error ~ step^2
    s = run ? sn : s;
    t = run ? tn : t;
    ok |= run & good & conv;
    run &= good & ~conv;
    if ((run[0] | run[1] | run[2] | run[3]) == 0) break;
  }
  const v4d es = s - s0, et = t - t0;
  const v4d r2 = es * es + et * et;
  for (int c = 0; c < 4; ++c) d[c] = ok[c] ? std::sqrt(r2[c]) : -1.0;
}

}  // namespace


void FmmWorkspace::reserve(int ncells) {
  if (int(upos.size()) < ncells) {
    // invariant between calls: upos and uneg are +inf everywhere
    upos.assign(ncells, std::numeric_limits<double>::infinity());
    uneg.assign(ncells, std::numeric_limits<double>::infinity());
    state.resize(ncells);
    pos.resize(ncells);
  }
  if (int(heap.capacity()) < ncells) heap.reserve(ncells);
  if (int(init_cells.capacity()) < ncells) init_cells.reserve(ncells);
  if (int(accepted.capacity()) < ncells) accepted.reserve(ncells);
}

namespace {

/// Solves the upwind Eikonal quadratic of one cell from the data of its two directions:
/// v1 the smaller upwind neighbour (inf if none), v2 the next one beyond it when the
/// second-order difference applies (inf otherwise). h = dx.
inline double eikonal_update(const double v1[2], const double v2[2], double h, double h2) {
  const bool ok0 = v1[0] < kInf, ok1 = v1[1] < kInf;
  const bool so0 = v2[0] < kInf, so1 = v2[1] < kInf;
  if (ok0 && ok1) {
    // 1. both directions, second order where available
    if (so0 || so1) {
      const double al0 = so0 ? 2.25 : 1.0, al1 = so1 ? 2.25 : 1.0;
      const double be0 = so0 ? (4.0 * v1[0] - v2[0]) * (1.0 / 3.0) : v1[0];
      const double be1 = so1 ? (4.0 * v1[1] - v2[1]) * (1.0 / 3.0) : v1[1];
      const double A = al0 + al1, B = al0 * be0 + al1 * be1;
      const double C = al0 * be0 * be0 + al1 * be1 * be1;
      const double disc = B * B - A * (C - h2);
      if (disc >= 0.0) {
        const double inv_a = (so0 && so1) ? 1.0 / 4.5 : 1.0 / 3.25;  // 1 / A
        const double u = (B + std::sqrt(disc)) * inv_a;
        if (u >= std::max(v1[0], v1[1])) return u;
      }
    }
    // 2. both directions, first order
    const double diff = v1[0] - v1[1];
    if (std::abs(diff) < h) return 0.5 * (v1[0] + v1[1] + std::sqrt(2.0 * h2 - diff * diff));
  }
  // 3. the best single direction (u >= v1 always holds here)
  double best = kInf;
  if (ok0) best = so0 ? (4.0 * v1[0] - v2[0]) * (1.0 / 3.0) + (2.0 / 3.0) * h : v1[0] + h;
  if (ok1) {
    const double u = so1 ? (4.0 * v1[1] - v2[1]) * (1.0 / 3.0) + (2.0 / 3.0) * h : v1[1] + h;
    best = std::min(best, u);
  }
  return best;
}

}  // namespace

FmmStats reinitialise_fmm(View phi, int ni, int nj, double dx, double band,
                          FmmWorkspace& ws, const FmmOptions& opt) {
  if (ni < 2 || nj < 2) throw std::invalid_argument("reinitialise_fmm: window must be at least 2x2 cells");
  if (!(dx > 0.0) || !(band >= 0.0)) throw std::invalid_argument("reinitialise_fmm: need dx > 0 and band >= 0");

  const int W = ni + 2 * kPad;
  const int H = nj + 2 * kPad;
  const int ncell = W * H;
  ws.reserve(ncell);

  double* up = ws.upos.data();
  double* un = ws.uneg.data();
  std::uint8_t* st = ws.state.data();
  auto L = [W](int i, int j) { return (j + kPad) * W + (i + kPad); };

  // ---- reset: padding flags, sign bits of the window (upos/uneg are +inf already) --
  std::fill(st, st + kPad * W, kBorder);
  std::fill(st + (H - kPad) * W, st + H * W, kBorder);
  for (int j = 0; j < nj; ++j) {
    std::uint8_t* row = st + L(0, j);
    row[-2] = row[-1] = kBorder;
    row[ni] = row[ni + 1] = kBorder;
    const double* prow = &phi(0, j);
    for (int i = 0; i < ni; ++i) row[i] = prow[i] < 0.0 ? kNeg : 0;
  }

  FmmStats stats;
  ws.init_cells.clear();
  const double inv_dx = 1.0 / dx;

  // Records an initial (unsigned) distance d for cell k: the minimum over calls. The
  // value is kept in the array of the cell's own side until the signs are applied.
  auto record = [&](int k, double d) {
    double* u = (st[k] & kNeg) ? un : up;
    if (st[k] & kAcc) {
      if (d < u[k]) u[k] = d;
    } else {
      st[k] |= kAcc;
      u[k] = d;
      ws.init_cells.push_back(k);
    }
  };

  // ---- initialisation near the front ------------------------------------------------
  if (opt.init == FmmInit::Chopp) {
    // f = phi / dx in cell units; derivatives by central differences (one-sided at the
    // window edge) in cell units.
    auto node_data = [&](int i, int j, double& f, double& fs, double& ft, double& fst) {
      const int im = std::max(i - 1, 0), ip = std::min(i + 1, ni - 1);
      const int jm = std::max(j - 1, 0), jp = std::min(j + 1, nj - 1);
      f = phi(i, j) * inv_dx;
      fs = (phi(ip, j) - phi(im, j)) * inv_dx / double(ip - im);
      ft = (phi(i, jp) - phi(i, jm)) * inv_dx / double(jp - jm);
      fst = (phi(ip, jp) - phi(ip, jm) - phi(im, jp) + phi(im, jm)) * inv_dx /
            double((ip - im) * (jp - jm));
    };
    for (int j = 0; j + 1 < nj; ++j) {
      const std::uint8_t* r0 = st + L(0, j);
      const std::uint8_t* r1 = st + L(0, j + 1);
      for (int i = 0; i + 1 < ni; ++i) {
        // skip 8 quads at a time when their 4 x 9 corner signs all agree
        while (i + 9 <= ni && uniform8(r0 + i, r1 + i)) i += 8;
        if (i + 1 >= ni) break;
        const int nneg = (r0[i] & kNeg) + (r0[i + 1] & kNeg) + (r1[i] & kNeg) + (r1[i + 1] & kNeg);
        if (nneg == 0 || nneg == 4 * kNeg) continue;
        // corners: (a, b) = (0,0) is cell (i,j), (1,0) is (i+1,j), (0,1) is (i,j+1) ...
        double f[2][2], fs[2][2], ft[2][2], fst[2][2];
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) node_data(i + a, j + b, f[a][b], fs[a][b], ft[a][b], fst[a][b]);
        const double F[4][4] = {{f[0][0], f[0][1], ft[0][0], ft[0][1]},
                                {f[1][0], f[1][1], ft[1][0], ft[1][1]},
                                {fs[0][0], fs[0][1], fst[0][0], fst[0][1]},
                                {fs[1][0], fs[1][1], fst[1][0], fst[1][1]}};
        Bicubic bc;
        bc.build(F);
        double dc[4];
        closest_distance_newton4(bc, dc);
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) {
            double d = dc[2 * a + b];
            if (d < 0.0) d = closest_distance_simple(bc, double(a), double(b));
            if (d < 0.0) {
              ++stats.newton_failures;
              const double g = std::sqrt(fs[a][b] * fs[a][b] + ft[a][b] * ft[a][b]);
              d = f[a][b] == 0.0 ? 0.0 : (g > 1e-12 ? std::min(std::abs(f[a][b]) / g, 2.0) : 2.0);
            }
            record(L(i + a, j + b), d * dx);
          }
      }
    }
  } else {
    // linear interpolation of the crossing along each grid edge
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        const int k = L(i, j);
        const std::uint8_t sk = st[k] & kNeg;
        const double p0 = phi(i, j);
        double tx = kInf, ty = kInf;
        auto cross = [&](int kn, int in, int jn, double& t) {
          if ((st[kn] & kBorder) || (st[kn] & kNeg) == sk) return;
          t = std::min(t, p0 / (p0 - phi(in, jn)));
        };
        cross(k - 1, i - 1, j, tx);
        cross(k + 1, i + 1, j, tx);
        cross(k - W, i, j - 1, ty);
        cross(k + W, i, j + 1, ty);
        if (tx == kInf && ty == kInf) continue;
        double d;
        if (tx == kInf) d = ty;
        else if (ty == kInf) d = tx;
        else d = tx * ty / std::max(std::hypot(tx, ty), 1e-300);
        record(k, d * dx);
      }
  }
  // initialised cells: +d on their own side, -d as seen from the other side
  for (int k : ws.init_cells) {
    if (st[k] & kNeg) up[k] = -un[k];
    else un[k] = -up[k];
  }
  stats.accepted_init = int(ws.init_cells.size());

  // ---- march ----------------------------------------------------------------------
  const double h = dx, h2 = dx * dx;
  const bool second = opt.second_order;
  MinHeap heap(ws.heap, ws.pos);
  const int* pos = ws.pos.data();

  // Upwind data of one direction (offset o) from the own-side array u, in which only
  // Accepted cells (and initialised cells across the front) are finite.
  auto dir_data = [&](const double* u, int k, int o, double& v1, double& v2) {
    const double aL = u[k - o], aR = u[k + o];
    const bool left = aL <= aR;
    v1 = left ? aL : aR;
    const double b = left ? u[k - 2 * o] : u[k + 2 * o];
    v2 = (second && b <= v1) ? b : kInf;
  };

  auto update = [&](int kn) {
    const std::uint8_t s = st[kn];
    if (s & (kAcc | kBorder)) return;
    const double* u = (s & kNeg) ? un : up;
    double v1[2], v2[2];
    dir_data(u, kn, 1, v1[0], v2[0]);
    dir_data(u, kn, W, v1[1], v2[1]);
    const double d = eikonal_update(v1, v2, h, h2);
    if (s & kTrial) {
      if (d < ws.heap[pos[kn]].key) heap.decrease(kn, d);
    } else {
      st[kn] = s | kTrial;
      heap.push(kn, d);
    }
  };

  for (int k : ws.init_cells) {
    update(k - 1);
    update(k + 1);
    update(k - W);
    update(k + W);
  }
  ws.accepted.clear();
  while (!heap.empty()) {
    const HeapEntry e = heap.top();
    if (e.key > band) break;
    heap.pop();
    const int k = e.cell;
    st[k] = (st[k] & ~kTrial) | kAcc;
    ((st[k] & kNeg) ? un : up)[k] = e.key;
    ws.accepted.push_back(k);
    update(k - 1);
    update(k + 1);
    update(k - W);
    update(k + W);
  }
  stats.marched = int(ws.accepted.size());

  // ---- write back, and restore the +inf invariant of upos/uneg ----------------------
  // far cells: +-band (streaming pass); then the Accepted cells from the lists
  for (int j = 0; j < nj; ++j) {
    double* prow = &phi(0, j);
    for (int i = 0; i < ni; ++i) prow[i] = prow[i] < 0.0 ? -band : band;
  }
  const double inv_w = 1.0 / W;
  auto write_back = [&](int k) {
    int jj = int((k + 0.5) * inv_w);  // k / W without an integer division
    jj -= (jj * W > k);
    jj += ((jj + 1) * W <= k);
    const int i = k - jj * W - kPad, j = jj - kPad;
    const bool neg = st[k] & kNeg;
    const double c = std::min(neg ? un[k] : up[k], band);
    // phi < 0 stays < 0 even where the computed distance rounds to 0
    phi(i, j) = neg ? -std::max(c, kTinyDistance) : c;
    up[k] = un[k] = kInf;
  };
  for (int k : ws.init_cells) write_back(k);
  for (int k : ws.accepted) write_back(k);
  return stats;
}

}  // namespace refmap
