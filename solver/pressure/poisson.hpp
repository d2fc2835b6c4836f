#pragma once
// The pressure-correction Poisson problem of Algorithm 1, step 6 (eq. 5.4):
//
//     (1/dx^2) * sum_faces beta_f (x_nb - x_P) = rhs_P      for every cell P,
//
// with beta = 1/rho on faces. beta_x is an x-face field ((nx+1) x ny, face i is the left
// face of cell i), beta_y a y-face field (nx x (ny+1)). Each side has a FaceKind
// (kernels/boundary_kind.hpp). Walls are homogeneous Neumann: the caller sets beta = 0 on
// wall faces. A periodic direction wraps: face 0 and face n are the same face and carry
// the same beta. Without a sink the problem is singular (constants are the null space):
// solvers project the right-hand side onto zero mean and return the zero-mean solution.
//
// Optional sink c >= 0 (PoissonOperator::sink, cell field):
//
//     (1/dx^2) * sum_faces beta_f (x_nb - x_P) - c_P x_P = rhs_P.
//
// With any c_P > 0 the problem is non-singular: no mean is removed from rhs or x, and the
// multigrid coarsest solve factors -L + diag(c) directly. Uses:
//  * Helmholtz (implicit viscosity): (rho/dt) u - div(mu grad u) = r  <=>  beta = mu,
//    c = rho/dt, rhs = -r;
//  * a Dirichlet side x = 0: make that side a Wall (beta = 0 on its faces) and give the
//    cells next to it c_P = 2 beta_face / dx^2 (the boundary face is half a cell away;
//    second-order accurate, tests/test_poisson_sink.cpp).
// sink == nullptr (or all zeros) runs exactly the arithmetic of the sink-free solvers.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "kernels/boundary_kind.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/io/enum_names.hpp"

namespace refmap {

struct PoissonOperator {
  Grid grid;
  Sides sides;  ///< walls on all four sides by default
  const Field* beta_x = nullptr;  ///< (nx+1) x ny
  const Field* beta_y = nullptr;  ///< nx x (ny+1)
  /// Optional cell sink c >= 0 (nx x ny, may be nullptr): the problem becomes
  ///   (1/dx^2) sum_f beta_f (x_nb - x_P) - c_P x_P = rhs_P.
  /// With any c_P > 0 the problem is non-singular: no mean is removed from rhs or x.
  const Field* sink = nullptr;
};

/// Pressure solver: geometric multigrid, plain CG, or multigrid-preconditioned CG.
enum class PoissonMethod { Multigrid, Cg, Mgpcg };
enum class MgCycle { V, F };
/// Red-black Gauss-Seidel (over-relaxed by rbgs_omega) or weighted Jacobi.
enum class MgSmoother { Rbgs, Jacobi };
/// Multigrid coarse-face coefficients (solver/pressure/poisson_multigrid.hpp): the restriction-
/// weighted mean of the fine beta ("average"), or the fine faces in series normal to the
/// coarse face and the fine strips in parallel ("harmonic": keeps the flux across a density
/// jump), or the Galerkin operator P^T L P with an operator-dependent prolongation
/// ("galerkin": 9-point coarse stencils, solver/pressure/multigrid_galerkin.hpp).
enum class MgCoarseOperator { Average, Harmonic, Galerkin };

// Their names (solver/io/enum_names.hpp: to_string, parse_option); defined in
// solver/pressure/poisson_factory.cpp, so the pressure layer names its options without the scene's.
std::span<const OptionName<PoissonMethod>> option_names(PoissonMethod);
std::span<const OptionName<MgCycle>> option_names(MgCycle);
std::span<const OptionName<MgSmoother>> option_names(MgSmoother);
std::span<const OptionName<MgCoarseOperator>> option_names(MgCoarseOperator);

struct PoissonOptions {
  PoissonMethod method = PoissonMethod::Multigrid;
  MgCycle cycle = MgCycle::V;
  MgSmoother smoother = MgSmoother::Rbgs;
  MgCoarseOperator coarse_operator = MgCoarseOperator::Average;
  int pre_smooth = 2, post_smooth = 2;
  double tol = 1e-10;                ///< relative residual ||r||_2 / ||rhs||_2
  int max_iter = 200;
  int coarse_cells = 64;             ///< stop coarsening at or below this many cells
  double jacobi_omega = 0.8;         ///< weight of the "jacobi" smoother (4/5: optimal for 2-D 5-point)
  double rbgs_omega = 1.25;          ///< over-relaxation of the "rbgs" smoother (1 = plain Gauss-Seidel)
  bool record_history = false;       ///< fill SolveStats::history (allocates; tests/studies only)
};

struct SolveStats {
  int iterations = 0;
  double rel_residual = 0.0;  ///< final ||r||_2 / ||rhs||_2 (0 when rhs = 0)
  bool converged = false;
  std::vector<double> history;  ///< relative residual before the first and after every iteration
                                ///< (only with PoissonOptions::record_history)
};

class PoissonSolver {
 public:
  virtual ~PoissonSolver() = default;
  /// (Re)build whatever depends on the coefficients; call when beta changes.
  virtual void setup(const PoissonOperator& op) = 0;
  /// Solve A x = rhs; x holds the initial guess on entry. Ghosts of x are used freely.
  virtual SolveStats solve(const Field& rhs, Field& x) = 0;
  /// The relative residual the next solves stop at (PoissonOptions::tol until called).
  virtual void set_tol(double tol) = 0;
  virtual double tol() const = 0;
  virtual std::string name() const = 0;
};

/// Factory: throws std::invalid_argument for out-of-range numeric options.
std::unique_ptr<PoissonSolver> make_poisson_solver(const PoissonOptions& opt);

}  // namespace refmap
