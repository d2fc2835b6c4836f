#include "solver/model/simulation.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "kernels/advection.hpp"
#include "kernels/loop.hpp"
#include "kernels/projection.hpp"
#include "kernels/rk4.hpp"
#include "kernels/verlet.hpp"
#include "kernels/viscous.hpp"
#include "solver/model/boundary.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/picard_anderson.hpp"
#include "solver/components/contact_component.hpp"
#include "solver/components/control_volume_forces.hpp"
#include "solver/components/implicit_velocity_step.hpp"
#include "solver/components/rigid_bodies.hpp"
#include "solver/components/solids.hpp"
#include "solver/io/expression.hpp"
#include "solver/model/time_step_limits.hpp"

namespace refmap {

Simulation::Simulation(const Config& cfg) : cfg_(cfg), sides_(face_sides(cfg_.bc)) {
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny, ng = Grid::ng;
  for (Field* f : {&u_, &v_, &p_, &rho_, &rho_old_, &mu_, &dp_, &rhs_, &mx_, &my_, &kx_, &ky_,
                   &sx_, &sy_, &fx_, &fy_})
    f->resize(nx, ny, ng);
  for (Field* f : {&uf_, &beta_x_, &gxf_}) f->resize(nx + 1, ny, ng);
  for (Field* f : {&vf_, &beta_y_, &gyf_}) f->resize(nx, ny + 1, ng);
  for (Field* f : {&k2x_, &k2y_}) f->resize(nx, ny, ng);
  if (Solids::needed(cfg_)) {
    // a component made before the initial state (the initial velocity and density are the
    // solids'); its records are registered by register_state(), where they were before it
    // was a component, and add_components puts it first
    auto c = std::make_unique<Solids>(cfg_, sides_);
    solids_ = c.get();
    components_.push_back(std::move(c));
  }
  const bool elastic = solids_ && solids_->elastic();
  density_contrast_ = solids_ && solids_->density_contrast();
  if (density_contrast_ && cfg_.advection == FluxScheme::Central && cfg_.jump_flux == JumpFlux::Superbee) {
    jump_x_.resize(nx + 1, ny, ng);
    jump_y_.resize(nx, ny + 1, ng);
  }
  if (RigidBodies::needed(cfg_)) {
    // a component made before the initial state: the initial projection cuts its faces
    // (add_components registers its state and puts it after contact)
    auto b = std::make_unique<RigidBodiesComponent>(cfg_);
    bodies_ = &b->bodies();
    components_.push_back(std::move(b));
  }
  increment_ = cfg_.splitting == Splitting::Increment;
  if (increment_)
    for (Field* f : {&gcx_n_, &gcy_n_, &vnx_, &vny_, &srcx_, &srcy_}) f->resize(nx, ny, ng);
  poisson_ = make_poisson_solver(cfg_.poisson);
  if (ImplicitVelocityStep::needed(cfg_)) {
    // made before the initial state so that register_state() can put its records where the
    // flow's end, as before it was a component (add_components attaches it after the bodies)
    auto c = std::make_unique<ImplicitVelocityStep>(cfg_);
    implicit_ = c.get();
    components_.push_back(std::move(c));
  }
  verlet_ = elastic && verlet_coupling(cfg_);
  if (verlet_) {
    for (Field* f : {&fpx_, &fpy_, &dfx_, &dfy_, &vpx_, &vpy_}) f->resize(nx, ny, ng);
    for (Field* f : {&ufp_, &wf_}) f->resize(nx + 1, ny, ng);
    for (Field* f : {&vfp_, &wv_}) f->resize(nx, ny + 1, ng);
    if (cfg_.verlet_project_drift) {
      cxf_.resize(nx + 1, ny, ng);
      cyf_.resize(nx, ny + 1, ng);
      phic_.resize(nx, ny, ng);
    }
  }
  // time.solid_picard_force = "trapezoidal" (solver/model/solid_picard.cpp): the kick's fields
  picard_trapezoid_ = elastic && cfg_.solid_picard > 0 && cfg_.solid_picard_force == PicardForce::Trapezoidal;
  if (picard_trapezoid_)
    for (Field* f : {&fpx_, &fpy_, &dfx_, &dfy_, &vpx_, &vpy_}) f->resize(nx, ny, ng);
  initialise();
  register_state();
  add_components();
  // the component that holds cells through the substeps, if any (Component::held_cells),
  // and the one that takes the velocity step (Component::takes_velocity_step)
  for (const auto& c : components_) {
    if (const auto* h = c->held_cells()) {
      if (held_) throw std::invalid_argument("two components hold cells through the substeps");
      held_ = h;
    }
    if (c->takes_velocity_step()) {
      if (velocity_step_) throw std::invalid_argument("two components take the velocity step");
      velocity_step_ = c.get();
    }
  }
  if (held_ && cfg_.solid_time == SolidStressTime::UpperConvected)
    throw std::invalid_argument("solid.forcing_hold is not offered with time.solid_stress = \"upper_convected\"");
}

void Simulation::register_state() {
  // the checkpoint's records, in this order (solver/model/checkpoint.cpp)
  state_.add_value("sim.t", t_);
  state_.add_count("sim.step", nstep_);
  // the solids' blended stress tensor and elastic energy keep their place among the flow's
  // records (empty fields and a zero without a solid)
  const auto stress = solids_ ? solids_->stress_fields() : std::array<Field*, 3>{&no_stress_, &no_stress_, &no_stress_};
  const std::pair<const char*, Field*> fields[] = {
      {"u", &u_},          {"v", &v_},          {"p", &p_},          {"rho", &rho_},      {"rho_old", &rho_old_},
      {"mu", &mu_},        {"uf", &uf_},        {"vf", &vf_},        {"dp", &dp_},        {"gxf", &gxf_},
      {"gyf", &gyf_},      {"sxx", stress[0]},  {"sxy", stress[1]},  {"syy", stress[2]},  {"beta_x", &beta_x_},
      {"beta_y", &beta_y_}};
  for (const auto& [name, f] : fields) state_.add_field(std::string("sim.") + name, *f);
  state_.add_value("sim.elastic_energy", solids_ ? solids_->elastic_energy_mut() : no_energy_);
  state_.add_count("sim.poisson_iterations", last_stats_.iterations);
  state_.add_value("sim.poisson_residual", last_stats_.rel_residual);
  // the solids' component's records (the count, each solid's window and arrays), here (not
  // when attached) so that checkpoints keep their order
  if (solids_) solids_->register_state(state_);
  // the implicit velocity step's initial guesses (warm start) and solve statistics: its
  // component's records, here (not when attached) so that checkpoints keep their order
  if (implicit_) implicit_->register_state(state_);
  if (verlet_) {  // the last step's force and face velocities (time.elastic_coupling = "verlet")
    for (const auto& [name, f] : {std::pair<const char*, Field*>{"fpx", &fpx_}, {"fpy", &fpy_}, {"dfx", &dfx_},
                                  {"dfy", &dfy_}, {"ufp", &ufp_}, {"vfp", &vfp_}})
      state_.add_field(std::string("sim.verlet.") + name, *f);
    state_.add_value("sim.verlet.dt_prev", dt_prev_);
    state_.add_count("sim.verlet.steps", verlet_steps_);
  }
  if (picard_trapezoid_) {  // the last step's solid force F^n (time.solid_picard_force)
    state_.add_field("sim.picard.fpx", fpx_);
    state_.add_field("sim.picard.fpy", fpy_);
    state_.add_count("sim.picard.steps", verlet_steps_);
  }
}

void Simulation::add_components() {
  // the components made before the initial state (the solids, the rigid bodies, then the
  // implicit velocity step): the solids first, the others after contact
  std::vector<std::unique_ptr<Component>> early = std::move(components_);
  components_.clear();
  for (auto& c : early)
    if (c && c.get() == solids_) components_.push_back(std::move(c));  // registered by register_state()
  // contact first whenever there are solids: its hooks come first at each step point (the
  // gaps are observed at the step's end before any other component moves anything; its
  // force is in G_f before the rigid bodies' cut faces) and its time-step limit reads the
  // flow's limit alone (flow_limit)
  if (solids_) add_component(std::make_unique<ContactComponent>(*this));
  for (auto& c : early) {
    if (!c) continue;  // the solids, attached above
    if (c.get() == implicit_) components_.push_back(std::move(c));  // registered by register_state()
    else add_component(std::move(c));
  }
  // the scene's components, each made by its kind (solver/model/component_kind.hpp) in
  // registration order, which is the order of their hooks at one step point
  for (const auto& [kind, options] : cfg_.components)
    if (auto c = component_kind(kind).make(*options, *this)) add_component(std::move(c));
  if (solids_) solids_->invalidate_diagnostics();  // u_mut()/v_mut() may still change the initial state
}

void Simulation::add_component(std::unique_ptr<Component> c) {
  c->register_state(state_);
  components_.push_back(std::move(c));
}

void Simulation::call_components(StepPoint p, double dt, bool timed) {
  if (!timed) {
    for (const auto& c : components_)
      if (c->has_hooks()) c->at(p, *this, dt);
    return;
  }
  for (const auto& c : components_) {
    if (!c->has_hooks()) continue;
    ScopedPhase ph(timers_, c->name());
    c->at(p, *this, dt);
  }
}

namespace {

/// set_stage_probe's function as a component, called at the two points inside the step.
class StageProbe : public Component {
 public:
  explicit StageProbe(std::function<void(StepPoint, double)> f) : f_(std::move(f)) {}
  const char* name() const override { return "stage probe"; }
  void at(StepPoint p, Simulation&, double dt) override {
    if (p == StepPoint::Advected || p == StepPoint::Stressed) f_(p, dt);
  }

 private:
  std::function<void(StepPoint, double)> f_;
};

}  // namespace

void Simulation::set_stage_probe(std::function<void(Stage, double dt)> probe) {
  add_component(std::make_unique<StageProbe>(std::move(probe)));
}

const ControlVolumeForces* Simulation::control_volume_forces() const { return component<ControlVolumeForces>(); }
const ImplicitVelocity* Simulation::implicit_velocity() const { return implicit_ ? &implicit_->solver() : nullptr; }
const BodyLoad* Simulation::solid_load(int k) const {
  for (auto c = components_.rbegin(); c != components_.rend(); ++c) {
    const BodyLoad* load = nullptr;
    if ((*c)->solid_load(k, load)) return load;
  }
  return nullptr;
}
const Contact* Simulation::contact() const {
  const ContactComponent* c = component<ContactComponent>();
  return c ? &c->contact() : nullptr;
}

namespace {

/// The initial (or, for FlowMode::Prescribed, the imposed) velocity at (x, y, t).
struct VelocityFunction {
  const InitialVelocity& in;
  const Grid& g;
  Expression eu, ev;
  double k;
  VelocityFunction(const InitialVelocity& init, const Grid& grid) : in(init), g(grid) {
    if (in.kind == InitialKind::Expression) {
      eu = Expression(in.u_expr);
      ev = Expression(in.v_expr);
    }
    k = in.wavenumber > 0.0 ? in.wavenumber : 2.0 * M_PI / g.lx();
  }
  void operator()(double x, double y, double t, double& u, double& v) const {
    u = v = 0.0;
    if (in.kind == InitialKind::Uniform) {
      u = in.u; v = in.v;
    } else if (in.kind == InitialKind::TaylorGreen) {
      const double X = k * (x - g.x0), Y = k * (y - g.y0);
      u = in.amplitude * std::sin(X) * std::cos(Y);
      v = -in.amplitude * std::cos(X) * std::sin(Y);
    } else if (in.kind == InitialKind::Expression) {
      u = eu.eval(x, y, t);
      v = ev.eval(x, y, t);
    }
  }
};

}  // namespace

void Simulation::impose_prescribed_velocity(double t) {
  const Grid& g = cfg_.grid;
  VelocityFunction vel(cfg_.init, g);
  double a, b;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      vel(g.xc(i), g.yc(j), t, u_(i, j), v_(i, j));
    }
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i) { vel(g.xf(i), g.yc(j), t, a, b); uf_(i, j) = a; }
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) { vel(g.xc(i), g.yf(j), t, a, b); vf_(i, j) = b; }
  apply_velocity_bc(u_, v_, t);
}

void Simulation::blend_material_fields() {
  // eq. (3.6): q = q_f + sum_i (1 - H_i) (q_s,i - q_f) for density and viscosity
  parallel_fill(rho_.raw(), rho_.raw_size(), cfg_.rho_f);
  parallel_fill(mu_.raw(), mu_.raw_size(), cfg_.mu_f);
  if (solids_) solids_->blend(rho_, mu_, cfg_.rho_f, cfg_.mu_f);
  fill_scalar_ghosts(rho_, cfg_.bc);
  fill_scalar_ghosts(mu_, cfg_.bc);
}

void Simulation::update_solids(double dt) {
  // time.solid_picard_iterations: a repeated pass moves xi with the blend of u^n and the
  // last pass's u^{n+1} (solver/model/solid_picard.cpp); time.elastic_coupling = "verlet":
  // with the drift's midpoint faces
  if (!solids_) return;
  if (xi_transport_) solids_->move({uf_adv_, vf_adv_, u_adv_, v_adv_}, dt, components_, timers_);
  else solids_->move({verlet_ ? wf_ : uf_, verlet_ ? wv_ : vf_, u_, v_}, dt, components_, timers_);
}

void Simulation::drift_velocities(double dt) {
  // w = u^n + dt/2 a^n on the faces: a^n from the last step's change of the projected face
  // velocities, its stress part moved from (F^{n-1} + F^n) / 2 to F^n (kernels/verlet.hpp);
  // a first step (no history) drifts with u^n, its F^0 = F(xi^0) taken as 0 (xi = x)
  const Grid& g = cfg_.grid;
  const bool history = verlet_steps_ > 0;
  const double cv = history ? 0.5 * dt / dt_prev_ : 0.0, cf = history ? 0.25 * dt : 0.0;
  if (cfg_.verlet_project_drift && history) {
    project_drift(cv, cf);
  } else {
    verlet_drift_faces(uf_.cview(), vf_.cview(), ufp_.cview(), vfp_.cview(), dfx_.cview(), dfy_.cview(), rho_.cview(),
                       wf_.view(), wv_.view(), g.nx, g.ny, cv, cf, sides_);
  }
  ufp_ = uf_;
  vfp_ = vf_;
  dt_prev_ = dt;
}

void Simulation::project_drift(double cv, double cf) {
  // time.verlet_project_drift: w = w0 + P c, with w0 = u_f + cv (u_f - u_f,prev) (projected
  // fields: divergence-free) and c = cf <(F^n - F^{n-1}) / rho>_f. Unprojected, c carries
  // the gradient part of the stress force's change, which the pressure balances in the kick
  // but which in the drift moves xi with a compressing velocity: the Turek & Hron flag's map
  // compressed by J = 1.17 at t = 10 against 1.09 with w0 alone (results/fsi.md). P is the
  // projection of Algorithm 1 step 8 with the current beta_f (1 / rho^n) and sides: the
  // operator the pressure solver holds since the last step's setup.
  ScopedPhase ph(timers_, "verlet projection");
  const Grid& g = cfg_.grid;
  const double zero = 0.0;
  verlet_drift_faces(uf_.cview(), vf_.cview(), ufp_.cview(), vfp_.cview(), dfx_.cview(), dfy_.cview(), rho_.cview(),
                     wf_.view(), wv_.view(), g.nx, g.ny, cv, zero, sides_);  // w0
  verlet_drift_faces(uf_.cview(), vf_.cview(), ufp_.cview(), vfp_.cview(), dfx_.cview(), dfy_.cview(), rho_.cview(),
                     cxf_.view(), cyf_.view(), g.nx, g.ny, cv, cf, sides_);  // w0 + c
  parallel_rows(0, g.ny, g.nx, [&](int j) {
    for (int i = 0; i <= g.nx; ++i) cxf_(i, j) -= wf_(i, j);
  });
  parallel_rows(0, g.ny + 1, g.nx, [&](int j) {
    for (int i = 0; i < g.nx; ++i) cyf_(i, j) -= wv_(i, j);
  });
  // c is O(dt^2 dF/dt / rho) beside w0: a relative residual of 1e-6 leaves its divergence
  // far below the pressure solve's own
  face_divergence(cxf_.view(), cyf_.view(), rhs_.view(), g.nx, g.ny, g.dx, 1.0);
  phic_.fill(0.0);
  const double tol = poisson_->tol();
  poisson_->set_tol(std::max(tol, 1e-6));
  poisson_->solve(rhs_, phic_);
  poisson_->set_tol(tol);
  fill_scalar_ghosts(phic_, cfg_.bc);
  correct_face_velocity(cxf_.view(), cyf_.view(), phic_.view(), beta_x_.view(), beta_y_.view(), g.nx, g.ny, g.dx, 1.0,
                        sides_);
  parallel_rows(0, g.ny, g.nx, [&](int j) {
    for (int i = 0; i <= g.nx; ++i) wf_(i, j) += cxf_(i, j);
  });
  parallel_rows(0, g.ny + 1, g.nx, [&](int j) {
    for (int i = 0; i < g.nx; ++i) wv_(i, j) += cyf_(i, j);
  });
}

void Simulation::solid_force() {
  if (solids_) solids_->stress_force(fx_, fy_, cfg_);
}

std::pair<double, double> Simulation::momentum() const {
  const Grid& g = cfg_.grid;
  double mx = 0, my = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      mx += rho_(i, j) * u_(i, j);
      my += rho_(i, j) * v_(i, j);
    }
  return {mx * g.dx * g.dx, my * g.dx * g.dx};
}

Simulation::~Simulation() = default;

void Simulation::initialise() {
  const Grid& g = cfg_.grid;
  t_ = cfg_.t_start;
  nstep_ = 0;
  rho_.fill(cfg_.rho_f);
  rho_old_.fill(cfg_.rho_f);
  mu_.fill(cfg_.mu_f);
  p_.fill(0.0);
  dp_.fill(0.0);

  if (cfg_.flow == FlowMode::Prescribed) {
    blend_material_fields();
    impose_prescribed_velocity(t_);
    prescribed_depends_on_time_ =
        cfg_.init.kind == InitialKind::Expression &&
        (Expression(cfg_.init.u_expr).uses_time() || Expression(cfg_.init.v_expr).uses_time());
    return;
  }
  VelocityFunction vel(cfg_.init, g);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) vel(g.xc(i), g.yc(j), t_, u_(i, j), v_(i, j));
  if (solids_) solids_->impose_initial_velocity(u_, v_);
  blend_material_fields();
  rho_old_ = rho_;
  build_poisson_coefficients();

  // Initial projection: make the face velocities exactly divergence-free (and remove the
  // discrete divergence of the initial cell field) without touching the pressure.
  apply_velocity_bc(u_, v_, t_);
  gxf_.fill(0.0);
  gyf_.fill(0.0);
  predict_face_velocity(u_.view(), v_.view(), gxf_.view(), gyf_.view(), uf_.view(), vf_.view(),
                        g.nx, g.ny, 0.0, sides_);
  call_components(StepPoint::Predicted, 0.0, false);  // the rigid bodies' cut faces
  face_divergence(uf_.view(), vf_.view(), rhs_.view(), g.nx, g.ny, g.dx, 1.0);
  dp_.fill(0.0);
  last_stats_ = poisson_->solve(rhs_, dp_);
  fill_scalar_ghosts(dp_, cfg_.bc);
  correct_face_velocity(uf_.view(), vf_.view(), dp_.view(), beta_x_.view(), beta_y_.view(), g.nx,
                        g.ny, g.dx, 1.0, sides_);
  face_accel(dp_.view(), beta_x_.view(), beta_y_.view(), gxf_.view(), gyf_.view(), g.nx, g.ny,
             g.dx, 0.0, 0.0, cfg_.rho_f, sides_);
  // only the components made before the initial state are attached (the rigid bodies' cut faces)
  call_components(StepPoint::FaceAccelerations, 0.0, false);
  correct_cell_velocity(u_.view(), v_.view(), gxf_.view(), gyf_.view(), g.nx, g.ny, 1.0);
  apply_velocity_bc(u_, v_, t_);
  dp_.fill(0.0);
}

void Simulation::apply_velocity_bc(Field& u, Field& v, double t) const {
  fill_vector_ghosts(u, v, cfg_.bc, cfg_.grid, t);
}

void Simulation::build_poisson_coefficients() {
  const Grid& g = cfg_.grid;
  face_beta(rho_.view(), beta_x_.view(), beta_y_.view(), g.nx, g.ny, sides_);
  // forcing = "sharp": no pressure coupling across the faces of a body's inside cells
  call_components(StepPoint::PoissonCoefficients, 0.0, false);
  poisson_->setup(poisson_operator());
}

PoissonOperator Simulation::poisson_operator() {
  PoissonOperator op;
  op.grid = cfg_.grid;
  op.sides = sides_.pressure();
  op.beta_x = &beta_x_;
  op.beta_y = &beta_y_;
  // an outflow side fixes the pressure's constant: the problem is no longer singular
  if (outflow_sink(beta_x_, beta_y_, sides_, cfg_.grid, sink_)) op.sink = &sink_;
  return op;
}

double Simulation::stable_dt() const {
  const Grid& g = cfg_.grid;
  // advective: dt (|u| + |v|)_max / dx <= cfl (section 4; RK-4 with central fluxes is stable
  // to a Courant number of 2.8 on the imaginary axis, the scene's cfl keeps a margin)
  double umax = parallel_rows_max(0, g.ny, g.nx, [&](int j) {
    double m = 0.0;
    for (int i = 0; i < g.nx; ++i) m = std::max(m, std::abs(u_(i, j)) + std::abs(v_(i, j)));
    return m;
  });
  for (const SideBc& s : cfg_.bc)
    if (s.type == BcType::MovingWall) umax = std::max(umax, std::abs(s.velocity));
  umax = std::max(umax, max_inflow_speed(cfg_.bc, g, t_));
  double dt = cfg_.dt_max;
  // gravity acts on rho - rho_f (Algorithm 1 step 5): a solid accelerates by at most
  // |g| |rho_s - rho_f| / rho_s (a light one rises faster than |g|), the fluid by none;
  // |g| itself is kept as a floor
  const double gmag = std::hypot(cfg_.gx, cfg_.gy);
  const double accel = solids_ && gmag > 0.0 ? solids_->gravity_acceleration(gmag) : gmag;
  if (accel > 0.0) {
    // with gravity, the speed at the step's end, umax + a dt, in the Courant number:
    // dt (umax + a dt) <= cfl dx, so a step from rest is bounded too (cfl dx / umax is
    // infinite there; the contact spring's limit used to cover that: the contact component's max_dt)
    const double c = cfg_.cfl * g.dx;
    dt = std::min(dt, 2.0 * c / (umax + std::sqrt(umax * umax + 4.0 * accel * c)));
  } else if (umax > 0.0) {
    dt = std::min(dt, cfg_.cfl * g.dx / umax);
  }
  // viscous: forward Euler is stable for dt <= rho dx^2 / (6 mu) (solver/model/time_step_limits.hpp)
  double nu_max = parallel_rows_max(0, g.ny, g.nx, [&](int j) {
    double m = 0.0;
    for (int i = 0; i < g.nx; ++i) m = std::max(m, mu_(i, j) / rho_(i, j));
    return m;
  });
  // (no viscous limit with the implicit viscous step, no shear-wave limit with the
  // semi-implicit solid stress: solver/model/implicit_step.hpp)
  if (nu_max > 0.0 && cfg_.viscous_time == ViscousTime::Explicit)
    dt = std::min(dt, viscous_dt_limit(cfg_.visc_safety, g.dx, nu_max));
  if (cfg_.solid_time == SolidStressTime::Explicit && solids_) dt = std::min(dt, solids_->explicit_dt());
  // the velocity step's own limit in their place (the implicit stress's cap
  // time.solid_implicit_cfl: solver/components/implicit_velocity_step.hpp), part of the flow's
  if (velocity_step_) dt = std::min(dt, velocity_step_->velocity_step_dt(*this));
  // the components' limits (the contact spring's: solver/components/contact_component.hpp)
  flow_limit_ = {umax, dt};
  for (const auto& c : components_) dt = std::min(dt, c->max_dt(*this));
  return dt;
}

double Simulation::step(double dt) {
  if (dt <= 0.0) dt = cfg_.dt_fixed > 0.0 ? cfg_.dt_fixed : stable_dt();
  call_components(StepPoint::Begin, dt);
  dt = step_state(dt);
  call_components(StepPoint::End, dt);
  return dt;
}

double Simulation::step_state(double dt) {
  if (dt <= 0.0) dt = cfg_.dt_fixed > 0.0 ? cfg_.dt_fixed : stable_dt();
  if (cfg_.flow == FlowMode::Prescribed) return step_prescribed(dt);
  if (cfg_.solid_picard > 0 && solids_) return step_picard(dt);
  return step_once(dt);
}

double Simulation::step_once(double dt) {
  if (solids_) {
    rho_old_ = rho_;
    if (verlet_) drift_velocities(dt);   // time.elastic_coupling = "verlet"
    move_solids(dt);                     // steps 1-3
  }
  advect_momentum(dt);                   // step 4
  call_components(StepPoint::Advected, dt);
  apply_viscous_and_solid_stress(dt);
  if (increment_) end_substeps(dt);      // time.splitting = "increment": u += dt G_c^n
  call_components(StepPoint::Stressed, dt);
  if (solids_) setup_poisson();
  call_components(StepPoint::Forces, dt);  // face forces of the new configuration (contact)
  face_accelerations(dt);                // step 5's G_f, eq. (5.3)
  call_components(StepPoint::BeforePredictor, dt);  // rigid bodies' forcing ("bodies")
  predict_face_velocities(dt);           // step 5
  solve_pressure();                      // step 6
  project(dt);                           // steps 7-9
  t_ += dt;
  ++nstep_;
  return dt;
}

double Simulation::step_prescribed(double dt) {
  // kinematics only: move the solids in the imposed flow
  move_solids(dt);
  t_ += dt;
  ++nstep_;
  if (prescribed_depends_on_time_) {
    ScopedPhase ph(timers_, "prescribed flow");
    impose_prescribed_velocity(t_);
  }
  return dt;
}

void Simulation::move_solids(double dt) {
  // Algorithm 1, steps 1-3: advect and extrapolate xi, rebuild phi, new rho and mu
  update_solids(dt);
  blend_material_fields();
}

void Simulation::advect_momentum(double dt) {
  // step 4, eq. (5.1): momentum rho*u advected by the divergence-free face velocities of
  // the previous step, RK-4 in time (the face velocities are frozen over the stages)
  ScopedPhase ph(timers_, "advection");
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny;
  const FluxScheme scheme = cfg_.advection;
  const double t = t_;
  if (increment_ || held_) begin_substeps(dt);
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      mx_(i, j) = rho_old_(i, j) * u_(i, j);
      my_(i, j) = rho_old_(i, j) * v_(i, j);
    }
  });
  // at a density jump the central flux of rho*u is not damped: it feeds the heavy side's
  // momentum into light cells (divided by their small rho^{n+1}) and the energy grows until
  // the run blows up (ratio 100, docs/density_ratio.md); those faces take Superbee values
  const bool hybrid = jump_x_.nx() > 0;
  if (hybrid)
    flag_density_jump_faces(rho_old_.cview(), rho_.cview(), jump_x_.view(), jump_y_.view(), nx, ny);
  // kernels/rk4.hpp: (mx_, my_) holds q^n and receives q^{n+1}; stage states in (sx_, sy_)
  Rk4Fields f;
  f.q0x = mx_.cview();
  f.q0y = my_.cview();
  f.sx = sx_.view();
  f.sy = sy_.view();
  f.accx = kx_.view();
  f.accy = ky_.view();
  f.kx = k2x_.view();
  f.ky = k2y_.view();
  f.outx = mx_.view();
  f.outy = my_.view();
  f.ni = nx;
  f.nj = ny;
  rk4_step(f, dt, [&](int stage, View kx, View ky) {
    Field& qx = stage == 1 ? mx_ : sx_;
    Field& qy = stage == 1 ? my_ : sy_;
    fill_vector_ghosts(qx, qy, cfg_.bc, g, t, cfg_.rho_f);
    if (hybrid)
      advect_rhs2_hybrid(qx.view(), qy.view(), uf_.view(), vf_.view(), jump_x_.cview(), jump_y_.cview(), kx,
                         ky, nx, ny, g.dx);
    else
      advect_rhs2(qx.view(), qy.view(), uf_.view(), vf_.view(), kx, ky, nx, ny, g.dx, scheme);
    if (increment_)  // the last pressure gradient and viscous force, held over the stages
      parallel_rows(0, ny, nx, [&](int j) {
        for (int i = 0; i < nx; ++i) {
          kx(i, j) += srcx_(i, j);
          ky(i, j) += srcy_(i, j);
        }
      });
    // held cells: their rate is the momentum the hold takes (RK-4 weights 1, 2, 2, 1 over 6)
    if (held_) call_rates(kx, ky, dt * (stage == 1 || stage == 4 ? 1.0 : 2.0) / 6.0, dt);
  });
  // u* = (rho u)* / rho^{n+1}
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      u_(i, j) = mx_(i, j) / rho_(i, j);
      v_(i, j) = my_(i, j) / rho_(i, j);
    }
  });
}

void Simulation::apply_viscous_and_solid_stress(double dt) {
  // eq. (5.2): split viscous step, forward Euler, divergence of the (blended) stress
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny;
  const bool viscous = cfg_.mu_f > 0.0 || (solids_ && solids_->viscous());
  const bool elastic = solids_ && solids_->elastic();
  if (viscous || elastic) {
    ScopedPhase ph(timers_, "viscous");
    apply_velocity_bc(u_, v_, t_ + dt);
    if (viscous && increment_ && !velocity_step_) {
      fx_.fill(0.0);  // time.splitting = "increment": the advection carried it (of u^n)
      fy_.fill(0.0);
    } else if (viscous) {
      viscous_force(u_.view(), v_.view(), mu_.view(), fx_.view(), fy_.view(), nx, ny, g.dx);
      if (increment_)  // only the change of the viscous force since u^n (the advection carried that)
        parallel_rows(0, ny, nx, [&](int j) {
          for (int i = 0; i < nx; ++i) {
            fx_(i, j) -= vnx_(i, j);
            fy_(i, j) -= vny_(i, j);
          }
        });
    } else {
      fx_.fill(0.0);
      fy_.fill(0.0);
    }
  }
  if (elastic) {
    ScopedPhase ph(timers_, "solid stress");
    const bool mean_force = verlet_ || picard_trapezoid_;  // time.solid_picard_force = "trapezoidal" too
    if (mean_force) {
      vpx_ = fx_;
      vpy_ = fy_;
    }
    solid_force();
    if (mean_force) {  // fx_ = viscous + (F^n + F^{n+1}) / 2 (kernels/verlet.hpp)
      verlet_kick(fx_.view(), fy_.view(), vpx_.cview(), vpy_.cview(), fpx_.view(), fpy_.view(), dfx_.view(),
                  dfy_.view(), nx, ny);
      ++verlet_steps_;
    }
  }
  if ((viscous || elastic) && velocity_step_) {
    // a component's step in place of forward Euler (the implicit velocity step,
    // solver/components/implicit_velocity_step.hpp), timed on a row of its own, one call a
    // step (the component's hooks at the timed points are booked under its name)
    ScopedPhase ph(timers_, "implicit velocity");
    // time.solid_picard_defect (semi_implicit only): fx_, fy_ -= A(eta) of the last pass's
    // change (solver/model/solid_picard.cpp); it reads none of what the step sets up
    if (defect_) picard_defect_force(dt);
    velocity_step_->velocity_step(*this, dt);
    // the held cells' rates (held cells are refused with the upper-convected stress)
    if (held_) call_components(StepPoint::HeldSolved, dt, false);
  } else if (viscous || elastic) {
    if (held_) call_rates(fx_.view(), fy_.view(), dt, dt);
    apply_force(u_.view(), v_.view(), fx_.view(), fy_.view(), rho_.view(), dt, nx, ny);
  }
}

void Simulation::begin_substeps(double dt) {
  const Grid& g = cfg_.grid;
  const int nx = g.nx, ny = g.ny;
  call_components(StepPoint::Substeps, dt, false);  // the held cells (forcing_hold)
  if (!increment_) return;
  // G_f^n: the face accelerations of p^n (pressure, gravity, contact), as eq. (5.7) applied
  // them at the end of the last step; the cell average as correct_cell_velocity takes it
  fill_scalar_ghosts(p_, cfg_.bc);
  face_accel(p_.view(), beta_x_.view(), beta_y_.view(), gxf_.view(), gyf_.view(), nx, ny, g.dx, cfg_.gx,
             cfg_.gy, cfg_.rho_f, sides_);
  call_components(StepPoint::FaceAccelerations, dt, false);  // contact, the bodies' cut faces
  const bool viscous = cfg_.mu_f > 0.0 || (solids_ && solids_->viscous());
  if (viscous) {
    apply_velocity_bc(u_, v_, t_);
    viscous_force(u_.view(), v_.view(), mu_.view(), vnx_.view(), vny_.view(), nx, ny, g.dx);
  } else {
    vnx_.fill(0.0);
    vny_.fill(0.0);
  }
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      gcx_n_(i, j) = 0.5 * (gxf_(i, j) + gxf_(i + 1, j));
      gcy_n_(i, j) = 0.5 * (gyf_(i, j) + gyf_(i, j + 1));
      srcx_(i, j) = vnx_(i, j) - rho_old_(i, j) * gcx_n_(i, j);
      srcy_(i, j) = vny_(i, j) - rho_old_(i, j) * gcy_n_(i, j);
    }
  });
}

void Simulation::end_substeps(double dt) {
  const Grid& g = cfg_.grid;
  parallel_rows(0, g.ny, g.nx, [&](int j) {
    for (int i = 0; i < g.nx; ++i) {
      u_(i, j) += dt * gcx_n_(i, j);
      v_(i, j) += dt * gcy_n_(i, j);
    }
  });
}

void Simulation::call_rates(View kx, View ky, double weight, double dt) {
  rate_x_ = kx;
  rate_y_ = ky;
  rate_w_ = weight;
  call_components(StepPoint::Rates, dt, false);
}

void Simulation::setup_poisson() {
  ScopedPhase ph(timers_, "poisson setup");
  build_poisson_coefficients();
}

void Simulation::face_accelerations(double dt) {
  // eq. (5.3)'s G_f: old pressure gradient, gravity and contact force on the faces; read by
  // the bodies' forcing and the predictor. Booked with the predictor's phase (no call of
  // its own, so the phase still counts one call per step)
  const auto t0 = PhaseTimers::clock::now();
  const Grid& g = cfg_.grid;
  fill_scalar_ghosts(p_, cfg_.bc);
  face_accel(p_.view(), beta_x_.view(), beta_y_.view(), gxf_.view(), gyf_.view(), g.nx, g.ny,
             g.dx, cfg_.gx, cfg_.gy, cfg_.rho_f, sides_);
  // contact; forcing = "sharp": the bodies' G_f of the cut faces (where face_accel left -g)
  call_components(StepPoint::FaceAccelerations, dt, false);
  timers_.add("face velocities", std::chrono::duration<double>(PhaseTimers::clock::now() - t0).count(), 0);
}

void Simulation::predict_face_velocities(double dt) {
  ScopedPhase ph(timers_, "face velocities");
  const Grid& g = cfg_.grid;
  apply_velocity_bc(u_, v_, t_ + dt);
  // step 5, eq. (5.3): Rhie-Chow-like face velocity with the old pressure and the body force
  // (G_f from face_accelerations)
  predict_face_velocity(u_.view(), v_.view(), gxf_.view(), gyf_.view(), uf_.view(), vf_.view(),
                        g.nx, g.ny, dt, sides_);
  const double tau = projection_time(dt);
  if (tau != dt) {
    // time.rhie_chow_dt: u_f* += (dt - tau) (G_f - <G_c>_f) on the interior faces, so that
    // after the projection by tau grad dp a steady state's faces carry <u> + tau (<G_c> - G_f)
    const double c = dt - tau;
    parallel_rows(0, g.ny, g.nx, [&](int j) {
      for (int i = 1; i < g.nx; ++i)
        uf_(i, j) += c * (0.5 * gxf_(i, j) - 0.25 * (gxf_(i - 1, j) + gxf_(i + 1, j)));
    });
    parallel_rows(1, g.ny, g.nx, [&](int j) {
      for (int i = 0; i < g.nx; ++i)
        vf_(i, j) += c * (0.5 * gyf_(i, j) - 0.25 * (gyf_(i, j - 1) + gyf_(i, j + 1)));
    });
  }
  // forcing = "sharp": the cut faces carry the body's velocity (beta = 0 there: the
  // projection keeps it, whatever dt)
  call_components(StepPoint::Predicted, dt, false);
  face_divergence(uf_.view(), vf_.view(), rhs_.view(), g.nx, g.ny, g.dx, 1.0 / tau);
}

double Simulation::projection_time(double dt) const {
  return cfg_.rhie_chow_dt > 0.0 ? cfg_.rhie_chow_dt : dt;
}

void Simulation::solve_pressure() {
  // step 6, eq. (5.4); dp from the previous step is the initial guess
  ScopedPhase ph(timers_, "poisson");
  last_stats_ = poisson_->solve(rhs_, dp_);
}

void Simulation::project(double dt) {
  ScopedPhase ph(timers_, "projection");
  const Grid& g = cfg_.grid;
  fill_scalar_ghosts(dp_, cfg_.bc);
  // step 7, eq. (5.5)
  parallel_rows(0, g.ny, g.nx, [&](int j) {
    for (int i = 0; i < g.nx; ++i) p_(i, j) += dp_(i, j);
  });
  call_components(StepPoint::PressureUpdated, dt, false);  // the bodies' cut cells: the fluid's pressure
  fill_scalar_ghosts(p_, cfg_.bc);
  // step 8, eq. (5.6): exactly divergence-free face velocities
  correct_face_velocity(uf_.view(), vf_.view(), dp_.view(), beta_x_.view(), beta_y_.view(),
                        g.nx, g.ny, g.dx, projection_time(dt), sides_);
  // step 9, eq. (5.7): cell velocities with the new pressure
  face_accel(p_.view(), beta_x_.view(), beta_y_.view(), gxf_.view(), gyf_.view(), g.nx, g.ny,
             g.dx, cfg_.gx, cfg_.gy, cfg_.rho_f, sides_);
  call_components(StepPoint::FaceAccelerations, dt, false);  // contact, the bodies' cut faces
  correct_cell_velocity(u_.view(), v_.view(), gxf_.view(), gyf_.view(), g.nx, g.ny, dt);
  apply_velocity_bc(u_, v_, t_ + dt);
}

Field Simulation::named_field(const std::string& name) const {
  const Grid& g = cfg_.grid;
  Field out(g.nx, g.ny, Grid::ng);
  if (name == "u") out = u_;
  else if (name == "v") out = v_;
  else if (name == "p") out = p_;
  else if (name == "density") out = rho_;
  else if (name == "speed") {
    for (int j = -Grid::ng; j < g.ny + Grid::ng; ++j)
      for (int i = -Grid::ng; i < g.nx + Grid::ng; ++i) out(i, j) = std::hypot(u_(i, j), v_(i, j));
    return out;
  } else if (name == "vorticity") {
    const double s = 0.5 / g.dx;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        out(i, j) = s * (v_(i + 1, j) - v_(i - 1, j) - u_(i, j + 1) + u_(i, j - 1));
    // ghosts: linear extrapolation (vorticity has no boundary condition of its own)
    for (int j = 0; j < g.ny; ++j)
      for (int gI = 1; gI <= Grid::ng; ++gI) {
        out(-gI, j) = 2.0 * out(-gI + 1, j) - out(-gI + 2, j);
        out(g.nx - 1 + gI, j) = 2.0 * out(g.nx - 2 + gI, j) - out(g.nx - 3 + gI, j);
      }
    for (int gJ = 1; gJ <= Grid::ng; ++gJ)
      for (int i = -Grid::ng; i < g.nx + Grid::ng; ++i) {
        out(i, -gJ) = 2.0 * out(i, -gJ + 1) - out(i, -gJ + 2);
        out(i, g.ny - 1 + gJ) = 2.0 * out(i, g.ny - 2 + gJ) - out(i, g.ny - 3 + gJ);
      }
    return out;
  } else {
    throw std::invalid_argument("unknown field '" + name + "'");
  }
  return out;
}

double Simulation::kinetic_energy() const {
  // keyed by the step count like solid_diagnostics(): the state changes only in step(),
  // load_state() and through u_mut()/v_mut(), which all reset the key
  if (ke_step_ == nstep_) return ke_cache_;
  const Grid& g = cfg_.grid;
  ke_cache_ = g.dx * g.dx * parallel_rows_sum(0, g.ny, g.nx, [&](int j) {
    double s = 0.0;
    for (int i = 0; i < g.nx; ++i)
      s += 0.5 * rho_(i, j) * (u_(i, j) * u_(i, j) + v_(i, j) * v_(i, j));
    return s;
  });
  ke_step_ = nstep_;
  return ke_cache_;
}

double Simulation::max_face_divergence() const {
  const Grid& g = cfg_.grid;
  return max_abs_face_divergence(uf_.view(), vf_.view(), g.nx, g.ny, g.dx);
}

const std::vector<SolidDiagnostics>& Simulation::solid_diagnostics() const {
  // keyed by the step count: the state changes only in step() (and through u_mut()/v_mut()
  // before the first step, which add_components' invalidation covers)
  static const std::vector<SolidDiagnostics> none;
  return solids_ ? solids_->diagnostics(u_, v_, nstep_) : none;
}

std::vector<std::unique_ptr<Solid>>& Simulation::solids_mut() {
  if (!solids_) return no_solids_;
  solids_->invalidate_diagnostics();
  return solids_->list();
}
const std::vector<std::unique_ptr<Solid>>& Simulation::solids() const { return solids_ ? solids_->list() : no_solids_; }
double Simulation::elastic_energy() const { return solids_ ? solids_->elastic_energy() : 0.0; }
const Field& Simulation::solid_stress_xx() const { return solids_ ? solids_->stress_xx() : no_stress_; }
const Field& Simulation::solid_stress_xy() const { return solids_ ? solids_->stress_xy() : no_stress_; }
const Field& Simulation::solid_stress_yy() const { return solids_ ? solids_->stress_yy() : no_stress_; }

}  // namespace refmap
