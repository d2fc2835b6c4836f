#pragma once
// The fluid's force and torque on every body from a control-volume momentum balance
// (output.body_force = "control_volume"; docs/bodies.md, "Force from a control volume";
// the sums are kernels/control_volume.hpp).
//
// A BODY is a solid that is not clamped: a rigid body together with the soft solids clamped
// to it (the Turek & Hron cylinder + flag), or a free soft solid. Its control volume is a
// rectangle of cells: the bounding box of the cells where some member's phi < w_T (the
// smoothed Heaviside's half-width: outside it the density and viscosity are the fluid's),
// grown by kMargin cells on every side and clipped to the domain. It is fixed over a step
// (taken at the step's start; a body moves less than a cell per step), and over the step
//     F = (S^n + S^{n+1}) / 2 - (P^{n+1} - P^n) / dt - rho_f g (V^n + V^{n+1}) / 2,
// S the surface sum of box_surface_force (fluid stress and momentum flux, with the solid
// stress where a solid crosses the surface), P the FLUID momentum in the box (the fluid
// fraction w = 1 - sum (1 - H_k) times rho_f u: the solids' inertia is left out), V the
// solids' volume in the box (buoyancy: refmap's pressure excludes the hydrostatic rho_f g.x,
// gravity acts on rho - rho_f). The torque likewise, about the body's reference point at
// the step's start (a rigid body's centre or pivot, a soft solid's centroid).
// This is the force the fluid exerts on everything inside the box except the fluid,
// buoyancy included, the bodies' weight and any support (the forcing) excluded.
#include <array>
#include <span>
#include <vector>

#include "core/field.hpp"
#include "kernels/control_volume.hpp"
#include "solver/model/component.hpp"
#include "solver/io/enum_names.hpp"
#include "solver/model/rigid_body.hpp"

namespace refmap {

/// output.body_force: the force written as solidK_fx, _fy, _torque. Forcing: a rigid
/// body's, the momentum its direct forcing adds (solver/model/rigid_body.hpp); ControlVolume:
/// every body's, from this component. The key and its parser are this component's kind
/// (control_volume_forces_kind in control_volume_forces.cpp); the scene adds the component
/// with ControlVolume.
enum class BodyForceEstimator { Forcing, ControlVolume };
std::span<const OptionName<BodyForceEstimator>> option_names(BodyForceEstimator);

class Simulation;

/// A component (solver/model/component.hpp): begin_step at the step's start, end_step at its end.
class ControlVolumeForces : public Component {
 public:
  /// Cells between the box and the nearest cell with phi < w_T of a member: the faces of
  /// the surface then have fluid (H = 1) on both sides and in their tangential stencils.
  static constexpr int kMargin = 2;

  explicit ControlVolumeForces(const Simulation& sim);

  /// True if solid k carries a force (not clamped to another body).
  bool has_load(int k) const { return owner_[std::size_t(k)] == k; }
  /// The force and torque of the last step on body k (zero before the first step).
  const BodyLoad& load(int k) const { return load_[std::size_t(k)]; }
  /// Body k's control volume of the last step (empty for a clamped solid).
  const ControlBox& box(int k) const { return box_[std::size_t(k)]; }

  /// At the start of a step, before the solids move: each body's box, reference point,
  /// surface sum and fluid momentum.
  void begin_step(const Simulation& sim);
  /// At the end of the step of size dt: the force over it.
  void end_step(const Simulation& sim, double dt);

  // Component
  const char* name() const override { return "body forces"; }
  void at(StepPoint p, Simulation& sim, double dt) override {
    if (p == StepPoint::Begin) begin_step(sim);
    if (p == StepPoint::End) end_step(sim, dt);
  }
  /// Every body's balance (a clamped solid's force is its body's).
  bool solid_load(int k, const BodyLoad*& load) const override {
    load = has_load(k) ? &load_[std::size_t(k)] : nullptr;
    return true;
  }

 private:
  /// the fluid fraction w = 1 - sum_k (1 - H_k) into frac_
  void fluid_fraction(const Simulation& sim);
  std::array<double, 3> surface(const Simulation& sim, int k) const;
  std::array<double, 6> momentum(const Simulation& sim, int k) const;
  BoxFrame frame(const Simulation& sim, int k) const;

  std::vector<int> owner_;  ///< the body solid k belongs to (itself unless clamped)
  std::vector<ControlBox> box_;
  std::vector<std::array<double, 2>> ref_;        ///< reference point at the step's start
  std::vector<std::array<double, 3>> s0_;         ///< surface sum at the step's start
  std::vector<std::array<double, 6>> p0_;         ///< box_momentum at the step's start
  std::vector<BodyLoad> load_;
  Field frac_;
};

}  // namespace refmap
