#pragma once
// Contact as a component (solver/model/component.hpp): the contact model of
// solver/model/contact.hpp (force, gaps, events) in the step. The Simulation adds it first,
// whenever the scene has solids (before the scene's optional components), so its hooks
// come first at each step point and its columns keep their place. It
//  * computes the contact force density on the faces of the new configuration at
//    StepPoint::Forces and subtracts beta_f F_f from the face accelerations at every
//    StepPoint::FaceAccelerations (balanced-force, like gravity: eqs. 5.3 and 5.7);
//  * observes the gaps and the contact events at StepPoint::End;
//  * limits the step by the contact spring only in a step that can bring a surface into
//    range (Contact::clear_of_contact, with the flow's speed of Simulation::flow_limit);
//  * registers the tracker's state and the face force (read at the next step's start with
//    time.splitting = "increment");
//  * writes contact_energy after total_energy in diagnostics.csv, gap_solid and gap_wall
//    after sigma_max in solids.csv, and events.csv at the end of the run.
// Its scene keys ([contact]) are its kind's (contact_kind in contact_component.cpp: keys,
// parser into ContactOptions); the kind makes nothing, the Simulation adds the component.
#include <string>
#include <vector>

#include "core/field.hpp"
#include "solver/model/component.hpp"
#include "solver/model/contact.hpp"

namespace refmap {

class ContactComponent : public Component {
 public:
  /// At the end of sim's constructor (the initial state is final): the velocity scale of
  /// the contact pressure from it, and the first observation of the gaps. Its options are
  /// the Config's "contact" entry (the defaults without one).
  explicit ContactComponent(Simulation& sim);

  const Contact& contact() const { return contact_; }
  /// The contact force density of the last step on x- and y-faces (empty without force).
  const Field& force_x() const { return cfx_; }
  const Field& force_y() const { return cfy_; }

  // Component
  const char* name() const override { return "contact"; }
  void register_state(StateRegistry& reg) override;
  double max_dt(const Simulation& sim) const override;
  void at(StepPoint p, Simulation& sim, double dt) override;
  std::vector<std::string> columns() const override { return {"contact_energy"}; }
  void values(const Simulation&, std::vector<double>& out) const override { out.push_back(contact_.energy()); }
  const char* columns_after() const override { return "total_energy"; }
  std::vector<std::string> solid_columns() const override { return {"gap_solid", "gap_wall"}; }
  void solid_values(const Simulation&, int k, std::vector<double>& out) const override;
  const char* solid_columns_after() const override { return "sigma_max"; }
  /// Closes the event log (restitution of a rebound still being tracked) and writes
  /// events.csv.
  void finish(Simulation& sim, const std::string& out_dir) override;

 private:
  /// The contact force on the faces of the new configuration.
  void add_force(const Simulation& sim);
  /// G_f -= beta_f F_f on the faces that carry a normal velocity.
  void subtract_from_face_accelerations(Simulation& sim) const;

  Contact contact_;
  Field cfx_, cfy_;
  bool written_ = true;  ///< cfx_/cfy_ may be nonzero (add_force)
};

}  // namespace refmap
