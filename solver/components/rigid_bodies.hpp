#pragma once
// The rigid bodies as a component (solver/model/component.hpp): the poses, the direct forcing
// and the cut faces of solver/model/rigid_body.hpp in the step. The Simulation makes it
// whenever a solid is rigid, before the initial state (the initial projection cuts its
// faces), and attaches it right after contact, so that at StepPoint::FaceAccelerations its
// cut faces come after the contact force, as in Algorithm 1's order. It
//  * moves every body to its pose of t + dt at StepPoint::Begin (RigidBodies::advance);
//  * sets the reference map of a rigid solid (the whole window) and of a soft solid
//    clamped to a body (inside the body) in the per-solid loop of Algorithm 1 steps 1-2
//    (moves_solid, place_solid: a rigid solid is neither advected nor extrapolated);
//  * with forcing = "sharp": zeroes the cut faces' Poisson coefficients
//    (StepPoint::PoissonCoefficients), sets their G_f (StepPoint::FaceAccelerations) and
//    their face velocities (StepPoint::Predicted), and fills the pressure inside
//    (StepPoint::PressureUpdated);
//  * forces the cell velocities towards the bodies' (StepPoint::BeforePredictor, timed as
//    "bodies"), aiming at the predictor's G_f;
//  * registers the bodies' state (record "bodies");
//  * writes angle and omega after torque in solids.csv (nan on a soft solid's rows).
// Still in the Simulation: the calls of the held cells of forcing_hold (the RK-4 stages' and
// the explicit stress step's rates: Simulation::call_rates, begin_substeps; the implicit
// solve holds Simulation::held_cells, solver/components/implicit_velocity_step.hpp) and the
// solids.csv columns fx, fy, torque, shared with the control-volume forces
// (solver/model/diagnostics.cpp); docs/components.md.
// Its kind (rigid_bodies_kind, rigid_bodies.cpp) declares the rigid bodies' keys in
// `[[solid]]` (motion, forcing, path, pivot, clamp); the solids' parser
// (solver/components/solids_keys.cpp) calls the readers below at their place in each table.
#include <memory>
#include <string>
#include <vector>

#include "solver/model/component.hpp"
#include "solver/model/config.hpp"
#include "solver/model/rigid_body.hpp"

namespace refmap {

class TomlTable;

/// Solid `s`'s motion and, for a rigid body, its forcing (before its material: a rigid body
/// takes no `mu_s`). Throws SceneError on bad input.
void parse_body_motion(const TomlTable& s, SolidSpec& sp);
/// A rigid body's initial velocity from its motion (after the solid's own initial velocity,
/// whose keys it refuses), its path or pivot, and a soft solid's `clamp`; (cx, cy) is the
/// point its rotation refers to (the centre, or the bounding box's for a tabulated shape).
void parse_body_velocity(const TomlTable& s, SolidSpec& sp, const Config& cfg, double cx, double cy);
/// Every clamped soft solid's body, by name: it must be a rigid solid of the scene.
void resolve_clamps(const TomlTable& top, std::vector<SolidSpec>& solids);

class RigidBodiesComponent : public Component {
 public:
  explicit RigidBodiesComponent(const Config& cfg)
      : bodies_(cfg), cuts_(bodies_.cuts_faces()), holds_(bodies_.holds()) {}

  RigidBodies& bodies() { return bodies_; }
  const RigidBodies& bodies() const { return bodies_; }

  // Component
  const char* name() const override { return "bodies"; }
  void register_state(StateRegistry& reg) override;
  void at(StepPoint p, Simulation& sim, double dt) override;
  bool moves_solid(int k) const override { return bodies_.rigid(k); }
  void place_solid(int k, const std::vector<std::unique_ptr<Solid>>& solids) const override {
    bodies_.place(k, solids);  // rigid: the whole map; clamped: inside its body
  }
  std::vector<std::string> solid_columns() const override { return {"angle", "omega"}; }
  void solid_values(const Simulation&, int k, std::vector<double>& out) const override;
  /// After the loads (fx, fy, torque); without them (no solid has a load) at the end, which
  /// is the same place: after sigma_max and the contact's gaps
  const char* solid_columns_after() const override { return "torque"; }
  /// forcing_hold: the cells the forcing sets, held through the substeps (made at
  /// StepPoint::Substeps); their rates at StepPoint::Rates and HeldSolved are the momentum
  /// the hold takes, booked to the body (RigidBodies::add_held) and zeroed.
  const std::vector<std::array<int, 3>>* held_cells() const override { return holds_ ? &held_ : nullptr; }
  /// The forcing's load on every rigid body (the momentum it removes, solver/model/rigid_body.hpp).
  bool solid_load(int k, const BodyLoad*& load) const override {
    load = bodies_.rigid(k) ? &bodies_.load(k) : nullptr;
    return true;
  }

 private:
  /// The held cells' rates (weight w) into the bodies' held momentum, and zeroed there
  /// (serial: a body's few hundred cells, and the sums must have the same bits for any threads).
  void hold_rates(View kx, View ky, double w, const Grid& g);

  RigidBodies bodies_;
  bool cuts_;   ///< a body with forcing = "sharp"
  bool holds_;  ///< a body with forcing_hold
  std::vector<std::array<int, 3>> held_;  ///< the held cells of this step: i, j, body
};

}  // namespace refmap
