#include "solver/model/implicit_step.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/helmholtz.hpp"
#include "kernels/loop.hpp"
#include "solver/model/boundary.hpp"

namespace refmap {

namespace {

/// The pressure solver's method and options (V-cycle, 2 + 2 red-black sweeps by default)
/// with the velocity solve's own tolerance, time.implicit_tol. Its unknown is the change d
/// over a step, so a relative residual tol leaves an error of about tol |d| per step,
/// far below the O(dt) error of the time discretisation, while the pressure's tolerance
/// sets the divergence of the projected field; the projection after this step removes
/// any divergence d carries. Measured (results/implicit.md, "Semi-implicit stepping"): at
/// 1e-5 the errors of couette_elastic and the shear wave are those of a 1e-10 solve to 4
/// digits with a third to a quarter of the cycles. F-cycles saved no cycles (each dearer:
/// 5.1 vs 5.3 per step on couette_elastic, 4.1 both on soft_disc_cavity at 1e-6), 1 + 1
/// sweeps took more than 2 + 2 (7.6 vs 5.3).
PoissonOptions velocity_solver_options(const Config& cfg) {
  PoissonOptions o = cfg.poisson;
  o.tol = cfg.implicit_tol;
  return o;
}

}  // namespace

ImplicitVelocity::ImplicitVelocity(const Config& cfg)
    : cfg_(cfg), sides_(face_sides(cfg.bc)), tol_(cfg.implicit_tol) {
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny, ng = Grid::ng;
  for (int comp = 0; comp < 2; ++comp)
    for (int s = 0; s < 4; ++s)  // component 0 (u) is normal to the left and right sides
      fixed_[std::size_t(comp)][std::size_t(s)] =
          velocity_prescribed(cfg_.bc[std::size_t(s)], (comp == 0) == (s == Left || s == Right));
  for (int comp = 0; comp < 2; ++comp) {
    bx_[std::size_t(comp)].resize(nx + 1, ny, ng);
    by_[std::size_t(comp)].resize(nx, ny + 1, ng);
    c_[std::size_t(comp)].resize(nx, ny, ng);
    solver_[std::size_t(comp)] = make_poisson_solver(velocity_solver_options(cfg_));
  }
  for (Field* f : {&rhs_, &du_, &dv_, &du2_, &dv2_}) f->resize(nx, ny, ng);
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
  if (held_ && !held_->empty()) hold_cells(comp, g.dx);
  solver_[k]->setup(op);
  // sink-API form: (1/dx^2) sum beta (d_nb - d_P) - c d_P = -f
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) rhs_(i, j) = -f(i, j);
  });
  if (held_)
    for (const auto& c : *held_) rhs_(c[0], c[1]) = 0.0;  // with no faces: d = 0 there
  // initial guess: the last step's change (d = 0 would be u^n itself)
  return solver_[k]->solve(rhs_, d);
}

void ImplicitVelocity::hold_cells(int comp, double dx) {
  const std::size_t k = std::size_t(comp);
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny;
  Field &bx = bx_[k], &by = by_[k], &c = c_[k];
  if (held_mark_.nx() == 0) held_mark_.resize(nx, ny, Grid::ng);
  for (const auto& h : *held_) held_mark_(h[0], h[1]) = 1.0;
  auto& beta = held_beta_[k];
  beta.clear();
  for (const auto& h : *held_) {
    const int i = h[0], j = h[1];
    beta.push_back({bx(i, j), bx(i + 1, j), by(i, j), by(i, j + 1)});
  }
  // Dirichlet d = 0 at the held cell: the flux beta (d_nb - 0) / dx^2 of each face is the
  // neighbour's sink term beta / dx^2; the face leaves the operator. Faces on the domain's
  // sides are left to their conditions (a held cell does not reach them in the scenes).
  const double inv2 = 1.0 / (dx * dx);
  for (const auto& h : *held_) {
    const int i = h[0], j = h[1];
    const int ni[4] = {i - 1, i + 1, i, i}, nj[4] = {j, j, j - 1, j + 1};
    double* face[4] = {&bx(i, j), &bx(i + 1, j), &by(i, j), &by(i, j + 1)};
    for (int f = 0; f < 4; ++f) {
      const int a = ni[f], b = nj[f];
      if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
      if (held_mark_(a, b) == 0.0) c(a, b) += *face[f] * inv2;
      *face[f] = 0.0;
    }
  }
  for (const auto& h : *held_) held_mark_(h[0], h[1]) = 0.0;
}

void ImplicitVelocity::held_rates(int comp, const Field& f, const Field& d, bool solved) {
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny;
  const double inv2 = 1.0 / (cfg_.grid.dx * cfg_.grid.dx);
  held_rate_.resize(held_->size());
  for (std::size_t n = 0; n < held_->size(); ++n) {
    const int i = (*held_)[n][0], j = (*held_)[n][1];
    double r = f(i, j);
    if (solved) {
      const int ni[4] = {i - 1, i + 1, i, i}, nj[4] = {j, j, j - 1, j + 1};
      const auto& beta = held_beta_[std::size_t(comp)][n];
      for (int q = 0; q < 4; ++q) {
        const int a = ni[q], b = nj[q];
        if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
        r += beta[std::size_t(q)] * inv2 * d(a, b);  // d = 0 at a held neighbour
      }
    }
    held_rate_[n][std::size_t(comp)] = r;
  }
}

void ImplicitVelocity::set_tol(double tol) {
  tol_ = tol;
  for (auto& s : solver_) s->set_tol(tol);
}

void ImplicitVelocity::predict_changes(double dt) {
  const Grid& g = cfg_.grid;
  // Initial guesses: the rate d / dt extrapolated linearly in time from the last two steps
  // (their midpoints), times this step's dt. Against the last step's d alone this takes
  // couette_elastic (64 cells per unit) from 8.5 to 5.3 cycles per step at implicit_tol
  // 1e-6 (results/implicit.md, "Semi-implicit stepping"); a poor guess (a sudden change,
  // e.g. at an impact) only costs cycles, the tolerance is the same.
  if (steps_ >= 1) {
    const bool lin = steps_ >= 2;
    const double e = lin ? (dt + dt1_) / (dt1_ + dt2_) : 0.0;
    const double i1 = 1.0 / dt1_, i2 = lin ? 1.0 / dt2_ : 0.0;
    parallel_rows(0, g.ny, g.nx, [&](int j) {
      for (int i = 0; i < g.nx; ++i) {
        const double gu = du_(i, j) * i1, gv = dv_(i, j) * i1;
        const double gu2 = lin ? du2_(i, j) * i2 : gu, gv2 = lin ? dv2_(i, j) * i2 : gv;
        du2_(i, j) = du_(i, j);
        dv2_(i, j) = dv_(i, j);
        du_(i, j) = dt * (gu + e * (gu - gu2));
        dv_(i, j) = dt * (gv + e * (gv - gv2));
      }
    });
  }
  dt2_ = dt1_;
  dt1_ = dt;
  ++steps_;
}

void ImplicitVelocity::apply(Field& u, Field& v, const Field& fx, const Field& fy,
                             const Field& rho, const Field& m, double dt) {
  const Grid& g = cfg_.grid;
  predict_changes(dt);
  // The tolerance is on the velocity vector: a component whose force is below tol times
  // the whole force's norm is within it with d = 0 (v in a shear flow, whose force is
  // round-off: its own relative residual would chase that noise down to the tolerance).
  double nu2 = 0.0, nv2 = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      nu2 += fx(i, j) * fx(i, j);
      nv2 += fy(i, j) * fy(i, j);
    }
  const double lim2 = tol_ * tol_ * (nu2 + nv2);
  auto solve_or_skip = [&](int comp, const Field& f, double n2, Field& d) {
    if (n2 <= lim2) {
      d.fill(0.0);
      SolveStats st;
      st.converged = true;
      return st;
    }
    return solve(comp, f, rho, m, dt, d);
  };
  const SolveStats su = solve_or_skip(0, fx, nu2, du_);
  const SolveStats sv = solve_or_skip(1, fy, nv2, dv_);
  if (held_ && !held_->empty()) {
    for (const auto& c : *held_) du_(c[0], c[1]) = dv_(c[0], c[1]) = 0.0;  // exactly held
    held_rates(0, fx, du_, nu2 > lim2);
    held_rates(1, fy, dv_, nv2 > lim2);
  }
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

void ImplicitVelocity::change_ghosts(Field& d, int comp) const {
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny;
  const auto& fx = fixed_[std::size_t(comp)];
  auto sign = [&](Side s) { return fx[std::size_t(s)] ? -1.0 : 1.0; };
  const bool px = sides_[Left] == FaceKind::Periodic, py = sides_[Bottom] == FaceKind::Periodic;
  for (int j = 0; j < ny; ++j) {
    d(-1, j) = px ? d(nx - 1, j) : sign(Left) * d(0, j);
    d(nx, j) = px ? d(0, j) : sign(Right) * d(nx - 1, j);
  }
  for (int i = -1; i <= nx; ++i) {
    d(i, -1) = py ? d(i, ny - 1) : sign(Bottom) * d(i, 0);
    d(i, ny) = py ? d(i, 0) : sign(Top) * d(i, ny - 1);
  }
}

void ImplicitVelocity::apply_rate(Field& u, Field& v, const Field& fx, const Field& fy,
                                  const Field& rho, const Field& m, const Field& qxx,
                                  const Field& qxy, const Field& qyy, double dt) {
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny, ng = Grid::ng;
  if (cx_.nx() == 0) {
    for (Field* f : {&cx_, &cy_, &dprev_, &kx_[0], &ky_[0], &kx_[1], &ky_[1]}) f->resize(nx, ny, ng);
  }
  predict_changes(dt);
  // compact coefficients per component, ghosts included (m and q carry theirs): u sees
  // 2 (m + q_xx) on x faces and m + q_yy on y faces, v m + q_xx and 2 (m + q_yy)
  for (int j = -1; j <= ny; ++j)
    for (int i = -1; i <= nx; ++i) {
      kx_[0](i, j) = 2.0 * (m(i, j) + qxx(i, j));
      ky_[0](i, j) = m(i, j) + qyy(i, j);
      kx_[1](i, j) = m(i, j) + qxx(i, j);
      ky_[1](i, j) = 2.0 * (m(i, j) + qyy(i, j));
    }
  for (int comp = 0; comp < 2; ++comp) {
    const std::size_t k = std::size_t(comp);
    helmholtz_faces_cells(kx_[k].cview(), ky_[k].cview(), bx_[k].view(), by_[k].view(), nx, ny, sides_);
    helmholtz_sink_cells(rho.cview(), kx_[k].cview(), ky_[k].cview(), c_[k].view(), nx, ny, g.dx, dt,
                         sides_, fixed_[k]);
    PoissonOperator op;
    op.grid = g;
    op.sides = sides_.pressure();
    op.beta_x = &bx_[k];
    op.beta_y = &by_[k];
    op.sink = &c_[k];
    solver_[k]->setup(op);
  }
  double nf2 = 0.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) nf2 += fx(i, j) * fx(i, j) + fy(i, j) * fy(i, j);
  const double lim2 = tol_ * tol_ * nf2;
  // The first sweep leaves the cross terms out (lagged at u*); each further sweep takes them
  // at the previous sweep's solution. Not at the extrapolated initial guess: the cross terms
  // of the guess fed back through the next step's extrapolation and grew (couette_elastic
  // at 64 cells per unit went unstable that way: L-inf 2.8 against 0.009)
  const int sweeps = std::max(1, cfg_.solid_rate_sweeps);
  iterations_ = 0;
  residual_ = 0.0;
  sweep_change_ = 0.0;
  // one component: the cross terms at the latest (du, dv) into the right-hand side, then
  // the compact solve (block Gauss-Seidel: v sees the u just solved)
  auto solve_comp = [&](int comp, const Field& f, Field& d, bool cross) {
    if (cross) {
      change_ghosts(du_, 0);
      change_ghosts(dv_, 1);
      rate_stress_force(du_.cview(), dv_.cview(), qxx.cview(), qxy.cview(), qyy.cview(), cx_.view(),
                        cy_.view(), nx, ny, g.dx, false);
    }
    const Field& c = comp == 0 ? cx_ : cy_;
    double n2 = 0.0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        rhs_(i, j) = -(f(i, j) + (cross ? c(i, j) : 0.0));
        n2 += rhs_(i, j) * rhs_(i, j);
      }
    if (n2 <= lim2) {
      d.fill(0.0);
      return;
    }
    const SolveStats st = solver_[std::size_t(comp)]->solve(rhs_, d);
    iterations_ += st.iterations;
    residual_ = std::max(residual_, st.rel_residual);
  };
  for (int s = 0; s < sweeps; ++s) {
    double dmax = 0.0, cmax = 0.0;
    for (int comp = 0; comp < 2; ++comp) {
      Field& d = comp == 0 ? du_ : dv_;
      if (sweeps > 1) dprev_ = d;
      solve_comp(comp, comp == 0 ? fx : fy, d, s > 0);
      if (sweeps > 1)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i) {
            dmax = std::max(dmax, std::abs(d(i, j)));
            cmax = std::max(cmax, std::abs(d(i, j) - dprev_(i, j)));
          }
    }
    if (s > 0) sweep_change_ = dmax > 0.0 ? cmax / dmax : 0.0;
  }
  total_iterations_ += iterations_;
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      u(i, j) += du_(i, j);
      v(i, j) += dv_(i, j);
    }
  });
}

void ImplicitVelocity::compact_operator(const Field& m, const Field& du, const Field& dv, Field& ou, Field& ov) {
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny, ng = Grid::ng;
  if (opc_.nx() == 0) {
    opx_.resize(nx + 1, ny, ng);
    opy_.resize(nx, ny + 1, ng);
    for (Field* f : {&opc_, &zero_, &dtmp_}) f->resize(nx, ny, ng);
    zero_.fill(0.0);
  }
  for (int comp = 0; comp < 2; ++comp) {
    const double ax = comp == 0 ? 2.0 : 1.0, ay = comp == 0 ? 1.0 : 2.0;
    // the faces and the Dirichlet wall terms of solve(); rho = 0 leaves the sink rho/dt out
    helmholtz_faces(m.cview(), opx_.view(), opy_.view(), nx, ny, ax, ay, sides_);
    helmholtz_sink(zero_.cview(), m.cview(), opc_.view(), nx, ny, g.dx, 1.0, ax, ay, sides_,
                   fixed_[std::size_t(comp)]);
    dtmp_ = comp == 0 ? du : dv;
    helmholtz_ghosts(dtmp_.view(), nx, ny, sides_);
    helmholtz_apply(dtmp_.cview(), opx_.cview(), opy_.cview(), opc_.cview(), (comp == 0 ? ou : ov).view(), nx,
                    ny, g.dx);
  }
}

void ImplicitVelocity::register_state(StateRegistry& reg) {
  reg.add_field("implicit.du", du_);
  reg.add_field("implicit.dv", dv_);
  reg.add_field("implicit.du2", du2_);
  reg.add_field("implicit.dv2", dv2_);
  reg.add_value("implicit.dt1", dt1_);
  reg.add_value("implicit.dt2", dt2_);
  reg.add_count("implicit.steps", steps_);
  reg.add_count("implicit.iterations", iterations_);
  reg.add_value("implicit.residual", residual_);
  reg.add_count("implicit.total_iterations", total_iterations_);
  reg.add_value("implicit.sweep_change", sweep_change_);
}

}  // namespace refmap
