#include "solver/model/diagnostics.hpp"

#include <limits>

#include "solver/components/control_volume_forces.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {

namespace {

/// What the columns of one row are computed from.
struct RowState {
  const Simulation& sim;
  double last_dt;
  double wall_s;
  double kinetic_energy;  ///< computed once: two columns use it
  const std::vector<SolidDiagnostics>& solid;  ///< Simulation's per-step cache
};

struct Column {
  const char* name;
  bool needs_solids;  ///< only written when the scene has solids
  double (*value)(const RowState&);
};

// clang-format off
const Column kColumns[] = {
    {"step",               false, [](const RowState& r) { return double(r.sim.steps()); }},
    {"time",               false, [](const RowState& r) { return r.sim.time(); }},
    {"dt",                 false, [](const RowState& r) { return r.last_dt; }},
    {"kinetic_energy",     false, [](const RowState& r) { return r.kinetic_energy; }},
    {"max_div_face",       false, [](const RowState& r) { return r.sim.max_face_divergence(); }},
    {"poisson_iterations", false, [](const RowState& r) { return double(r.sim.last_poisson_iterations()); }},
    {"poisson_residual",   false, [](const RowState& r) { return r.sim.last_poisson_residual(); }},
    {"wall_time",          false, [](const RowState& r) { return r.wall_s; }},
    {"elastic_energy",     true,  [](const RowState& r) { return r.sim.elastic_energy(); }},
    {"total_energy",       true,  [](const RowState& r) { return r.kinetic_energy + r.sim.elastic_energy(); }},
    {"contact_energy",     true,  [](const RowState& r) { return r.sim.contact()->energy(); }},
};

/// The columns of solids.csv after step, time and solid: one row per solid and output step.
struct SolidColumn {
  const char* name;
  double (*value)(const RowState&, int k);
};

const SolidColumn kSolidColumns[] = {
    {"area",      [](const RowState& r, int k) { return r.solid[k].area; }},
    {"cx",        [](const RowState& r, int k) { return r.solid[k].cx; }},
    {"cy",        [](const RowState& r, int k) { return r.solid[k].cy; }},
    {"u",         [](const RowState& r, int k) { return r.solid[k].u; }},
    {"v",         [](const RowState& r, int k) { return r.solid[k].v; }},
    {"sigma_max", [](const RowState& r, int k) { return r.solid[k].sigma_max; }},
    {"gap_solid", [](const RowState& r, int k) { return r.sim.contact()->gap_solid(k); }},
    {"gap_wall",  [](const RowState& r, int k) { return r.sim.contact()->gap_wall(k); }},
};

/// The force the columns below report (output.body_force): a rigid body's direct forcing,
/// or every body's control-volume balance (solver/components/control_volume_forces.hpp).
const BodyLoad& body_load(const Simulation& sim, int k) {
  return sim.control_volume_forces() ? sim.control_volume_forces()->load(k) : sim.bodies()->load(k);
}

/// solids.csv columns after those for every solid k with a force (a rigid solid, motion != "free";
/// with output.body_force = "control_volume" also a free soft solid, not a clamped one):
/// the fluid's force and torque on it (drag and lift for a flow along x); nan on the
/// rows of the other solids.
const SolidColumn kForceColumns[] = {
    {"fx",     [](const RowState& r, int k) { return body_load(r.sim, k).fx; }},
    {"fy",     [](const RowState& r, int k) { return body_load(r.sim, k).fy; }},
    {"torque", [](const RowState& r, int k) { return body_load(r.sim, k).torque; }},
};

/// Then, for a rigid solid (solver/model/rigid_body.hpp), its rotation.
const SolidColumn kBodyColumns[] = {
    {"angle",  [](const RowState& r, int k) { return r.sim.bodies()->pose(k).theta; }},
    {"omega",  [](const RowState& r, int k) { return r.sim.bodies()->pose(k).omega; }},
};
// clang-format on

/// Written last, only when the implicit velocity step is on (time.viscous = "implicit" or
/// time.solid_stress = "semi_implicit"; solver/model/implicit_step.hpp), so the other scenes'
/// files keep their columns: the multigrid cycles of its last solve (u and v summed).
const Column kImplicitColumns[] = {
    {"implicit_iterations", false, [](const RowState& r) { return double(r.sim.implicit_velocity()->last_iterations()); }},
};

/// Written after those, only with time.solid_picard_iterations > 0 (solver/model/solid_picard.cpp):
/// the last iteration's relative velocity change and the multigrid cycles of all the step's passes.
const Column kPicardColumns[] = {
    {"picard_change", false, [](const RowState& r) { return r.sim.picard_change(); }},
    {"picard_cycles", false, [](const RowState& r) { return double(r.sim.picard_cycles()); }},
};

bool is_body(const Simulation& sim, int k) { return sim.bodies() && sim.bodies()->rigid(k); }
bool has_force(const Simulation& sim, int k) {
  return sim.control_volume_forces() ? sim.control_volume_forces()->has_load(k) : is_body(sim, k);
}

bool any_body(const Simulation& sim) {
  for (int k = 0; k < int(sim.solids().size()); ++k)
    if (is_body(sim, k)) return true;
  return false;
}

bool any_force(const Simulation& sim) {
  for (int k = 0; k < int(sim.solids().size()); ++k)
    if (has_force(sim, k)) return true;
  return false;
}

}  // namespace

std::vector<std::string> diagnostic_columns(const Simulation& sim) {
  const int nsolids = int(sim.solids().size());
  std::vector<std::string> c;
  for (const Column& col : kColumns)
    if (!col.needs_solids || nsolids > 0) c.push_back(col.name);
  if (sim.implicit_velocity())
    for (const Column& col : kImplicitColumns) c.push_back(col.name);
  if (sim.config().solid_picard > 0)
    for (const Column& col : kPicardColumns) c.push_back(col.name);
  for (const auto& comp : sim.components())  // solver/model/component.hpp, in the order added
    for (const std::string& name : comp->columns()) c.push_back(name);
  return c;
}

std::vector<double> diagnostic_values(const Simulation& sim, double last_dt, double wall_s) {
  const int nsolids = int(sim.solids().size());
  const RowState r{sim, last_dt, wall_s, sim.kinetic_energy(), sim.solid_diagnostics()};
  std::vector<double> v;
  for (const Column& col : kColumns)
    if (!col.needs_solids || nsolids > 0) v.push_back(col.value(r));
  if (sim.implicit_velocity())
    for (const Column& col : kImplicitColumns) v.push_back(col.value(r));
  if (sim.config().solid_picard > 0)
    for (const Column& col : kPicardColumns) v.push_back(col.value(r));
  for (const auto& comp : sim.components()) comp->values(sim, v);
  return v;
}

}  // namespace refmap

namespace refmap {

std::vector<std::string> solid_columns(const Simulation& sim) {
  if (sim.solids().empty()) return {};
  std::vector<std::string> c{"step", "time", "solid"};
  for (const SolidColumn& col : kSolidColumns) c.push_back(col.name);
  if (any_force(sim))
    for (const SolidColumn& col : kForceColumns) c.push_back(col.name);
  if (any_body(sim))
    for (const SolidColumn& col : kBodyColumns) c.push_back(col.name);
  return c;
}

std::vector<std::vector<double>> solid_values(const Simulation& sim) {
  const int nsolids = int(sim.solids().size());
  if (nsolids == 0) return {};
  const RowState r{sim, 0.0, 0.0, 0.0, sim.solid_diagnostics()};  // no global column is read
  const bool forces = any_force(sim), bodies = any_body(sim);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(nsolids));
  for (int k = 0; k < nsolids; ++k) {
    std::vector<double>& v = rows[std::size_t(k)];
    v = {double(sim.steps()), sim.time(), double(k)};
    for (const SolidColumn& col : kSolidColumns) v.push_back(col.value(r, k));
    if (forces)
      for (const SolidColumn& col : kForceColumns) v.push_back(has_force(sim, k) ? col.value(r, k) : nan);
    if (bodies)
      for (const SolidColumn& col : kBodyColumns) v.push_back(is_body(sim, k) ? col.value(r, k) : nan);
  }
  return rows;
}

}  // namespace refmap
