// Geometric multigrid hierarchy and the "multigrid" Poisson solver; see poisson_multigrid.hpp.
#include "solver/pressure/poisson_multigrid.hpp"

#include "solver/pressure/multigrid_coarse.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "kernels/loop.hpp"

namespace refmap {

namespace {

void check_field(const Field* f, int nx, int ny, const char* what) {
  if (!f) throw std::invalid_argument(std::string("Poisson operator: ") + what + " is null");
  if (f->nx() != nx || f->ny() != ny)
    throw std::invalid_argument(std::string("Poisson operator: ") + what + " has size " +
                                std::to_string(f->nx()) + " x " + std::to_string(f->ny()) +
                                ", expected " + std::to_string(nx) + " x " + std::to_string(ny));
}

/// Face distance between the centres on either side of face e of a 1-D partition.
inline double face_dist(const std::vector<double>& c, double length, int e) {
  const int n = int(c.size());
  if (e > 0 && e < n) return c[e] - c[e - 1];
  return c[0] + length - c[n - 1];  // periodic wrap face (0 == n)
}

void compute_invd(const mg::Stencil& s, Field& invd) {
  const int nx = s.nx, ny = s.ny;
  if (s.c.p) {  // sink: the diagonal of -L is sum_f T_f + c_P
    parallel_rows(0, ny, nx, [&](int j) {
      for (int i = 0; i < nx; ++i) {
        const double d = s.tx(i, j) + s.tx(i + 1, j) + s.ty(i, j) + s.ty(i, j + 1) + s.c(i, j);
        invd(i, j) = d > 0 ? 1.0 / d : 0.0;
      }
    });
    return;
  }
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      const double d = s.tx(i, j) + s.tx(i + 1, j) + s.ty(i, j) + s.ty(i, j + 1);
      invd(i, j) = d > 0 ? 1.0 / d : 0.0;
    }
  });
}

/// Rediscretised coarse coefficients. The coarse face beta is the mean of the fine-face
/// beta along the coarse face's grid line, weighted tangentially with the restriction
/// weights P^T (on uniform levels 1/4, 3/4, 3/4, 1/4 over the two fine faces the coarse face
/// covers and the next fine face on either side), and T_c = beta_c * len_c / dist_c.
/// In terms of the fine T (= beta len / dist):
///   T_c = [sum_j w_j T_f(e, j)] * (dist_f(e) / dist_c) * (len_c / sum_j w_j len_j).
/// For constant beta this is exactly the 5-point operator of the coarse grid. (Plain
/// averaging over the two covered faces only is ~10% faster per cycle at moderate density
/// ratios but lets the V-cycle diverge at ratio 1000 on 1024^2 and with Jacobi smoothing.)
void coarsen_operator(const MultigridHierarchy::Level& F, MultigridHierarchy::Level& C) {
  constexpr int K = mg::Transfer1D::K;
  parallel_rows(0, C.ny, C.nx, [&](int J) {
    double wl = 0.0;
    for (int k = 0; k < K; ++k) wl += F.try_.rw[J * K + k] * F.wy[F.try_.ri[J * K + k]];
    const double tang = C.wy[J] / wl;
    for (int I = 0; I <= C.nx; ++I) {
      if (I == 0 || I == C.nx) {
        switch (C.sides[I == 0 ? Left : Right]) {
          case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
          case FaceKind::Outflow:
          case FaceKind::Wall: C.tx(I, J) = 0.0; continue;
          case FaceKind::Periodic: break;  // the wrap face: rediscretised like an interior one
        }
      }
      const int e = (I == C.nx) ? F.nx : 2 * I;
      double s = 0.0;
      for (int k = 0; k < K; ++k) s += F.try_.rw[J * K + k] * F.tx(e, F.try_.ri[J * K + k]);
      C.tx(I, J) = s * tang * face_dist(F.cx, F.lx, e) / face_dist(C.cx, C.lx, I);
    }
  });
  std::vector<double> tang_x(C.nx);
  for (int I = 0; I < C.nx; ++I) {
    double wl = 0.0;
    for (int k = 0; k < K; ++k) wl += F.trx.rw[I * K + k] * F.wx[F.trx.ri[I * K + k]];
    tang_x[I] = C.wx[I] / wl;
  }
  parallel_rows(0, C.ny + 1, C.nx, [&](int J) {
    if (J == 0 || J == C.ny) {
      switch (C.sides[J == 0 ? Bottom : Top]) {
        case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
        case FaceKind::Outflow:
        case FaceKind::Wall:
          for (int I = 0; I < C.nx; ++I) C.ty(I, J) = 0.0;
          return;
        case FaceKind::Periodic: break;
      }
    }
    const int e = (J == C.ny) ? F.ny : 2 * J;
    const double normal = face_dist(F.cy, F.ly, e) / face_dist(C.cy, C.ly, J);
    for (int I = 0; I < C.nx; ++I) {
      double s = 0.0;
      for (int k = 0; k < K; ++k) s += F.trx.rw[I * K + k] * F.ty(F.trx.ri[I * K + k], e);
      C.ty(I, J) = s * tang_x[I] * normal;
    }
  });
}

/// Flux-preserving coarse coefficients ("harmonic"): the coarse face between coarse cells
/// A and B carries the conductance of the fine strips in parallel, each strip (one fine row
/// across an x-face, one fine column across a y-face) being the fine faces in series from
/// the centre of A to the centre of B. Along a strip the fine operator's resistance
/// between consecutive fine centres k-1, k is 1/T_f(k); the coarse path covers a fraction
/// of each such interval (1/2, 1, 1/2 on uniform levels), so
///   T_c = sum_strips 1 / sum_k (overlap_k / dist_k) / T_f(k).
/// For constant beta this is the coarse 5-point operator exactly; across a density jump it
/// keeps the flux a fine solution would carry (the normal direction averages harmonically,
/// the tangential one arithmetically), where the restriction-weighted mean of beta
/// ("average") overstates the conductance into a heavy (low-beta) region.
struct Strip1D {
  const std::vector<double>* c;  ///< fine centres
  double length;
  bool periodic;
  int n() const { return int(c->size()); }
  /// Centre of fine cell m for any m (periodic: shifted copies).
  double centre(int m) const {
    const int nf = n();
    if (!periodic) return (*c)[m];
    const int q = (m >= 0) ? m / nf : -((-m + nf - 1) / nf);
    return (*c)[m - q * nf] + q * length;
  }
  /// Fine face index (0..nf) of the face between extended cells k-1 and k.
  int face(int k) const {
    const int nf = n();
    int e = ((k % nf) + nf) % nf;
    return e;  // periodic face 0 == face nf (same T)
  }
};

/// Resistance of the path [a, b] along a strip; T(e) gives the fine T of face e. The path
/// crosses the intervals between extended fine centres k-1 and k for k in [k0, k1].
template <class TF>
double strip_resistance(const Strip1D& s, double a, double b, int k0, int k1, TF&& T) {
  double r = 0.0;
  for (int k = k0; k <= k1; ++k) {
    if (!s.periodic && (k < 1 || k > s.n() - 1)) continue;
    const double lo = s.centre(k - 1), hi = s.centre(k);
    const double o = std::min(b, hi) - std::max(a, lo);
    if (o <= 0) continue;
    const double t = T(s.face(k));
    if (!(t > 0)) return std::numeric_limits<double>::infinity();
    r += (o / (hi - lo)) / t;
  }
  return r;
}

void coarsen_operator_harmonic(const MultigridHierarchy::Level& F, MultigridHierarchy::Level& C) {
  const Strip1D sx{&F.cx, F.lx, C.sides.periodic_x()};
  const Strip1D sy{&F.cy, F.ly, C.sides.periodic_y()};
  // fine rows (columns) a coarse row (column) covers: 2J, 2J+1 (and 2J+2 for the last of an odd count)
  auto span = [](int J, int nc, int nf, int& lo, int& hi) {
    lo = 2 * J;
    hi = (J == nc - 1) ? nf : 2 * J + 2;
  };
  parallel_rows(0, C.ny, C.nx, [&](int J) {
    int j0, j1;
    span(J, C.ny, F.ny, j0, j1);
    for (int I = 0; I <= C.nx; ++I) {
      if (I == 0 || I == C.nx) {
        if (C.sides[I == 0 ? Left : Right] == FaceKind::Wall) { C.tx(I, J) = 0.0; continue; }
      }
      const double a = (I == 0 || I == C.nx) ? C.cx[C.nx - 1] - C.lx : C.cx[I - 1];
      const double b = (I == 0 || I == C.nx) ? C.cx[0] : C.cx[I];
      const int e = (I == C.nx) ? 0 : 2 * I;  // fine face at the coarse face
      double s = 0.0;
      for (int j = j0; j < j1; ++j) {
        const double r = strip_resistance(sx, a, b, e - 3, e + 3, [&](int f) { return F.tx(f, j); });
        if (r > 0 && std::isfinite(r)) s += 1.0 / r;
      }
      C.tx(I, J) = s;
    }
  });
  parallel_rows(0, C.ny + 1, C.nx, [&](int J) {
    if (J == 0 || J == C.ny) {
      if (C.sides[J == 0 ? Bottom : Top] == FaceKind::Wall) {
        for (int I = 0; I < C.nx; ++I) C.ty(I, J) = 0.0;
        return;
      }
    }
    const double a = (J == 0 || J == C.ny) ? C.cy[C.ny - 1] - C.ly : C.cy[J - 1];
    const double b = (J == 0 || J == C.ny) ? C.cy[0] : C.cy[J];
    const int e = (J == C.ny) ? 0 : 2 * J;
    for (int I = 0; I < C.nx; ++I) {
      int i0, i1;
      span(I, C.nx, F.nx, i0, i1);
      double s = 0.0;
      for (int i = i0; i < i1; ++i) {
        const double r = strip_resistance(sy, a, b, e - 3, e + 3, [&](int f) { return F.ty(i, f); });
        if (r > 0 && std::isfinite(r)) s += 1.0 / r;
      }
      C.ty(I, J) = s;
    }
  });
}

/// Coarse cell-integrated sink: the sum of the fine c over the fine cells the coarse cell
/// covers (2I, 2I+1, and 2I+2 for the last coarse cell of an odd count), so that the coarse
/// operator absorbs the same total sink as the fine one for a constant field.
void coarsen_sink(const MultigridHierarchy::Level& F, MultigridHierarchy::Level& C) {
  parallel_rows(0, C.ny, C.nx, [&](int J) {
    const int j0 = 2 * J, j1 = (J == C.ny - 1) ? F.ny : 2 * J + 2;
    for (int I = 0; I < C.nx; ++I) {
      const int i0 = 2 * I, i1 = (I == C.nx - 1) ? F.nx : 2 * I + 2;
      double a = 0.0;
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) a += F.c(i, j);
      C.c(I, J) = a;
    }
  });
}

}  // namespace

// ------------------------------------------------------------------------------------------
void validate_poisson_operator(const PoissonOperator& op) {
  const int nx = op.grid.nx, ny = op.grid.ny;
  if (nx < 1 || ny < 1)
    throw std::invalid_argument("Poisson operator: grid has " + std::to_string(nx) + " x " +
                                std::to_string(ny) + " cells");
  if (!(op.grid.dx > 0)) throw std::invalid_argument("Poisson operator: dx must be > 0");
  check_field(op.beta_x, nx + 1, ny, "beta_x");
  check_field(op.beta_y, nx, ny + 1, "beta_y");
  if (op.sink) {
    check_field(op.sink, nx, ny, "sink");
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (!((*op.sink)(i, j) >= 0.0) || !std::isfinite((*op.sink)(i, j)))
          throw std::invalid_argument("Poisson operator: sink must be finite and >= 0 (cell " +
                                      std::to_string(i) + ", " + std::to_string(j) + ")");
  }
}

bool has_sink(const PoissonOperator& op) {
  if (!op.sink) return false;
  for (int j = 0; j < op.grid.ny; ++j)
    for (int i = 0; i < op.grid.nx; ++i)
      if ((*op.sink)(i, j) > 0.0) return true;
  return false;
}

bool build_fine_operator(const PoissonOperator& op, Field& tx, Field& ty, Field& invd, Field& c) {
  const int nx = op.grid.nx, ny = op.grid.ny;
  const bool sink = has_sink(op);
  if (sink) {
    if (c.nx() != nx || c.ny() != ny || c.ng() < 1) c.resize(nx, ny, 1);
    const double h2 = op.grid.dx * op.grid.dx;  // cell-integrated: c_int = dx^2 c
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) c(i, j) = h2 * (*op.sink)(i, j);
  }
  if (tx.nx() != nx + 1 || tx.ny() != ny || tx.ng() < 1) tx.resize(nx + 1, ny, 1);
  if (ty.nx() != nx || ty.ny() != ny + 1 || ty.ng() < 1) ty.resize(nx, ny + 1, 1);
  if (invd.nx() != nx || invd.ny() != ny || invd.ng() < 1) invd.resize(nx, ny, 1);
  const Field& bx = *op.beta_x;
  const Field& by = *op.beta_y;
  const Sides sides = op.sides;
  // a periodic direction's faces 0 and n are one face: both get the mean of the two betas
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 1; i < nx; ++i) tx(i, j) = bx(i, j);
    switch (sides[Left]) {
      case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
      case FaceKind::Outflow:
      case FaceKind::Wall: tx(0, j) = 0.0; break;
      case FaceKind::Periodic: tx(0, j) = 0.5 * (bx(0, j) + bx(nx, j)); break;
    }
    switch (sides[Right]) {
      case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
      case FaceKind::Outflow:
      case FaceKind::Wall: tx(nx, j) = 0.0; break;
      case FaceKind::Periodic: tx(nx, j) = tx(0, j); break;
    }
  });
  parallel_rows(1, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) ty(i, j) = by(i, j);
  });
  switch (sides[Bottom]) {
    case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
    case FaceKind::Outflow:
    case FaceKind::Wall:
      for (int i = 0; i < nx; ++i) ty(i, 0) = 0.0;
      break;
    case FaceKind::Periodic:
      for (int i = 0; i < nx; ++i) ty(i, 0) = 0.5 * (by(i, 0) + by(i, ny));
      break;
  }
  switch (sides[Top]) {
    case FaceKind::Inflow:   // open sides reach the solvers as walls (Sides::pressure())
    case FaceKind::Outflow:
    case FaceKind::Wall:
      for (int i = 0; i < nx; ++i) ty(i, ny) = 0.0;
      break;
    case FaceKind::Periodic:
      for (int i = 0; i < nx; ++i) ty(i, ny) = ty(i, 0);
      break;
  }
  mg::Stencil s;
  s.nx = nx;
  s.ny = ny;
  s.tx = tx.cview();
  s.ty = ty.cview();
  if (sink) s.c = c.cview();
  compute_invd(s, invd);
  return sink;
}

// ------------------------------------------------------------------------------------------
MultigridHierarchy::MultigridHierarchy() : coarse_(std::make_unique<CoarseDirect>()) {}
MultigridHierarchy::~MultigridHierarchy() = default;

mg::Stencil MultigridHierarchy::stencil(int l) const {
  const Level& L = levels_[l];
  mg::Stencil s;
  s.nx = L.nx;
  s.ny = L.ny;
  s.sides = L.sides;
  s.tx = L.tx.cview();
  s.ty = L.ty.cview();
  s.invd = L.invd.cview();
  if (sink_) s.c = L.c.cview();
  s.threads = L.threads;
  return s;
}

void MultigridHierarchy::update_threads() {
  const int mt = std::max(1, std::min(omp_get_max_threads(), scratch_.nthreads));
  for (Level& L : levels_)
    L.threads = std::size_t(L.nx) * std::size_t(L.ny) >= min_parallel_cells() ? mt : 1;
  if (galerkin_) galerkin_->update_threads();
}

void MultigridHierarchy::setup(const PoissonOperator& op, const PoissonOptions& opt,
                               bool symmetric) {
  validate_poisson_operator(op);
  if (opt.pre_smooth < 0 || opt.post_smooth < 0 || opt.pre_smooth + opt.post_smooth < 1)
    throw std::invalid_argument("multigrid: pre_smooth/post_smooth must be >= 0 and not both 0");
  if (opt.coarse_cells < 1) throw std::invalid_argument("multigrid: coarse_cells must be >= 1");
  jacobi_ = opt.smoother == MgSmoother::Jacobi;
  coarse_op_ = opt.coarse_operator;
  const bool galerkin = coarse_op_ == MgCoarseOperator::Galerkin;
  if (galerkin && jacobi_)
    throw std::invalid_argument("multigrid: coarse_operator \"galerkin\" needs the rbgs smoother");
  pre_ = opt.pre_smooth;
  post_ = opt.post_smooth;
  omega_ = opt.jacobi_omega;
  rb_omega_ = opt.rbgs_omega;
  symmetric_ = symmetric;

  const int nx = op.grid.nx, ny = op.grid.ny;
  const Sides sides = op.sides;
  const bool reuse = !levels_.empty() && levels_[0].nx == nx && levels_[0].ny == ny &&
                     levels_[0].sides == sides &&
                     coarse_cells_ == opt.coarse_cells &&
                     scratch_.nthreads >= omp_get_max_threads() &&
                     (built_op_ == MgCoarseOperator::Galerkin) == galerkin;
  coarse_cells_ = opt.coarse_cells;
  built_op_ = coarse_op_;
  if (!reuse) {
    levels_.clear();
    levels_.reserve(32);
    Level L0;
    L0.nx = nx;
    L0.ny = ny;
    L0.sides = sides;
    L0.cx.resize(nx);
    L0.wx.assign(nx, 1.0);
    L0.cy.resize(ny);
    L0.wy.assign(ny, 1.0);
    for (int i = 0; i < nx; ++i) L0.cx[i] = i + 0.5;
    for (int j = 0; j < ny; ++j) L0.cy[j] = j + 0.5;
    L0.lx = nx;
    L0.ly = ny;
    levels_.push_back(std::move(L0));
    for (;;) {
      Level& F = levels_.back();
      if (galerkin) break;  // the coarse levels live in galerkin_
      if (std::size_t(F.nx) * F.ny <= std::size_t(coarse_cells_) || F.nx < 4 || F.ny < 4) break;
      Level C;
      C.sides = sides;
      C.lx = F.lx;
      C.ly = F.ly;
      F.trx = mg::build_transfer(F.cx, F.wx, F.lx, sides[Left], sides[Right], C.cx, C.wx);
      F.try_ = mg::build_transfer(F.cy, F.wy, F.ly, sides[Bottom], sides[Top], C.cy, C.wy);
      C.nx = int(C.cx.size());
      C.ny = int(C.cy.size());
      C.tx.resize(C.nx + 1, C.ny, 1);
      C.ty.resize(C.nx, C.ny + 1, 1);
      C.invd.resize(C.nx, C.ny, 1);
      C.x.resize(C.nx, C.ny, 1);
      C.f.resize(C.nx, C.ny, 1);
      C.c.resize(C.nx, C.ny, 1);
      levels_.push_back(std::move(C));
    }
    std::size_t per = 8;
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      const int nxc = l + 1 < levels_.size() ? levels_[l + 1].nx : levels_[l].nx;
      per = std::max(per, mg::scratch_per_thread(levels_[l].nx, nxc));
    }
    const int nt = std::max(1, omp_get_max_threads());
    scratch_store_.assign(per * std::size_t(nt), 0.0);
    scratch_.p = scratch_store_.data();
    scratch_.per_thread = per;
    scratch_.nthreads = nt;
  }
  sink_ = build_fine_operator(op, levels_[0].tx, levels_[0].ty, levels_[0].invd, levels_[0].c);
  if (galerkin) {
    update_threads();
    if (!galerkin_) galerkin_ = std::make_unique<GalerkinLevels>();
    galerkin_->setup(stencil(0), sink_, coarse_cells_, pre_, post_, rb_omega_, symmetric_);
    return;
  }
  galerkin_.reset();
  for (std::size_t l = 1; l < levels_.size(); ++l) {
    switch (coarse_op_) {
      case MgCoarseOperator::Average: coarsen_operator(levels_[l - 1], levels_[l]); break;
      case MgCoarseOperator::Harmonic: coarsen_operator_harmonic(levels_[l - 1], levels_[l]); break;
      case MgCoarseOperator::Galerkin: break;  // handled above
    }
    if (sink_) coarsen_sink(levels_[l - 1], levels_[l]);
    mg::Stencil s = stencil(int(l));
    compute_invd(s, levels_[l].invd);
  }
  build_coarse_solver();
  update_threads();
}

void MultigridHierarchy::build_coarse_solver() {
  const Level& L = levels_.back();
  const int nx = L.nx, ny = L.ny;
  auto idx = [nx](int i, int j) { return i + nx * j; };
  // -L (+ diag c): every interior/periodic face once (wall faces carry T = 0 and couple
  // nothing; a face from a cell to itself, periodic n == 1, does nothing)
  const bool wrap_x = L.sides.periodic_x(), wrap_y = L.sides.periodic_y();
  std::vector<CoarseDirect::Entry> e;
  e.reserve(std::size_t(nx) * ny * 9);
  auto face = [&](int k, int m, double T) {
    if (k == m) return;
    e.push_back({k, k, T});
    e.push_back({m, m, T});
    e.push_back({k, m, -T});
    e.push_back({m, k, -T});
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // east face i+1 (wraps when periodic), north face j+1
      if (i + 1 < nx || wrap_x) face(idx(i, j), idx((i + 1) % nx, j), L.tx(i + 1, j));
      if (j + 1 < ny || wrap_y) face(idx(i, j), idx(i, (j + 1) % ny), L.ty(i, j + 1));
    }
  if (sink_)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) e.push_back({idx(i, j), idx(i, j), L.c(i, j)});
  coarse_->factor(nx, ny, sink_, e, "multigrid");
}

void MultigridHierarchy::coarse_solve(int l, View x, CView f) {
  coarse_->solve(x, f);
  mg::fill_ghosts(stencil(l), x);
}

void MultigridHierarchy::smooth(int l, View x, CView f, int sweeps, bool post, double* res2) {
  const mg::Stencil s = stencil(l);
  if (jacobi_ || sweeps <= 0) {
    mg::smooth_jacobi(s, x, f, sweeps, omega_, scratch_);
    if (res2) *res2 = mg::residual(s, x, f, View{});
  } else {
    mg::smooth_rbgs(s, x, f, sweeps, /*black_first=*/post && symmetric_, rb_omega_, res2);
  }
}

void MultigridHierarchy::pre_smooth_restrict(int l, View x, CView f) {
  const Level& F = levels_[l];
  const mg::Stencil s = stencil(l);
  if (jacobi_ || pre_ <= 0) {
    smooth(l, x, f, pre_, false, nullptr);
    mg::residual_restrict(s, x, f, F.trx, F.try_, levels_[l + 1].f.view(), scratch_);
  } else {
    mg::smooth_rbgs_restrict(s, x, f, pre_, /*black_first=*/false, rb_omega_, F.trx, F.try_,
                             levels_[l + 1].f.view(), scratch_);
  }
}

void MultigridHierarchy::prolong_post_smooth(int l, View x, CView f, double* res2) {
  const Level& F = levels_[l];
  const mg::Stencil s = stencil(l);
  if (jacobi_ || post_ <= 0) {
    mg::prolong_add(s, F.trx, F.try_, levels_[l + 1].x.cview(), x, scratch_);
    smooth(l, x, f, post_, true, res2);
  } else {
    mg::prolong_smooth_rbgs(s, F.trx, F.try_, levels_[l + 1].x.cview(), x, f, post_,
                            /*black_first=*/symmetric_, rb_omega_, scratch_, res2);
  }
}

void MultigridHierarchy::cycle(int l, View x, CView f, bool f_cycle, double* res2) {
  if (galerkin_) {
    galerkin_->cycle(stencil(0), x, f, f_cycle, res2);
    return;
  }
  if (l == num_levels() - 1) {
    coarse_solve(l, x, f);
    if (res2) *res2 = mg::residual(stencil(l), x, f, View{});
    return;
  }
  Level& C = levels_[l + 1];
  pre_smooth_restrict(l, x, f);
  const mg::Stencil sc = stencil(l + 1);
  mg::fill(sc, C.x.view(), 0.0);
  mg::fill_ghosts(sc, C.x.view());
  // V: one coarse cycle; F: an F-cycle then a V-cycle on the coarse level
  cycle(l + 1, C.x.view(), C.f.cview(), f_cycle, nullptr);
  if (f_cycle) cycle(l + 1, C.x.view(), C.f.cview(), false, nullptr);
  prolong_post_smooth(l, x, f, res2);
}

void MultigridHierarchy::cycle(View x, CView f, bool f_cycle, double* res2) { cycle(0, x, f, f_cycle, res2); }

void MultigridHierarchy::precondition(CView r, View z) {
  const mg::Stencil s = stencil(0);
  mg::fill(s, z, 0.0);
  mg::fill_ghosts(s, z);
  cycle(0, z, r, false, nullptr);
}

// ------------------------------------------------------------------------------------------
namespace detail {

double prepare_rhs(const PoissonOperator& op, const mg::Stencil& s, const Field& rhs,
                   const Field& x, View f) {
  const int nx = op.grid.nx, ny = op.grid.ny;
  if (rhs.nx() != nx || rhs.ny() != ny)
    throw std::invalid_argument("Poisson solve: rhs is " + std::to_string(rhs.nx()) + " x " +
                                std::to_string(rhs.ny()) + ", grid is " + std::to_string(nx) +
                                " x " + std::to_string(ny));
  if (x.nx() != nx || x.ny() != ny)
    throw std::invalid_argument("Poisson solve: x is " + std::to_string(x.nx()) + " x " +
                                std::to_string(x.ny()) + ", grid is " + std::to_string(nx) +
                                " x " + std::to_string(ny));
  if (x.ng() < 1) throw std::invalid_argument("Poisson solve: x needs at least one ghost layer");
  // with a sink (s.c) the problem is non-singular: the rhs keeps its mean
  const double mean = s.c.p ? 0.0 : mg::sum(s, rhs.cview()) / double(op.grid.cells());
  const double h2 = op.grid.dx * op.grid.dx;
  return std::sqrt(mg::shift_scale(s, rhs.cview(), mean, h2, f));
}

bool start_solve(const mg::Stencil& s, double bnorm, View x, bool record, SolveStats& st) {
  if (bnorm == 0.0) {
    mg::fill(s, x, 0.0);
    mg::fill_ghosts(s, x);
    st.converged = true;
    if (record) st.history.push_back(0.0);
    return false;
  }
  mg::fill_ghosts(s, x);
  return true;
}

void remove_mean(const mg::Stencil& s, View x) {
  if (s.c.p) {  // with a sink the solution is unique: nothing to remove
    mg::fill_ghosts(s, x);
    return;
  }
  const double mean = mg::sum(s, x) / (double(s.nx) * double(s.ny));
  mg::add_scalar(s, x, -mean);
  mg::fill_ghosts(s, x);
}

}  // namespace detail

// ------------------------------------------------------------------------------------------
MultigridSolver::MultigridSolver(const PoissonOptions& opt) : opt_(opt) {}

void MultigridSolver::setup(const PoissonOperator& op) {
  mg_.setup(op, opt_);
  op_ = op;
  if (f0_.nx() != op.grid.nx || f0_.ny() != op.grid.ny) f0_.resize(op.grid.nx, op.grid.ny, 1);
  ready_ = true;
}

std::string MultigridSolver::name() const {
  return std::string("multigrid(") + to_string(opt_.cycle) + "-cycle, " + to_string(opt_.smoother) + " " +
         std::to_string(opt_.pre_smooth) + "/" + std::to_string(opt_.post_smooth) + ")";
}

SolveStats MultigridSolver::solve(const Field& rhs, Field& x) {
  if (!ready_) throw std::logic_error("multigrid: solve() before setup()");
  mg_.update_threads();
  const mg::Stencil s = mg_.stencil(0);
  SolveStats st;
  const double bnorm = detail::prepare_rhs(op_, s, rhs, x, f0_.view());
  View xv = x.view();
  if (!detail::start_solve(s, bnorm, xv, opt_.record_history, st)) return st;
  double rel = std::sqrt(mg::residual(s, xv, f0_.cview(), View{})) / bnorm;
  if (opt_.record_history) st.history.push_back(rel);
  const bool f_cycle = opt_.cycle == MgCycle::F;
  int it = 0;
  while (rel > opt_.tol && it < opt_.max_iter) {
    double r2 = 0.0;  // ||f - L x||^2 after the cycle (fused into the last smoothing pass)
    mg_.cycle(xv, f0_.cview(), f_cycle, &r2);
    ++it;
    rel = std::sqrt(r2) / bnorm;
    if (opt_.record_history) st.history.push_back(rel);
    if (!std::isfinite(rel)) break;
  }
  detail::remove_mean(s, xv);
  st.iterations = it;
  st.rel_residual = rel;
  st.converged = rel <= opt_.tol;
  return st;
}

}  // namespace refmap
