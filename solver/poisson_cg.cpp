// Jacobi-preconditioned CG and multigrid-preconditioned CG; see poisson_cg.hpp.
#include "solver/poisson_cg.hpp"

#include "solver/option_names.hpp"

#include <cmath>
#include <stdexcept>

#include "kernels/loop.hpp"

namespace refmap {

namespace {
void ensure(Field& f, int nx, int ny) {
  if (f.nx() != nx || f.ny() != ny || f.ng() < 1) f.resize(nx, ny, 1);
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
  s.threads = threads_;
  return s;
}

void CGSolver::setup(const PoissonOperator& op) {
  validate_poisson_operator(op);
  op_ = op;
  build_fine_operator(op, tx_, ty_, invd_);
  const int nx = op.grid.nx, ny = op.grid.ny;
  ensure(f_, nx, ny);
  ensure(r_, nx, ny);
  ensure(p_, nx, ny);
  ensure(q_, nx, ny);
  ready_ = true;
}

SolveStats CGSolver::solve(const Field& rhs, Field& x) {
  if (!ready_) throw std::logic_error("cg: solve() before setup()");
  threads_ = loop_threads(op_.grid.cells(), op_.grid.ny);
  const mg::Stencil s = stencil();
  SolveStats st;
  const double bnorm = detail::prepare_rhs(op_, s, rhs, x, f_.view());
  View xv = x.view();
  if (!detail::start_solve(s, bnorm, xv, opt_.record_history, st)) return st;
  double rel = std::sqrt(mg::residual(s, xv, f_.cview(), r_.view())) / bnorm;
  if (opt_.record_history) st.history.push_back(rel);
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
  detail::remove_mean(s, xv);
  st.iterations = it;
  st.rel_residual = rel;
  st.converged = rel <= opt_.tol;
  return st;
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
  ensure(f_, nx, ny);
  ensure(r_, nx, ny);
  ensure(p_, nx, ny);
  ensure(q_, nx, ny);
  ensure(z_, nx, ny);
  ready_ = true;
}

SolveStats MGPCGSolver::solve(const Field& rhs, Field& x) {
  if (!ready_) throw std::logic_error("mgpcg: solve() before setup()");
  mg_.update_threads();
  const mg::Stencil s = mg_.stencil(0);
  SolveStats st;
  const double bnorm = detail::prepare_rhs(op_, s, rhs, x, f_.view());
  View xv = x.view();
  if (!detail::start_solve(s, bnorm, xv, opt_.record_history, st)) return st;
  double rel = std::sqrt(mg::residual(s, xv, f_.cview(), r_.view())) / bnorm;
  if (opt_.record_history) st.history.push_back(rel);
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
  detail::remove_mean(s, xv);
  st.iterations = it;
  st.rel_residual = rel;
  st.converged = rel <= opt_.tol;
  return st;
}

}  // namespace refmap
