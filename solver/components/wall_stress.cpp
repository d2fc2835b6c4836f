#include "solver/components/wall_stress.hpp"

#include <memory>

#include "solver/model/component_kind.hpp"
#include "solver/model/simulation.hpp"
#include "solver/io/toml_reader.hpp"

namespace refmap {

void WallStress::values(const Simulation& sim, std::vector<double>& out) const {
  const Grid& g = sim.grid();
  const Field &u = sim.u(), &mu = sim.viscosity();
  // the cell velocity's ghosts hold the walls' condition at the current time (the step
  // ends with apply_velocity_bc)
  double b = 0.0, t = 0.0;
  for (int i = 0; i < g.nx; ++i) {
    b += mu(i, 0) * (u(i, 0) - u(i, -1));
    t += mu(i, g.ny - 1) * (u(i, g.ny) - u(i, g.ny - 1));
  }
  b /= g.nx * g.dx;
  t /= g.nx * g.dx;
  const double gamma = (top_.speed(sim.time()) - bottom_.speed(sim.time())) / g.ly();
  out.push_back(b);
  out.push_back(t);
  out.push_back(gamma != 0.0 ? 0.5 * (b + t) / (mu_f_ * gamma) : 0.0);
}

namespace {

/// output.wall_stress: on (no options beyond that) or off (null).
std::shared_ptr<const ComponentOptions> parse_wall_stress(const TomlTable& top, const Config& cfg) {
  const toml::table* t = top.table("output", false);
  if (!t) return nullptr;
  const TomlTable o = top.sub(*t, "output", "output");
  if (!o.boolean("wall_stress")) return nullptr;
  auto wall = [](const SideBc& b) { return b.type == BcType::NoSlip || b.type == BcType::MovingWall; };
  o.require(wall(cfg.bc[Bottom]) && wall(cfg.bc[Top]), "wall_stress",
            "needs no-slip or moving walls at the bottom and the top");
  return std::make_shared<ComponentOptions>();
}

std::unique_ptr<Component> make_wall_stress(const ComponentOptions&, Simulation& sim) {
  return std::make_unique<WallStress>(sim.config());
}

}  // namespace

ComponentKind wall_stress_kind() {
  ComponentKind k;
  k.name = "wall stress";
  k.keys = {keys::boolean("output", "wall_stress", false,
                          "shear stress on the bottom and top walls and the relative viscosity of a shear cell in "
                          "`diagnostics.csv` (both must be walls)")};
  k.after = "output.diagnostics_every";
  k.parse = parse_wall_stress;
  k.make = make_wall_stress;
  return k;
}

}  // namespace refmap
