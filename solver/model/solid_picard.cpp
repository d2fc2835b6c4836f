// time.solid_picard_iterations (docs/implicit.md, "The implicit step in xi"): a
// fixed-point iteration of the whole step in which the elastic response of the new step is
// implicit where the stress is.
//
// Algorithm 1 moves xi with the velocity of the step's start (eq. 3.3 with u_f^n) and then
// applies the stress of that xi: symplectic Euler, whose elastic step is bounded by the
// shear wave (dt <= P dx sqrt(rho_s / G)); the semi-implicit splitting does not lift that
// bound for a solid in a fluid (the measurements in docs/implicit.md). Here the step is taken
// once as before, then repeated N times from a snapshot of the state at t^n, each repetition
// moving xi with
//     u_xi = (1 - theta) u^n + theta u^{n+1,(k)}          (faces and cells alike)
// where u^{n+1,(k)} is the previous pass's end-of-step velocity (its projected face
// velocities: divergence-free, like u_f^n, so the blend is too). theta = 1/2 is the implicit
// midpoint of the transport (energy-neutral for the linear 1-D oscillator's position update),
// theta = 1 backward Euler. Everything downstream of xi (level set, blend, stress, momentum,
// projection) is recomputed from the new xi, so at convergence the stress of the new step,
// its blend and its band all belong to xi^{n+1}(u^{n+1}).
//
// The solid force of a pass (time.solid_picard_force), with F^(k) = F(xi^{n+1,(k)}):
//  * "new": F^(k) whole. For the 1-D oscillator (x' = v, v' = -omega^2 x, h = dt,
//    w = (omega h)^2) the fixed point x1 = x0 + h ((1 - theta) v0 + theta v1),
//    v1 = v0 - h omega^2 x1 has det = 1 / (1 + theta w): the energy falls by that factor per
//    step, a damping like backward Euler's on the resolved modes (measured in
//    results/implicit_picard.csv).
//  * "trapezoidal": (F^n + F^(k)) / 2, F^n = F(xi^n) the last step's final force (the fields
//    and kick of velocity Verlet, kernels/verlet.hpp; a first step computes it,
//    picard_start_force). The fixed point x1 = x0 + h ((1 - theta) v0 + theta v1),
//    v1 = v0 - h omega^2 (x0 + x1) / 2 has det = (1 + (1 - theta) w / 2) / (1 + theta w / 2):
//    with theta = 1/2 it is the trapezoidal rule (the Cayley transform of the oscillator:
//    |lambda| = 1 and v^2 + omega^2 x^2 kept exactly at every dt, the phase per step
//    2 atan(sqrt(w) / 2) instead of sqrt(w)).
//
// The iteration. Plain repetition of the step (time.solid_picard_defect = false): x^(k)
// depends on v^(k) through h theta, so the factor of the map v^(k) -> v^(k+1) is theta w
// ("new") or theta w / 2 ("trapezoidal"): it converges only below the explicit limit. With
// time.solid_picard_defect each repeated pass is a defect correction through the
// semi-implicit operator instead:
//     (rho/dt - A(m)) d^(k+1) = f(xi^(k)) - A(eta) d^(k),     m = mu_impl + eta,
// eta = k G dt (1 - H): at convergence the eta terms cancel and (rho/dt) d = f, the step
// above with no stabilising term left; the eta multigrid is the preconditioner. For the 1-D
// oscillator, (1 + k w) d^(k+1) = h f^(k) / rho + k w d^(k) with h f^(k) / rho = const - s w d^(k),
// s = theta ("new") or theta / 2 ("trapezoidal", half the force moves with xi^(k)): the
// iteration factor is
//     w (k - s) / (1 + k w),
// zero for k = s (the linearised elastic Jacobian dt s G lap is exactly the stabilising
// operator k G dt lap in the solid's interior: one pass converges), below 1 for every w when
// k >= s / 2, and tending to 1 - s / k as w -> infinity. So the trapezoidal force wants
// k = theta / 2 (1/4 at theta = 1/2; k >= 1/4 is also the stability bound of the first,
// semi-implicit pass, implicit_step.hpp); at k = theta = 1/2, right for "new", its factor tends
// to 1/2 and two passes leave a quarter of the first pass's error. What the band and the
// blend do to it is what the iteration measures (results/implicit_picard.csv).
//
// Each pass costs a whole step (xi advection and extrapolation, a velocity and a pressure
// solve): picard_cycles() counts the multigrid cycles of all of them, picard_velocity_cycles()
// those of the velocity solves. Every pass but the last solves only to time.solid_picard_tol
// (the measurements that set its default: results/implicit.md, "The passes before the last"),
// and time.solid_picard_anderson mixes the passes (picard_anderson.hpp).
#include <algorithm>
#include <cmath>

#include "solver/io/checkpoint_io.hpp"
#include "solver/model/boundary.hpp"
#include "solver/components/implicit_velocity_step.hpp"
#include "solver/components/solids.hpp"
#include "solver/model/implicit_step.hpp"
#include "solver/model/picard_anderson.hpp"
#include "solver/model/simulation.hpp"
#include "solver/model/solid.hpp"

namespace refmap {

namespace {

/// out = (1 - th) a + th b over the whole array (ghosts included).
void blend_into(Field& out, const Field& a, const Field& b, double th) {
  const double* pa = a.raw();
  const double* pb = b.raw();
  double* po = out.raw();
  for (std::size_t n = 0; n < out.raw_size(); ++n) po[n] = (1.0 - th) * pa[n] + th * pb[n];
}

}  // namespace

double Simulation::step_picard(double dt) {
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny, ng = Grid::ng;
  const bool defect = cfg_.solid_picard_defect && implicit_;
  if (uk_.nx() == 0) {
    for (Field* f : {&u_adv_, &v_adv_, &uk_, &vk_}) f->resize(nx, ny, ng);
    for (Field* f : {&uf_adv_, &ufk_}) f->resize(nx + 1, ny, ng);
    for (Field* f : {&vf_adv_, &vfk_}) f->resize(nx, ny + 1, ng);
    if (defect)
      for (Field* f : {&eta_, &dprev_u_, &dprev_v_, &aeu_, &aev_}) f->resize(nx, ny, ng);
  }
  // the state at t^n: every record a step reads (the checkpoint's, so a pass from it is the
  // step from t^n bit for bit; tests/test_solid_picard.cpp checks that)
  if (picard_trapezoid_ && verlet_steps_ == 0) picard_start_force();  // F^n of the first step
  CheckpointWriter snap;
  state_.save(snap);
  // Every pass but the last only gives the velocity u^{n+1,(k)} that moves xi in the next, so
  // its solves stop at time.solid_picard_tol (an inexact fixed-point iteration: the solve's
  // error need only be small against the change between passes, 0.04 .. 0.2 % of max |u| at
  // the median step); the last pass solves to solver.tol and time.implicit_tol.
  const double p_tol = poisson_->tol(), v_tol = implicit_ ? implicit_->solver().tol() : 0.0;
  auto tolerances = [&](bool last) {
    const double loose = cfg_.solid_picard_tol;
    poisson_->set_tol(last ? p_tol : std::max(p_tol, loose));
    if (implicit_) implicit_->solver().set_tol(last ? v_tol : std::max(v_tol, loose));
  };
  tolerances(cfg_.solid_picard == 0);
  // time.solid_picard_anderson: the first pass's input is u^n (xi moved by it alone)
  const bool anderson = cfg_.solid_picard_anderson > 0;
  if (anderson) {
    if (!picard_mix_) picard_mix_ = std::make_unique<AndersonMixer>(cfg_.solid_picard_anderson);
    picard_mix_->reset();
    uk_ = u_;
    vk_ = v_;
    if (picard_ru_.nx() == 0)
      for (Field* f : {&picard_ru_, &picard_rv_}) f->resize(nx, ny, ng);
  }
  step_once(dt);
  long vcycles = implicit_ ? implicit_->solver().last_iterations() : 0;
  long cycles = last_stats_.iterations + vcycles;
  picard_change_ = 0.0;
  const double th = cfg_.solid_picard_theta;
  for (int it = 1; it <= cfg_.solid_picard; ++it) {
    if (anderson) {
      // the next input from the outputs and residuals of the passes so far (picard_anderson.hpp)
      const double* pu = u_.raw();
      const double* pv = v_.raw();
      const double* ku = uk_.raw();
      const double* kv = vk_.raw();
      double* ru = picard_ru_.raw();
      double* rv = picard_rv_.raw();
      for (std::size_t n = 0; n < u_.raw_size(); ++n) {
        ru[n] = pu[n] - ku[n];
        rv[n] = pv[n] - kv[n];
      }
      std::vector<const Field*> g{&u_, &v_, &uf_, &vf_};
      std::vector<Field*> x{&uk_, &vk_, &ufk_, &vfk_};
      if (defect) {
        g.insert(g.end(), {&implicit_->solver().last_change(0), &implicit_->solver().last_change(1)});
        x.insert(x.end(), {&dprev_u_, &dprev_v_});
      }
      picard_mix_->next(g, {&picard_ru_, &picard_rv_}, x);
    } else {
      uk_ = u_;
      vk_ = v_;
      ufk_ = uf_;
      vfk_ = vf_;
      if (defect) {
        dprev_u_ = implicit_->solver().last_change(0);
        dprev_v_ = implicit_->solver().last_change(1);
      }
    }
    CheckpointReader r = CheckpointReader::from_payload(snap.payload(), "the step's snapshot");
    state_.load(r);
    if (solids_) solids_->invalidate_diagnostics();  // caches keyed by the step count (as load_state)
    ke_step_ = -1;
    blend_into(uf_adv_, uf_, ufk_, th);
    blend_into(vf_adv_, vf_, vfk_, th);
    blend_into(u_adv_, u_, uk_, th);
    blend_into(v_adv_, v_, vk_, th);
    xi_transport_ = true;
    defect_ = defect;
    tolerances(it == cfg_.solid_picard);
    step_once(dt);
    xi_transport_ = false;
    defect_ = false;
    const long v = implicit_ ? implicit_->solver().last_iterations() : 0;
    vcycles += v;
    cycles += last_stats_.iterations + v;
    double dmax = 0.0, umax = 0.0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        dmax = std::max({dmax, std::abs(u_(i, j) - uk_(i, j)), std::abs(v_(i, j) - vk_(i, j))});
        umax = std::max({umax, std::abs(u_(i, j)), std::abs(v_(i, j))});
      }
    picard_change_ = umax > 0.0 ? dmax / umax : 0.0;
  }
  picard_cycles_ = cycles;
  picard_velocity_cycles_ = vcycles;
  return dt;
}

void Simulation::picard_start_force() {
  // F(xi^n) of the state as a step's stress computes it (xi, its band and phi are those the
  // last move_solids or the construction left); the step recomputes the stress tensor and the
  // elastic energy of its own xi, the energy is kept for the diagnostics of t^n
  const double e = solids_->elastic_energy();
  fx_.fill(0.0);
  fy_.fill(0.0);
  solid_force();
  fpx_ = fx_;
  fpy_ = fy_;
  solids_->elastic_energy_mut() = e;
}

void Simulation::picard_defect_force(double dt) {
  // eta exactly as the implicit velocity step puts it into its implicit viscosity in this
  // pass (the same add_solid_viscosity; solver/components/implicit_velocity_step.hpp)
  eta_.fill(0.0);
  implicit_->add_solid_viscosity(*this, eta_, dt);
  fill_scalar_ghosts(eta_, cfg_.bc);
  implicit_->solver().compact_operator(eta_, dprev_u_, dprev_v_, aeu_, aev_);
  for (int j = 0; j < cfg_.grid.ny; ++j)
    for (int i = 0; i < cfg_.grid.nx; ++i) {
      fx_(i, j) -= aeu_(i, j);
      fy_(i, j) -= aev_(i, j);
    }
}

}  // namespace refmap
