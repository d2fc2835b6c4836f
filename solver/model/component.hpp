#pragma once
// An optional part of a run attached to a Simulation: the solids, contact, rigid bodies, the
// implicit velocity step, tracers, material markers, actuated solids, or anything a scene
// (or a test) adds (docs/components.md). Simulation keeps the flow state and
// Algorithm 1; a component
//  * registers its persistent state once (StateRegistry: checkpointed by construction),
//  * may limit the time step (max_dt),
//  * is called at fixed, named points of Simulation::step (StepPoint) - the points stay in
//    the step's order whatever the order in which components were added; at one point the
//    components are called in the order they were added,
//  * may add columns to diagnostics.csv (the values of the current state) and to
//    solids.csv (one value per solid), each after the built-in column it names or at the
//    end, cell fields to the VTK frames and CSV files of its own (files(): the run loop
//    writes them at every VTK frame, keeps them across a checkpoint and names none of
//    them),
//  * is told when the run ends (finish: close what is still open, write the files of the
//    run's end),
//  * may take over the velocity step of eq. (5.2) (takes_velocity_step: the implicit
//    velocity step, solver/components/implicit_velocity_step.hpp) in place of the
//    Simulation's explicit forward-Euler update, with a limit of its own on the step.
// A scene's components are made by their kinds (solver/model/component_kind.hpp: keys, parser,
// factory), so adding one takes its own files and one registration - or add_component()
// from outside, as the tests do.
#include <array>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/field.hpp"

namespace refmap {

struct BodyLoad;
class Simulation;
class Solid;
class StateRegistry;

/// The points of Simulation::step at which components are called.
enum class StepPoint {
  /// Before anything moves; dt is already chosen (the state is that of time t).
  Begin,
  /// At the start of the velocity's substeps (step 4), after the solids moved (xi^{n+1},
  /// rho^{n+1}), before the first rate: data the substeps keep fixed (the rigid bodies' held
  /// cells). Only when a component holds cells (Component::held_cells) or with
  /// time.splitting = "increment". Not timed on its own ("advection").
  Substeps,
  /// Each time a rate of the velocity's substeps is formed, before it is applied: every RK-4
  /// stage of the advection (the stage's rate of rho u, weight dt w_s with w = 1, 2, 2, 1 over
  /// 6) and the explicit viscous and stress force of eq. (5.2) (weight dt):
  /// Simulation::rate_x_mut(), rate_y_mut(), rate_weight(). Only when a component holds cells.
  /// Not timed on its own (booked in "advection" and "viscous").
  Rates,
  /// After the implicit velocity solve with held cells (Component::velocity_step of the
  /// implicit velocity step, solver/components/implicit_velocity_step.hpp):
  /// ImplicitVelocity::held_rate() (solver/model/implicit_step.hpp) holds, per held cell, the
  /// rate the solve kept from it. Only when a component holds cells. Not timed on its own
  /// ("implicit velocity").
  HeldSolved,
  /// After step 4, eq. (5.1): u(), v() hold u*, rho() rho^{n+1}, the solids xi^{n+1}.
  Advected,
  /// After eq. (5.2): u(), v() hold u**, solid_stress_*() the stress the step used.
  Stressed,
  /// Each time the Poisson coefficients beta_f = 1/rho_f are built from the density
  /// (beta_x_mut, beta_y_mut), before the pressure solver takes them: in the initial
  /// projection and in every step's Poisson setup (the rigid bodies' cut faces). Not timed
  /// on its own (booked in the phase that builds them).
  PoissonCoefficients,
  /// After the Poisson setup of the new density (the face coefficients beta_f = 1/rho_f of
  /// the solids at xi^{n+1}), before the face accelerations G_f of eq. (5.3) are
  /// assembled: face forces of the new configuration are computed here (contact).
  Forces,
  /// Each time G_f is assembled (Simulation::face_accel_x_mut): with the pressure gradient
  /// and gravity in it, before the rigid bodies' cut faces. Two or three times a step:
  /// for the predictor (step 5, eq. 5.3), for the cell velocities (step 9, eq. 5.7), and
  /// with time.splitting = "increment" at the step's start (G_f^n, inside the advection).
  /// A face force F_f enters as G_f -= beta_f F_f. Not timed on its own: its time is
  /// booked in the phase that assembles G_f. Also once in the initial projection (G_f of
  /// the pressure correction alone), where only the components the Simulation makes before
  /// the initial state (the rigid bodies) are attached.
  FaceAccelerations,
  /// After the predictor's G_f (step 5, eq. 5.3) is assembled, before the predicted face
  /// velocities: a forcing of the cell velocities that aims at the predictor's G_f (the
  /// rigid bodies' direct forcing, solver/model/rigid_body.hpp).
  BeforePredictor,
  /// After the predicted face velocities u_f* (eq. 5.3, with the Rhie-Chow term), before
  /// their divergence is taken: face velocities a component imposes (the rigid bodies' cut
  /// faces); also in the initial projection. Not timed on its own ("face velocities").
  Predicted,
  /// After p += dp (step 7, eq. 5.5), before the pressure's ghosts are filled (the
  /// pressure inside the rigid bodies' cut cells). Not timed on its own ("projection").
  PressureUpdated,
  /// After the step (the state is that of time t + dt, Simulation::time() included).
  End,
};

/// A CSV file of a component's own in the run's output directory. The run loop
/// (solver/app/run.cpp) writes it only with VTK frames (output.vtk): it creates it with
/// its column header, appends the rows of the current state at every frame (the first,
/// the scheduled ones, the last), records its length in every checkpoint (a resumed run
/// cuts it back to the rows of the checkpoint and continues it) and removes an earlier
/// run's copy from a reused directory (the file names of every kind:
/// ComponentKind::files, solver/model/component_kind.hpp).
struct ComponentFile {
  /// Its name in the output directory, "<stem>.csv"; its checkpoint records are
  /// run.<stem>_bytes and run.<stem>_rows.
  std::string name;
  std::vector<std::string> columns;
  /// Appends the rows of frame `frame` (the index of frame_NNNNN.vti) for the current state.
  std::function<void(const Simulation&, int frame, std::vector<std::vector<double>>& rows)> rows;
};

/// The cell fields a VTK frame gets from the components (Component::frame_fields): scalars
/// and vectors of nx x ny fields, each named; a component's state field by its address, a
/// field computed for the frame alone in `owned`, which lives until the frame is written.
struct FrameFields {
  struct Vector {
    std::string name;
    const Field* x;
    const Field* y;
  };
  std::vector<std::pair<std::string, const Field*>> scalars;
  std::vector<Vector> vectors;
  std::deque<Field> owned;
};

class Component {
 public:
  virtual ~Component() = default;
  /// Its name: the phase its hooks are timed under in the timing table, and the prefix
  /// of its checkpoint records.
  virtual const char* name() const = 0;
  /// Registers every array and number that carries information from one step to the next.
  virtual void register_state(StateRegistry&) {}
  /// Its limit on the next step for the current state (infinity: none).
  virtual double max_dt(const Simulation&) const { return std::numeric_limits<double>::infinity(); }
  /// Called at each point of every step, in the step's order.
  virtual void at(StepPoint, Simulation&, double /*dt*/) {}
  /// False for a component whose work the Simulation calls at fixed points through typed
  /// calls of its own (the solids: solver/components/solids.hpp): at() is then never called
  /// and the timing table has no row of its name.
  virtual bool has_hooks() const { return true; }
  /// Whether it sets solid k's reference map itself (a rigid body's, from its pose): the
  /// solid is then neither advected nor extrapolated by Algorithm 1 steps 1-2.
  virtual bool moves_solid(int /*k*/) const { return false; }
  /// Solid k's reference map after its own advection and extrapolation (if any), before its
  /// level set is rebuilt (Algorithm 1 steps 1-2). Called for the solids concurrently,
  /// inside the per-solid loop: it may change solid k only.
  virtual void place_solid(int /*k*/, const std::vector<std::unique_ptr<Solid>>& /*solids*/) const {}
  /// Its diagnostics.csv columns (fixed for the run) and their values for the current state.
  virtual std::vector<std::string> columns() const { return {}; }
  virtual void values(const Simulation&, std::vector<double>& /*out*/) const {}
  /// Where they go: right after the built-in column of this name (solver/model/diagnostics.cpp),
  /// or after the columns of a component placed before it that writes a column of this name
  /// (a component's columns stay together: contact's follow the solids' total_energy), or
  /// (null, or a column this run does not write) after every built-in column, in the order
  /// the components were added.
  virtual const char* columns_after() const { return nullptr; }
  /// Its solids.csv columns (fixed for the run), the values of solid k for the current
  /// state, and where they go (as columns_after, among the per-solid columns; "solid", the
  /// last of the leading step, time, solid, puts them first: the solids' own).
  virtual std::vector<std::string> solid_columns() const { return {}; }
  virtual void solid_values(const Simulation&, int /*k*/, std::vector<double>& /*out*/) const {}
  virtual const char* solid_columns_after() const { return nullptr; }
  /// Whether it measures the fluid's force and torque on the solids (solids.csv `fx`, `fy`,
  /// `torque`): if so, `load` is set to solid k's (null: k has none, e.g. a solid clamped to
  /// a body). The last component added that measures loads answers for every solid
  /// (Simulation::solid_load): the control-volume balance, when on, replaces the forcing's.
  virtual bool solid_load(int /*k*/, const BodyLoad*& /*load*/) const { return false; }
  /// The cells whose velocity it holds through the step's substeps (i, j, solid; made at
  /// StepPoint::Substeps), or null if it holds none: the RK-4 stages and the explicit stress
  /// step then call it at StepPoint::Rates, and the implicit velocity solve keeps these cells
  /// fixed and calls it at StepPoint::HeldSolved. Fixed for the run (null or not).
  virtual const std::vector<std::array<int, 3>>* held_cells() const { return nullptr; }
  /// Its cell fields (nx x ny) for a VTK frame, added to `out`: written after the built-in
  /// ones (solver/app/run.cpp), the components in the order added.
  virtual void frame_fields(FrameFields& /*out*/) const {}
  /// Whether it takes the velocity step of eq. (5.2), u** from u* and the step's force
  /// (Simulation::step_force_x, _y: viscous plus solid stress), in place of the Simulation's
  /// explicit forward-Euler update (the implicit velocity step,
  /// solver/components/implicit_velocity_step.hpp). At most one component does; asked once,
  /// when the Simulation is built (fixed for the run, like held_cells). The step is a
  /// replacement, not an addition, which is why it is not a StepPoint: no other component
  /// sees it, and the Simulation calls the held cells' StepPoint::HeldSolved after it.
  virtual bool takes_velocity_step() const { return false; }
  /// That step (only if takes_velocity_step): u(), v() hold u* with the walls of t + dt,
  /// rho() rho^{n+1}; leaves u** in u_mut(), v_mut(), holding Simulation::held_cells()
  /// fixed. The Simulation times it on the row "implicit velocity" (one call a step).
  virtual void velocity_step(Simulation&, double /*dt*/) {}
  /// Its limit on the next step (only if takes_velocity_step), for the current state: one of
  /// the flow's own limits (Simulation::flow_limit, which the contact's max_dt reads), not a
  /// component's max_dt, since it stands in for the explicit step's limits it lifts
  /// (infinity: none).
  virtual double velocity_step_dt(const Simulation&) const { return std::numeric_limits<double>::infinity(); }
  /// Its own output files (ComponentFile), in the order of their checkpoint records.
  virtual std::vector<ComponentFile> files() const { return {}; }
  /// At the end of a run (solver/app/run.cpp: also after a failure or a signal), after the
  /// last output: closes what is still open at the current time and writes the files of
  /// the run's end into `out_dir` ("": no output directory, nothing to write).
  virtual void finish(Simulation&, const std::string& /*out_dir*/) {}
};

}  // namespace refmap
