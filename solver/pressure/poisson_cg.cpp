// Jacobi-preconditioned CG and multigrid-preconditioned CG; see poisson_cg.hpp.
#include "solver/pressure/poisson_cg.hpp"

#include <cmath>
#include <initializer_list>
#include <stdexcept>

#include "kernels/loop.hpp"

namespace refmap {

namespace {
/// The solver's work vectors, sized for an nx x ny operator (kept when they already are).
void ensure(int nx, int ny, std::initializer_list<Field*> fields) {
  for (Field* f : fields)
    if (f->nx() != nx || f->ny() != ny || f->ng() < 1) f->resize(nx, ny, 1);
}
/// The start of a CG solve: the scaled right-hand side f, the first residual r = f - L x
/// and its relative norm; false when there is nothing to solve (st is then complete).
bool begin(const PoissonOperator& op, const mg::Stencil& s, const Field& rhs, Field& x, Field& f, Field& r,
           bool record, SolveStats& st, double& bnorm, double& rel) {
  bnorm = detail::prepare_rhs(op, s, rhs, x, f.view());
  View xv = x.view();
  if (!detail::start_solve(s, bnorm, xv, record, st)) return false;
  rel = std::sqrt(mg::residual(s, xv, f.cview(), r.view())) / bnorm;
  if (record) st.history.push_back(rel);
  return true;
}

/// The end of a CG solve: the pressure's free constant removed, the counts recorded.
SolveStats finish(const mg::Stencil& s, View xv, SolveStats st, int it, double rel, double tol) {
  detail::remove_mean(s, xv);
  st.iterations = it;
  st.rel_residual = rel;
  st.converged = rel <= tol;
  return st;
}

}  // namespace

// ------------------------------------------------------------------------------------------
CGSolver::CGSolver(const PoissonOptions& opt) : opt_(opt) {}

mg::Stencil CGSolver::stencil() const {
  mg::Stencil s;
  s.nx = op_.grid.nx;
  s.ny = op_.grid.ny;
  s.sides = op_.sides;
  s.tx = tx_.cview();
  s.ty = ty_.cview();
  s.invd = invd_.cview();
  if (sink_) s.c = c_.cview();
  s.threads = threads_;
  return s;
}

void CGSolver::setup(const PoissonOperator& op) {
  validate_poisson_operator(op);
  op_ = op;
  sink_ = build_fine_operator(op, tx_, ty_, invd_, c_);
  const int nx = op.grid.nx, ny = op.grid.ny;
  ensure(nx, ny, {&f_, &r_, &p_, &q_});
  ready_ = true;
}

SolveStats CGSolver::solve(const Field& rhs, Field& x) {
  if (!ready_) throw std::logic_error("cg: solve() before setup()");
  threads_ = loop_threads(op_.grid.cells(), op_.grid.ny);
  const mg::Stencil s = stencil();
  SolveStats st;
  View xv = x.view();
  double bnorm = 0.0, rel = 0.0;
  if (!begin(op_, s, rhs, x, f_, r_, opt_.record_history, st, bnorm, rel)) return st;
  int it = 0;
  if (rel > opt_.tol) {
    double rz = mg::jacobi_precondition(s, r_.cview(), p_.view());  // p = z = D^{-1} r
    mg::fill_ghosts(s, p_.view());
    while (it < opt_.max_iter) {
      const double pq = mg::apply_dot(s, p_.cview(), q_.view());
      if (!(pq < 0.0)) break;  // breakdown (p in the null space) or NaN
      const double alpha = rz / pq;
      double rz_new = 0.0;
      const double rr = mg::cg_update_jacobi(s, alpha, xv, p_.cview(), r_.view(), q_.cview(), rz_new);
      ++it;
      rel = std::sqrt(rr) / bnorm;
      if (!std::isfinite(rel)) break;
      if (rel <= opt_.tol) {
        // the recursively updated residual drifts from the true one over many
        // iterations: confirm with the true residual, restart from it if needed
        mg::fill_ghosts(s, xv);
        rel = std::sqrt(mg::residual(s, xv, f_.cview(), r_.view())) / bnorm;
        if (opt_.record_history) st.history.push_back(rel);
        if (rel <= opt_.tol) break;
        rz = mg::jacobi_precondition(s, r_.cview(), p_.view());
        mg::fill_ghosts(s, p_.view());
        continue;
      }
      if (opt_.record_history) st.history.push_back(rel);
      const double beta = rz_new / rz;
      rz = rz_new;
      mg::cg_direction_jacobi(s, r_.cview(), beta, p_.view());
    }
  }
  return finish(s, xv, st, it, rel, opt_.tol);
}

// ------------------------------------------------------------------------------------------
MGPCGSolver::MGPCGSolver(const PoissonOptions& opt) : opt_(opt) {}

std::string MGPCGSolver::name() const {
  return std::string("mgpcg(V-cycle, ") + to_string(opt_.smoother) + " " + std::to_string(opt_.pre_smooth) + "/" +
         std::to_string(opt_.post_smooth) + ")";
}

void MGPCGSolver::setup(const PoissonOperator& op) {
  mg_.setup(op, opt_, /*symmetric=*/true);
  op_ = op;
  const int nx = op.grid.nx, ny = op.grid.ny;
  ensure(nx, ny, {&f_, &r_, &p_, &q_, &z_});
  ready_ = true;
}

SolveStats MGPCGSolver::solve(const Field& rhs, Field& x) {
  if (!ready_) throw std::logic_error("mgpcg: solve() before setup()");
  mg_.update_threads();
  const mg::Stencil s = mg_.stencil(0);
  SolveStats st;
  View xv = x.view();
  double bnorm = 0.0, rel = 0.0;
  if (!begin(op_, s, rhs, x, f_, r_, opt_.record_history, st, bnorm, rel)) return st;
  int it = 0;
  if (rel > opt_.tol) {
    mg_.precondition(r_.cview(), z_.view());
    double rz = mg::dot(s, r_.cview(), z_.cview());
    mg::cg_direction(s, z_.cview(), 0.0, p_.view());
    while (it < opt_.max_iter) {
      const double pq = mg::apply_dot(s, p_.cview(), q_.view());
      if (!(pq < 0.0)) break;
      const double alpha = rz / pq;
      const double rr = mg::cg_update(s, alpha, xv, p_.cview(), r_.view(), q_.cview());
      ++it;
      rel = std::sqrt(rr) / bnorm;
      if (!std::isfinite(rel)) break;
      if (rel <= opt_.tol) {  // confirm with the true residual (see CGSolver)
        mg::fill_ghosts(s, xv);
        rel = std::sqrt(mg::residual(s, xv, f_.cview(), r_.view())) / bnorm;
        if (opt_.record_history) st.history.push_back(rel);
        if (rel <= opt_.tol) break;
        mg_.precondition(r_.cview(), z_.view());
        rz = mg::dot(s, r_.cview(), z_.cview());
        mg::cg_direction(s, z_.cview(), 0.0, p_.view());
        continue;
      }
      if (opt_.record_history) st.history.push_back(rel);
      mg_.precondition(r_.cview(), z_.view());
      const double rz_new = mg::dot(s, r_.cview(), z_.cview());
      const double beta = rz_new / rz;
      rz = rz_new;
      mg::cg_direction(s, z_.cview(), beta, p_.view());
    }
  }
  return finish(s, xv, st, it, rel, opt_.tol);
}

}  // namespace refmap
