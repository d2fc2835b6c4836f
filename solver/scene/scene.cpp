// Scene files: TOML -> Config. See scenes/README.md for the key reference.
//
// Structure: the schema. Every table is read through the generic TomlTable
// (solver/io/toml_reader.hpp) that knows its dotted prefix and its entry in the key table
// (solver/scene/scene_keys.cpp), hands out typed values with the table's defaults, type, range
// and choice checks, and rejects keys that are not in the table. Adding a key = one entry
// in scene_keys.cpp plus one getter call here; adding a table = one TableDef plus a
// parse_xxx. Checks that involve several keys stay here, next to the getters. The components
// parse their own keys (solver/model/component_kind.hpp; parse_components below): the solids'
// [solids] and [[solid]] (solver/components/solids_keys.cpp, with the rigid bodies' keys of
// solver/components/rigid_bodies.cpp), the implicit step's keys of [time]
// (solver/components/implicit_velocity_step.cpp), and every optional component's.
#include "solver/scene/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string_view>

#include "solver/model/boundary.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/io/expression.hpp"
#include "solver/scene/memory_estimate.hpp"
#include "solver/scene/option_names.hpp"
#include "solver/scene/scene_keys.hpp"
#include "solver/scene/suspension.hpp"
#include "solver/model/shape.hpp"
#include "solver/model/time_step_limits.hpp"
#include "solver/io/toml_reader.hpp"

namespace refmap {

// the generic reader (solver/io/toml_reader.hpp), under the short names the schema uses
using Ctx = TomlContext;
using Table = TomlTable;
using namespace toml_text;

namespace {

// ---------------------------------------------------------------------------------------
// the schema

void parse_domain_grid(const Ctx& ctx, const Table& top, Config& cfg) {
  Table grid(ctx, *top.table("grid", true), "grid", "grid");
  grid.allow();
  const long nx = grid.integer("nx");
  const long ny = grid.integer("ny");
  constexpr long kMax = 1L << 20;
  for (auto [key, n] : {std::pair<const char*, long>{"nx", nx}, {"ny", ny}})  // a sanity limit, not physics
    grid.require(n <= kMax, key, "must be <= " + std::to_string(kMax) + ", got " + std::to_string(n));
  grid.require(double(nx) * double(ny) <= 2.0e9, "ny", "grid too large: nx * ny must be <= 2e9");
  cfg.grid.nx = int(nx);
  cfg.grid.ny = int(ny);

  Table dom(ctx, *top.table("domain", true), "domain", "domain");
  dom.allow();
  cfg.grid.x0 = dom.number("x0");
  cfg.grid.y0 = dom.number("y0");
  const double lx = dom.number("lx");
  const double ly_expected = lx * double(ny) / double(nx);
  if (dom.has("ly")) {
    const double ly = dom.number("ly");
    dom.require(std::fabs(ly - ly_expected) <= 1e-12 * ly_expected, "ly",
                "must equal domain.lx * grid.ny / grid.nx = " + fmt_num(ly_expected) +
                    " (cells must be square, dx = dy), got " + fmt_num(ly));
  }
  cfg.grid.dx = lx / double(nx);
}

void parse_fluid(const Ctx& ctx, const Table& top, Config& cfg) {
  Table f(ctx, *top.table("fluid", true), "fluid", "fluid");
  f.allow();
  cfg.rho_f = f.number("density");
  cfg.mu_f = f.number("viscosity");
}

SideBc parse_side(const Ctx& ctx, const Table& b, const char* side) {
  const std::vector<std::string> kinds = canonical_names<BcType>();
  const toml::node* n = b.node(side);
  if (!n) b.fail_missing(side);
  SideBc bc;
  auto set_kind = [&](const std::string& s, auto&& failer) {
    if (const auto t = parse_option<BcType>(s)) bc.type = *t;
    else
      failer("unknown boundary condition " + dq(s) + suggestion(s, kinds, true) +
             " (expected \"no_slip\", \"free_slip\", \"periodic\", \"outflow\", { type = \"moving_wall\", "
             "velocity = ... } or { type = \"inflow\", u = ..., v = ... })");
  };
  if (auto s = n->as_string()) {
    set_kind(s->get(), [&](const std::string& w) { b.fail(side, w); });
    if (bc.type == BcType::MovingWall)
      b.fail(side, "a moving wall needs a velocity: write { type = \"moving_wall\", velocity = 1.0 }");
    if (bc.type == BcType::Inflow)
      b.fail(side, std::string("an inflow needs its velocity: write { type = \"inflow\", ") +
                       (std::string(side) == "left" || std::string(side) == "right" ? "u = \"...\" }"
                                                                                    : "v = \"...\" }") +
                       " with an expression of x, y and t");
    return bc;
  }
  const toml::table* t = n->as_table();
  if (!t)
    b.fail(side, "expected a boundary condition (\"no_slip\", \"free_slip\", \"periodic\" or { type = \"moving_wall\", "
                 "velocity = ... }), got " + describe(*n));
  Table s(ctx, *t, b.full(side), "boundary.side");
  s.allow();
  set_kind(s.string("type"), [&](const std::string& w) { s.fail("type", w); });
  if (bc.type != BcType::Inflow)
    for (const char* k : {"u", "v"})
      if (s.has(k)) s.fail(k, "only an inflow takes u and v (the velocity on the side)");
  if (bc.type == BcType::Inflow) {
    for (const char* k : {"velocity", "omega", "phase"})
      if (s.has(k)) s.fail(k, "only a moving_wall takes a velocity, omega or phase (an inflow takes u and v)");
    const bool xside = std::string(side) == "left" || std::string(side) == "right";
    const char* normal = xside ? "u" : "v";
    if (!s.has(normal))
      s.fail("type", std::string("an inflow on the ") + side + " side needs its normal velocity `" + normal +
                         "` (an expression of x, y, t)");
    // a plain number is accepted as an expression too (u = 1); an absent component is 0
    for (const char* k : {"u", "v"})
      (std::string(k) == "u" ? bc.inflow_u : bc.inflow_v) = Expression(s.has(k) ? expression_text(s, k) : "0");
    return bc;
  }
  if (bc.type != BcType::MovingWall) {
    for (const char* k : {"velocity", "omega", "phase"})
      if (s.has(k)) s.fail(k, "only a moving_wall takes a velocity, omega or phase");
    return bc;
  }
  bc.velocity = s.number("velocity");
  if (s.has("omega")) {
    bc.oscillating = true;
    bc.omega = s.number("omega");
    bc.phase = s.number("phase");
  } else if (s.has("phase")) {
    s.fail("phase", "phase needs omega (speed = velocity * sin(omega t + phase))");
  }
  return bc;
}

void parse_boundary(const Ctx& ctx, const Table& top, Config& cfg) {
  Table b(ctx, *top.table("boundary", true), "boundary", "boundary");
  b.allow();
  const char* names[4] = {"left", "right", "bottom", "top"};
  for (int s = 0; s < 4; ++s) cfg.bc[s] = parse_side(ctx, b, names[s]);
  for (auto [a, c] : {std::pair<int, int>{Left, Right}, {Bottom, Top}}) {
    const bool pa = cfg.bc[a].type == BcType::Periodic, pc = cfg.bc[c].type == BcType::Periodic;
    if (pa != pc) {
      const int bad = pa ? c : a, good = pa ? a : c;
      b.fail(names[bad], std::string("must be \"periodic\" because boundary.") + names[good] +
                             " is: periodic must be set on both sides of a direction");
    }
  }
  // an inflow without an outflow: the pressure Poisson problem is singular and solvable
  // only if the net inflow vanishes at every instant, which refmap does not check; ask for
  // an outflow side instead (docs/boundaries.md)
  int inflow = -1;
  bool outflow = false;
  for (int s = 0; s < 4; ++s) {
    if (cfg.bc[s].type == BcType::Inflow && inflow < 0) inflow = s;
    outflow = outflow || cfg.bc[s].type == BcType::Outflow;
  }
  if (inflow >= 0 && !outflow)
    b.fail(names[inflow], "an inflow side needs an \"outflow\" side for the fluid to leave through "
                          "(with walls and periodic sides only, the inflow could not be balanced)");
}

void parse_initial(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* t = top.table("initial", false);
  if (!t) return;
  Table in(ctx, *t, "initial", "initial");
  in.allow();
  InitialVelocity& iv = cfg.init;
  iv.kind = in.option<InitialKind>("velocity");
  if (const auto k = in.misplaced("velocity", to_string(iv.kind)))
    in.fail(*k, "only used with initial.velocity = \"" + in.entry(*k).only.front() + "\" (velocity is \"" +
                    to_string(iv.kind) + "\")");
  if (iv.kind == InitialKind::Uniform) {
    iv.u = in.number("u");
    iv.v = in.number("v");
  } else if (iv.kind == InitialKind::TaylorGreen) {
    iv.amplitude = in.number("amplitude");
    iv.wavenumber = in.number("wavenumber");
  } else if (iv.kind == InitialKind::Expression) {
    // a plain number is accepted as an expression too (u_expr = 0)
    auto expr_text = [&](const char* key) {
      const toml::node* n = in.node(key);
      if (n && n->as_integer()) return std::to_string(n->as_integer()->get());
      if (n && n->as_floating_point()) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", n->as_floating_point()->get());
        return std::string(buf);
      }
      return in.string(key);
    };
    iv.u_expr = expr_text("u_expr");
    iv.v_expr = expr_text("v_expr");
    for (const char* k : {"u_expr", "v_expr"}) {
      const std::string& text = std::string(k) == "u_expr" ? iv.u_expr : iv.v_expr;
      try {
        Expression e(text);
        (void)e;
      } catch (const std::invalid_argument& ex) {
        in.fail(k, "invalid expression " + dq(text) + ": " + ex.what());
      }
    }
  }
}

void parse_gravity(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* t = top.table("gravity", false);
  if (!t) return;
  Table g(ctx, *t, "gravity", "gravity");
  g.allow();
  const auto v = g.vec2("g");
  cfg.gx = v[0];
  cfg.gy = v[1];
}

void parse_time(const Ctx& ctx, const Table& top, Config& cfg) {
  Table t(ctx, *top.table("time", true), "time", "time");
  t.allow();
  cfg.t_start = t.number("start");
  cfg.t_end = t.number("end");
  t.require(cfg.t_end > cfg.t_start, "end",
            "must be > time.start = " + fmt_num(cfg.t_start) + ", got " + fmt_num(cfg.t_end));
  cfg.cfl = t.number("cfl");
  cfg.visc_safety = t.number("viscous_safety");
  cfg.dt_fixed = t.number("dt");
  cfg.dt_max = t.number("dt_max");
  cfg.max_steps = t.integer("max_steps");
  cfg.steady_tol = t.number("steady_tol");
  cfg.viscous_time = t.option<ViscousTime>("viscous");
  cfg.splitting = t.option<Splitting>("splitting");
  cfg.rhie_chow_dt = t.number("rhie_chow_dt");
  cfg.solid_time = t.option<SolidStressTime>("solid_stress");
  // the default, "verlet", falls back to symplectic Euler where it does not apply (an
  // implicit solid stress here, xi moved by cell velocities in the solids' check_elastic_coupling,
  // solver/components/solids_keys.cpp);
  // given explicitly it is refused there
  cfg.elastic_coupling = t.option<ElasticCoupling>("elastic_coupling");
  cfg.verlet_project_drift = t.boolean("verlet_project_drift");
  if (!t.has("elastic_coupling") && cfg.solid_time != SolidStressTime::Explicit)
    cfg.elastic_coupling = ElasticCoupling::SymplecticEuler;
  t.require(cfg.elastic_coupling == ElasticCoupling::SymplecticEuler || cfg.solid_time == SolidStressTime::Explicit,
            "elastic_coupling",
            "\"verlet\" needs solid_stress = \"explicit\" (the implicit solid terms are first order anyway)");
  t.require(!cfg.verlet_project_drift || cfg.elastic_coupling == ElasticCoupling::Verlet, "verlet_project_drift",
            "needs elastic_coupling = \"verlet\" (it projects the Verlet drift's correction)");
}

void parse_solver(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* tp = top.table("solver", false);
  if (!tp) return;
  Table s(ctx, *tp, "solver", "solver");
  s.allow();
  PoissonOptions& p = cfg.poisson;
  cfg.flow = s.option<FlowMode>("flow");
  cfg.advection = s.option<FluxScheme>("advection");
  cfg.jump_flux = s.option<JumpFlux>("density_jump_flux");
  p.method = s.option<PoissonMethod>("poisson");
  p.cycle = s.option<MgCycle>("cycle");
  p.smoother = s.option<MgSmoother>("smoother");
  p.coarse_operator = s.option<MgCoarseOperator>("coarse_operator");
  p.pre_smooth = int(s.integer("pre_smooth"));  // ranges of solver/scene/scene_keys.cpp fit an int
  p.post_smooth = int(s.integer("post_smooth"));
  p.tol = s.number("tol");
  p.max_iter = int(s.integer("max_iter"));
  p.coarse_cells = int(s.integer("coarse_cells"));
}

void parse_output(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* tp = top.table("output", false);
  if (!tp) return;
  Table o(ctx, *tp, "output", "output");
  o.allow();
  cfg.output_interval = o.number("interval");
  cfg.write_vtk = o.boolean("vtk");
  cfg.checkpoint_frames = o.boolean("checkpoint");
  cfg.checkpoint_minutes = o.number("checkpoint_minutes");
  const long de = o.integer("diagnostics_every");
  o.require(de <= std::numeric_limits<int>::max(), "diagnostics_every",
            "must be <= " + std::to_string(std::numeric_limits<int>::max()) + ", got " + std::to_string(de));
  cfg.diagnostics_every = int(de);
  cfg.log_interval_s = o.number("log_interval");
}

void parse_probes(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::node* n = top.node("probe");
  if (!n) return;
  const toml::array* arr = n->as_array();
  if (!arr) top.fail("probe", "expected an array of tables ([[probe]] sections), got " + describe(*n));
  const Grid& g = cfg.grid;
  const double tol = 1e-12 * std::max(g.lx(), g.ly());
  std::set<std::string> names;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string prefix = "probe[" + std::to_string(i) + "]";
    const toml::table* t = arr->get(i)->as_table();
    if (!t) ctx.fail(prefix, arr->get(i), "expected a table ([[probe]] section), got " + describe(*arr->get(i)));
    Table p(ctx, *t, prefix, "probe");
    p.allow();
    ProbeSpec spec;
    spec.name = p.string("name");
    bool ok = !spec.name.empty();
    for (char c : spec.name) ok = ok && (std::isalnum((unsigned char)c) || c == '_');
    p.require(ok, "name", "must be a non-empty name of letters, digits and '_' (it names the output file), got " + dq(spec.name));
    p.require(names.insert(spec.name).second, "name", "duplicate probe name " + dq(spec.name));
    spec.field = p.choice("field");
    for (const char* key : {"start", "end"}) {
      const auto xy = p.vec2(key);
      const bool inside = xy[0] >= g.x0 - tol && xy[0] <= g.x0 + g.lx() + tol && xy[1] >= g.y0 - tol &&
                          xy[1] <= g.y0 + g.ly() + tol;
      p.require(inside, key,
                "point [" + fmt_num(xy[0]) + ", " + fmt_num(xy[1]) + "] is outside the domain [" + fmt_num(g.x0) + ", " +
                    fmt_num(g.x0 + g.lx()) + "] x [" + fmt_num(g.y0) + ", " + fmt_num(g.y0 + g.ly()) + "]");
      // snap onto the wall if within round-off of it
      const double x = std::clamp(xy[0], g.x0, g.x0 + g.lx()), y = std::clamp(xy[1], g.y0, g.y0 + g.ly());
      if (std::string(key) == "start") { spec.x0 = x; spec.y0 = y; }
      else { spec.x1 = x; spec.y1 = y; }
    }
    spec.points = int(p.integer("points"));
    cfg.probes.push_back(spec);
  }
}

/// [suspension]: random particles (solver/scene/suspension.hpp), appended to the [[solid]] array
/// of the file as ordinary solid tables before the solids' parser reads them
/// (solver/components/solids_keys.cpp), so every check of a solid (and the overlap check of
/// check_start_state) applies to them too.
void parse_suspension(const Ctx& ctx, toml::table& root, const Table& top, const Config& cfg) {
  const toml::table* tp = top.table("suspension", false);
  if (!tp) return;
  Table s(ctx, *tp, "suspension", "suspension");
  s.allow();
  SuspensionSpec sp;
  sp.count = s.integer("count");
  sp.area_fraction = s.number("area_fraction");
  // the required keys are range-checked where given and reported missing after every other
  // key's own check (a bad value is named before a missing neighbour)
  auto given = [&](const char* k) { return s.has(k) ? s.number(k) : 0.0; };
  sp.radius = given("radius");
  sp.radius2 = s.number("radius2");
  sp.fraction2 = s.number("fraction2");
  sp.aspect = s.number("aspect");
  sp.seed = s.integer("seed");
  sp.gap = s.number("gap");
  sp.attempts = s.integer("attempts");
  sp.name = s.string("name");
  sp.mu_s = given("mu_s");
  sp.density = given("density");
  sp.viscosity = s.number("viscosity");
  for (const char* k : {"radius", "mu_s", "density"})
    if (!s.has(k)) s.fail_missing(k);
  // after every key's own range check
  if ((sp.count > 0) == (sp.area_fraction > 0.0))
    s.fail(s.has("count") ? "count" : "area_fraction",
           "give exactly one of suspension.count (> 0) and suspension.area_fraction (> 0), got count = " +
               std::to_string(sp.count) + " and area_fraction = " + fmt_num(sp.area_fraction));
  const Grid& g = cfg.grid;
  PlacementBox box{g.x0, g.y0, g.lx(), g.ly(), cfg.bc[Left].type == BcType::Periodic,
                   cfg.bc[Bottom].type == BcType::Periodic};
  const char* amount = sp.count > 0 ? "count" : "area_fraction";
  const Placement pl = place_suspension(sp, box);
  if (pl.requested == 0)
    s.fail(amount, "area_fraction = " + fmt_num(sp.area_fraction) + " is less than half a particle's area of the "
                   "domain: no particle to place");
  if (!pl.complete())
    s.fail(amount, "the random placement reached area fraction " + fmt_num(pl.area_fraction(box)) + " (" +
                       std::to_string(pl.particles.size()) + " of " + std::to_string(pl.requested) +
                       " particles) and found no free position for the next one in " + std::to_string(sp.attempts) +
                       " tries (suspension.attempts); random sequential addition of equal discs jams near 0.55, "
                       "and the gap to the walls and between particles (suspension.gap = " + fmt_num(sp.gap) +
                       " radii) lowers that; ask for less, or a smaller gap or radius");
  toml::array* arr = nullptr;
  if (toml::node* n = root.get("solid")) {
    arr = n->as_array();
    if (!arr) top.fail("solid", "expected an array of tables ([[solid]] sections), got " + describe(*n));
  } else {
    arr = root.insert("solid", toml::array{}).first->second.as_array();
  }
  for (std::size_t i = 0; i < pl.particles.size(); ++i) {
    const Particle& p = pl.particles[i];
    toml::table t;
    t.insert("name", sp.name + std::to_string(i));
    if (p.a == p.b) {
      t.insert("shape", "circle");
      t.insert("radius", p.a);
    } else {
      t.insert("shape", "ellipse");
      t.insert("semi_axes", toml::array{p.a, p.b});
      t.insert("angle", p.angle);
    }
    t.insert("center", toml::array{p.x, p.y});
    t.insert("mu_s", sp.mu_s);
    t.insert("density", sp.density);
    t.insert("viscosity", sp.viscosity);
    t.insert("velocity", "fluid");
    arr->push_back(std::move(t));
  }
}


// ---------------------------------------------------------------------------------------
// the state at the start: everything the run would otherwise find only after the output
// directory was made (exit 2 here, before anything is written)

/// The node of solid k's key `key` (for the message position), or the solid's table.
const toml::node* solid_node(const Table& top, std::size_t k, const char* key) {
  const toml::array* arr = top.node("solid")->as_array();
  const toml::table* t = arr->get(k)->as_table();
  const toml::node* n = t->get(key);
  return n ? n : t;
}

void check_start_state(const Ctx& ctx, const Table& top, const Config& cfg) {
  const Grid& g = cfg.grid;
  // 1. the initial (or imposed) velocity expressions must be finite wherever they are
  //    evaluated: cell centres and face centres at the start time
  if (cfg.init.kind == InitialKind::Expression) {
    Table in(ctx, *top.table("initial", true), "initial", "initial");
    for (const char* key : {"u_expr", "v_expr"}) {
      const Expression e(std::string(key) == std::string("u_expr") ? cfg.init.u_expr : cfg.init.v_expr);
      for (int j = 0; j <= g.ny; ++j)
        for (int i = 0; i <= g.nx; ++i)
          for (auto [x, y] : {std::pair{g.xc(std::min(i, g.nx - 1)), g.yc(std::min(j, g.ny - 1))},
                              std::pair{g.xf(i), g.yc(std::min(j, g.ny - 1))},
                              std::pair{g.xc(std::min(i, g.nx - 1)), g.yf(j)}}) {
            const double v = e.eval(x, y, cfg.t_start);
            if (!std::isfinite(v))
              in.fail(key, "evaluates to " + fmt_num(v) + " at x = " + fmt_num(x) + ", y = " + fmt_num(y) +
                               ", t = " + fmt_num(cfg.t_start) + " (it must be finite over the whole grid)");
          }
    }
  }
  // 1b. an inflow profile must be finite along its side (ghost rows included) at the start
  for (int side = 0; side < 4; ++side) {
    const SideBc& bc = cfg.bc[std::size_t(side)];
    if (bc.type != BcType::Inflow) continue;
    const char* names[4] = {"left", "right", "bottom", "top"};
    const bool xside = side == Left || side == Right;
    const double xf = side == Left ? g.x0 : g.x0 + g.lx(), yf = side == Bottom ? g.y0 : g.y0 + g.ly();
    const int n = xside ? g.ny : g.nx;
    for (int k = -Grid::ng; k < n + Grid::ng; ++k)
      for (const Expression* e : {&bc.inflow_u, &bc.inflow_v}) {
        const double x = xside ? xf : g.xc(k), y = xside ? g.yc(k) : yf;
        const double v = e->eval(x, y, cfg.t_start);
        if (!std::isfinite(v))
          ctx.fail(std::string("boundary.") + names[side] + (e == &bc.inflow_u ? ".u" : ".v"),
                   top.table("boundary", true)->get(names[side]),
                   "evaluates to " + fmt_num(v) + " at x = " + fmt_num(x) + ", y = " + fmt_num(y) + ", t = " +
                       fmt_num(cfg.t_start) + " (it must be finite along the whole side)");
      }
  }
  if (cfg.solids.empty()) return;
  // 2. the extrapolated band must fit in the grid
  if (top.has("solids")) {
    Table so(ctx, *top.table("solids", true), "solids", "solids");
    so.require(cfg.solid_opt.band < std::min(g.nx, g.ny), "band",
               "the band (" + fmt_num(cfg.solid_opt.band) + " cells) is wider than the grid (" +
                   std::to_string(g.nx) + " x " + std::to_string(g.ny) + " cells)");
  }
  const Sides sides = face_sides(cfg.bc);
  const double x1 = g.x0 + g.lx(), y1 = g.y0 + g.ly();
  // a solid that does not span a periodic direction may cross its sides (its window then
  // does: solver/model/periodic_window.hpp) but its window -- the band and a margin of 3 cells
  // either side, one more for the rounding to cells (solver/model/solid.cpp) -- must be
  // narrower than the period
  const double reach = (cfg.solid_opt.band + 4.0) * g.dx;
  std::vector<BoundingBox> boxes;
  std::vector<std::unique_ptr<Shape>> shapes;
  for (std::size_t k = 0; k < cfg.solids.size(); ++k) {
    const SolidSpec& sp = cfg.solids[k];
    shapes.push_back(make_shape(sp.shape));
    const BoundingBox bb = shapes.back()->bbox();
    boxes.push_back(bb);
    const char* where = sp.shape.kind == ShapeKind::Tabulated ? "file" : "center";
    const std::string key = "solid[" + std::to_string(k) + "]." + where;
    auto fail = [&](const std::string& what) {
      ctx.fail(key, solid_node(top, k, where), "solid '" + sp.name + "' " + what);
    };
    // 3. inside the walls; 4. spanning a periodic direction or narrower than its period
    struct Axis { double lo, hi, d0, d1; Side s0, s1; const char* name; };
    for (const Axis& a : {Axis{bb.xmin, bb.xmax, g.x0, x1, Left, Right, "x"},
                          Axis{bb.ymin, bb.ymax, g.y0, y1, Bottom, Top, "y"}}) {
      switch (sides[a.s0]) {
        // a solid starts inside an inflow or outflow side like inside a wall (it may leave
        // through an outflow later: docs/boundaries.md)
        case FaceKind::Inflow:
        case FaceKind::Outflow:
        case FaceKind::Wall:
          if (a.lo < a.d0 || a.hi > a.d1)
            fail(std::string("does not fit inside the walls: it spans ") + a.name + " = [" + fmt_num(a.lo) + ", " +
                 fmt_num(a.hi) + "], the domain [" + fmt_num(a.d0) + ", " + fmt_num(a.d1) + "]");
          break;
        case FaceKind::Periodic: {
          const bool spans = a.hi - a.lo >= a.d1 - a.d0;
          if (!spans && a.hi - a.lo + 2.0 * reach > a.d1 - a.d0)
            fail(std::string("is too wide for the periodic direction ") + a.name + ": with its band and margin it spans " +
                 a.name + " = [" + fmt_num(a.lo - reach) + ", " + fmt_num(a.hi + reach) + "], more than the period [" +
                 fmt_num(a.d0) + ", " + fmt_num(a.d1) + "] (a solid that does not span the whole period must leave "
                 "2 (solids.band + 4) cells of it free; shrink it, narrow the band or enlarge the domain)");
          break;
        }
      }
    }
  }
  // 5. no two solids overlap at the start (sampled at the cell centres)
  for (std::size_t a = 0; a < shapes.size(); ++a)
    for (std::size_t b = a + 1; b < shapes.size(); ++b) {
      // a clamped soft solid overlaps its rigid body on purpose
      if (cfg.solids[a].clamp_index == int(b) || cfg.solids[b].clamp_index == int(a)) continue;
      // and every image of b by whole periods in a periodic direction (solids may cross its
      // sides: the cells are then sampled at unwrapped positions, beyond [0, n))
      const bool px = sides[Left] == FaceKind::Periodic, py = sides[Bottom] == FaceKind::Periodic;
      for (int sy = py ? -1 : 0; sy <= (py ? 1 : 0); ++sy)
        for (int sx = px ? -1 : 0; sx <= (px ? 1 : 0); ++sx) {
          const double ox = sx * g.lx(), oy = sy * g.ly();
          const BoundingBox &A = boxes[a], B{boxes[b].xmin + ox, boxes[b].ymin + oy, boxes[b].xmax + ox, boxes[b].ymax + oy};
          const double xa = std::max(A.xmin, B.xmin), xb = std::min(A.xmax, B.xmax);
          const double ya = std::max(A.ymin, B.ymin), yb = std::min(A.ymax, B.ymax);
          if (xa > xb || ya > yb) continue;
          int i0 = int(std::floor((xa - g.x0) / g.dx)), i1 = int(std::ceil((xb - g.x0) / g.dx));
          int j0 = int(std::floor((ya - g.y0) / g.dx)), j1 = int(std::ceil((yb - g.y0) / g.dx));
          if (!px) { i0 = std::max(0, i0); i1 = std::min(g.nx - 1, i1); }
          if (!py) { j0 = std::max(0, j0); j1 = std::min(g.ny - 1, j1); }
          for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
              if (shapes[a]->phi0(g.xc(i), g.yc(j)) < 0.0 && shapes[b]->phi0(g.xc(i) - ox, g.yc(j) - oy) < 0.0) {
                const char* where = cfg.solids[b].shape.kind == ShapeKind::Tabulated ? "file" : "center";
                ctx.fail("solid[" + std::to_string(b) + "]." + where, solid_node(top, b, where),
                         "solid '" + cfg.solids[b].name + "' overlaps solid '" + cfg.solids[a].name +
                             "' at the start (cell (" + std::to_string(i) + ", " + std::to_string(j) + "), x = " +
                             fmt_num(g.xc(i)) + ", y = " + fmt_num(g.yc(j)) + ")");
              }
        }
    }
}

/// 7. A fixed time.dt must obey the explicit limits that the adaptive step takes from the
/// material constants (solver/model/time_step_limits.hpp, the same formulas Simulation::stable_dt
/// uses): past the viscous one the explicit viscous term blows up within a few hundred steps
/// (scenes/cylinder_re20.toml refined to 20 cells per diameter with its step scaled with dx:
/// dt = 0.0046 against the limit 0.0042, face divergence at t = 0.46), past the solid one
/// the explicit stress does. The advective and contact limits depend on the flow and are not
/// known here.
void check_fixed_step(const Ctx& ctx, const Table& top, const Config& cfg) {
  if (cfg.dt_fixed <= 0.0 || cfg.flow == FlowMode::Prescribed) return;  // prescribed: no flow solve
  const double dx = cfg.grid.dx;
  Table t(ctx, *top.table("time", true), "time", "time");  // time.dt was given
  const std::string given = fmt_num(cfg.dt_fixed) + " is above the explicit ";
  if (cfg.viscous_time == ViscousTime::Explicit) {
    // the largest mu / rho on the grid: the blend of eq. (3.6) is a convex combination where
    // the solids do not overlap, and the ratio of two convex combinations with the same
    // weights lies between the pure materials' ratios, so the largest material ratio bounds
    // it (and is reached wherever that material fills a cell)
    double nu = cfg.mu_f / cfg.rho_f;
    std::string whose = "the fluid";
    for (const SolidSpec& s : cfg.solids)
      if (s.viscosity / s.density > nu) {
        nu = s.viscosity / s.density;
        whose = "solid '" + s.name + "'";
      }
    if (nu > 0.0) {
      const double limit = viscous_dt_limit(cfg.visc_safety, dx, nu);
      if (cfg.dt_fixed > limit)
        t.fail("dt", given + "viscous limit " + fmt_num(limit) + " of this scene (time.viscous_safety rho dx^2 / (6 mu) = " +
                         fmt_num(cfg.visc_safety) + " x " + fmt_num(dx) + "^2 / 6 / " + fmt_num(nu) + ", mu / rho = " +
                         fmt_num(nu) + " of " + whose + "; it falls with dx^2, so a step scaled with dx crosses it "
                         "on refinement); lower it, or set time.viscous = \"implicit\" (no viscous limit, docs/implicit.md)");
    }
  }
  if (cfg.solid_time == SolidStressTime::Explicit)
    for (const SolidSpec& s : cfg.solids) {
      const double g = rest_wave_modulus(s);
      if (g <= 0.0) continue;  // a rigid body or a solid without stiffness
      const double limit = shear_wave_dt_limit(cfg.solid_opt.solid_cfl, dx, g, s.density);
      if (cfg.dt_fixed > limit)
        t.fail("dt", given + "solid time-step limit " + fmt_num(limit) + " of solid '" + s.name +
                         "' (solids.solid_cfl dx sqrt(rho_s / G) = " + fmt_num(cfg.solid_opt.solid_cfl) + " x " +
                         fmt_num(dx) + " x sqrt(" + fmt_num(s.density) + " / " + fmt_num(g) +
                         "), G its shear modulus at rest); lower it, or set time.solid_stress = \"semi_implicit\" or "
                         "\"upper_convected\" (no solid limit, docs/implicit.md), or raise solids.solid_cfl (stiff "
                         "solids fail from about 0.75, docs/stability.md)");
    }
}

/// 6. The memory the run will hold (solver/scene/memory_estimate.hpp) against what the machine
/// has free: a grid far too large stops here, naming the grid keys.
void check_memory(const Ctx& ctx, const Table& top, const Config& cfg) {
  const MemoryEstimate m = estimate_memory(cfg);
  const std::size_t avail = available_memory_bytes();
  if (avail == 0 || m.total() <= avail) return;
  Table grid(ctx, *top.table("grid", true), "grid", "grid");
  grid.fail("nx", "the scene needs about " + m.summary() + " of memory, this machine has " + format_bytes(avail) +
                      " available (grid " + std::to_string(cfg.grid.nx) + " x " + std::to_string(cfg.grid.ny) + ")");
}

/// The components' own keys (solver/model/component_kind.hpp), in registration order: first
/// those the core reads too (the solids, the implicit step: ComponentKind::configure, into the
/// Config), then the others' options (ComponentKind::parse); a kind the scene does not use adds
/// nothing.
void parse_components(const Table& top, Config& cfg) {
  for (const ComponentKind& k : component_kinds())
    if (k.configure) k.configure(top, cfg);
  for (const ComponentKind& k : component_kinds())
    if (k.parse)
      if (auto o = k.parse(top, cfg)) cfg.components.push_back({k.name, std::move(o)});
}

Config build_config(Ctx& ctx, toml::table& root, const std::vector<std::string>& sets) {
  for (const auto& s : sets) apply_override(ctx, root, s);

  Config cfg;
  cfg.scene_path = ctx.file;
  Table top(ctx, root, "", "");
  top.allow();

  cfg.name = std::filesystem::path(ctx.file).stem().string();
  if (top.has("name")) {
    cfg.name = top.string("name");
    const bool ok = !cfg.name.empty() && cfg.name != "." && cfg.name != ".." &&
                    cfg.name.find_first_of("/\\") == std::string::npos;
    top.require(ok, "name", "must be a non-empty name without '/' (it names the output directory), got " + dq(cfg.name));
  }
  if (cfg.name.empty()) cfg.name = "scene";

  parse_domain_grid(ctx, top, cfg);
  parse_fluid(ctx, top, cfg);
  parse_boundary(ctx, top, cfg);
  parse_initial(ctx, top, cfg);
  parse_gravity(ctx, top, cfg);
  parse_time(ctx, top, cfg);
  parse_solver(ctx, top, cfg);
  parse_output(ctx, top, cfg);
  parse_probes(ctx, top, cfg);
  parse_suspension(ctx, root, top, cfg);  // before the solids' keys: its particles are [[solid]] tables
  parse_components(top, cfg);  // after the core: a component's checks may use any of it
  check_start_state(ctx, top, cfg);
  check_fixed_step(ctx, top, cfg);  // after the solids' keys: their limits
  check_memory(ctx, top, cfg);
  return cfg;
}

}  // namespace

Config load_scene_string(const std::string& text, const std::string& path, const std::vector<std::string>& sets) {
  Ctx ctx;
  ctx.file = path;
  ctx.catalog = &scene_catalog();
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw SceneError(path, "", "TOML syntax error: " + std::string(e.description()), long(b.line), long(b.column));
  }
  return build_config(ctx, root, sets);
}

Config load_scene(const std::string& path, const std::vector<std::string>& sets) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError(path, "", "cannot read scene file: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const bool exists = std::filesystem::exists(path, ec);
    throw SceneError(path, "", exists ? "cannot read scene file: permission denied or unreadable"
                                      : "cannot read scene file: no such file");
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw SceneError(path, "", "cannot read scene file: read error");
  return load_scene_string(ss.str(), path, sets);
}

}  // namespace refmap
