#pragma once
// Matrix-free geometric multigrid for the variable-coefficient pressure Poisson problem of
// solver/pressure/poisson.hpp (methods "multigrid" and, as preconditioner, "mgpcg").
//
// Discretisation on every level (see kernels/multigrid.hpp): cell-integrated 5-point
// operator (L x)_P = sum_f T_f (x_nb - x_P); on the finest level T = beta, L = dx^2 A.
//
// Coarsening: cell-centred, by two in both directions at once. Coarse cell I covers fine
// cells 2I and 2I+1; when the fine count n is odd the LAST coarse cell covers the three
// cells n-3, n-2, n-1 (coarse count floor(n/2)). Cells are therefore not all equal on
// coarse levels; each level keeps its cell centres and widths (in finest-cell units)
// and everything below is the exact finite-volume expression on that non-uniform grid.
// This works the same for walls and periodic directions (a periodic direction of odd
// length wraps the 3-cell coarse cell onto coarse cell 0). Coarsening stops when
// nx*ny <= coarse_cells or either direction has fewer than 4 cells.
//
// Coarse operator (rediscretisation, 5-point on every level): the coarse face beta is the
// mean of the fine-face beta along the coarse face's grid line, weighted tangentially with
// the restriction weights (uniform levels: 1/4, 3/4, 3/4, 1/4 over the two fine faces the
// coarse face covers and the next fine face on either side), T_c = beta_c * len / dist.
// (Averaging the two covered faces only was measured: V-cycles then diverge at density
// ratio 1000 on 1024^2, and with the Jacobi smoother already on 256^2.)
// "galerkin" (opt-in) replaces all coarse levels by Galerkin operators P^T L P with an
// operator-dependent prolongation (solver/pressure/multigrid_galerkin.hpp; 9-point coarse stencils).
// This is coarse_operator = "average" (the default). "harmonic" (opt-in,
// solver.coarse_operator) puts the fine faces in series between the two coarse centres and
// the fine strips the coarse face covers in parallel -- the flux-preserving rule for a
// density jump, identical for constant beta. With the bilinear prolongation it is WORSE on
// the standard ratio-1000 disc (V-cycles: 48 instead of 13 on 256^2, no convergence on
// 512^2; results/poisson_contrast.csv, results/multigrid.md "Multigrid and density
// contrast"); kept selectable for that comparison.
// Prolongation: linear interpolation between cell centres in each direction (bilinear,
// weights 9/16 3/16 3/16 1/16 on uniform levels), Neumann reflection (constant
// extrapolation) at walls, wrap in periodic directions. Restriction: exactly P^T applied to
// the cell-integrated residual (16-point full weighting on uniform levels; area-consistent).
// Smoothers: red-black Gauss-Seidel over-relaxed by rbgs_omega (default 1.25; on the 256^2
// constant-coefficient problem V(2,2) needs 7 cycles to 1e-11 at a factor ~0.025 instead
// of 10 cycles at ~0.1 with plain GS, and 18 instead of 23 cycles to 1e-10 at density
// ratio 1000), or weighted Jacobi (jacobi_omega, default 0.8). Colour order red-black
// before and after the coarse correction for "multigrid" (black-red after would repeat the
// last colour: ~1 half-sweep lost per cycle), black-red after for mgpcg (symmetric).
// Coarsest level: exact solve (dense Cholesky of -L + alpha 1 1^T up to 512 cells, sparse
// Cholesky with one pinned cell above -- only for degenerate grids, e.g. 4 x 5000, and that
// path allocates in solve), right-hand side projected to zero sum, zero-mean solution.
// With a sink (PoissonOperator::sink, some c > 0) every level carries the cell-integrated
// c (finest dx^2 c, coarse: the sum over the covered fine cells), and the coarsest solve is
// the Cholesky of -L + diag(c) as it stands (no alpha, no pinned cell, no mean removed).
// With equal pre/post smoothing counts and symmetric = true the V-cycle is a symmetric
// linear operator (used by mgpcg).
// Passes over memory per level and cycle (red-black smoother, walls in y): two -- the
// pre-smoothing sweeps with the residual restriction fused (mg::smooth_rbgs_restrict), and
// the prolongation with the post-smoothing sweeps (mg::prolong_smooth_rbgs); the same
// arithmetic as the separate kernels, so the same iterates bit for bit.
#include <memory>
#include <vector>

#include "kernels/multigrid.hpp"
#include "solver/pressure/multigrid_galerkin.hpp"
#include "solver/pressure/poisson.hpp"

namespace refmap {

/// Checks shared by the solvers: operator fields present and of the right size.
void validate_poisson_operator(const PoissonOperator& op);

/// True when op.sink is given and has a cell with c > 0 (the problem is then definite).
bool has_sink(const PoissonOperator& op);

/// Finest-level coefficients: tx = beta_x with wall faces set to 0 and the two periodic
/// faces set to their mean, ty likewise; with a sink (has_sink) c = dx^2 sink (cell
/// integrated) and invd = 1/(sum T + c), else c is left alone and invd = 1/sum T (0 if no
/// face). Fields are (re)sized with one ghost layer. Returns has_sink(op).
bool build_fine_operator(const PoissonOperator& op, Field& tx, Field& ty, Field& invd, Field& c);

class MultigridHierarchy {
 public:
  struct Level {
    int nx = 0, ny = 0;
    Sides sides;
    std::vector<double> cx, cy, wx, wy;  ///< cell centres / widths, finest-cell units
    double lx = 0, ly = 0;               ///< domain length, finest-cell units
    Field tx, ty, invd;                  ///< operator
    Field c;                             ///< cell-integrated sink (used only with one)
    Field x, f;                          ///< iterate and right-hand side (levels >= 1)
    mg::Transfer1D trx, try_;            ///< transfer to level + 1 (unused on the last level)
    int threads = 1;
  };

  MultigridHierarchy();
  ~MultigridHierarchy();
  MultigridHierarchy(const MultigridHierarchy&) = delete;
  MultigridHierarchy& operator=(const MultigridHierarchy&) = delete;

  /// Honours opt.smoother, pre_smooth, post_smooth, coarse_cells, jacobi_omega, rbgs_omega.
  /// symmetric: post-smoothing in reversed colour order (black-red) so that the V-cycle is
  /// a symmetric operator (for mgpcg); otherwise red-black before and after (faster
  /// convergence: the pre- and post-sweeps then do not repeat a colour back to back).
  /// Reuses all storage when the grid shape is unchanged since the last call.
  void setup(const PoissonOperator& op, const PoissonOptions& opt, bool symmetric = false);

  int num_levels() const { return int(levels_.size()); }
  const Level& level(int l) const { return levels_[l]; }
  mg::Stencil stencil(int l) const;
  const mg::Scratch& scratch() const { return scratch_; }
  /// The 9-point coarse levels of coarse_operator = "galerkin" (nullptr otherwise; the
  /// hierarchy then holds the finest level only).
  const GalerkinLevels* galerkin() const { return galerkin_.get(); }
  /// Re-read omp_get_max_threads() (capped by the scratch allocated in setup).
  void update_threads();

  /// One cycle on the finest level for L x = f (finest-level, cell-integrated form: f is
  /// dx^2 * rhs with zero sum); x ghosts must be consistent, and are on return.
  /// With res2: *res2 = ||f - L x||^2 after the cycle (fused into the last smoothing pass
  /// when possible).
  void cycle(View x, CView f, bool f_cycle, double* res2 = nullptr);
  /// z = V-cycle applied to r with zero initial guess (symmetric when pre == post).
  void precondition(CView r, View z);

 private:
  /// One V- or F-cycle from level l down.
  void cycle(int l, View x, CView f, bool f_cycle, double* res2);
  void smooth(int l, View x, CView f, int sweeps, bool post, double* res2);
  /// Pre-smoothing on level l and the restricted residual into level l+1's f (fused).
  void pre_smooth_restrict(int l, View x, CView f);
  /// x += P x_{l+1} and post-smoothing on level l (fused), res2 as in cycle().
  void prolong_post_smooth(int l, View x, CView f, double* res2);
  void coarse_solve(int l, View x, CView f);
  void build_coarse_solver();

  std::vector<Level> levels_;
  std::vector<double, AlignedAllocator<double>> scratch_store_;
  mg::Scratch scratch_;
  bool jacobi_ = false;
  int pre_ = 2, post_ = 2;
  double omega_ = 0.8;
  double rb_omega_ = 1.0;
  bool symmetric_ = false;
  MgCoarseOperator coarse_op_ = MgCoarseOperator::Average;
  MgCoarseOperator built_op_ = MgCoarseOperator::Average;  ///< the operator levels_ was built for
  std::unique_ptr<GalerkinLevels> galerkin_;  ///< coarse levels of "galerkin"
  bool sink_ = false;  ///< the operator has a sink (PoissonOperator::sink with some c > 0)
  int coarse_cells_ = 64;
  std::unique_ptr<CoarseDirect> coarse_;  ///< the coarsest level's exact solve
};

/// Method "multigrid": repeated V- or F-cycles until ||r||/||rhs|| <= tol.
class MultigridSolver final : public PoissonSolver {
 public:
  explicit MultigridSolver(const PoissonOptions& opt);
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
  Field f0_;  ///< dx^2 (rhs - mean)
  bool ready_ = false;
};

namespace detail {
/// Shared solve prologue: checks x/rhs shapes (x needs >= 1 ghost layer), writes
/// f = dx^2 (rhs - mean rhs) into f (f = dx^2 rhs with a sink, s.c), returns ||f||_2.
double prepare_rhs(const PoissonOperator& op, const mg::Stencil& s, const Field& rhs,
                   const Field& x, View f);
/// Shared start of a solve after prepare_rhs: if bnorm = 0 sets x = 0 and a converged
/// `st` and returns false (nothing to solve); else refreshes x's ghosts and returns true.
bool start_solve(const mg::Stencil& s, double bnorm, View x, bool record, SolveStats& st);
/// Shared epilogue: x -= mean(x) (not with a sink, s.c), ghosts refreshed.
void remove_mean(const mg::Stencil& s, View x);
}  // namespace detail

}  // namespace refmap
