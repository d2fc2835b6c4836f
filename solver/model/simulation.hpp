#pragma once
// One time step over the state: Algorithm 1 of Jain & Mani (fluid steps 4-9 here; the
// solids' steps 1-3 and their stress are the solids' component's, solver/components/solids.hpp,
// called at their fixed places). The run loop, output and diagnostics are in solver/app/run.hpp.
#include <array>
#include <functional>
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include "solver/model/component.hpp"
#include "solver/model/config.hpp"
#include "kernels/boundary_kind.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/pressure/poisson.hpp"
#include "solver/model/rigid_body.hpp"
#include "solver/model/solid.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/io/timers.hpp"

namespace refmap {

class AndersonMixer;
class CheckpointWriter;
class CheckpointReader;
class ControlVolumeForces;
class Contact;
class ImplicitVelocity;
class ImplicitVelocityStep;
class Solids;

class Simulation {
 public:
  explicit Simulation(const Config& cfg);
  ~Simulation();

  /// One time step of size dt (dt <= 0: choose it from the stability limits).
  /// Returns the dt taken.
  double step(double dt = 0.0);

  /// The stability-limited time step of section 4 (advective, viscous, solid shear wave, or
  /// the limit of the component that takes the velocity step: velocity_step_dt), then every
  /// component's max_dt.
  double stable_dt() const;
  /// The flow's own part of the last stable_dt(): its fastest speed (|u| + |v|)max (with
  /// moving walls and inflow) and the step its limits allow before the components' max_dt
  /// (the velocity step's limit included; the contact limit depends on both:
  /// solver/components/contact_component.hpp).
  struct FlowLimit {
    double speed = 0.0, dt = 0.0;
  };
  const FlowLimit& flow_limit() const { return flow_limit_; }

  // state
  const Config& config() const { return cfg_; }
  const Grid& grid() const { return cfg_.grid; }
  double time() const { return t_; }
  long steps() const { return nstep_; }
  const Field& u() const { return u_; }
  const Field& v() const { return v_; }
  const Field& p() const { return p_; }
  const Field& rho() const { return rho_; }
  const Field& uf() const { return uf_; }  ///< x-face normal velocity, (nx+1) x ny
  /// time.elastic_coupling = "verlet": the midpoint face velocities that carried xi in the
  /// last step (empty fields with the other coupling)
  const Field& drift_uf() const { return wf_; }
  const Field& drift_vf() const { return wv_; }
  const Field& vf() const { return vf_; }  ///< y-face normal velocity, nx x (ny+1)
  Field& u_mut() { ke_step_ = -1; return u_; }
  Field& v_mut() { ke_step_ = -1; return v_; }

  // components (solver/model/component.hpp)
  /// Attaches a component: its state joins the checkpoint, its hooks the step, its columns
  /// diagnostics.csv. The scene's own components are added by the constructor.
  void add_component(std::unique_ptr<Component> c);
  const std::vector<std::unique_ptr<Component>>& components() const { return components_; }
  /// The first component of type T (null: none).
  template <class T>
  const T* component() const {
    for (const auto& c : components_)
      if (const T* p = dynamic_cast<const T*>(c.get())) return p;
    return nullptr;
  }
  /// Every array and number that carries information from one step to the next
  /// (solver/io/state_registry.hpp); save_state / load_state iterate it.
  const StateRegistry& state() const { return state_; }
  /// The solids, for components that change them between steps (actuation).
  std::vector<std::unique_ptr<Solid>>& solids_mut();

  /// For the components at StepPoint::FaceAccelerations: the face accelerations G_f
  /// being assembled, the face coefficients beta_f = 1/rho_f and the sides.
  Field& face_accel_x_mut() { return gxf_; }
  Field& face_accel_y_mut() { return gyf_; }
  const Field& face_accel_x() const { return gxf_; }
  const Field& face_accel_y() const { return gyf_; }
  const Field& beta_x() const { return beta_x_; }
  const Field& beta_y() const { return beta_y_; }
  /// For the components at StepPoint::PoissonCoefficients (beta_f before the solver takes
  /// it), ::Predicted (the predicted face velocities) and ::PressureUpdated (p^{n+1}).
  Field& beta_x_mut() { return beta_x_; }
  Field& beta_y_mut() { return beta_y_; }
  Field& uf_mut() { return uf_; }
  Field& vf_mut() { return vf_; }
  Field& p_mut() { return p_; }
  /// For the components at StepPoint::Rates: the rate being formed (rho u per time, cell
  /// field) and the weight that turns it into the momentum it adds over the step.
  View rate_x_mut() { return rate_x_; }
  View rate_y_mut() { return rate_y_; }
  double rate_weight() const { return rate_w_; }
  const Sides& sides() const { return sides_; }
  /// For the component that takes the velocity step (Component::velocity_step): the force
  /// per volume of eq. (5.2) the step applies, viscous plus solid stress (cell fields).
  const Field& step_force_x() const { return fx_; }
  const Field& step_force_y() const { return fy_; }
  /// The cells a component holds through the substeps (Component::held_cells; null: none).
  const std::vector<std::array<int, 3>>* held_cells() const { return held_; }

  /// Cell field by probe/output name: u, v, p, density, speed, vorticity (ghosts filled).
  Field named_field(const std::string& name) const;

  // solids: the solids' component (solver/components/solids.hpp), null without a solid
  const Solids* solid_set() const { return solids_; }
  const std::vector<std::unique_ptr<Solid>>& solids() const;
  double elastic_energy() const;  ///< at the last stress evaluation
  /// Global blended solid stress (conservative form); empty when there are no elastic solids.
  const Field& solid_stress_xx() const;
  const Field& solid_stress_xy() const;
  const Field& solid_stress_yy() const;
  /// Contact model and gap/event tracker of the contact component
  /// (solver/components/contact_component.hpp; null without solids).
  const Contact* contact() const;
  /// Rigid bodies' poses and loads (solver/model/rigid_body.hpp) of the rigid bodies'
  /// component (solver/components/rigid_bodies.hpp); null without a rigid body.
  const RigidBodies* bodies() const { return bodies_; }
  /// Bodies' forces from the fluid's momentum balance (output.body_force = "control_volume";
  /// solver/components/control_volume_forces.hpp), else null.
  const ControlVolumeForces* control_volume_forces() const;
  /// The fluid's force and torque on solid k as the solids.csv columns report it: from the
  /// last component added that measures loads (Component::solid_load), null if none does or
  /// solid k has no load of its own.
  const BodyLoad* solid_load(int k) const;
  /// Total momentum sum rho u dx^2 (x and y).
  std::pair<double, double> momentum() const;

  // diagnostics
  /// sum 0.5 rho |u|^2 dx^2 over cells; computed once per step (the blow-up check and the
  /// diagnostics row both read it)
  double kinetic_energy() const;
  double max_face_divergence() const;  ///< max over cells of |div u_f| (faces' net flux / dx)
  int last_poisson_iterations() const { return last_stats_.iterations; }
  /// The solver of the implicit velocity step's component (time.viscous / time.solid_stress,
  /// solver/components/implicit_velocity_step.hpp; null when explicit).
  const ImplicitVelocity* implicit_velocity() const;
  double last_poisson_residual() const { return last_stats_.rel_residual; }
  const PhaseTimers& timers() const { return timers_; }
  /// The run loop books its output phases here and resets it after the warm-up.
  PhaseTimers& timers() { return timers_; }
  /// Solid::diagnostics of every solid for the current state, computed once per step and
  /// shared by the contact log and the diagnostics.csv row.
  const std::vector<SolidDiagnostics>& solid_diagnostics() const;

  /// Everything step() needs to continue bit for bit (solver/model/checkpoint.cpp): the records
  /// of state() in order. load_state expects a Simulation built from the same scene (and
  /// with the same components added).
  void save_state(CheckpointWriter& w) const;
  void load_state(CheckpointReader& r);

  /// Fill ghost cells of the cell velocity from the boundary conditions at time t.
  void apply_velocity_bc(Field& u, Field& v, double t) const;

  /// Inside step(), for probes that need the split step's intermediate velocities (the
  /// energy budget of bench/energy_budget/energy_budget.cpp, docs/implicit.md): `probe` is
  /// called at StepPoint::Advected and ::Stressed of every step, as a component.
  using Stage = StepPoint;
  void set_stage_probe(std::function<void(Stage, double dt)> probe);
  /// The blended mixture viscosity of the current configuration (eq. 3.6).
  const Field& viscosity() const { return mu_; }

  /// time.solid_picard_iterations (solver/model/solid_picard.cpp): max |u^(N) - u^(N-1)| /
  /// max |u^(N)| of the last step's last iteration (0 without iterations), and the multigrid
  /// cycles of all its solves (pressure and velocity, every iteration).
  double picard_change() const { return picard_change_; }
  long picard_cycles() const { return picard_cycles_; }
  long picard_velocity_cycles() const { return picard_velocity_cycles_; }  ///< of them, the velocity solves'

 private:
  void initialise();
  /// The flow's and the solids' records of state_, then the implicit velocity step's (its
  /// component registers them here, where they were before it was a component); the other
  /// components add theirs when attached.
  void register_state();
  /// The components: contact with solids (solver/components/contact_component.hpp), the
  /// rigid bodies and the implicit velocity step (made before the initial state;
  /// solver/components/rigid_bodies.hpp, implicit_velocity_step.hpp), then the scene's
  /// (Config::components, each made by its kind: solver/model/component_kind.hpp), in the
  /// order of their hooks.
  void add_components();
  /// Calls every component's hook at point p, timed under the component's name (timed =
  /// false: inside a phase that books the time).
  void call_components(StepPoint p, double dt, bool timed = true);
  /// step() without the components' hooks (which step() calls around it).
  double step_state(double dt);
  /// One pass of Algorithm 1 (steps 1-9) from the current state.
  double step_once(double dt);
  /// time.solid_picard_iterations: the step repeated from a snapshot of the state with xi
  /// moved by the blend of u^n and the last pass's u^{n+1} (solver/model/solid_picard.cpp).
  double step_picard(double dt);
  /// fx_, fy_ -= A(eta) of the last pass's velocity change (time.solid_picard_defect).
  void picard_defect_force(double dt);
  /// time.solid_picard_force = "trapezoidal", first step: F(xi^n) of the state into fpx_, fpy_.
  void picard_start_force();
  void build_poisson_coefficients();
  /// The pressure solver's operator of the current beta (open sides as walls, the outflow
  /// sides' Dirichlet condition as the cell sink sink_).
  PoissonOperator poisson_operator();
  // The phases of step(), in order; each books its time under the phase of the same name
  // in the timing table.
  /// flow = "prescribed": only the solids move, in the imposed velocity field.
  double step_prescribed(double dt);
  /// Algorithm 1 steps 1-3: "xi advection", "extrapolation", "level set" of every solid,
  /// then density and viscosity of the mixture.
  void move_solids(double dt);
  /// Step 4, eq. (5.1), "advection": RK-4 advection of the momentum rho u.
  void advect_momentum(double dt);
  /// Eq. (5.2), "viscous" and "solid stress": split forward-Euler step of the stresses, or
  /// the step of the component that takes it (Component::velocity_step: the implicit
  /// velocity step, "implicit velocity").
  void apply_viscous_and_solid_stress(double dt);
  /// "poisson setup": the face coefficients 1/rho of the new density.
  void setup_poisson();
  /// Step 5, eq. (5.3), "face velocities": predicted face velocities and their divergence.
  void face_accelerations(double dt);
  void predict_face_velocities(double dt);
  /// Step 6, eq. (5.4), "poisson": the pressure correction.
  void solve_pressure();
  /// Steps 7-9, eqs. (5.5)-(5.7), "projection": new pressure, face and cell velocities.
  void project(double dt);
  /// time.splitting = "increment" and held cells ([[solid]] forcing_hold), before the
  /// advection: the cell average G_c^n of the face accelerations of the step's start, the
  /// viscous force of u^n, the advection's momentum source and the list of held cells.
  void begin_substeps(double dt);
  /// time.splitting = "increment", after the viscous step: u += dt G_c^n, so the forcing,
  /// the predictor and the projection see the velocity of Algorithm 1's convention.
  void end_substeps(double dt);
  /// Held cells: books dt (the rate of (kx, ky) at the held cells) times `weight` as the
  /// momentum the hold takes from their body, then zeroes the rate there.
  /// StepPoint::Rates for the rate (kx, ky) of weight `weight` (rate_x_mut() ...).
  void call_rates(View kx, View ky, double weight, double dt);
  /// The time the projection corrects the face velocities with: time.rhie_chow_dt, or dt.
  double projection_time(double dt) const;

  /// Algorithm 1 steps 1-2 for every solid (Solids::move, timed as "xi advection",
  /// "extrapolation", "level set"); xi is carried by the face velocities uf_, vf_ or, with
  /// time.elastic_coupling = "verlet", by the midpoint faces wf_, wv_.
  void update_solids(double dt);
  /// time.elastic_coupling = "verlet", before the solids move: the midpoint face velocities
  /// wf_, wv_ of the drift (kernels/verlet.hpp), then the current faces kept for the next step.
  void drift_velocities(double dt);
  /// time.verlet_project_drift: wf_, wv_ = w0 + P c, the drift's stress correction c projected
  /// with the pressure operator (cv, cf: the coefficients of verlet_drift_faces).
  void project_drift(double cv, double cf);
  void blend_material_fields();
  /// Force of the solid stresses (conservative or not) added to fx_, fy_ (Solids::stress_force).
  void solid_force();
  void impose_prescribed_velocity(double t);

  Config cfg_;
  /// The sides as the projection and the pressure solvers see them (built once).
  Sides sides_;
  double t_ = 0.0;
  long nstep_ = 0;

  Field u_, v_, p_, rho_, rho_old_, mu_;   // cell-centred
  Field jump_x_, jump_y_;                  // faces at a density jump (limited momentum flux)
  bool density_contrast_ = false;          // some solid's density differs from the fluid's
  Field uf_, vf_;                          // face-normal velocities (exactly divergence-free)
  Field beta_x_, beta_y_;                  // 1/rho on faces for the Poisson problem
  Field dp_, rhs_;                         // pressure correction and Poisson right-hand side
  Field sink_;                             // outflow sides' Poisson sink (empty without one)
  // RK-4 work arrays (momentum rho u, rho v)
  Field mx_, my_, kx_, ky_, sx_, sy_, fx_, fy_, k2x_, k2y_;
  Field gxf_, gyf_;                        // face accelerations G_f of eqs. (5.3), (5.7)
  /// The solids' component (owned by components_; null without a solid): the solids, their
  /// blended stress, elastic energy and diagnostics (solver/components/solids.hpp).
  Solids* solids_ = nullptr;
  /// What the solids' accessors and records show without a solid (always empty / zero).
  std::vector<std::unique_ptr<Solid>> no_solids_;
  Field no_stress_;
  double no_energy_ = 0.0;
  mutable double ke_cache_ = 0.0;                     ///< kinetic_energy() of step ke_step_
  mutable long ke_step_ = -1;                         ///< (-1: none)
  bool prescribed_depends_on_time_ = false;  ///< flow = "prescribed" with an expression of t
  /// the rigid bodies' component's (solver/components/rigid_bodies.hpp); null unless a solid
  /// is rigid (bodies(), for tests and tools).
  RigidBodies* bodies_ = nullptr;
  bool increment_ = false;                 // time.splitting = "increment"
  const std::vector<std::array<int, 3>>* held_ = nullptr;  // a component's held cells (held_cells)
  View rate_x_, rate_y_;                   // the rate of StepPoint::Rates and its weight
  double rate_w_ = 0.0;
  Field gcx_n_, gcy_n_;                    // increment: G_c^n, the cell average of the face accelerations
  Field vnx_, vny_;                        // increment: viscous force of u^n
  Field srcx_, srcy_;                      // increment: the advection's momentum source vn - rho_old G_c^n
  std::unique_ptr<PoissonSolver> poisson_;
  SolveStats last_stats_;
  /// The component that takes the velocity step of eq. (5.2) (Component::takes_velocity_step;
  /// null: the explicit forward Euler), and the implicit velocity step's component, typed, for
  /// time.solid_picard_iterations (its tolerance, cycles and A(eta); solid_picard.cpp). Both
  /// are owned by components_; null without time.viscous = "implicit" or an implicit
  /// time.solid_stress.
  Component* velocity_step_ = nullptr;
  ImplicitVelocityStep* implicit_ = nullptr;
  // time.solid_picard_iterations (solver/model/solid_picard.cpp)
  bool xi_transport_ = false;            ///< move xi with (uf_adv_, vf_adv_, u_adv_, v_adv_), not uf_, u_
  Field uf_adv_, vf_adv_, u_adv_, v_adv_;
  bool defect_ = false;                  ///< this pass subtracts A(eta) (dprev_u_, dprev_v_) from the force
  Field eta_, dprev_u_, dprev_v_, aeu_, aev_;
  Field uk_, vk_, ufk_, vfk_;            ///< the last pass's end-of-step velocities
  double picard_change_ = 0.0;
  long picard_cycles_ = 0;
  long picard_velocity_cycles_ = 0;
  /// time.solid_picard_anderson: the mixing of the passes and its residual fields
  std::unique_ptr<AndersonMixer> picard_mix_;
  Field picard_ru_, picard_rv_;
  /// time.solid_picard_force = "trapezoidal": the passes kick with (F^n + F^{n+1,(k)}) / 2
  /// through verlet_kick and the fields below (fpx_, fpy_, verlet_steps_ are then state)
  bool picard_trapezoid_ = false;
  mutable FlowLimit flow_limit_;  ///< of the last stable_dt()
  // time.elastic_coupling = "verlet" (kernels/verlet.hpp); empty otherwise (fpx_, fpy_,
  // dfx_, dfy_, vpx_, vpy_ and verlet_steps_ also with picard_trapezoid_)
  bool verlet_ = false;
  Field fpx_, fpy_;        ///< the stress force F^n of the last step's xi (state)
  Field dfx_, dfy_;        ///< F^n - F^{n-1} (state)
  Field ufp_, vfp_;        ///< the face velocities of the last step's start, u_f^{n-1} (state)
  Field wf_, wv_;          ///< the drift's midpoint face velocities (scratch)
  Field cxf_, cyf_, phic_; ///< time.verlet_project_drift: the correction and its potential (scratch)
  Field vpx_, vpy_;        ///< the explicit viscous force before the stress is added (scratch)
  double dt_prev_ = 0.0;   ///< the last step's dt (state)
  long verlet_steps_ = 0;  ///< steps taken with this coupling: 0 = no history yet (state)
  PhaseTimers timers_;
  std::vector<std::unique_ptr<Component>> components_;
  StateRegistry state_;
};

}  // namespace refmap
