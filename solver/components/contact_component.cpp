#include "solver/components/contact_component.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "kernels/loop.hpp"
#include "solver/io/checkpoint_io.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {

namespace {

/// The velocity scale of the contact pressure (solver/model/contact.hpp): the largest
/// initial speed on the grid and the free-fall speed over the domain along g.
double initial_velocity_scale(const Simulation& sim) {
  const Config& cfg = sim.config();
  const Grid& g = sim.grid();
  double umax = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) umax = std::max(umax, std::hypot(sim.u()(i, j), sim.v()(i, j)));
  const double gmag = std::hypot(cfg.gx, cfg.gy);
  if (gmag > 0.0) {
    const double L = (std::abs(cfg.gx) * g.lx() + std::abs(cfg.gy) * g.ly()) / gmag;
    umax = std::max(umax, std::sqrt(2.0 * gmag * L));
  }
  return umax;
}

}  // namespace

ContactComponent::ContactComponent(Simulation& sim)
    : contact_(sim.config(), contact_options(sim.config()), initial_velocity_scale(sim)) {
  const Grid& g = sim.grid();
  if (contact_.force_enabled()) {
    cfx_.resize(g.nx + 1, g.ny, Grid::ng);
    cfy_.resize(g.nx, g.ny + 1, Grid::ng);
  }
  contact_.observe(sim.time(), sim.solids(), sim.solid_diagnostics());
}

void ContactComponent::register_state(StateRegistry& reg) {
  // the face force is read before this step's add_force with time.splitting = "increment"
  // (G_f^n); written_ is not state: with written_ = false the fields are zero, and
  // subtracting beta_f * (+0) leaves G_f's bits
  reg.add_field("contact.cfx", cfx_);
  reg.add_field("contact.cfy", cfy_);
  reg.add_record(
      "contact", [this](CheckpointWriter& w) { contact_.save_state(w); },
      [this](CheckpointReader& r) {
        contact_.load_state(r);
        written_ = true;  // the loaded face force may be nonzero (a resume, or a restored
                          // snapshot of time.solid_picard_iterations): clear it before writing
      });
}

double ContactComponent::max_dt(const Simulation& sim) const {
  if (!contact_.force_enabled()) return std::numeric_limits<double>::infinity();
  // the force acts in the layer -2 dx < phi < 0 of a solid, where the blended density is
  // at least the mean of the solid's and the fluid's
  double rho_min = 1e300;
  for (const auto& s : sim.solids()) rho_min = std::min(rho_min, 0.5 * (s->spec().density + sim.config().rho_f));
  // the spring only acts on gaps below its range: its limit (dt ~ 0.1 dx / U) is needed
  // only in a step that can bring a surface into range (solver/model/contact.hpp), judged
  // with the flow's own limit and speed of this evaluation
  const double dt_contact = contact_.min_dt(rho_min);
  const Simulation::FlowLimit& flow = sim.flow_limit();
  if (flow.dt > dt_contact && !contact_.clear_of_contact(flow.speed, flow.dt)) return dt_contact;
  return std::numeric_limits<double>::infinity();
}

void ContactComponent::at(StepPoint p, Simulation& sim, double) {
  switch (p) {
    case StepPoint::Forces:
      if (contact_.force_enabled()) add_force(sim);
      break;
    case StepPoint::FaceAccelerations:
      // nothing to add when no face got a contact force (G_f - beta_f * (+0) is G_f, bit for bit)
      if (contact_.force_enabled() && written_) subtract_from_face_accelerations(sim);
      break;
    case StepPoint::End:  // the gap and event tracker after the step
      contact_.observe(sim.time(), sim.solids(), sim.solid_diagnostics());
      break;
    default:
      break;
  }
}

void ContactComponent::add_force(const Simulation& sim) {
  // contact force on the faces of the new configuration (solver/model/contact.hpp), applied
  // with the pressure gradient and gravity in the balanced-force face accelerations.
  // The force is zero away from the solids' contact layers, i.e. everywhere in most steps:
  // the fields are cleared only after a step that wrote into them (two full passes over
  // memory per step otherwise, most of this phase on large grids)
  if (written_) {
    parallel_fill(cfx_.raw(), cfx_.raw_size(), 0.0);
    parallel_fill(cfy_.raw(), cfy_.raw_size(), 0.0);
  }
  written_ = contact_.add_force(sim.solids(), cfx_, cfy_);
}

void ContactComponent::subtract_from_face_accelerations(Simulation& sim) const {
  // G_f -= beta_f F_f: the contact force per unit volume on each face, over the face density
  const Grid& g = sim.grid();
  const Sides& sides = sim.sides();
  const Field &beta_x = sim.beta_x(), &beta_y = sim.beta_y();
  Field &gxf = sim.face_accel_x_mut(), &gyf = sim.face_accel_y_mut();
  // the boundary faces of a direction: a wall face carries no normal velocity (nothing to
  // add); a periodic direction's faces 0 and n are one face
  bool x_seam = false, y_seam = false;
  switch (sides[Left]) {
    case FaceKind::Wall:
    case FaceKind::Inflow:
    case FaceKind::Outflow: break;  // no contact force on an open face (solver/model/contact.cpp)
    case FaceKind::Periodic: x_seam = true; break;
  }
  switch (sides[Bottom]) {
    case FaceKind::Wall:
    case FaceKind::Inflow:
    case FaceKind::Outflow: break;
    case FaceKind::Periodic: y_seam = true; break;
  }
  parallel_rows(0, g.ny, g.nx, [&](int j) {
    for (int i = 1; i < g.nx; ++i) gxf(i, j) -= beta_x(i, j) * cfx_(i, j);
    if (x_seam) {
      gxf(0, j) -= beta_x(0, j) * cfx_(0, j);
      gxf(g.nx, j) = gxf(0, j);
    }
  });
  parallel_rows(0, g.ny + 1, g.nx, [&](int j) {
    if ((j == 0 || j == g.ny) && !y_seam) return;
    const int jj = j == g.ny ? 0 : j;
    for (int i = 0; i < g.nx; ++i) gyf(i, j) -= beta_y(i, jj) * cfy_(i, jj);
  });
}

void ContactComponent::solid_values(const Simulation&, int k, std::vector<double>& out) const {
  out.push_back(contact_.gap_solid(k));
  out.push_back(contact_.gap_wall(k));
}

void ContactComponent::finish(Simulation& sim, const std::string& out_dir) {
  contact_.finish(sim.time());
  if (out_dir.empty()) return;
  // events.csv: the contact event log, one "time,solid,event,value,with" row per event
  const std::string path = (std::filesystem::path(out_dir) / "events.csv").string();
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fprintf(f, "time,solid,event,value,with\n");
  for (const ContactEvent& e : contact_.events())
    std::fprintf(f, "%.10g,%d,%s,%.10g,%s\n", e.time, e.solid, e.event.c_str(), e.value, e.with.c_str());
  std::fclose(f);
}

namespace {

/// [contact]: its options when the scene has the table (null: the defaults). The Simulation
/// adds the component itself, whatever the scene says (make_contact).
std::shared_ptr<const ComponentOptions> parse_contact(const TomlTable& top, const Config& cfg) {
  const toml::table* t = top.table("contact", false);
  if (!t) return nullptr;
  const TomlTable c = top.sub(*t, "contact", "contact");
  c.allow();
  auto o = std::make_shared<ContactOptions>();
  o->enabled = c.boolean("enabled");
  o->walls = c.boolean("walls");
  o->range = c.number("range");
  c.require(o->range > 0 && o->range < cfg.solid_opt.band, "range",
            "must be in (0, solids.band = " + toml_text::fmt_num(cfg.solid_opt.band) +
                ") cells (the level sets are only known within the band), got " + toml_text::fmt_num(o->range));
  o->stiffness = c.number("stiffness");
  o->velocity_scale = c.number("velocity_scale");
  o->cfl = c.number("cfl");
  return o;
}

/// Nothing: contact is not switched on by the scene. The Simulation adds it first for every
/// run with solids (Simulation::add_components, also for a Config made without the loader),
/// so that its hooks come first at each step point; it reads its options from the Config.
std::unique_ptr<Component> make_contact(const ComponentOptions&, Simulation&) { return nullptr; }

}  // namespace

ComponentKind contact_kind() {
  using namespace keys;
  const ContactOptions d;
  ComponentKind k;
  k.name = "contact";
  k.tables = {{{"contact", "`[contact]`", false, false, false,
                "On by default whenever there are solids and `solver.flow = \"solve\"`."},
               "suspension"}};
  k.keys = {
      boolean("contact", "enabled", d.enabled, "contact force on (the gaps and events are reported either way)"),
      boolean("contact", "walls", d.walls,
              "also repulsion from the no_slip, moving_wall and free_slip sides (periodic sides never repel)"),
      num("contact", "range", d.range, text_range("in (0, `solids.band`)"),
          "d in cells: the force acts once a gap is below d Δx; also the threshold of the contact events"),
      num("contact", "stiffness", d.stiffness, ge(0),
          "P, the contact pressure at zero gap, in units of ρ_max U² (independent of the solids' `mu_s`)"),
      num("contact", "velocity_scale", d.velocity_scale, ge(0, "0 = automatic"),
          "U; 0 = automatic: the initial and free-fall speeds, raised to the fastest solid seen"),
      num("contact", "cfl", d.cfl, gt(0),
          "the contact spring's step bound dt ≤ cfl / ω, in a step that can bring a surface into range "
          "(docs/contact.md)"),
  };
  k.parse = parse_contact;
  k.make = make_contact;
  return k;
}

}  // namespace refmap
