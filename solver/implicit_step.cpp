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
    case BcType::Periodic: return false;
  }
  return false;
}

}  // namespace

ImplicitVelocity::ImplicitVelocity(const Config& cfg) : cfg_(cfg), sides_(face_sides(cfg.bc)) {
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny, ng = Grid::ng;
  for (int comp = 0; comp < 2; ++comp)
    for (int s = 0; s < 4; ++s) fixed_[std::size_t(comp)][std::size_t(s)] = prescribed(cfg_.bc[std::size_t(s)], comp, Side(s));
  bx_.resize(nx + 1, ny, ng);
  by_.resize(nx, ny + 1, ng);
  for (Field* f : {&c_, &rhs_, &r_, &z_, &p_, &q_, &du_, &dv_}) f->resize(nx, ny, ng);
}

SolveStats ImplicitVelocity::solve(int comp, const Field& f, const Field& rho, const Field& m,
                                   double dt, Field& d) {
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny;
  const double dx = g.dx;
  // x faces carry 2 m for u and m for v, y faces the reverse (kernels/helmholtz.hpp)
  const double ax = comp == 0 ? 2.0 : 1.0, ay = comp == 0 ? 1.0 : 2.0;
  helmholtz_faces(m.cview(), bx_.view(), by_.view(), nx, ny, ax, ay, sides_);
  helmholtz_sink(rho.cview(), m.cview(), c_.view(), nx, ny, dx, dt, ax, ay, sides_,
                 fixed_[std::size_t(comp)]);
  // Jacobi-preconditioned conjugate gradients on M d = f, M = -(the sink-API operator),
  // symmetric positive definite (c > 0)
  const double inv2 = 1.0 / (dx * dx);
  SolveStats st;
  auto dot = [&](const Field& a, const Field& b) {
    return parallel_rows_sum(0, ny, nx, [&](int j) {
      double s = 0.0;
      for (int i = 0; i < nx; ++i) s += a(i, j) * b(i, j);
      return s;
    });
  };
  helmholtz_ghosts(d.view(), nx, ny, sides_);
  helmholtz_apply(d.cview(), bx_.cview(), by_.cview(), c_.cview(), q_.view(), nx, ny, dx);
  auto diag = [&](int i, int j) {
    return c_(i, j) + (bx_(i, j) + bx_(i + 1, j) + by_(i, j) + by_(i, j + 1)) * inv2;
  };
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      r_(i, j) = f(i, j) + q_(i, j);  // f - M d
      z_(i, j) = r_(i, j) / diag(i, j);
      p_(i, j) = z_(i, j);
    }
  });
  const double fnorm = std::sqrt(dot(f, f));
  if (fnorm == 0.0) {
    d.fill(0.0);
    st.converged = true;
    return st;
  }
  double rz = dot(r_, z_);
  double rn = std::sqrt(dot(r_, r_)) / fnorm;
  const double tol = cfg_.poisson.tol;
  const int max_iter = std::max(cfg_.poisson.max_iter, 1000);
  while (rn > tol && st.iterations < max_iter) {
    helmholtz_ghosts(p_.view(), nx, ny, sides_);
    helmholtz_apply(p_.cview(), bx_.cview(), by_.cview(), c_.cview(), q_.view(), nx, ny, dx);
    const double pq = -dot(p_, q_);  // p^T M p
    const double alpha = rz / pq;
    parallel_rows(0, ny, nx, [&](int j) {
      for (int i = 0; i < nx; ++i) {
        d(i, j) += alpha * p_(i, j);
        r_(i, j) += alpha * q_(i, j);  // r -= alpha M p
        z_(i, j) = r_(i, j) / diag(i, j);
      }
    });
    const double rz_new = dot(r_, z_);
    const double beta = rz_new / rz;
    rz = rz_new;
    parallel_rows(0, ny, nx, [&](int j) {
      for (int i = 0; i < nx; ++i) p_(i, j) = z_(i, j) + beta * p_(i, j);
    });
    rn = std::sqrt(dot(r_, r_)) / fnorm;
    ++st.iterations;
  }
  st.rel_residual = rn;
  st.converged = rn <= tol;
  return st;
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
