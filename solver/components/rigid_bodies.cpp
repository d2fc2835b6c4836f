#include "solver/components/rigid_bodies.hpp"

#include <limits>

#include "solver/io/checkpoint_io.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/model/implicit_step.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {

void RigidBodiesComponent::register_state(StateRegistry& reg) {
  // the poses, the last loads and forcing regions, the held momentum (solver/model/rigid_body.hpp)
  reg.add_record(
      "bodies", [this](CheckpointWriter& w) { bodies_.save_state(w); },
      [this](CheckpointReader& r) { bodies_.load_state(r); });
}

void RigidBodiesComponent::solid_values(const Simulation&, int k, std::vector<double>& out) const {
  // a soft solid's rows (a clamped one, or a free one beside the bodies) have no rotation
  const bool body = bodies_.rigid(k);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.push_back(body ? bodies_.pose(k).theta : nan);
  out.push_back(body ? bodies_.pose(k).omega : nan);
}

void RigidBodiesComponent::at(StepPoint p, Simulation& sim, double dt) {
  const Grid& g = sim.grid();
  switch (p) {
    case StepPoint::Begin:  // from t to t + dt, before the solids are moved
      bodies_.advance(sim.time(), dt);
      break;
    case StepPoint::PoissonCoefficients:  // forcing = "sharp": no pressure coupling across a cut face
      if (cuts_) bodies_.clear_cut_faces(sim.solids(), sim.beta_x_mut(), sim.beta_y_mut(), g);
      break;
    case StepPoint::FaceAccelerations:  // forcing = "sharp": G_f of the cut faces (face_accel left -g there)
      if (cuts_) bodies_.cut_face_accel(sim.solids(), sim.face_accel_x_mut(), sim.face_accel_y_mut(), g);
      break;
    case StepPoint::BeforePredictor:
      // with the face accelerations the predictor will subtract: the forcing aims at
      // u_body + dt G_c so that the predicted face velocities inside a body are its velocity
      bodies_.force(sim.solids(), sim.u_mut(), sim.v_mut(), sim.rho(), sim.face_accel_x(), sim.face_accel_y(),
                    sim.p(), g, dt);
      break;
    case StepPoint::Predicted:  // forcing = "sharp": the cut faces carry the body's velocity
      if (cuts_) bodies_.impose_cut_faces(sim.solids(), sim.uf_mut(), sim.vf_mut(), g);
      break;
    case StepPoint::PressureUpdated:  // cut out of the solve: the fluid's pressure inside
      if (cuts_) bodies_.fill_inside_pressure(sim.solids(), sim.p_mut(), g);
      break;
    case StepPoint::Substeps:  // forcing_hold: the cells held through the substeps
      if (holds_) bodies_.held_cells(sim.solids(), g, held_);
      break;
    case StepPoint::Rates:  // an RK-4 stage's or the explicit stress step's rate
      if (holds_) hold_rates(sim.rate_x_mut(), sim.rate_y_mut(), sim.rate_weight(), g);
      break;
    case StepPoint::HeldSolved:  // the implicit solve's rates at the held cells (held exactly)
      if (holds_) {
        const auto& r = sim.implicit_velocity()->held_rate();
        for (std::size_t n = 0; n < held_.size(); ++n)
          bodies_.add_held(held_[n][2], held_[n][0], held_[n][1], dt * r[n][0], dt * r[n][1], g);
      }
      break;
    default:
      break;
  }
}

void RigidBodiesComponent::hold_rates(View kx, View ky, double w, const Grid& g) {
  for (const auto& c : held_) {
    const int i = c[0], j = c[1];
    bodies_.add_held(c[2], i, j, w * kx(i, j), w * ky(i, j), g);
    kx(i, j) = 0.0;
    ky(i, j) = 0.0;
  }
}

}  // namespace refmap
