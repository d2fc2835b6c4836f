#include "solver/implicit_step.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/helmholtz.hpp"
#include "kernels/loop.hpp"
#include "solver/boundary.hpp"

namespace refmap {

namespace {

/// Is velocity component comp (0 = u, 1 = v) prescribed on side s? The mirror of
/// solver/boundary.cpp: ghost = -inside (+ 2 U) is a value on the face.
bool prescribed(const SideBc& bc, int comp, Side s) {
  const bool normal = (comp == 0) == (s == Left || s == Right);
  switch (bc.type) {
    case BcType::NoSlip:
    case BcType::MovingWall: return true;
    case BcType::FreeSlip: return normal;
    // the inflow profile is held at its value of the step's start for the change d (a
    // ramped profile's change over one step enters at the next step's explicit part)
    case BcType::Inflow: return true;
    case BcType::Outflow:  // zero normal derivative
    case BcType::Periodic: return false;
  }
  return false;
}

}  // namespace

ImplicitVelocity::ImplicitVelocity(const Config& cfg) : cfg_(cfg), sides_(face_sides(cfg.bc)) {
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny, ng = Grid::ng;
  for (int comp = 0; comp < 2; ++comp)
    for (int s = 0; s < 4; ++s) fixed_[std::size_t(comp)][std::size_t(s)] = prescribed(cfg_.bc[std::size_t(s)], comp, Side(s));
  for (int comp = 0; comp < 2; ++comp) {
    bx_[std::size_t(comp)].resize(nx + 1, ny, ng);
    by_[std::size_t(comp)].resize(nx, ny + 1, ng);
    c_[std::size_t(comp)].resize(nx, ny, ng);
    solver_[std::size_t(comp)] = make_poisson_solver(cfg_.poisson);
  }
  for (Field* f : {&rhs_, &du_, &dv_}) f->resize(nx, ny, ng);
}

SolveStats ImplicitVelocity::solve(int comp, const Field& f, const Field& rho, const Field& m,
                                   double dt, Field& d) {
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny;
  const std::size_t k = std::size_t(comp);
  // x faces carry 2 m for u and m for v, y faces the reverse (kernels/helmholtz.hpp)
  const double ax = comp == 0 ? 2.0 : 1.0, ay = comp == 0 ? 1.0 : 2.0;
  helmholtz_faces(m.cview(), bx_[k].view(), by_[k].view(), nx, ny, ax, ay, sides_);
  helmholtz_sink(rho.cview(), m.cview(), c_[k].view(), nx, ny, g.dx, dt, ax, ay, sides_, fixed_[k]);
  PoissonOperator op;
  op.grid = g;
  op.sides = sides_.pressure();  // open sides: their condition is in the faces and sink
  op.beta_x = &bx_[k];
  op.beta_y = &by_[k];
  op.sink = &c_[k];
  solver_[k]->setup(op);
  // sink-API form: (1/dx^2) sum beta (d_nb - d_P) - c d_P = -f
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) rhs_(i, j) = -f(i, j);
  });
  // initial guess: the last step's change (d = 0 would be u^n itself)
  return solver_[k]->solve(rhs_, d);
}

void ImplicitVelocity::apply(Field& u, Field& v, const Field& fx, const Field& fy,
                             const Field& rho, const Field& m, double dt) {
  const Grid& g = cfg_.grid;
  const SolveStats su = solve(0, fx, rho, m, dt, du_);
  const SolveStats sv = solve(1, fy, rho, m, dt, dv_);
  iterations_ = su.iterations + sv.iterations;
  residual_ = std::max(su.rel_residual, sv.rel_residual);
  total_iterations_ += iterations_;
  parallel_rows(0, g.ny, g.nx, [&](int j) {
    for (int i = 0; i < g.nx; ++i) {
      u(i, j) += du_(i, j);
      v(i, j) += dv_(i, j);
    }
  });
}

}  // namespace refmap
