// Stateless OpenMP stencil kernels for the multigrid / CG Poisson solvers; see multigrid.hpp.
#include "kernels/multigrid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "kernels/loop.hpp"
#include "kernels/multigrid9_rows.hpp"
#include "kernels/stencil5.hpp"

namespace refmap::mg {

namespace {

inline std::size_t round8(std::size_t n) { return (n + 7) / 8 * 8; }

/// Copy the periodic ghost rows (including ghost columns): row -1 <- ny-1, row ny <- 0.
inline void copy_ghost_rows(const Stencil& s, View x) {
  const std::size_t bytes = sizeof(double) * std::size_t(s.nx + 2);
  std::memcpy(&x(-1, -1), &x(-1, s.ny - 1), bytes);
  std::memcpy(&x(-1, s.ny), &x(-1, 0), bytes);
}

inline void ghost_cols(const Stencil& s, double* xr) {
  if (s.sides.periodic_x()) {
    xr[-1] = xr[s.nx - 1];
    xr[s.nx] = xr[0];
  }
}

/// Inner loop of a half-sweep: the cells i = par, par + 2, ... of one row. A stride-2 loop:
/// GCC vectorises the loads with permutes and stores element-wise, so only cells of the
/// colour are written. (Alternatives measured slower: a contiguous loop with a masked
/// store stalls on store-to-load forwarding, x[i-1] being loaded right after x[i..i+7] is
/// stored; computing a block into a buffer first doubles the arithmetic.) Kept out of line:
/// GCC 12 refuses to vectorise it once it sees that xr aliases xs/xn.
__attribute__((noinline)) void rb_row_kernel(double* xr, const double* __restrict xs,
                                             const double* __restrict xn,
                                             const double* __restrict fr,
                                             const double* __restrict t,
                                             const double* __restrict ts,
                                             const double* __restrict tn,
                                             const double* __restrict id, int nx, int par,
                                             double omega) {
#pragma omp simd
  for (int i = par; i < nx; i += 2) {
    const double g = stencil5_relax(t[i], t[i + 1], ts[i], tn[i], xr[i - 1], xr[i + 1], xs[i], xn[i],
                                    fr[i], id[i]);
    xr[i] += omega * (g - xr[i]);
  }
}

/// One colour of an (over-relaxed) Gauss-Seidel half-sweep on row j: cells with
/// (i + j) % 2 == colour; periodic ghost columns refreshed.
inline void rb_row(const Stencil& s, View x, CView f, int j, int colour, double omega) {
  double* xr = &x(0, j);
  rb_row_kernel(xr, &x(0, j - 1), &x(0, j + 1), &f(0, j), &s.tx(0, j),
                &s.ty(0, j), &s.ty(0, j + 1), &s.invd(0, j), s.nx, (colour + j) & 1, omega);
  ghost_cols(s, xr);
}

}  // namespace

void residual_row(const Stencil& s, CView x, CView f, int j, double* __restrict out) {
  const double* xr = &x(0, j);
  const double* xs = &x(0, j - 1);
  const double* xn = &x(0, j + 1);
  const double* fr = &f(0, j);
  const double* t = &s.tx(0, j);
  const double* ts = &s.ty(0, j);
  const double* tn = &s.ty(0, j + 1);
  const int nx = s.nx;
  if (s.c.p) {  // sink: (L x)_P gains -c_P x_P
    const double* cr = &s.c(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i)
      out[i] = fr[i] - stencil5_apply(t[i], t[i + 1], ts[i], tn[i], xr[i - 1], xr[i + 1], xs[i], xn[i], xr[i]) +
               cr[i] * xr[i];
    return;
  }
#pragma omp simd
  for (int i = 0; i < nx; ++i)
    out[i] = fr[i] - stencil5_apply(t[i], t[i + 1], ts[i], tn[i], xr[i - 1], xr[i + 1], xs[i], xn[i], xr[i]);
}

namespace {

/// out[I] = sum_i P(i, I) rr[i]  (x-direction restriction of one row).
inline void restrict_row(const Transfer1D& T, const double* __restrict rr, double* __restrict out) {
  constexpr int K = Transfer1D::K;
  const int* ri = T.ri.data();
  const double* rw = T.rw.data();
  auto general = [&](int I) {
    double a = 0.0;
    for (int k = 0; k < K; ++k) a += rw[I * K + k] * rr[ri[I * K + k]];
    out[I] = a;
  };
  for (int I = 0; I < T.r_lo; ++I) general(I);
  const int lo = T.r_lo, hi = T.r_hi;
#pragma omp simd
  for (int I = lo; I < hi; ++I)
    out[I] = 0.25 * (rr[2 * I - 1] + rr[2 * I + 2]) + 0.75 * (rr[2 * I] + rr[2 * I + 1]);
  for (int I = std::max(T.r_hi, T.r_lo); I < T.nc; ++I) general(I);
}

/// x[i] += sum_I P(i, I) t[I]  (x-direction prolongation of one row).
inline void prolong_row(const Transfer1D& T, const double* __restrict t, double* __restrict x) {
  const int* p0 = T.p0.data();
  const int* p1 = T.p1.data();
  const double* w0 = T.w0.data();
  const double* w1 = T.w1.data();
  for (int i = 0; i < 2 * T.p_lo; ++i) x[i] += w0[i] * t[p0[i]] + w1[i] * t[p1[i]];
  const int lo = T.p_lo, hi = T.p_hi;
#pragma omp simd
  for (int I = lo; I < hi; ++I) {
    const double c = 0.75 * t[I];
    x[2 * I] += c + 0.25 * t[I - 1];
    x[2 * I + 1] += c + 0.25 * t[I + 1];
  }
  for (int i = 2 * std::max(T.p_hi, T.p_lo); i < T.nf; ++i)
    x[i] += w0[i] * t[p0[i]] + w1[i] * t[p1[i]];
}

}  // namespace

// ------------------------------------------------------------------------------------------
Transfer1D build_transfer(const std::vector<double>& cf, const std::vector<double>& wf,
                          double length, FaceKind lo, FaceKind hi, std::vector<double>& cc,
                          std::vector<double>& cw) {
  const int nf = int(cf.size());
  if (nf < 2 || int(wf.size()) != nf) throw std::invalid_argument("build_transfer: need >= 2 cells");
  const int nc = nf / 2;
  std::vector<double> ef(nf + 1);
  ef[0] = cf[0] - 0.5 * wf[0];
  for (int i = 0; i < nf; ++i) ef[i + 1] = ef[i] + wf[i];
  cc.assign(nc, 0.0);
  cw.assign(nc, 0.0);
  for (int I = 0; I < nc; ++I) {
    const int lo = 2 * I, hi = (I == nc - 1) ? nf : 2 * I + 2;
    cw[I] = ef[hi] - ef[lo];
    cc[I] = 0.5 * (ef[lo] + ef[hi]);
  }
  Transfer1D T;
  T.nf = nf;
  T.nc = nc;
  T.p0.assign(nf, 0);
  T.p1.assign(nf, 0);
  T.w0.assign(nf, 1.0);
  T.w1.assign(nf, 0.0);
  for (int i = 0; i < nf; ++i) {
    const int I = std::min(i / 2, nc - 1);
    T.p0[i] = T.p1[i] = I;
    const double d = cf[i] - cc[I];
    if (std::abs(d) <= 1e-9 * wf[i]) continue;  // middle child of a 3-cell coarse cell
    int nb = I;
    double cn = cc[I];
    if (d < 0) {
      if (I > 0) { nb = I - 1; cn = cc[I - 1]; }
      else switch (lo) {
        case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
        case FaceKind::Outflow:
        case FaceKind::Wall: continue;  // Neumann reflection -> constant extrapolation
        case FaceKind::Periodic: nb = nc - 1; cn = cc[nc - 1] - length; break;
      }
    } else {
      if (I < nc - 1) { nb = I + 1; cn = cc[I + 1]; }
      else switch (hi) {
        case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
        case FaceKind::Outflow:
        case FaceKind::Wall: continue;
        case FaceKind::Periodic: nb = 0; cn = cc[0] + length; break;
      }
    }
    const double wn = (cf[i] - cc[I]) / (cn - cc[I]);
    T.p1[i] = nb;
    T.w0[i] = 1.0 - wn;
    T.w1[i] = wn;
  }
  auto near = [](double a, double b) { return std::abs(a - b) < 1e-13; };
  auto preg = [&](int i) {
    if (i >= nf) return false;
    const int I = i / 2;
    const int nb = (i & 1) ? I + 1 : I - 1;
    return T.p0[i] == I && T.p1[i] == nb && near(T.w0[i], 0.75) && near(T.w1[i], 0.25);
  };
  // longest run of regular coarse cells for the prolongation fast path
  {
    int best_lo = 0, best_hi = 0, run_lo = -1;
    for (int I = 0; I <= nc; ++I) {
      const bool ok = I < nc && preg(2 * I) && preg(2 * I + 1);
      if (ok && run_lo < 0) run_lo = I;
      if (!ok && run_lo >= 0) {
        if (I - run_lo > best_hi - best_lo) { best_lo = run_lo; best_hi = I; }
        run_lo = -1;
      }
    }
    T.p_lo = best_lo;
    T.p_hi = best_hi;
  }
  // restriction = P^T, gathered per coarse cell
  constexpr int K = Transfer1D::K;
  std::vector<std::vector<std::pair<int, double>>> lists(nc);
  for (int i = 0; i < nf; ++i) {
    if (T.w0[i] > 0) lists[T.p0[i]].push_back({i, T.w0[i]});
    if (T.w1[i] > 0) lists[T.p1[i]].push_back({i, T.w1[i]});
  }
  T.ri.assign(std::size_t(nc) * K, 0);
  T.rw.assign(std::size_t(nc) * K, 0.0);
  for (int I = 0; I < nc; ++I) {
    if (int(lists[I].size()) > K) throw std::logic_error("build_transfer: restriction stencil too wide");
    for (int k = 0; k < K; ++k) {
      if (k < int(lists[I].size())) {
        T.ri[I * K + k] = lists[I][k].first;
        T.rw[I * K + k] = lists[I][k].second;
      } else {
        T.ri[I * K + k] = lists[I].empty() ? 0 : lists[I][0].first;
        T.rw[I * K + k] = 0.0;
      }
    }
  }
  auto rreg = [&](int I) {
    if (lists[I].size() != 4) return false;
    const int want[4] = {2 * I - 1, 2 * I, 2 * I + 1, 2 * I + 2};
    const double ww[4] = {0.25, 0.75, 0.75, 0.25};
    for (int m = 0; m < 4; ++m) {
      bool found = false;
      for (auto& e : lists[I])
        if (e.first == want[m] && near(e.second, ww[m])) found = true;
      if (!found) return false;
    }
    return true;
  };
  {
    int best_lo = 0, best_hi = 0, run_lo = -1;
    for (int I = 0; I <= nc; ++I) {
      const bool ok = I < nc && rreg(I);
      if (ok && run_lo < 0) run_lo = I;
      if (!ok && run_lo >= 0) {
        if (I - run_lo > best_hi - best_lo) { best_lo = run_lo; best_hi = I; }
        run_lo = -1;
      }
    }
    T.r_lo = best_lo;
    T.r_hi = best_hi;
  }
  return T;
}

std::size_t scratch_per_thread(int nxf, int nxc) {
  // residual row + 8 restricted rows (+ one coarse row for the fused prolongation)
  const std::size_t restrict_need = round8(nxf) + 9 * round8(nxc);
  const std::size_t jacobi_need = 4 * round8(nxf + 2);
  return round8(std::max({restrict_need, jacobi_need, round8(nxc), std::size_t(8)}));
}

// ------------------------------------------------------------------------------------------
namespace {
/// The column (row) whose value the first ghost column (row) beyond a side copies.
inline int ghost_source(FaceKind k, int adjacent, int wrapped) {
  switch (k) {
    case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
    case FaceKind::Outflow:
    case FaceKind::Wall: return adjacent;  // any finite value: it meets T = 0
    case FaceKind::Periodic: return wrapped;
  }
  return adjacent;
}
}  // namespace

void fill_ghosts(const Stencil& s, View x) {
  const int nx = s.nx, ny = s.ny;
  const int left = ghost_source(s.sides[Left], 0, nx - 1);
  const int right = ghost_source(s.sides[Right], nx - 1, 0);
  const int bottom = ghost_source(s.sides[Bottom], 0, ny - 1);
  const int top = ghost_source(s.sides[Top], ny - 1, 0);
  for (int j = 0; j < ny; ++j) {
    x(-1, j) = x(left, j);
    x(nx, j) = x(right, j);
  }
  const std::size_t bytes = sizeof(double) * std::size_t(nx + 2);
  std::memcpy(&x(-1, -1), &x(-1, bottom), bytes);
  std::memcpy(&x(-1, ny), &x(-1, top), bytes);
}

namespace {

/// sum over row j of (f - L x)^2.
inline double residual_row_norm2(const Stencil& s, CView x, CView f, int j) {
  const double* xr = &x(0, j);
  const double* xs = &x(0, j - 1);
  const double* xn = &x(0, j + 1);
  const double* fr = &f(0, j);
  const double* t = &s.tx(0, j);
  const double* ts = &s.ty(0, j);
  const double* tn = &s.ty(0, j + 1);
  const int nx = s.nx;
  double a = 0.0;
  if (s.c.p) {  // sink: (L x)_P gains -c_P x_P
    const double* cr = &s.c(0, j);
#pragma omp simd reduction(+ : a)
    for (int i = 0; i < nx; ++i) {
      const double v =
          fr[i] - stencil5_apply(t[i], t[i + 1], ts[i], tn[i], xr[i - 1], xr[i + 1], xs[i], xn[i], xr[i]) +
          cr[i] * xr[i];
      a += v * v;
    }
    return a;
  }
#pragma omp simd reduction(+ : a)
  for (int i = 0; i < nx; ++i) {
    const double v =
        fr[i] - stencil5_apply(t[i], t[i + 1], ts[i], tn[i], xr[i - 1], xr[i + 1], xs[i], xn[i], xr[i]);
    a += v * v;
  }
  return a;
}

/// Prolongation of one fine row: x(., r) += P x_c (prolong_add and the fused pass).
inline void prolong_fine_row(const Stencil& s, const Transfer1D& trx, const Transfer1D& try_,
                             CView xc, View x, int r, double* __restrict tmp) {
  const int ncx = trx.nc;
  const double a = try_.w0[r], b = try_.w1[r];
  const double* __restrict c0 = &xc(0, try_.p0[r]);
  const double* __restrict c1 = &xc(0, try_.p1[r]);
#pragma omp simd
  for (int I = 0; I < ncx; ++I) tmp[I] = a * c0[I] + b * c1[I];
  double* xr = &x(0, r);
  prolong_row(trx, tmp, xr);
  ghost_cols(s, xr);
}

/// First and last fine row with a nonzero restriction weight for coarse row J.
inline void restrict_span(const Transfer1D& T, int J, int& lo, int& hi) {
  constexpr int K = Transfer1D::K;
  lo = T.nf;
  hi = -1;
  for (int k = 0; k < K; ++k)
    if (T.rw[J * K + k] != 0.0) {
      lo = std::min(lo, T.ri[J * K + k]);
      hi = std::max(hi, T.ri[J * K + k]);
    }
}

/// fc = P^T (f - L x) computed from a stream of fine rows r0, r0 + 1, ... (each row's
/// residual is x-restricted into a ring of kRing slots); coarse row J is written as soon
/// as its last fine row has arrived, with exactly the arithmetic of residual_restrict.
/// Emits the coarse rows J in [J, J_end) whose fine rows all lie in the stream.
struct RestrictStream {
  static constexpr int kRing = 8;
  const Stencil* s = nullptr;
  CView x, f;
  const Transfer1D* trx = nullptr;
  const Transfer1D* try_ = nullptr;
  View fc;
  double* rrow = nullptr;   ///< fine residual row
  double* ring = nullptr;   ///< kRing x slotW
  std::size_t slotW = 0;
  int r0 = 0, J = 0, J_end = 0, jlo = 0, jhi = 0;

  void init(const Stencil& st, CView xv, CView fv, const Transfer1D& tx, const Transfer1D& ty,
            View out, double* scratch) {
    s = &st;
    x = xv;
    f = fv;
    trx = &tx;
    try_ = &ty;
    fc = out;
    rrow = scratch;
    ring = scratch + round8(st.nx);
    slotW = round8(tx.nc);
  }
  /// Start a stream at fine row `first`, emitting coarse rows J >= J_first with all their
  /// fine rows >= first, up to (excluding) J_last.
  void begin(int first, int J_first, int J_last) {
    r0 = first;
    J = J_first;
    J_end = J_last;
    while (J < J_end) {
      restrict_span(*try_, J, jlo, jhi);
      if (jlo >= r0) break;
      ++J;
    }
  }
  /// Fine row r (= previous + 1) has its final x on rows r-1..r+1.
  void push(int r) {
    constexpr int K = Transfer1D::K;
    residual_row(*s, x, f, r, rrow);
    restrict_row(*trx, rrow, ring + std::size_t(r % kRing) * slotW);
    const int ncx = trx->nc;
    while (J < J_end && jhi <= r) {
      double* __restrict out = &fc(0, J);
      for (int I = 0; I < ncx; ++I) out[I] = 0.0;
      for (int k = 0; k < K; ++k) {
        const double w = try_->rw[J * K + k];
        if (w == 0.0) continue;
        const double* __restrict src = ring + std::size_t(try_->ri[J * K + k] % kRing) * slotW;
#pragma omp simd
        for (int I = 0; I < ncx; ++I) out[I] += w * src[I];
      }
      if (++J < J_end) restrict_span(*try_, J, jlo, jhi);
    }
  }
};

/// Walls in y: all `sweeps` sweeps in ONE pass over memory. The 2*sweeps half-sweeps
/// ("stages"; stage k has colour c1 + k mod 2) form a pipeline, stage k trailing stage
/// k-1 by one row: at step j, stage k updates row j - k. Stage k on row r needs stage k-1
/// on rows r-1..r+1 (done earlier in the same step or before) and must precede stage k+1
/// on rows r-1..r+1 (done later) -- exactly the order of sequential sweeps, so the result
/// is bitwise that of `sweeps` separate sweeps. Optional extra stages:
///  * pin (prolongation) as stage 0, ahead of the sweeps: x(., r) += P x_c, bitwise
///    prolong_add followed by the sweeps;
///  * a last "residual" stage one row behind the last sweep: with res2 it accumulates
///    ||f - L x||^2 of the final iterate; with pout it computes fc = P^T (f - L x)
///    (RestrictStream), bitwise residual_restrict after the sweeps.
/// Threads own row chunks [j0, j1). In the pipelined pass thread t does stage k on rows
/// [j0 + k, j1 - k) (the whole range at the domain walls); the rows left over around each
/// chunk boundary b (stage k: [b - k, b + k)) form a "valley" which thread t finishes after
/// a barrier, stage by stage. The coarse rows of pout that need fine residual rows of a
/// valley are then computed by the thread of that valley, recomputing the residual rows
/// they need. Needs chunks of >= 2 * stages + 8 rows. ||f - L x||^2 is summed from one
/// partial per row in row order (kernels/loop.hpp: same bits for any team size).
/// The pipeline's optional first stage, x(., r) += P x_c for the cell-centred transfers
/// (prolong_add), and its optional last stage, fc = P^T (f - L x) (residual_restrict).
struct PipeIn {
  const Transfer1D* trx;
  const Transfer1D* try_;
  CView xc;
  void row(const Stencil& s, View x, int r, double* tmp) const {
    prolong_fine_row(s, *trx, *try_, xc, x, r, tmp);
  }
  /// where this stage's coarse row buffer sits in a thread's scratch
  std::size_t tmp_offset(const Stencil& s) const {
    return round8(s.nx) + RestrictStream::kRing * round8(trx->nc);
  }
};
struct PipeOut {
  const Transfer1D* trx;
  const Transfer1D* try_;
  View fc;
  using Stream = RestrictStream;
  int ncy() const { return try_->nc; }
  void span(int J, int& lo, int& hi) const { restrict_span(*try_, J, lo, hi); }
  void init(Stream& rs, const Stencil& s, View x, CView f, double* scratch) const {
    rs.init(s, x, f, *trx, *try_, fc, scratch);
  }
};

/// The same two stages for the Galerkin levels' operator-dependent transfers
/// (kernels/multigrid9.hpp: prolong9_add, residual_restrict5). Coarse row J restricts the
/// fine residual rows 2J - 1 .. 2J + 1, kept in a ring of kRing rows.
struct RestrictStream9 {
  static constexpr int kRing = 4;
  const Stencil* s = nullptr;
  CView x, f;
  const Prolong9* P = nullptr;
  View fc;
  double* ring = nullptr;
  std::size_t slotW = 0;
  int J = 0, J_end = 0;

  static void span(const Prolong9& P, int J, int& lo, int& hi) {
    lo = std::max(2 * J - 1, 0);
    hi = std::min(2 * J + 1, P.nfy - 1);
  }
  double* slot(int r) const { return ring + std::size_t(r % kRing) * slotW; }
  void begin(int first, int J_first, int J_last) {
    J = J_first;
    J_end = J_last;
    int lo = 0, hi = 0;
    while (J < J_end) {
      span(*P, J, lo, hi);
      if (lo >= first) break;
      ++J;
    }
  }
  /// Fine row r (= previous + 1) has its final x on rows r-1..r+1.
  void push(int r) {
    residual_row(*s, x, f, r, slot(r));
    int lo = 0, hi = 0;
    while (J < J_end) {
      span(*P, J, lo, hi);
      if (hi > r) break;
      const int j = 2 * J;
      rows9::restrict_row(*P, J, J > 0 ? slot(j - 1) : nullptr, slot(j),
                          j + 1 < P->nfy ? slot(j + 1) : nullptr, fc);
      ++J;
    }
  }
};
struct PipeIn9 {
  const Prolong9* P;
  CView xc;
  void row(const Stencil& s, View x, int r, double*) const {
    double* xr = &x(0, r);
    rows9::prolong_row(*P, xc, xr, r);
    ghost_cols(s, xr);
  }
  std::size_t tmp_offset(const Stencil&) const { return 0; }
};
struct PipeOut9 {
  const Prolong9* P;
  View fc;
  using Stream = RestrictStream9;
  int ncy() const { return P->ncy; }
  void span(int J, int& lo, int& hi) const { RestrictStream9::span(*P, J, lo, hi); }
  void init(Stream& rs, const Stencil& st, View xv, CView fv, double* scratch) const {
    rs.s = &st;
    rs.x = xv;
    rs.f = fv;
    rs.P = P;
    rs.fc = fc;
    rs.ring = scratch;
    rs.slotW = rows9::row_slot(st.nx);
  }
};

template <class In = PipeIn, class Out = PipeOut>
void rbgs_pipeline_walls(const Stencil& s, View x, CView f, int sweeps, int c1, double omega,
                         double* res2, const In* pin = nullptr, const Out* pout = nullptr,
                         const Scratch* sc = nullptr) {
  const int S = 2 * sweeps, ny = s.ny;
  const int k0 = pin ? 1 : 0;                // first sweep stage
  const int kres = k0 + S;                   // residual stage (if any)
  const bool tail = res2 || pout;
  const int stages = kres + (tail ? 1 : 0);
  int want = team_size(s.threads, ny / (2 * stages + 8));
  if (sc) want = std::min(want, sc->nthreads);
  RowPartials rows2(res2 ? std::size_t(ny) : 0);  // ||f - L x||^2 of each row
  double* r2 = rows2.data();
  team_region(want, [&](const Team& tm) {
    const int nt = tm.nt, t = tm.t;
    const auto [j0, j1] = tm.rows(ny);
    const bool first = tm.first(), last = tm.last();
    const int jend = last ? j1 + stages - 1 : j1;
    double* tmp = nullptr;
    typename Out::Stream rs;
    int ncy = 0;
    if (pin) tmp = sc->thread(t) + pin->tmp_offset(s);
    if (pout) {
      pout->init(rs, s, x, f, sc->thread(t));
      ncy = pout->ncy();
      rs.begin(first ? 0 : j0 + kres, 0, ncy);
    }
    auto stage = [&](int k, int r) {
      if (k < k0)
        pin->row(s, x, r, tmp);
      else if (k < kres)
        rb_row(s, x, f, r, (c1 + k - k0) & 1, omega);
      else {
        if (pout) rs.push(r);
        if (res2) r2[r] = residual_row_norm2(s, x, f, r);
      }
    };
    for (int j = j0; j < jend; ++j)
      for (int k = 0; k < stages; ++k) {
        const int r = j - k;
        const int lo = first ? 0 : j0 + k, hi = last ? ny : j1 - k;
        if (r < lo || r >= hi) continue;
        stage(k, r);
      }
    if (nt > 1) {
      tm.barrier();
      if (!last) {
        for (int k = 1; k < kres; ++k)  // stage 0 (prolongation or first sweep) has no valley
          for (int r = j1 - k; r < j1 + k; ++r) rb_row(s, x, f, r, (c1 + k - k0) & 1, omega);
        if (res2)
          for (int r = j1 - kres; r < j1 + kres; ++r) r2[r] = residual_row_norm2(s, x, f, r);
        if (pout) {
          // coarse rows touching the fine residual rows [j1 - kres, j1 + kres) that no
          // thread's pipelined pass covered
          const int gap_lo = j1 - kres, gap_hi = j1 + kres;
          int Ja = 0, lo = 0, hi = -1;
          while (Ja < ncy) {
            pout->span(Ja, lo, hi);
            if (hi >= gap_lo) break;
            ++Ja;
          }
          int Jb = Ja, rfirst = lo, rlast = lo - 1;
          while (Jb < ncy) {
            pout->span(Jb, lo, hi);
            if (lo >= gap_hi) break;
            rfirst = std::min(rfirst, lo);
            rlast = std::max(rlast, hi);
            ++Jb;
          }
          rs.begin(rfirst, Ja, Jb);
          for (int r = rfirst; r <= rlast; ++r) rs.push(r);
        }
      }
    }
  });
  if (res2) *res2 = rows2.sum(std::size_t(ny));
}

}  // namespace

void smooth_rbgs(const Stencil& s, View x, CView f, int sweeps, bool black_first, double omega,
                 double* res2) {
  if (sweeps <= 0) {
    if (res2) *res2 = residual(s, x, f, View{});
    return;
  }
  const int c1 = black_first ? 1 : 0, c2 = 1 - c1;
  if (!s.sides.periodic_y()) {
    rbgs_pipeline_walls(s, x, f, sweeps, c1, omega, res2);
    return;
  }
  // periodic in y: one sweep per pass, the wrap rows finished after a barrier with the
  // ghost rows refreshed in between
  team_region(team_size(s.threads, s.ny), [&](const Team& tm) {
    const auto [j0, j1] = tm.rows(s.ny);
    for (int sw = 0; sw < sweeps; ++sw) {
      // phase 1: first colour on every row, second colour trailing one row behind on the
      // rows whose three first-colour neighbours rows are all owned by this thread
      for (int j = j0; j < j1; ++j) {
        rb_row(s, x, f, j, c1, omega);
        if (j - 1 > j0) rb_row(s, x, f, j - 1, c2, omega);
      }
      tm.barrier();
      tm.single([&] { copy_ghost_rows(s, x); });
      // phase 2: second colour on the two chunk-boundary rows
      if (j1 > j0) {
        rb_row(s, x, f, j0, c2, omega);
        if (j1 - 1 > j0) rb_row(s, x, f, j1 - 1, c2, omega);
      }
      tm.barrier();
      tm.single([&] { copy_ghost_rows(s, x); });
    }
  });
  if (res2) *res2 = residual(s, x, f, View{});
}

void smooth_rbgs_restrict(const Stencil& s, View x, CView f, int sweeps, bool black_first,
                          double omega, const Transfer1D& trx, const Transfer1D& try_, View fc,
                          const Scratch& sc) {
  if (sweeps > 0 && !s.sides.periodic_y()) {
    const PipeOut po{&trx, &try_, fc};
    rbgs_pipeline_walls<PipeIn, PipeOut>(s, x, f, sweeps, black_first ? 1 : 0, omega, nullptr, nullptr, &po, &sc);
    return;
  }
  smooth_rbgs(s, x, f, sweeps, black_first, omega);
  residual_restrict(s, x, f, trx, try_, fc, sc);
}

void prolong_smooth_rbgs(const Stencil& s, const Transfer1D& trx, const Transfer1D& try_,
                         CView xc, View x, CView f, int sweeps, bool black_first, double omega,
                         const Scratch& sc, double* res2) {
  if (sweeps > 0 && !s.sides.periodic_y()) {
    const PipeIn pi{&trx, &try_, xc};
    rbgs_pipeline_walls<PipeIn, PipeOut>(s, x, f, sweeps, black_first ? 1 : 0, omega, res2, &pi, nullptr, &sc);
    return;
  }
  prolong_add(s, trx, try_, xc, x, sc);
  smooth_rbgs(s, x, f, sweeps, black_first, omega, res2);
}

void smooth_rbgs_restrict9(const Stencil& s, View x, CView f, int sweeps, bool black_first,
                           double omega, const Prolong9& P, View fc, const Scratch& sc) {
  if (sweeps > 0 && !s.sides.periodic_y()) {
    const PipeOut9 po{&P, fc};
    rbgs_pipeline_walls<PipeIn, PipeOut9>(s, x, f, sweeps, black_first ? 1 : 0, omega, nullptr,
                                          nullptr, &po, &sc);
    return;
  }
  smooth_rbgs(s, x, f, sweeps, black_first, omega);
  residual_restrict5(s, x, f, P, fc, sc);
}

void prolong9_smooth_rbgs(const Stencil& s, const Prolong9& P, CView xc, View x, CView f,
                          int sweeps, bool black_first, double omega, const Scratch& sc,
                          double* res2) {
  if (sweeps > 0 && !s.sides.periodic_y()) {
    const PipeIn9 pi{&P, xc};
    rbgs_pipeline_walls<PipeIn9, PipeOut>(s, x, f, sweeps, black_first ? 1 : 0, omega, res2, &pi,
                                          nullptr, &sc);
    return;
  }
  prolong9_add(P, xc, x, s.threads);
  fill_ghosts(s, x);
  smooth_rbgs(s, x, f, sweeps, black_first, omega, res2);
}

void smooth_jacobi(const Stencil& s, View x, CView f, int sweeps, double omega,
                   const Scratch& sc) {
  if (sweeps <= 0) return;
  const int nx = s.nx, ny = s.ny;
  const std::size_t W = round8(nx + 2);
  const std::size_t bytes = sizeof(double) * std::size_t(nx + 2);
  team_region(team_size(std::min(s.threads, sc.nthreads), ny), [&](const Team& tm) {
    const int nt = tm.nt, t = tm.t;
    const auto [j0, j1] = tm.rows(ny);
    double* base = sc.thread(t);
    double* bufA = base + 1;
    double* bufB = base + W + 1;
    double* first = base + 2 * W + 1;  // shared: old first row of this chunk
    double* last = base + 3 * W + 1;   // shared: old last row of this chunk
    for (int sw = 0; sw < sweeps; ++sw) {
      std::memcpy(first - 1, &x(-1, j0), bytes);
      std::memcpy(last - 1, &x(-1, j1 - 1), bytes);
      tm.barrier();
      const double* prev = (t == 0) ? &x(0, -1) : sc.thread(t - 1) + 3 * W + 1;
      double* keep = bufA;
      double* spare = bufB;
      for (int j = j0; j < j1; ++j) {
        const double* next = (j + 1 < j1) ? &x(0, j + 1)
                             : (t == nt - 1 ? &x(0, ny) : sc.thread(t + 1) + 2 * W + 1);
        std::memcpy(keep - 1, &x(-1, j), bytes);  // old row j (with ghost columns)
        const double* c = keep;
        double* __restrict xr = &x(0, j);
        const double* __restrict fr = &f(0, j);
        const double* __restrict tt = &s.tx(0, j);
        const double* __restrict ts = &s.ty(0, j);
        const double* __restrict tn = &s.ty(0, j + 1);
        const double* __restrict id = &s.invd(0, j);
#pragma omp simd
        for (int i = 0; i < nx; ++i) {
          const double g =
              stencil5_relax(tt[i], tt[i + 1], ts[i], tn[i], c[i - 1], c[i + 1], prev[i], next[i], fr[i], id[i]);
          xr[i] = c[i] + omega * (g - c[i]);
        }
        ghost_cols(s, xr);
        prev = keep;
        std::swap(keep, spare);
      }
      tm.barrier();
      if (s.sides.periodic_y()) tm.single([&] { copy_ghost_rows(s, x); });
    }
  });
}

double residual(const Stencil& s, CView x, CView f, View r) {
  const int nx = s.nx, ny = s.ny;
  if (r.p)
    return parallel_rows_sum_on(s.threads, 0, ny, [&](int j) {
      double* rr = &r(0, j);
      residual_row(s, x, f, j, rr);
      double a = 0.0;
#pragma omp simd reduction(+ : a)
      for (int i = 0; i < nx; ++i) a += rr[i] * rr[i];
      return a;
    });
  return parallel_rows_sum_on(s.threads, 0, ny,
                              [&](int j) { return residual_row_norm2(s, x, f, j); });
}

void residual_restrict(const Stencil& s, CView x, CView f, const Transfer1D& trx,
                       const Transfer1D& try_, View fc, const Scratch& sc) {
  constexpr int K = Transfer1D::K;
  constexpr int S = 8;  // cached x-restricted residual rows per thread
  const int ncx = trx.nc, ncy = try_.nc;
  const std::size_t rowW = round8(s.nx), slotW = round8(ncx);
  team_region(team_size(std::min(s.threads, sc.nthreads), ncy), [&](const Team& tm) {
    const auto [J0, J1] = tm.rows(ncy);
    double* rrow = sc.thread(tm.t);
    double* slots = rrow + rowW;
    int tags[S];
    for (int k = 0; k < S; ++k) tags[k] = -1;
    int victim = 0;
    for (int J = J0; J < J1; ++J) {
      double* __restrict out = &fc(0, J);
      for (int I = 0; I < ncx; ++I) out[I] = 0.0;
      for (int k = 0; k < K; ++k) {
        const double w = try_.rw[J * K + k];
        if (w == 0.0) continue;
        const int j = try_.ri[J * K + k];
        int slot = -1;
        for (int m = 0; m < S; ++m)
          if (tags[m] == j) slot = m;
        if (slot < 0) {
          slot = victim;
          victim = (victim + 1) % S;
          tags[slot] = j;
          residual_row(s, x, f, j, rrow);
          restrict_row(trx, rrow, slots + slot * slotW);
        }
        const double* __restrict src = slots + slot * slotW;
#pragma omp simd
        for (int I = 0; I < ncx; ++I) out[I] += w * src[I];
      }
    }
  });
}

void prolong_add(const Stencil& fs, const Transfer1D& trx, const Transfer1D& try_, CView xc,
                 View xf, const Scratch& sc) {
  team_region(team_size(std::min(fs.threads, sc.nthreads), fs.ny), [&](const Team& tm) {
    const auto [j0, j1] = tm.rows(fs.ny);
    double* __restrict tmp = sc.thread(tm.t);
    for (int j = j0; j < j1; ++j) prolong_fine_row(fs, trx, try_, xc, xf, j, tmp);
    if (fs.sides.periodic_y()) {
      tm.barrier();
      tm.single([&] { copy_ghost_rows(fs, xf); });
    }
  });
}

// ------------------------------------------------------------------------------------------
double sum(const Stencil& s, CView a) {
  const int nx = s.nx;
  return parallel_rows_sum_on(s.threads, 0, s.ny, [&](int j) {
    const double* ar = &a(0, j);
    double v = 0.0;
#pragma omp simd reduction(+ : v)
    for (int i = 0; i < nx; ++i) v += ar[i];
    return v;
  });
}

double dot(const Stencil& s, CView a, CView b) {
  const int nx = s.nx;
  return parallel_rows_sum_on(s.threads, 0, s.ny, [&](int j) {
    const double* ar = &a(0, j);
    const double* br = &b(0, j);
    double v = 0.0;
#pragma omp simd reduction(+ : v)
    for (int i = 0; i < nx; ++i) v += ar[i] * br[i];
    return v;
  });
}

void fill(const Stencil& s, View a, double v) {
  const int nx = s.nx;
  parallel_rows_on(s.threads, 0, s.ny, [&](int j) {
    double* ar = &a(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) ar[i] = v;
  });
}

void fill_all(Field& a, double v) { a.fill(v); }

void add_scalar(const Stencil& s, View a, double v) {
  const int nx = s.nx;
  parallel_rows_on(s.threads, 0, s.ny, [&](int j) {
    double* ar = &a(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) ar[i] += v;
  });
}

double shift_scale(const Stencil& s, CView in, double shift, double scale, View out) {
  const int nx = s.nx;
  return parallel_rows_sum_on(s.threads, 0, s.ny, [&](int j) {
    const double* ir = &in(0, j);
    double* orow = &out(0, j);
    double v = 0.0;
#pragma omp simd reduction(+ : v)
    for (int i = 0; i < nx; ++i) {
      const double o = scale * (ir[i] - shift);
      orow[i] = o;
      v += o * o;
    }
    return v;
  });
}

// ------------------------------------------------------------------------------------------
double apply_dot(const Stencil& s, CView p, View q) {
  const int nx = s.nx;
  return parallel_rows_sum_on(s.threads, 0, s.ny, [&](int j) {
    const double* pr = &p(0, j);
    const double* ps = &p(0, j - 1);
    const double* pn = &p(0, j + 1);
    const double* t = &s.tx(0, j);
    const double* ts = &s.ty(0, j);
    const double* tn = &s.ty(0, j + 1);
    double* __restrict qr = &q(0, j);
    double v = 0.0;
    if (s.c.p) {  // sink: (L p)_P gains -c_P p_P
      const double* cr = &s.c(0, j);
#pragma omp simd reduction(+ : v)
      for (int i = 0; i < nx; ++i) {
        const double c = pr[i];
        const double l =
            stencil5_apply(t[i], t[i + 1], ts[i], tn[i], pr[i - 1], pr[i + 1], ps[i], pn[i], c) - cr[i] * c;
        qr[i] = l;
        v += c * l;
      }
      return v;
    }
#pragma omp simd reduction(+ : v)
    for (int i = 0; i < nx; ++i) {
      const double c = pr[i];
      const double l = stencil5_apply(t[i], t[i + 1], ts[i], tn[i], pr[i - 1], pr[i + 1], ps[i], pn[i], c);
      qr[i] = l;
      v += c * l;
    }
    return v;
  });
}

double cg_update(const Stencil& s, double alpha, View x, CView p, View r, CView q) {
  const int nx = s.nx;
  return parallel_rows_sum_on(s.threads, 0, s.ny, [&](int j) {
    double* __restrict xr = &x(0, j);
    double* __restrict rr = &r(0, j);
    const double* __restrict pr = &p(0, j);
    const double* __restrict qr = &q(0, j);
    double v = 0.0;
#pragma omp simd reduction(+ : v)
    for (int i = 0; i < nx; ++i) {
      xr[i] += alpha * pr[i];
      const double rn = rr[i] - alpha * qr[i];
      rr[i] = rn;
      v += rn * rn;
    }
    return v;
  });
}

double cg_update_jacobi(const Stencil& s, double alpha, View x, CView p, View r, CView q,
                        double& rz) {
  const int nx = s.nx;
  const auto acc = parallel_rows_sums_on<2>(s.threads, 0, s.ny, [&](int j) {
    double* __restrict xr = &x(0, j);
    double* __restrict rr = &r(0, j);
    const double* __restrict pr = &p(0, j);
    const double* __restrict qr = &q(0, j);
    const double* __restrict id = &s.invd(0, j);
    double v = 0.0, w = 0.0;
#pragma omp simd reduction(+ : v, w)
    for (int i = 0; i < nx; ++i) {
      xr[i] += alpha * pr[i];
      const double rn = rr[i] - alpha * qr[i];
      rr[i] = rn;
      v += rn * rn;
      w -= rn * rn * id[i];
    }
    return std::array<double, 2>{v, w};
  });
  rz = acc[1];
  return acc[0];
}

void cg_direction(const Stencil& s, CView z, double beta, View p) {
  const int nx = s.nx;
  parallel_rows_on(s.threads, 0, s.ny, [&](int j) {
    const double* __restrict zr = &z(0, j);
    double* __restrict pr = &p(0, j);
    if (beta == 0.0) {  // first direction: p may hold anything
#pragma omp simd
      for (int i = 0; i < nx; ++i) pr[i] = zr[i];
    } else {
#pragma omp simd
      for (int i = 0; i < nx; ++i) pr[i] = zr[i] + beta * pr[i];
    }
    ghost_cols(s, pr);
  });
  if (s.sides.periodic_y()) copy_ghost_rows(s, p);
}

void cg_direction_jacobi(const Stencil& s, CView r, double beta, View p) {
  const int nx = s.nx;
  parallel_rows_on(s.threads, 0, s.ny, [&](int j) {
    const double* __restrict rr = &r(0, j);
    const double* __restrict id = &s.invd(0, j);
    double* __restrict pr = &p(0, j);
#pragma omp simd
    for (int i = 0; i < nx; ++i) pr[i] = -id[i] * rr[i] + beta * pr[i];
    ghost_cols(s, pr);
  });
  if (s.sides.periodic_y()) copy_ghost_rows(s, p);
}

double jacobi_precondition(const Stencil& s, CView r, View z) {
  const int nx = s.nx;
  return parallel_rows_sum_on(s.threads, 0, s.ny, [&](int j) {
    const double* __restrict rr = &r(0, j);
    const double* __restrict id = &s.invd(0, j);
    double* __restrict zr = &z(0, j);
    double v = 0.0;
#pragma omp simd reduction(+ : v)
    for (int i = 0; i < nx; ++i) {
      const double zz = -id[i] * rr[i];
      zr[i] = zz;
      v += rr[i] * zz;
    }
    return v;
  });
}

}  // namespace refmap::mg
