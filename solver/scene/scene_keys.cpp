// The scene-file schema (see solver/scene/scene_keys.hpp). One entry per key; the order here is
// the order of the reference in scenes/README.md. The optional components' keys are in
// their own files (solver/model/component_kind.hpp); a comment marks where each goes.
#include "solver/scene/scene_keys.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "solver/model/component_kind.hpp"
#include "solver/model/config.hpp"
#include "solver/scene/option_names.hpp"
#include "solver/scene/suspension.hpp"

namespace refmap {

namespace {

/// A float as a scene file would write it: 1 -> "1.0", 0.5 -> "0.5", 1e-8 -> "1e-8".
std::string float_text(double v) {
  std::string s = key_number_text(v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// the entry builders (solver/io/key_def.hpp)
using namespace keys;

std::vector<KeyDef> build_keys() {
  const Config d;  // the defaults (solver/model/config.hpp)
  const PoissonOptions& dp = d.poisson;
  const InitialVelocity& di = d.init;
  const SideBc db;
  const SuspensionSpec dsu;
  using KT = KeyType;
  std::vector<KeyDef> k = {
      shown_default(str("", "name", std::nullopt,
                        "name of the scene; the default output directory is `out/<name>`. Must not contain `/`"),
                    "file stem"),

      num("domain", "x0", d.grid.x0, {}, "x of the lower-left corner"),
      num("domain", "y0", d.grid.y0, {}, "y of the lower-left corner"),
      num("domain", "lx", std::nullopt, gt(0), "width of the domain"),
      shown_default(num("domain", "ly", std::nullopt, gt(0),
                        "height of the domain; cells are square, so it must equal `lx * ny / nx` (to 1e-12 "
                        "relative) and may be omitted"),
                    "`lx * ny / nx`"),

      integer("grid", "nx", std::nullopt, ge(8, "the multigrid solver needs at least 8 cells per direction"),
              "cells in x"),
      integer("grid", "ny", std::nullopt, ge(8, "the multigrid solver needs at least 8 cells per direction"),
              "cells in y"),

      num("fluid", "density", d.rho_f, gt(0), "fluid density rho_f"),
      num("fluid", "viscosity", std::nullopt, ge(0),
          "fluid dynamic viscosity mu_f (the kinematic viscosity is `viscosity / density`)"),

      key("boundary", "left", KT::Boundary, {}, {}, "boundary condition of the side x = x0"),
      key("boundary", "right", KT::Boundary, {}, {}, "boundary condition of the side x = x0 + lx"),
      key("boundary", "bottom", KT::Boundary, {}, {}, "boundary condition of the side y = y0"),
      key("boundary", "top", KT::Boundary, {}, {}, "boundary condition of the side y = y0 + ly"),

      choice<BcType>("boundary.side", "type", std::nullopt, "kind of the boundary condition"),
      only(num("boundary.side", "velocity", std::nullopt, {},
               "tangential wall speed U (u on bottom/top, v on left/right); the normal velocity is 0"),
           "type", {"moving_wall"}),
      only(shown_default(num("boundary.side", "omega", std::nullopt, gt(0),
                             "oscillating wall: speed U sin(omega t + phase)"),
                         "steady wall"),
           "type", {"moving_wall"}),
      only(num("boundary.side", "phase", db.phase, {}, "phase of the oscillating wall (needs `omega`)"), "type",
           {"moving_wall"}),
      only(shown_default(key("boundary.side", "u", KT::Expression, {}, {},
                             "x velocity u(x, y, t) on the side (see *Expressions*); required on the left and "
                             "right sides (the normal velocity)"),
                         "`0`"),
           "type", {"inflow"}),
      only(shown_default(key("boundary.side", "v", KT::Expression, {}, {},
                             "y velocity v(x, y, t) on the side; required on the bottom and top sides"),
                         "`0`"),
           "type", {"inflow"}),

      choice<InitialKind>("initial", "velocity", di.kind, "initial velocity field"),
      only(num("initial", "u", di.u, {}, "constant x velocity"), "velocity", {"uniform"}),
      only(num("initial", "v", di.v, {}, "constant y velocity"), "velocity", {"uniform"}),
      only(num("initial", "amplitude", di.amplitude, {},
               "A in u = A sin(k(x-x0)) cos(k(y-y0)), v = -A cos(k(x-x0)) sin(k(y-y0))"),
           "velocity", {"taylor_green"}),
      only(num("initial", "wavenumber", di.wavenumber, ge(0, "0 means 2 pi / domain.lx"), "k; 0 means 2 pi / lx"),
           "velocity", {"taylor_green"}),
      only(key("initial", "u_expr", KT::Expression, {}, {},
               "u(x, y, t) (see *Expressions*); checked when the scene is loaded"),
           "velocity", {"expression"}),
      only(key("initial", "v_expr", KT::Expression, {}, {},
               "v(x, y, t) (see *Expressions*); checked when the scene is loaded"),
           "velocity", {"expression"}),

      vec2("gravity", "g", std::array<double, 2>{d.gx, d.gy},
           "gravitational acceleration (gx, gy), e.g. `[0.0, -9.81]`; acts on rho - rho_f"),

      num("time", "start", d.t_start, {}, "initial time"),
      num("time", "end", std::nullopt, text_range("> start"), "final time"),
      num("time", "cfl", d.cfl, in(0, true, 2.5, false),
          "advective Courant number: dt (abs(u) + abs(v))_max / dx <= cfl"),
      num("time", "viscous_safety", d.visc_safety, in(0, true, 1, false),
          "fraction of the explicit viscous limit rho dx^2 / (6 mu) (the full-stress operator's stability bound)"),
      num("time", "dt", d.dt_fixed, ge(0, "0 = adaptive"),
          "fixed time step if > 0 (0: adaptive from the limits); refused above the explicit viscous limit "
          "(time.viscous = \"explicit\") or a solid's limit at rest (time.solid_stress = \"explicit\")"),
      shown_default(num("time", "dt_max", d.dt_max, gt(0), "upper bound of the adaptive time step"), "unlimited"),
      integer("time", "max_steps", d.max_steps, ge(0, "0 = unlimited"), "stop after this many steps (0: unlimited)"),
      num("time", "steady_tol", d.steady_tol, ge(0, "0 = off"),
          "stop when max abs(u^{n+1} - u^n) / dt < steady_tol (0: off)"),
      choice<ViscousTime>("time", "viscous", d.viscous_time,
                          "`\"explicit\"`: forward Euler (eq. 5.2; dt <= viscous_safety rho dx^2 / (6 mu)); "
                          "`\"implicit\"`: backward Euler in the compact part, solved by the pressure solver's "
                          "method with a sink term; no viscous time-step limit (docs/implicit.md)"),
      num("time", "rhie_chow_dt", d.rhie_chow_dt, ge(0, "0 = dt"),
          "the time tau of the Rhie-Chow term of the face velocities (eq. 5.3): a steady state's face "
          "velocities are <u> + tau (<G_c> - G_f), so a fixed tau keeps it from moving with dt; the "
          "projection then corrects the faces by tau grad dp and the pressure relaxes by dt / tau per step "
          "(tau <= 4 dt advised; 0: tau = dt, Algorithm 1; docs/method.md)"),
      choice<Splitting>("time", "splitting", d.splitting,
                        "`\"split\"`: Algorithm 1 (the advection and the viscous step act without the pressure "
                        "gradient, the projection applies it whole: a steady state moves with dt); `\"increment\"`: "
                        "the advection carries the last pressure gradient and viscous force as sources, the "
                        "viscous step only their change, so a steady state does not depend on dt "
                        "(docs/method.md, \"Splitting\")"),
      choice<SolidStressTime>("time", "solid_stress", d.solid_time,
                              "`\"explicit\"`: dt <= solid_cfl dx sqrt(rho_s / G); `\"semi_implicit\"`: an "
                              "implicit isotropic term eta = k G dt (1 - H) added and its explicit counterpart "
                              "subtracted (first order in dt); `\"upper_convected\"`: the stress increment 2 mu_s dt (L b + b L^T) "
                              "of the new velocity (upper-convected rate of b, blended with 1 - H) implicit in the "
                              "velocity solve, its explicit counterpart subtracted (first order in dt); no solid "
                              "time-step limit (docs/implicit.md)"),
      choice<ElasticCoupling>("time", "elastic_coupling", d.elastic_coupling,
                              "order of the explicit solid stress and the ξ advection in a step: "
                              "`\"symplectic_euler\"`, Algorithm 1 (ξ advected with the step's starting velocity, then "
                              "the new ξ's stress applied whole: the velocity runs half a step ahead of ξ and the total "
                              "energy is off by O(dt)); `\"verlet\"`, velocity Verlet (ξ advected with the midpoint velocity "
                              "u + dt a / 2, a the last step's acceleration, and the mean of the old and new ξ's stress "
                              "forces applied: second order, no extra stress evaluation); `\"verlet\"` needs time.solid_stress = "
                              "\"explicit\" and solids.xi_velocity = \"face\": given with others it is refused, "
                              "as the default it falls back to `\"symplectic_euler\"` there (docs/method.md, \"Time step\")"),
      boolean("time", "verlet_project_drift", d.verlet_project_drift,
              "with elastic_coupling = `\"verlet\"`: project the drift's stress correction (F^n - F^{n-1}) dt / (4 rho) "
              "onto divergence-free face velocities (one more solve of the pressure operator per step, to 1e-6 "
              "relative) so that xi is carried by a divergence-free velocity; unprojected it compresses thin solids' "
              "maps (results/fsi.md, \"What compresses the flag's map\")"),
      // time.solid_implicit_k ... time.implicit_tol: solver/components/implicit_velocity_step.cpp
      // (implicit_velocity_step_kind)

      choice<FlowMode>("solver", "flow", d.flow,
                       "`\"solve\"`: the Navier-Stokes equations; `\"prescribed\"`: no flow solve, the initial "
                       "velocity (e.g. an expression of t) is imposed at every step and only the solids move"),
      choice<FluxScheme>("solver", "advection", d.advection,
                         "momentum advection scheme: second-order central or Superbee-limited upwind (TVD)"),
      choice<JumpFlux>("solver", "density_jump_flux", d.jump_flux,
                       "with `advection = \"central\"` and a density contrast: the momentum's face values where "
                       "the density varies in the flux stencil, Superbee-limited (stable to ratio 100, "
                       "docs/density_ratio.md) or `\"same\"` central ones (the paper's; blows up from ratio 100)"),
      choice<PoissonMethod>("solver", "poisson", dp.method,
                            "pressure solver: multigrid, conjugate gradients, or multigrid-preconditioned CG"),
      choice<MgCycle>("solver", "cycle", dp.cycle, "multigrid cycle"),
      choice<MgSmoother>("solver", "smoother", dp.smoother,
                         "multigrid smoother: red-black Gauss-Seidel or weighted Jacobi"),
      choice<MgCoarseOperator>("solver", "coarse_operator", dp.coarse_operator,
                               "multigrid coarse coefficients: restriction-weighted mean of beta, or fine faces "
                               "in series normal to the coarse face, or Galerkin P^T L P with operator-dependent "
                               "prolongation (9-point coarse levels; robust to density contrast)"),
      integer("solver", "pre_smooth", dp.pre_smooth, in(1, false, 100, false),
              "smoothing sweeps before coarse-grid correction"),
      integer("solver", "post_smooth", dp.post_smooth, in(1, false, 100, false),
              "smoothing sweeps after coarse-grid correction"),
      num("solver", "tol", dp.tol, in(0, true, 1, true),
          "relative residual norm(r) / norm(rhs) at which the pressure solve stops"),
      integer("solver", "max_iter", dp.max_iter, in(1, false, 1000000, false), "iteration limit of the pressure solve"),
      integer("solver", "coarse_cells", dp.coarse_cells, in(1, false, 1000000, false),
              "multigrid stops coarsening at or below this many cells"),

      num("output", "interval", d.output_interval, ge(0, "0 = first and last frame only"),
          "simulated time between VTK frames (0: first and last frame only)"),
      boolean("output", "vtk", d.write_vtk, "write VTK frames (`.vti` files and a `.pvd` series for ParaView)"),
      boolean("output", "checkpoint", d.checkpoint_frames,
              "write a checkpoint (`checkpoint.bin`, for `refmap resume`) with every VTK frame"),
      num("output", "checkpoint_minutes", d.checkpoint_minutes, ge(0, "0 = not by wall time"),
          "also write a checkpoint every this many wall minutes (`--checkpoint-minutes` overrides)"),
      integer("output", "diagnostics_every", d.diagnostics_every, ge(1), "steps between rows of `diagnostics.csv`"),
      // output.wall_stress: solver/components/wall_stress.cpp (wall_stress_kind)
      // output.body_force: solver/components/control_volume_forces.cpp (control_volume_forces_kind)
      num("output", "log_interval", d.log_interval_s, gt(0, "seconds"),
          "wall seconds between progress log lines when stderr is not a terminal"),

      str("probe", "name", std::nullopt, "unique name of letters, digits and `_` (names the output file)"),
      [] {  // output field names, not a physics option
        KeyDef f = key("probe", "field", KT::Choice, {}, {}, "the sampled cell field");
        f.choices = {"u", "v", "p", "speed", "vorticity", "density"};
        return f;
      }(),
      vec2("probe", "start", std::nullopt, "first point (x, y), inside the domain (walls included)"),
      vec2("probe", "end", std::nullopt, "last point (x, y), inside the domain (walls included)"),
      integer("probe", "points", std::nullopt, in(2, false, 10000000, false), "number of samples"),

      // [[tracers]]: solver/components/tracers.cpp (tracers_kind)

      // [solids] and [[solid]]: solver/components/solids_keys.cpp (solids_kind); a rigid body's
      // keys in [[solid]]: solver/components/rigid_bodies.cpp (rigid_bodies_kind)
      // solid.markers, solid.boundary_markers: solver/components/markers.cpp (markers_kind)

      // solid.actuation and its table: solver/components/actuation.cpp (actuation_kind)

      integer("suspension", "count", dsu.count, ge(0, "0: from `area_fraction`"),
              "number of particles; give this or `area_fraction`"),
      num("suspension", "area_fraction", dsu.area_fraction, in(0, false, 0.9069, false),
          "sum of the particle areas over the domain's area; the count that comes closest is placed (within half "
          "a particle's area); give this or `count`"),
      num("suspension", "radius", std::nullopt, gt(0), "particle radius (of the first size)"),
      num("suspension", "radius2", dsu.radius2, ge(0, "0: one size"), "radius of the second size (0: one size)"),
      num("suspension", "fraction2", dsu.fraction2, in(0, false, 1, false),
          "share of the particles, by number, of the second size"),
      num("suspension", "aspect", dsu.aspect, ge(1),
          "a / b: ellipses of the disc's area (a = r sqrt(aspect), b = r / sqrt(aspect)) at random angles; 1: discs"),
      integer("suspension", "seed", dsu.seed, ge(0), "seed of the placement: the same seed gives the same particles"),
      num("suspension", "gap", dsu.gap, ge(0),
          "least distance between particle surfaces, and from a wall, in units of `radius` (across the periodic "
          "sides too)"),
      integer("suspension", "attempts", dsu.attempts, ge(1),
              "random positions tried per particle before the placement gives up (exit 2 with the fraction reached)"),
      str("suspension", "name", dsu.name, "particle i is the solid named <name><i>"),
      num("suspension", "mu_s", std::nullopt, ge(0), "each particle's `mu_s` (shear modulus G = 2 mu_s)"),
      num("suspension", "density", std::nullopt, gt(0), "each particle's `density`"),
      num("suspension", "viscosity", dsu.viscosity, ge(0), "each particle's (Kelvin-Voigt) `viscosity`"),


      // [contact]: solver/components/contact_component.cpp (contact_kind)
  };
  return k;
}

std::string join(const std::vector<std::string>& v, const std::string& sep, const std::string& last_sep,
                 const char* quote) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += i + 1 == v.size() ? last_sep : sep;
    s += quote + v[i] + quote;
  }
  return s;
}

}  // namespace

namespace {

/// The core's tables (the components' are merged in by scene_catalog).
std::vector<TableDef> core_tables() {
  return {
      {"", "Top level", false, false, false, ""},
      {"domain", "`[domain]`", true, false, false, ""},
      {"grid", "`[grid]`", true, false, false, ""},
      {"fluid", "`[fluid]`", true, false, false, ""},
      {"boundary", "`[boundary]`", true, false, false,
       "All four sides are required; each is a string or an inline table (see *Boundary conditions* below)."},
      {"boundary.side", "`boundary.<side>` as an inline table", false, false, true,
       "`{ type = \"moving_wall\", velocity = U }` or `{ type = \"inflow\", u = \"...\", v = \"...\" }`; "
       "the other kinds take no further keys. An inflow needs an `\"outflow\"` side (p = 0, zero normal "
       "derivative of the velocity); see docs/boundaries.md."},
      {"initial", "`[initial]`", false, false, false,
       "A key of another kind (e.g. `u` with `velocity = \"zero\"`) is an error."},
      {"gravity", "`[gravity]`", false, false, false, ""},
      {"time", "`[time]`", true, false, false, ""},
      {"solver", "`[solver]`", false, false, false, ""},
      {"output", "`[output]`", false, false, false, ""},
      {"probe", "`[[probe]]`", false, true, false, ""},
      // [[tracers]]: solver/components/tracers.cpp
      // [solids], [[solid]]: solver/components/solids_keys.cpp
      // solid.actuation: solver/components/actuation.cpp
      {"suspension", "`[suspension]`", false, false, false,
       "Particles at random positions without overlap (random sequential addition, solver/scene/suspension.hpp), "
       "expanded at load into soft `[[solid]]` tables named `<name><i>` (circles, or ellipses with `aspect` > 1) "
       "that start with the fluid's velocity. Deterministic from `seed`. A fraction the placement cannot reach "
       "in `attempts` tries per particle is an error (exit 2) naming the fraction reached."},
      // [contact]: solver/components/contact_component.cpp
  };
}

/// The core's tables and keys with every component kind's merged in, where each says
/// (solver/model/component_kind.hpp).
KeyCatalog with_components(std::vector<TableDef> tables, std::vector<KeyDef> all) {
  for (const ComponentKind& kind : component_kinds()) {
    for (const auto& t : kind.tables) {
      auto it = std::find_if(tables.begin(), tables.end(), [&](const TableDef& d) { return d.name == t.after; });
      tables.insert(it == tables.end() ? it : it + 1, t.def);
    }
    std::size_t pos = all.size();  // after the kind's anchor key, in a table of the core
    for (std::size_t i = 0; i < all.size(); ++i)
      if (!kind.after.empty() && all[i].dotted() == kind.after) pos = i + 1;
    for (const KeyDef& k : kind.keys) {
      if (pos > 0 && all[pos - 1].table == k.table)  // (pos == all.size(): the anchor is the last key)
        all.insert(all.begin() + std::ptrdiff_t(pos++), k);
      else
        all.push_back(k);
    }
  }
  // grouped by table in the tables' order (`refmap keys` lists them in this order; the
  // core's entries already are), each table's keys in the order above
  auto table_index = [&](const KeyDef& k) {
    for (std::size_t i = 0; i < tables.size(); ++i)
      if (tables[i].name == k.table) return i;
    return tables.size();
  };
  std::stable_sort(all.begin(), all.end(),
                   [&](const KeyDef& a, const KeyDef& b) { return table_index(a) < table_index(b); });
  return {std::move(tables), std::move(all)};
}

}  // namespace

const KeyCatalog& scene_catalog() {
  static const KeyCatalog c = with_components(core_tables(), build_keys());
  return c;
}

const std::vector<TableDef>& scene_tables() { return scene_catalog().tables; }

const std::vector<KeyDef>& scene_keys() { return scene_catalog().keys; }

const KeyDef& scene_key(const std::string& table, const std::string& name) { return scene_catalog().key(table, name); }

std::vector<std::string> scene_key_names(const std::string& table) { return scene_catalog().key_names(table); }

std::vector<std::string> scene_top_level_names() { return scene_catalog().top_level_names(); }

std::string key_type_text(const KeyDef& k) {
  std::string t;
  switch (k.type) {
    case KeyType::Float: t = "float"; break;
    case KeyType::Integer: t = "integer"; break;
    case KeyType::Bool: t = "boolean"; break;
    case KeyType::String: t = "string"; break;
    case KeyType::Choice: {
      std::vector<std::string> q;
      for (const auto& c : k.choices) q.push_back("`\"" + c + "\"`");
      return join(q, ", ", " or ", "");
    }
    case KeyType::Vec2: t = "[float, float]"; break;
    case KeyType::Points: t = "[[float, float], ...]"; break;
    case KeyType::InlineTable: t = "inline table"; break;
    case KeyType::Expression: t = "expression (string or number)"; break;
    case KeyType::Boundary: t = "boundary condition"; break;
  }
  const std::string r = k.range.phrase();
  return r.empty() ? t : t + " " + r;
}

std::string key_default_text(const KeyDef& k) {
  if (!k.default_text.empty()) return k.default_text;
  struct V {
    const KeyDef& k;
    std::string operator()(std::monostate) const { return "required"; }
    std::string operator()(double v) const { return "`" + float_text(v) + "`"; }
    std::string operator()(long v) const { return "`" + std::to_string(v) + "`"; }
    std::string operator()(bool v) const { return v ? "`true`" : "`false`"; }
    std::string operator()(const std::string& s) const { return "`\"" + s + "\"`"; }
    std::string operator()(const std::array<double, 2>& a) const {
      return "`[" + float_text(a[0]) + ", " + float_text(a[1]) + "]`";
    }
  };
  return std::visit(V{k}, k.def);
}

namespace {
std::string only_text(const KeyDef& k) {
  if (k.only.empty()) return "";
  std::vector<std::string> q;
  for (const auto& o : k.only) q.push_back("`" + o + "`");
  return join(q, ", ", " or ", "") + " only: ";
}
}  // namespace

std::string scene_keys_markdown() {
  std::ostringstream o;
  bool first = true;
  for (const auto& t : scene_tables()) {
    if (!first) o << "\n";
    first = false;
    o << "### " << t.heading;
    if (!t.name.empty() && !t.nested)
      o << " (" << (t.required ? "required" : "optional") << (t.repeatable ? ", repeatable" : "") << ")";
    o << "\n\n";
    if (!t.intro.empty()) o << t.intro << "\n\n";
    o << "| key | type | default | meaning |\n| --- | --- | --- | --- |\n";
    for (const auto& k : scene_keys())
      if (k.table == t.name)
        o << "| `" << k.name << "` | " << key_type_text(k) << " | " << key_default_text(k) << " | " << only_text(k)
          << k.description << " |\n";
  }
  return o.str();
}

std::string scene_keys_text() {
  std::ostringstream o;
  for (const auto& k : scene_keys()) {
    std::string name = k.table == "boundary.side" ? "boundary.<side>." + k.name : k.dotted();
    auto plain = [](std::string t) {
      std::string r;
      for (char c : t)
        if (c != '`') r += c;
      return r;
    };
    o << name << "  (" << plain(key_type_text(k)) << "; default " << plain(key_default_text(k)) << ")  "
      << plain(only_text(k) + k.description) << "\n";
  }
  return o.str();
}

}  // namespace refmap
