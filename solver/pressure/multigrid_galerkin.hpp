#pragma once
// The coarse levels of the multigrid with solver.coarse_operator = "galerkin" (results/multigrid.md,
// "The Galerkin coarse operator": a V-cycle count that does not grow with the density ratio).
//
// The finest level keeps its matrix-free 5-point operator and red-black smoother
// (kernels/multigrid.hpp). Below it, every level l >= 1 carries the Galerkin operator
//     L_{l} = P_l^T L_{l-1} P_l
// (9-point, kernels/multigrid9.hpp), where P_l is the operator-dependent prolongation of
// Dendy / de Zeeuw built from L_{l-1} (vertex-style coarsening on the cell unknowns: coarse
// point I on fine point 2I). Restriction is P^T, so the coarse operator is symmetric and the
// V-cycle with reversed colour order after the correction is a symmetric preconditioner
// (mgpcg). The sink of PoissonOperator::sink is part of the fine diagonal and so enters the
// product as P^T diag(c) P. Smoother on the 9-point levels: four-colour Gauss-Seidel.
// Coarsest level: dense Cholesky of -L (+ alpha 1 1^T without a sink) up to 512 points,
// sparse Cholesky with one pinned point above (a periodic direction of odd length cannot
// be coarsened this way and ends the hierarchy there).
#include <memory>
#include <vector>

#include "core/field.hpp"
#include "kernels/multigrid.hpp"
#include "kernels/multigrid9.hpp"
#include "solver/pressure/multigrid_coarse.hpp"

namespace refmap {

class GalerkinLevels {
 public:
  struct Level {
    int nx = 0, ny = 0;
    mg::Neighbours1D nbx, nby;
    std::vector<double> a;  ///< 9-point operator, 9 planes (levels >= 1; level 0 only if coarsest)
    std::vector<double> q;  ///< prolongation from level + 1 (unused on the last level)
    Field x, f, r;          ///< iterate, right-hand side, residual (levels >= 1)
    int threads = 1;
  };

  GalerkinLevels();
  ~GalerkinLevels();
  GalerkinLevels(const GalerkinLevels&) = delete;
  GalerkinLevels& operator=(const GalerkinLevels&) = delete;

  /// Builds the hierarchy below the finest 5-point operator s0. sink: s0.c is set and has
  /// some c > 0 (the problem is definite). Coarsening stops at nx*ny <= coarse_cells, a
  /// direction below 4 points, or a periodic direction of odd length.
  void setup(const mg::Stencil& s0, bool sink, int coarse_cells, int pre, int post,
             double fine_omega, bool symmetric);
  /// Re-read the team sizes (omp_get_max_threads()).
  void update_threads();

  int num_levels() const { return int(levels_.size()); }
  const Level& level(int l) const { return levels_[l]; }
  mg::Stencil9 stencil(int l) const;
  mg::Prolong9 prolongation(int l) const;  ///< from level l+1 to level l

  /// One V- or F-cycle for L x = f on the finest level (operator s0, as given to setup);
  /// x ghosts consistent on entry and return; res2 as MultigridHierarchy::cycle.
  void cycle(const mg::Stencil& s0, View x, CView f, bool f_cycle, double* res2);

 private:
  void cycle(int l, const mg::Stencil& s0, View x, CView f, bool f_cycle, double* res2);
  void coarse_solve(int l, View x, CView f);
  void build_coarse_solver();
  /// rbuf_ as the finest level's per-thread scratch (mg::scratch9_per_thread each).
  mg::Scratch scratch();

  std::vector<Level> levels_;
  std::vector<double> rbuf_;  ///< fine residual rows of the fused passes (scratch())
  bool sink_ = false, symmetric_ = false;
  int pre_ = 2, post_ = 2, coarse_cells_ = -1;
  double fine_omega_ = 1.0;
  std::unique_ptr<CoarseDirect> coarse_;  ///< the coarsest level's exact solve
};

}  // namespace refmap
