#pragma once
// The implicit velocity step as a component (solver/model/component.hpp): time.viscous =
// "implicit" or time.solid_stress = "semi_implicit" / "upper_convected" (docs/implicit.md).
// It owns the solver of solver/model/implicit_step.hpp (ImplicitVelocity) and the
// coefficients it is given each step, and
//  * takes the velocity step of eq. (5.2) in place of the explicit forward Euler
//    (Component::velocity_step, timed by the Simulation as "implicit velocity"): the implicit
//    viscosity m = mu_impl + eta, with time.solid_stress = "upper_convected" also the tensor q, then the
//    Helmholtz solve (with the held cells of forcing_hold fixed);
//  * caps the step with time.solid_implicit_cfl (velocity_step_dt, among the flow's limits;
//    the explicit viscous and shear-wave limits the Simulation leaves out with these keys);
//  * registers the solver's state (records "implicit.*": the warm start's last changes and
//    the solve statistics). The Simulation makes it before the initial state, calls its
//    register_state where the flow's records end (after the solids', before the Verlet
//    coupling's), so checkpoints keep the record order they had before the step was a
//    component, and attaches it after contact and the rigid bodies;
//  * writes diagnostics.csv `implicit_iterations` (the multigrid cycles of the last solve, u
//    and v summed) right after the last built-in column of the flow (total_energy with
//    solids, wall_time without), which is where the column was when it was built in.
// Still in the Simulation: the choice of the explicit limits it lifts (from the config), and
// time.solid_picard_iterations, which sets the solver's tolerance per pass, counts its
// cycles and subtracts A(eta) of the last pass's change (solver/model/solid_picard.cpp, through
// solver() and add_solid_viscosity).
#include <string>
#include <vector>

#include "core/field.hpp"
#include "solver/model/component.hpp"
#include "solver/model/config.hpp"
#include "solver/model/implicit_step.hpp"

namespace refmap {

// The step's own [time] keys (solid_implicit_k ... implicit_tol) are its kind's
// (implicit_velocity_step_kind, implicit_velocity_step.cpp).

class ImplicitVelocityStep : public Component {
 public:
  /// Whether the scene takes the implicit velocity step.
  static bool needed(const Config& cfg) {
    return cfg.viscous_time == ViscousTime::Implicit || cfg.solid_time != SolidStressTime::Explicit;
  }
  explicit ImplicitVelocityStep(const Config& cfg);

  ImplicitVelocity& solver() { return solver_; }
  const ImplicitVelocity& solver() const { return solver_; }

  /// m += eta = k G dt (1 - H) of every elastic solid (time.solid_implicit_k, blended like
  /// the stress, eq. 3.6, reaching time.solid_implicit_reach cells further out); no ghosts.
  /// The semi-implicit part of the implicit viscosity, and the A(eta) of
  /// time.solid_picard_defect (solver/model/solid_picard.cpp): both take it from here.
  void add_solid_viscosity(const Simulation& sim, Field& m, double dt) const;

  // Component
  /// Its hooks' row in the timing table (the empty calls at the timed step points); the
  /// solve itself is timed on its own row, "implicit velocity" (Simulation), one call a step
  const char* name() const override { return "implicit velocity step"; }
  void register_state(StateRegistry& reg) override { solver_.register_state(reg); }
  bool takes_velocity_step() const override { return true; }
  void velocity_step(Simulation& sim, double dt) override;
  double velocity_step_dt(const Simulation& sim) const override;
  std::vector<std::string> columns() const override { return {"implicit_iterations"}; }
  void values(const Simulation&, std::vector<double>& out) const override {
    out.push_back(double(solver_.last_iterations()));
  }
  const char* columns_after() const override { return solids_ ? "total_energy" : "wall_time"; }

 private:
  /// The implicit viscosity into mimp_: mu (time.viscous = "implicit") plus eta
  /// (time.solid_stress = "semi_implicit"), ghosts filled.
  void implicit_viscosity(const Simulation& sim, double dt);
  /// The upper-convected step's tensor q = 2 mu_s dt (1 - H) b (time.solid_stress =
  /// "upper_convected") of every elastic solid into qxx_, qxy_, qyy_, ghosts filled.
  void rate_coefficients(const Simulation& sim, double dt);

  Config cfg_;
  bool solids_;  ///< the scene has solids (where the column goes)
  ImplicitVelocity solver_;
  Field mimp_;                ///< the implicit viscosity m of this step
  Field qxx_, qxy_, qyy_;     ///< upper-convected: the tensor q of this step (kernels/helmholtz.hpp)
};

}  // namespace refmap
