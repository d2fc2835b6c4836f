#pragma once
// The time loop: Algorithm 1 of Jain & Mani (fluid steps 4-9 here; solids add steps 1-3).
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include "solver/config.hpp"
#include "solver/contact.hpp"
#include "solver/field.hpp"
#include "solver/grid.hpp"
#include "solver/poisson.hpp"
#include "solver/solid.hpp"
#include "solver/timers.hpp"

namespace refmap {

struct RunOptions {
  std::string out_dir;          ///< where VTK, pvd, diagnostics.csv and probes go ("" = no output)
  bool progress = true;         ///< print progress (live line on a terminal, log lines otherwise)
  bool quiet = false;           ///< no progress, no summary (tests)
  long timing_warmup_steps = 0; ///< reset the phase timers after this many steps (0: time all)
};

struct RunSummary {
  long steps = 0;
  double t_end = 0.0;
  double wall_s = 0.0;
  long timed_steps = 0;         ///< steps covered by the phase timers (after the warm-up)
  double timed_wall_s = 0.0;    ///< wall seconds covered by the phase timers
  bool steady = false;          ///< stopped by steady_tol
  bool failed = false;          ///< stopped because fields went non-finite / divergence exploded
  std::string failure;          ///< the message in that case
};

class Simulation {
 public:
  explicit Simulation(const Config& cfg);
  ~Simulation();

  /// Runs from t_start to t_end (or steady state), writing output to opt.out_dir.
  RunSummary run(const RunOptions& opt);

  /// One time step of size dt (dt <= 0: choose it from the stability limits).
  /// Returns the dt taken.
  double step(double dt = 0.0);

  /// The stability-limited time step of section 4 (advective, viscous, solid shear wave).
  double stable_dt() const;

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
  const Field& vf() const { return vf_; }  ///< y-face normal velocity, nx x (ny+1)
  Field& u_mut() { return u_; }
  Field& v_mut() { return v_; }

  /// Cell field by probe/output name: u, v, p, density, speed, vorticity (ghosts filled).
  Field named_field(const std::string& name) const;

  // solids
  const std::vector<std::unique_ptr<Solid>>& solids() const { return solids_; }
  double elastic_energy() const { return elastic_energy_; }  ///< at the last stress evaluation
  /// Global blended solid stress (conservative form); empty when there are no elastic solids.
  const Field& solid_stress_xx() const { return sxx_; }
  const Field& solid_stress_xy() const { return sxy_; }
  const Field& solid_stress_yy() const { return syy_; }
  /// Closes the contact event log at the current time (restitution of a rebound still
  /// being tracked); run() calls it at the end.
  void finish_events() { if (contact_) contact_->finish(t_); }
  /// Contact model and gap/event tracker (null without solids).
  const Contact* contact() const { return contact_.get(); }
  /// The contact force density of the last step on x- and y-faces (empty without contact).
  const Field& contact_force_x() const { return cfx_; }
  const Field& contact_force_y() const { return cfy_; }
  /// Total momentum sum rho u dx^2 (x and y).
  std::pair<double, double> momentum() const;

  // diagnostics
  double kinetic_energy() const;       ///< sum 0.5 rho |u|^2 dx^2 over cells
  double max_face_divergence() const;  ///< max over cells of |div u_f| (faces' net flux / dx)
  int last_poisson_iterations() const { return last_stats_.iterations; }
  double last_poisson_residual() const { return last_stats_.rel_residual; }
  const PhaseTimers& timers() const { return timers_; }

  /// Fill ghost cells of the cell velocity from the boundary conditions at time t.
  void apply_velocity_bc(Field& u, Field& v, double t) const;

 private:
  void initialise();
  void build_poisson_coefficients();
  /// Algorithm 1 steps 1-2 for every solid, then density and viscosity of the mixture.
  void update_solids(double dt);
  void blend_material_fields();
  /// Force of the solid stresses (conservative or not) into fx_, fy_ (which it overwrites).
  void solid_force();
  void impose_prescribed_velocity(double t);
  /// Solid::diagnostics of every solid for the current state, computed once per step and
  /// shared by the contact log and the diagnostics.csv row.
  const std::vector<SolidDiagnostics>& solid_diagnostics() const;
  std::vector<std::string> diagnostic_columns() const;
  std::vector<double> diagnostic_values(double last_dt, double wall) const;
  void solid_output_fields(Field& phi, Field& xix, Field& xiy, Field& normal) const;
  void project(double dt);
  /// Subtracts beta_f times the contact face force from the face accelerations gxf_, gyf_.
  void add_contact_face_accel();
  /// "" if the state is healthy, else a message naming the step, time and cell.
  std::string check_health(double dt) const;

  Config cfg_;
  double t_ = 0.0;
  long nstep_ = 0;

  Field u_, v_, p_, rho_, rho_old_, mu_;   // cell-centred
  Field uf_, vf_;                          // face-normal velocities (exactly divergence-free)
  Field beta_x_, beta_y_;                  // 1/rho on faces for the Poisson problem
  Field dp_, rhs_;                         // pressure correction and Poisson right-hand side
  // RK-4 work arrays (momentum rho u, rho v)
  Field mx_, my_, kx_, ky_, sx_, sy_, fx_, fy_, k2x_, k2y_, k3x_, k3y_, k4x_, k4y_;
  Field gxf_, gyf_;                        // face accelerations G_f of eqs. (5.3), (5.7)
  std::vector<std::unique_ptr<Solid>> solids_;
  mutable std::vector<SolidDiagnostics> solid_diag_;  ///< cache of solid_diagnostics()
  mutable long solid_diag_step_ = -1;                 ///< the step it belongs to (-1: none)
  Field sxx_, sxy_, syy_;                  // blended solid stress (global, if any solid is elastic)
  double elastic_energy_ = 0.0;
  bool prescribed_depends_on_time_ = false;  ///< flow = "prescribed" with an expression of t
  std::unique_ptr<Contact> contact_;
  Field cfx_, cfy_;                        // contact force density of the last step
  std::unique_ptr<PoissonSolver> poisson_;
  SolveStats last_stats_;
  PhaseTimers timers_;
};

}  // namespace refmap
