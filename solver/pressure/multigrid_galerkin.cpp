// Galerkin coarse levels of the multigrid; see multigrid_galerkin.hpp.
#include "solver/pressure/multigrid_galerkin.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kernels/loop.hpp"
#include "solver/pressure/multigrid_coarse.hpp"

namespace refmap {

namespace {
/// Over-relaxation of the four-colour Gauss-Seidel on the 9-point levels. Measured on the
/// standard disc problem (V(2,2) cycles to 1e-8 at 256^2 and 1024^2, ratio 1 and 1000):
/// omega = 1.0: 8 cycles; 1.1: 7; 1.2: 6; 1.3: 6-7 (F-cycles 4 / 6 and MGPCG 6-7 / 7
/// throughout).
constexpr double kCoarseOmega = 1.2;
}  // namespace

GalerkinLevels::GalerkinLevels() : coarse_(std::make_unique<CoarseDirect>()) {}
GalerkinLevels::~GalerkinLevels() = default;

mg::Stencil9 GalerkinLevels::stencil(int l) const {
  const Level& L = levels_[l];
  mg::Stencil9 s;
  s.nx = L.nx;
  s.ny = L.ny;
  s.a = L.a.data();
  s.nbx = &L.nbx;
  s.nby = &L.nby;
  s.threads = L.threads;
  return s;
}

mg::Prolong9 GalerkinLevels::prolongation(int l) const {
  const Level& F = levels_[l];
  const Level& C = levels_[l + 1];
  mg::Prolong9 p;
  p.nfx = F.nx;
  p.nfy = F.ny;
  p.ncx = C.nx;
  p.ncy = C.ny;
  p.px = F.nbx.periodic;
  p.py = F.nby.periodic;
  p.q = F.q.data();
  return p;
}

void GalerkinLevels::update_threads() {
  const int mt = std::max(1, omp_get_max_threads());
  for (Level& L : levels_)
    L.threads = std::size_t(L.nx) * std::size_t(L.ny) >= min_parallel_cells() ? mt : 1;
}

void GalerkinLevels::setup(const mg::Stencil& s0, bool sink, int coarse_cells, int pre, int post,
                           double fine_omega, bool symmetric) {
  sink_ = sink;
  symmetric_ = symmetric;
  pre_ = pre;
  post_ = post;
  fine_omega_ = fine_omega;
  const bool px = s0.sides.periodic_x(), py = s0.sides.periodic_y();
  const bool reuse = !levels_.empty() && levels_[0].nx == s0.nx && levels_[0].ny == s0.ny &&
                     levels_[0].nbx.periodic == px && levels_[0].nby.periodic == py &&
                     coarse_cells_ == coarse_cells;
  coarse_cells_ = coarse_cells;
  if (!reuse) {
    levels_.clear();
    levels_.reserve(32);
    Level L0;
    L0.nx = s0.nx;
    L0.ny = s0.ny;
    L0.nbx.build(L0.nx, px);
    L0.nby.build(L0.ny, py);
    levels_.push_back(std::move(L0));
    for (;;) {
      const Level& F = levels_.back();
      if (std::size_t(F.nx) * F.ny <= std::size_t(coarse_cells) || F.nx < 4 || F.ny < 4) break;
      if ((px && F.nx % 2) || (py && F.ny % 2)) break;  // a periodic odd length: no vertex coarsening
      Level C;
      C.nx = mg::coarse_count(F.nx, px);
      C.ny = mg::coarse_count(F.ny, py);
      if ((px && C.nx < 3) || (py && C.ny < 3)) break;  // offsets +-1 would meet across the wrap
      C.nbx.build(C.nx, px);
      C.nby.build(C.ny, py);
      C.x.resize(C.nx, C.ny, 1);
      C.f.resize(C.nx, C.ny, 1);
      levels_.push_back(std::move(C));
    }
    // level 0 restricts its residual fused (row buffers), the 9-point levels through r
    for (std::size_t l = 1; l + 1 < levels_.size(); ++l) levels_[l].r.resize(levels_[l].nx, levels_[l].ny, 1);
    rbuf_.assign(mg::scratch9_per_thread(s0.nx) * std::size_t(std::max(1, omp_get_max_threads())), 0.0);
  }
  update_threads();
  // operators and prolongations, level by level
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    Level& F = levels_[l];
    Level& C = levels_[l + 1];
    if (l == 0) {
      mg::build_prolongation(s0, C.nx, C.ny, F.q);
      mg::galerkin_product(s0, prolongation(0), C.a);
    } else {
      mg::build_prolongation(stencil(int(l)), C.nx, C.ny, F.q);
      mg::galerkin_product(stencil(int(l)), prolongation(int(l)), C.a);
    }
  }
  if (levels_.size() == 1) mg::five_to_nine(s0, levels_[0].a);
  // the 9-point smoother divides by a_C: a point without any coupling cannot be relaxed
  for (std::size_t l = 1; l < levels_.size(); ++l) {
    const Level& L = levels_[l];
    const std::size_t n = std::size_t(L.nx) * std::size_t(L.ny);
    for (std::size_t k = 0; k < n; ++k)
      if (!(L.a[4 * n + k] < 0.0))
        throw std::runtime_error("multigrid (galerkin): coarse level " + std::to_string(l) +
                                 " has a point without coupling (disconnected cells or beta <= 0?)");
  }
  build_coarse_solver();
}

void GalerkinLevels::build_coarse_solver() {
  const Level& L = levels_.back();
  const mg::Stencil9 s = stencil(num_levels() - 1);
  const int nx = L.nx, ny = L.ny;
  // -L over the 9 neighbours (the sink is in the Galerkin product); walls: the index
  // tables point at the cell itself with coefficient 0
  std::vector<CoarseDirect::Entry> e;
  e.reserve(std::size_t(nx) * ny * 9);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const double a = s.coef((dj + 1) * 3 + di + 1, i, j);
          if (a == 0.0) continue;
          const int i2 = di < 0 ? L.nbx.m[i] : di > 0 ? L.nbx.p[i] : i;
          const int j2 = dj < 0 ? L.nby.m[j] : dj > 0 ? L.nby.p[j] : j;
          e.push_back({i + nx * j, i2 + nx * j2, -a});
        }
  coarse_->factor(nx, ny, sink_, e, "multigrid (galerkin)");
}

void GalerkinLevels::coarse_solve(int /*l*/, View x, CView f) { coarse_->solve(x, f); }

mg::Scratch GalerkinLevels::scratch() {
  mg::Scratch sc;
  sc.p = rbuf_.data();
  sc.per_thread = mg::scratch9_per_thread(levels_[0].nx);
  sc.nthreads = int(rbuf_.size() / sc.per_thread);
  return sc;
}

void GalerkinLevels::cycle(const mg::Stencil& s0, View x, CView f, bool f_cycle, double* res2) {
  cycle(0, s0, x, f, f_cycle, res2);
}

void GalerkinLevels::cycle(int l, const mg::Stencil& s0, View x, CView f, bool f_cycle,
                           double* res2) {
  const int last = num_levels() - 1;
  if (l == last) {
    coarse_solve(l, x, f);
    if (l == 0) mg::fill_ghosts(s0, x);
    if (res2) *res2 = l == 0 ? mg::residual(s0, x, f, View{}) : mg::residual9(stencil(l), x, f, View{});
    return;
  }
  Level& F = levels_[l];
  Level& C = levels_[l + 1];
  // pre-smoothing and the residual (finest level: one pass, walls in y)
  if (l == 0) {
    mg::smooth_rbgs_restrict9(s0, x, f, pre_, /*black_first=*/false, fine_omega_, prolongation(0),
                              C.f.view(), scratch());
  } else {
    const mg::Stencil9 s = stencil(l);
    if (pre_ > 0) mg::smooth9(s, x, f, pre_, /*reverse=*/false, kCoarseOmega);
    mg::residual9(s, x, f, F.r.view());
    mg::restrict9(prolongation(l), F.r.cview(), C.f.view(), C.threads);
  }
  const mg::Prolong9 P = prolongation(l);
  View xc = C.x.view();
  parallel_rows_on(C.threads, 0, C.ny, [&](int j) {
    for (int i = 0; i < C.nx; ++i) xc(i, j) = 0.0;
  });
  cycle(l + 1, s0, xc, C.f.cview(), f_cycle, nullptr);
  if (f_cycle) cycle(l + 1, s0, xc, C.f.cview(), false, nullptr);
  // prolongation and post-smoothing (reversed colour order for a symmetric cycle; finest
  // level: one pass, walls in y)
  if (l == 0) {
    if (post_ > 0) {
      mg::prolong9_smooth_rbgs(s0, P, C.x.cview(), x, f, post_, /*black_first=*/symmetric_,
                               fine_omega_, scratch(), res2);
    } else {
      mg::prolong9_add(P, C.x.cview(), x, F.threads);
      mg::fill_ghosts(s0, x);
      if (res2) *res2 = mg::residual(s0, x, f, View{});
    }
  } else {
    mg::prolong9_add(P, C.x.cview(), x, F.threads);
    const mg::Stencil9 s = stencil(l);
    if (post_ > 0) {
      mg::smooth9(s, x, f, post_, /*reverse=*/symmetric_, kCoarseOmega, res2);
    } else if (res2) {
      *res2 = mg::residual9(s, x, f, View{});
    }
  }
}

}  // namespace refmap
