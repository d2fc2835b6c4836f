#pragma once
// The solids of a scene as one component: each solid's reference map, level set and stress
// (solver/model/solid.hpp), the blended stress tensor they put on the grid, their elastic
// energy and their per-step diagnostics. The Simulation calls it at the fixed points of
// Algorithm 1 (Jain & Mani) that are the solids' own, through the typed calls below, as
// it calls the velocity step's component (solver/model/component.hpp):
//  * steps 1-2, `move`: advect xi with the velocity the coupling chooses (eq. 3.3),
//    extrapolate it into the band (Algorithm 2), rebuild phi = phi0(xi) (eq. 3.2),
//    reinitialised by fast marching; the solids run concurrently, one per thread;
//  * step 3, `blend`: the mixture's density and viscosity (eq. 3.6);
//  * eq. (5.2), `stress_force`: every solid's stress (its constitutive law,
//    kernels/constitutive.hpp), blended into the global tensor, and its divergence as a force;
//  * section 4, `explicit_dt`: the shear-wave limit of the explicit stress.
// Its output is its own: the diagnostics columns elastic_energy and total_energy, the
// per-solid columns of solids.csv (area, centroid, velocity, sigma_max), and the VTK fields
// phi, xi, normal_stress and stress_*.
// Its checkpoint records are those the Simulation wrote for the solids before they were a
// component (the count, then each solid's window and arrays); the Simulation registers
// them where they were (register_state), so checkpoints keep their layout. The blended
// tensor and the elastic energy are the flow's records "sim.sxx" ... "sim.elastic_energy"
// for the same reason (stress_fields, elastic_energy_mut).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/field.hpp"
#include "solver/model/component.hpp"
#include "solver/model/config.hpp"
#include "solver/model/solid.hpp"

namespace refmap {

class PhaseTimers;

class Solids : public Component {
 public:
  /// The scene's solids on the grid of `cfg` with the sides the projection sees.
  Solids(const Config& cfg, const Sides& sides);
  /// A scene with at least one [[solid]].
  static bool needed(const Config& cfg) { return !cfg.solids.empty(); }

  const char* name() const override { return "solids"; }
  /// Its work is called through the typed calls below, at Algorithm 1's fixed points.
  bool has_hooks() const override { return false; }
  /// diagnostics.csv: elastic_energy and total_energy (kinetic plus elastic), right after
  /// the flow's last built-in column, wall_time (contact's and the implicit step's columns
  /// name total_energy and follow).
  std::vector<std::string> columns() const override { return {"elastic_energy", "total_energy"}; }
  void values(const Simulation& sim, std::vector<double>& out) const override;
  const char* columns_after() const override { return "wall_time"; }
  /// solids.csv: each solid's area, centroid, mean velocity and largest stress (from the
  /// per-step cache, diagnostics()), first after the row's step, time and solid: the loads
  /// fx, fy, torque, which the rigid bodies or the control-volume forces fill, follow.
  std::vector<std::string> solid_columns() const override { return {"area", "cx", "cy", "u", "v", "sigma_max"}; }
  void solid_values(const Simulation& sim, int k, std::vector<double>& out) const override;
  const char* solid_columns_after() const override { return "solid"; }
  /// VTK frames: phi and xi of the solid nearest each cell (smallest phi; xi 0 outside
  /// every band, phi capped at the widest band), the mean normal stress (sxx + syy) / 2, and
  /// with an elastic solid the blended tensor stress_xx, stress_xy, stress_yy.
  void frame_fields(FrameFields& out) const override;
  /// The count record "sim.solids" (a checkpoint of a scene with other solids fails on it),
  /// then "solid<k>" for each solid.
  void register_state(StateRegistry& reg) override;

  std::vector<std::unique_ptr<Solid>>& list() { return solids_; }
  const std::vector<std::unique_ptr<Solid>>& list() const { return solids_; }
  /// Some solid has a shear modulus: the blended stress tensor exists.
  bool elastic() const { return sxx_.nx() > 0; }
  /// Some solid has a viscosity of its own (the viscous term runs even with mu_f = 0).
  bool viscous() const;
  /// Some solid's density differs from the fluid's.
  bool density_contrast() const;
  /// The fastest acceleration gravity (magnitude gmag) gives a free solid:
  /// gmag |rho_s - rho_f| / rho_s, at least gmag (section 4's advective limit with gravity).
  double gravity_acceleration(double gmag) const;
  /// Section 4: the explicit stress's shear-wave limit, the smallest of the solids'.
  double explicit_dt() const;

  /// The initial velocity a solid imposes inside itself (its spec's velocity).
  void impose_initial_velocity(Field& u, Field& v) const;

  /// The velocity that carries xi in steps 1-2: face velocities (or the cell velocities,
  /// [[solid]] xi_velocity = "cell").
  struct Carrier {
    const Field& uf;
    const Field& vf;
    const Field& u;
    const Field& v;
  };
  /// Algorithm 1 steps 1-2 for every solid, concurrently: xi advected by `by` over dt and
  /// extrapolated (unless a component sets the solid's map: Component::moves_solid; then
  /// Component::place_solid), the level set rebuilt. Booked in `timers` as "xi advection",
  /// "extrapolation" and "level set", one call per solid each.
  void move(const Carrier& by, double dt, const std::vector<std::unique_ptr<Component>>& components,
            PhaseTimers& timers);
  /// Step 3: adds each solid's blend of its density and viscosity to rho and mu (which hold
  /// rho_f and mu_f), in solid order.
  void blend(Field& rho, Field& mu, double rho_f, double mu_f) const;
  /// Eq. (5.2): the stress of every solid, blended into the global tensor (conservative
  /// form: the face-stress divergence added to fx, fy by each solid; the cell form's
  /// divergence of the tensor added here). Sets the elastic energy. Nothing without an
  /// elastic solid.
  void stress_force(Field& fx, Field& fy, const Config& cfg);

  /// The blended tensor of the last stress_force (empty fields without an elastic solid).
  const Field& stress_xx() const { return sxx_; }
  const Field& stress_xy() const { return sxy_; }
  const Field& stress_yy() const { return syy_; }
  /// The flow's checkpoint records of the tensor ("sim.sxx", "sim.sxy", "sim.syy").
  std::array<Field*, 3> stress_fields() { return {&sxx_, &sxy_, &syy_}; }
  /// sum of the solids' elastic energies at the last stress_force.
  double elastic_energy() const { return elastic_energy_; }
  double& elastic_energy_mut() { return elastic_energy_; }

  /// Solid::diagnostics of every solid for the velocity (u, v) of step `step`, computed
  /// once per step (the cache is keyed by it; invalidate_diagnostics() when the state
  /// changes otherwise).
  const std::vector<SolidDiagnostics>& diagnostics(const Field& u, const Field& v, long step) const;
  void invalidate_diagnostics() { diag_step_ = -1; }

 private:
  std::vector<std::unique_ptr<Solid>> solids_;
  Grid grid_;
  double rho_f_;
  Field sxx_, sxy_, syy_;  ///< blended solid stress (global), if any solid is elastic
  double elastic_energy_ = 0.0;
  mutable std::vector<SolidDiagnostics> diag_;  ///< cache of diagnostics()
  mutable long diag_step_ = -1;                 ///< the step it belongs to (-1: none)
};

}  // namespace refmap
