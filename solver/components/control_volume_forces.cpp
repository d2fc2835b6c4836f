#include "solver/components/control_volume_forces.hpp"

#include <algorithm>
#include <climits>

#include <memory>

#include "kernels/loop.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/simulation.hpp"
#include "solver/io/toml_reader.hpp"

namespace refmap {

ControlVolumeForces::ControlVolumeForces(const Simulation& sim) {
  const auto& specs = sim.config().solids;
  const std::size_t n = specs.size();
  owner_.resize(n);
  for (std::size_t k = 0; k < n; ++k) owner_[k] = specs[k].clamp_index >= 0 ? specs[k].clamp_index : int(k);
  box_.resize(n);
  ref_.resize(n);
  s0_.resize(n);
  p0_.resize(n);
  load_.resize(n);
  frac_.resize(sim.grid().nx, sim.grid().ny, Grid::ng);
}

void ControlVolumeForces::fluid_fraction(const Simulation& sim) {
  parallel_fill(frac_.raw(), frac_.raw_size(), 1.0);
  for (const auto& s : sim.solids()) s->add_blend(frac_, 0.0, 1.0);  // w -= 1 - H
}

BoxFrame ControlVolumeForces::frame(const Simulation& sim, int k) const {
  const Grid& g = sim.grid();
  BoxFrame fr;
  fr.dx = g.dx;
  fr.x0 = g.x0;
  fr.y0 = g.y0;
  fr.nx = g.nx;
  fr.ny = g.ny;
  fr.xr = ref_[std::size_t(k)][0];
  fr.yr = ref_[std::size_t(k)][1];
  return fr;
}

std::array<double, 3> ControlVolumeForces::surface(const Simulation& sim, int k) const {
  SurfaceFields f;
  f.u = sim.u().cview();
  f.v = sim.v().cview();
  f.p = sim.p().cview();
  f.mu = sim.viscosity().cview();
  f.rho = sim.rho().cview();
  f.uf = sim.uf().cview();
  f.vf = sim.vf().cview();
  if (sim.solid_stress_xx().nx() > 0) {
    f.sxx = sim.solid_stress_xx().cview();
    f.sxy = sim.solid_stress_xy().cview();
    f.syy = sim.solid_stress_yy().cview();
  }
  return box_surface_force(f, box_[std::size_t(k)], frame(sim, k));
}

std::array<double, 6> ControlVolumeForces::momentum(const Simulation& sim, int k) const {
  return box_momentum(sim.u().cview(), sim.v().cview(), frac_.cview(), sim.config().rho_f, box_[std::size_t(k)],
                      frame(sim, k));
}

void ControlVolumeForces::begin_step(const Simulation& sim) {
  const Grid& g = sim.grid();
  const auto& solids = sim.solids();
  const int n = int(solids.size());
  // each body's box: the cells where a member's phi < w_T, grown by kMargin, clipped
  for (int k = 0; k < n; ++k) box_[std::size_t(k)] = {INT_MAX, INT_MAX, INT_MIN, INT_MIN};
  for (int m = 0; m < n; ++m) {
    const Solid& s = *solids[std::size_t(m)];
    ControlBox& b = box_[std::size_t(owner_[std::size_t(m)])];
    for (int j = 0; j < s.nj(); ++j)
      for (int i = 0; i < s.ni(); ++i)
        if (s.phi()(i, j) < s.transition()) {
          b.i0 = std::min(b.i0, s.i0() + i);
          b.i1 = std::max(b.i1, s.i0() + i + 1);
          b.j0 = std::min(b.j0, s.j0() + j);
          b.j1 = std::max(b.j1, s.j0() + j + 1);
        }
  }
  const std::vector<SolidDiagnostics>& diag = sim.solid_diagnostics();
  for (int k = 0; k < n; ++k) {
    ControlBox& b = box_[std::size_t(k)];
    if (!has_load(k) || b.i0 == INT_MAX) {
      b = ControlBox{};
      continue;
    }
    b = {std::max(b.i0 - kMargin, 0), std::max(b.j0 - kMargin, 0), std::min(b.i1 + kMargin, g.nx),
         std::min(b.j1 + kMargin, g.ny)};
    // torques about the rigid body's centre or pivot, or the soft solid's centroid
    if (sim.bodies() && sim.bodies()->rigid(k))
      ref_[std::size_t(k)] = {sim.bodies()->pose(k).cx, sim.bodies()->pose(k).cy};
    else
      ref_[std::size_t(k)] = {diag[std::size_t(k)].cx, diag[std::size_t(k)].cy};
  }
  fluid_fraction(sim);
  for (int k = 0; k < n; ++k) {
    if (box_[std::size_t(k)].empty()) continue;
    s0_[std::size_t(k)] = surface(sim, k);
    p0_[std::size_t(k)] = momentum(sim, k);
  }
}

void ControlVolumeForces::end_step(const Simulation& sim, double dt) {
  const Config& c = sim.config();
  fluid_fraction(sim);
  for (int k = 0; k < int(box_.size()); ++k) {
    BodyLoad& L = load_[std::size_t(k)];
    L = BodyLoad{};
    if (box_[std::size_t(k)].empty()) continue;
    const std::array<double, 3> s1 = surface(sim, k), &s0 = s0_[std::size_t(k)];
    const std::array<double, 6> p1 = momentum(sim, k), &p0 = p0_[std::size_t(k)];
    // the solids' volume and its first moment about the reference point, mean over the step
    const double V = 0.5 * (p0[3] + p1[3]), Vx = 0.5 * (p0[4] + p1[4]), Vy = 0.5 * (p0[5] + p1[5]);
    L.fx = 0.5 * (s0[0] + s1[0]) - (p1[0] - p0[0]) / dt - c.rho_f * c.gx * V;
    L.fy = 0.5 * (s0[1] + s1[1]) - (p1[1] - p0[1]) / dt - c.rho_f * c.gy * V;
    L.torque = 0.5 * (s0[2] + s1[2]) - (p1[2] - p0[2]) / dt - c.rho_f * (Vx * c.gy - Vy * c.gx);
  }
}

std::span<const OptionName<BodyForceEstimator>> option_names(BodyForceEstimator) {
  static const OptionName<BodyForceEstimator> n[] = {{BodyForceEstimator::Forcing, "forcing"},
                                                     {BodyForceEstimator::ControlVolume, "control_volume"}};
  return name_list(n);
}

namespace {

/// output.body_force = "control_volume": on (no options beyond that); "forcing": off (null).
std::shared_ptr<const ComponentOptions> parse_body_force(const TomlTable& top, const Config&) {
  const toml::table* t = top.table("output", false);
  if (!t) return nullptr;
  const TomlTable o = top.sub(*t, "output", "output");
  if (o.option<BodyForceEstimator>("body_force") != BodyForceEstimator::ControlVolume) return nullptr;
  return std::make_shared<ComponentOptions>();
}

/// Only with bodies and a flow that is solved (a prescribed flow has no momentum balance).
std::unique_ptr<Component> make_control_volume_forces(const ComponentOptions&, Simulation& sim) {
  if (sim.solids().empty() || sim.config().flow != FlowMode::Solve) return nullptr;
  return std::make_unique<ControlVolumeForces>(sim);
}

}  // namespace

ComponentKind control_volume_forces_kind() {
  ComponentKind k;
  k.name = "body forces";
  k.keys = {keys::choice<BodyForceEstimator>(
      "output", "body_force", BodyForceEstimator::Forcing,
      "the force in `solid<k>_fx`, `_fy`, `_torque`: `\"forcing\"`, a rigid body's direct "
      "forcing; `\"control_volume\"`, every unclamped solid's (a rigid body with its "
      "clamped solids), from the fluid's momentum balance on a box around it "
      "(docs/bodies.md)")};
  k.after = "output.wall_stress";
  k.parse = parse_body_force;
  k.make = make_control_volume_forces;
  return k;
}

}  // namespace refmap
