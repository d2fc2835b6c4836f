#pragma once
// Conjugate-gradient Poisson solvers (same interface as solver/pressure/poisson.hpp):
//  * CGSolver   (method "cg"):    CG with Jacobi (diagonal) preconditioning, matrix free;
//  * MGPCGSolver (method "mgpcg"): CG preconditioned by one symmetric multigrid V-cycle
//    (red-black before / black-red after the coarse correction, restriction = P^T, exact
//    coarse solve). Honours smoother, pre_smooth, post_smooth (symmetric only when
//    pre_smooth == post_smooth), coarse_cells, jacobi_omega; `cycle` is ignored (always V).
// Both iterate on the finest-level cell-integrated system L x = dx^2 (rhs - mean) (L
// negative semi-definite; CG's recurrences are sign-invariant) until ||r||/||rhs|| <= tol,
// or, with a sink, L x = dx^2 rhs with L negative definite (no mean removed anywhere),
// one "iteration" = one CG step (one operator application, one preconditioner call).
#include "solver/pressure/poisson.hpp"
#include "solver/pressure/poisson_multigrid.hpp"

namespace refmap {

class CGSolver final : public PoissonSolver {
 public:
  explicit CGSolver(const PoissonOptions& opt);
  void setup(const PoissonOperator& op) override;
  SolveStats solve(const Field& rhs, Field& x) override;
  std::string name() const override { return "cg(jacobi)"; }
  void set_tol(double tol) override { opt_.tol = tol; }
  double tol() const override { return opt_.tol; }

 private:
  mg::Stencil stencil() const;
  PoissonOptions opt_;
  PoissonOperator op_;
  Field tx_, ty_, invd_, c_;
  bool sink_ = false;  ///< c_ holds a cell-integrated sink (PoissonOperator::sink)
  Field f_, r_, p_, q_;
  int threads_ = 1;
  bool ready_ = false;
};

class MGPCGSolver final : public PoissonSolver {
 public:
  explicit MGPCGSolver(const PoissonOptions& opt);
  void setup(const PoissonOperator& op) override;
  SolveStats solve(const Field& rhs, Field& x) override;
  std::string name() const override;
  void set_tol(double tol) override { opt_.tol = tol; }
  double tol() const override { return opt_.tol; }
  const MultigridHierarchy& hierarchy() const { return mg_; }

 private:
  PoissonOptions opt_;
  PoissonOperator op_;
  MultigridHierarchy mg_;
  Field f_, r_, p_, q_, z_;
  bool ready_ = false;
};

}  // namespace refmap
