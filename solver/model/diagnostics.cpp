#include "solver/model/diagnostics.hpp"

#include <algorithm>
#include <cstring>
#include <functional>
#include <limits>

#include "solver/model/rigid_body.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {

namespace {

/// What the columns of one row are computed from.
struct RowState {
  const Simulation& sim;
  double last_dt;
  double wall_s;
  double kinetic_energy;  ///< computed once for the row
};

struct Column {
  const char* name;
  double (*value)(const RowState&);
};

// clang-format off
const Column kColumns[] = {
    {"step",               [](const RowState& r) { return double(r.sim.steps()); }},
    {"time",               [](const RowState& r) { return r.sim.time(); }},
    {"dt",                 [](const RowState& r) { return r.last_dt; }},
    {"kinetic_energy",     [](const RowState& r) { return r.kinetic_energy; }},
    {"max_div_face",       [](const RowState& r) { return r.sim.max_face_divergence(); }},
    {"poisson_iterations", [](const RowState& r) { return double(r.sim.last_poisson_iterations()); }},
    {"poisson_residual",   [](const RowState& r) { return r.sim.last_poisson_residual(); }},
    {"wall_time",          [](const RowState& r) { return r.wall_s; }},
};
// (then, with solids, elastic_energy and total_energy: the solids' component's columns, placed
// right after wall_time, solver/components/solids.hpp; contact's after those)

/// The built-in columns of solids.csv (one row per solid and output step), after step, time
/// and solid and the solids' component's own (area, cx, cy, u, v, sigma_max, placed after
/// "solid": solver/components/solids.hpp).
struct SolidColumn {
  const char* name;
  double (*value)(const RowState&, int k);
};

/// The force the columns below report (output.body_force): a rigid body's direct forcing,
/// or every body's control-volume balance, whichever component measures it
/// (Simulation::solid_load); only called for a solid that has one (has_force).
const BodyLoad& body_load(const Simulation& sim, int k) { return *sim.solid_load(k); }

/// solids.csv columns for every solid k with a force (a rigid solid, motion != "free";
/// with output.body_force = "control_volume" also a free soft solid, not a clamped one):
/// the fluid's force and torque on it (drag and lift for a flow along x); nan on the
/// rows of the other solids.
const SolidColumn kForceColumns[] = {
    {"fx",     [](const RowState& r, int k) { return body_load(r.sim, k).fx; }},
    {"fy",     [](const RowState& r, int k) { return body_load(r.sim, k).fy; }},
    {"torque", [](const RowState& r, int k) { return body_load(r.sim, k).torque; }},
};
// then, for a rigid solid, its rotation: the rigid bodies' component's columns
// (solver/components/rigid_bodies.hpp), after "torque"
// clang-format on

// (then, with the implicit velocity step, its column implicit_iterations: the component's,
// placed right after the columns above, solver/components/implicit_velocity_step.hpp)

/// Written after those, only with time.solid_picard_iterations > 0 (solver/model/solid_picard.cpp):
/// the last iteration's relative velocity change, the multigrid cycles of all the step's passes
/// and, of them, the velocity solves' cycles.
const Column kPicardColumns[] = {
    {"picard_change", [](const RowState& r) { return r.sim.picard_change(); }},
    {"picard_cycles", [](const RowState& r) { return double(r.sim.picard_cycles()); }},
    {"picard_velocity_cycles", [](const RowState& r) { return double(r.sim.picard_velocity_cycles()); }},
};

bool has_force(const Simulation& sim, int k) { return sim.solid_load(k) != nullptr; }

bool any_force(const Simulation& sim) {
  for (int k = 0; k < int(sim.solids().size()); ++k)
    if (has_force(sim, k)) return true;
  return false;
}

/// The parts of a row in order: the components whose `after` names `lead` (the last of the
/// row's fixed leading columns, if any), then every built-in column (as `builtin` takes them),
/// each followed by the components whose `after` names it, each of those followed in turn by
/// the components whose `after` names one of its own columns (`names`), then the components
/// placed after none (solver/model/component.hpp: columns_after, solid_columns_after), in the
/// order added.
template <class Builtin, class Comp>
void in_row_order(const Simulation& sim, const std::vector<const char*>& builtin_names, Builtin&& builtin,
                  const char* (Component::*after)() const, std::vector<std::string> (Component::*names)() const,
                  Comp&& comp, const char* lead = nullptr) {
  std::vector<const Component*> placed;
  const auto is_placed = [&](const Component* c) { return std::find(placed.begin(), placed.end(), c) != placed.end(); };
  const std::function<void(const char*)> follow = [&](const char* column) {
    for (const auto& c : sim.components()) {
      const char* a = ((*c).*after)();
      if (!a || std::strcmp(a, column) != 0 || is_placed(c.get())) continue;
      comp(*c);
      placed.push_back(c.get());
      for (const std::string& own : ((*c).*names)()) follow(own.c_str());
    }
  };
  if (lead) follow(lead);
  for (std::size_t n = 0; n < builtin_names.size(); ++n) {
    builtin(n);
    follow(builtin_names[n]);
  }
  for (const auto& c : sim.components())
    if (!is_placed(c.get())) comp(*c);
}

/// The built-in diagnostics.csv columns of this run, in order.
std::vector<const Column*> global_columns(const Simulation& sim) {
  std::vector<const Column*> cols;
  for (const Column& col : kColumns) cols.push_back(&col);
  if (sim.config().solid_picard > 0)
    for (const Column& col : kPicardColumns) cols.push_back(&col);
  return cols;
}

template <class C>
std::vector<const char*> names_of(const std::vector<const C*>& cols) {
  std::vector<const char*> n;
  for (const C* c : cols) n.push_back(c->name);
  return n;
}

}  // namespace

std::vector<std::string> diagnostic_columns(const Simulation& sim) {
  const auto cols = global_columns(sim);
  std::vector<std::string> c;
  in_row_order(
      sim, names_of(cols), [&](std::size_t n) { c.push_back(cols[n]->name); }, &Component::columns_after,
      &Component::columns, [&](const Component& comp) {
        for (const std::string& name : comp.columns()) c.push_back(name);
      });
  return c;
}

std::vector<double> diagnostic_values(const Simulation& sim, double last_dt, double wall_s) {
  const auto cols = global_columns(sim);
  const RowState r{sim, last_dt, wall_s, sim.kinetic_energy()};
  std::vector<double> v;
  in_row_order(
      sim, names_of(cols), [&](std::size_t n) { v.push_back(cols[n]->value(r)); }, &Component::columns_after,
      &Component::columns, [&](const Component& comp) { comp.values(sim, v); });
  return v;
}

}  // namespace refmap

namespace refmap {

namespace {

/// The built-in per-solid columns of this run, in order: the loads, only for the solids
/// with a force (nan on the other rows).
struct SolidPart {
  const SolidColumn* col;
};

std::vector<SolidPart> solid_parts(const Simulation& sim) {
  std::vector<SolidPart> parts;
  if (any_force(sim))
    for (const SolidColumn& col : kForceColumns) parts.push_back({&col});
  return parts;
}

std::vector<const char*> names_of(const std::vector<SolidPart>& parts) {
  std::vector<const char*> n;
  for (const SolidPart& p : parts) n.push_back(p.col->name);
  return n;
}

}  // namespace

std::vector<std::string> solid_columns(const Simulation& sim) {
  if (sim.solids().empty()) return {};
  std::vector<std::string> c{"step", "time", "solid"};
  const auto parts = solid_parts(sim);
  in_row_order(
      sim, names_of(parts), [&](std::size_t n) { c.push_back(parts[n].col->name); }, &Component::solid_columns_after,
      &Component::solid_columns,
      [&](const Component& comp) {
        for (const std::string& name : comp.solid_columns()) c.push_back(name);
      },
      "solid");
  return c;
}

std::vector<std::vector<double>> solid_values(const Simulation& sim) {
  const int nsolids = int(sim.solids().size());
  if (nsolids == 0) return {};
  const RowState r{sim, 0.0, 0.0, 0.0};  // no global column is read
  const auto parts = solid_parts(sim);
  const auto names = names_of(parts);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(nsolids));
  for (int k = 0; k < nsolids; ++k) {
    std::vector<double>& v = rows[std::size_t(k)];
    v = {double(sim.steps()), sim.time(), double(k)};
    const bool force = has_force(sim, k);
    in_row_order(
        sim, names,
        [&](std::size_t n) {
          v.push_back(force ? parts[n].col->value(r, k) : nan);
        },
        &Component::solid_columns_after, &Component::solid_columns,
        [&](const Component& comp) { comp.solid_values(sim, k, v); }, "solid");
  }
  return rows;
}

}  // namespace refmap
