#include "solver/components/actuation.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "solver/model/component_kind.hpp"
#include "solver/model/simulation.hpp"
#include "solver/io/toml_reader.hpp"

namespace refmap {

Actuation::Actuation(const ActuationSpec& spec, const std::string& solid_name)
    : stretch_(spec.stretch_x),
      shear_(spec.shear),
      has_stretch_(!spec.stretch_x.empty()),
      has_shear_(!spec.shear.empty()),
      name_(solid_name) {}

Affine2 Actuation::at(double t) const {
  // expressions of t only: x and y are 0
  const double s = has_stretch_ ? stretch_.eval(0.0, 0.0, t) : 1.0;
  const double g = has_shear_ ? shear_.eval(0.0, 0.0, t) : 0.0;
  if (!(s > 0.0 && std::isfinite(s)) || !std::isfinite(g)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "solid '%s': actuation gives stretch_x = %.6g, shear = %.6g at t = %.6g (stretch_x must be a finite number > 0)",
                  name_.c_str(), s, g, t);
    throw std::runtime_error(buf);
  }
  return {s, s * g, 0.0, 1.0 / s};
}

std::unique_ptr<ActuatedSolids> ActuatedSolids::from_options(const ActuationOptions& opt, const Config& cfg) {
  std::unique_ptr<ActuatedSolids> a;
  for (std::size_t k = 0; k < cfg.solids.size() && k < opt.per_solid.size(); ++k)
    if (opt.per_solid[k].enabled()) {
      if (!a) {
        a = std::make_unique<ActuatedSolids>();
        a->per_solid_.resize(cfg.solids.size());
      }
      a->per_solid_[k] = std::make_unique<Actuation>(opt.per_solid[k], cfg.solids[k].name);
    }
  return a;
}

void ActuatedSolids::at(StepPoint p, Simulation& sim, double dt) {
  if (p != StepPoint::Begin) return;
  auto& solids = sim.solids_mut();
  for (std::size_t k = 0; k < per_solid_.size(); ++k)
    if (per_solid_[k]) solids[k]->set_actuation(per_solid_[k]->at(sim.time() + dt));
}

namespace {

using namespace toml_text;

/// The `actuation` inline table of every [[solid]] (null: no solid is actuated). Each
/// expression must parse and give a finite value (stretch_x > 0) at the start time.
std::shared_ptr<const ComponentOptions> parse_actuation(const TomlTable& top, const Config& cfg) {
  if (cfg.solids.empty()) return nullptr;
  const toml::array* arr = top.node("solid")->as_array();  // the core checked it is one
  auto opt = std::make_shared<ActuationOptions>();
  bool any = false;
  for (std::size_t i = 0; i < cfg.solids.size(); ++i) {
    const std::string prefix = "solid[" + std::to_string(i) + "]";
    const TomlTable s = top.sub(*arr->get(i)->as_table(), prefix, "solid");
    ActuationSpec spec;
    if (const toml::node* an = s.node("actuation")) {
      const toml::table* at = an->as_table();
      if (!at) s.fail("actuation", "expected an inline table { stretch_x = \"...\", shear = \"...\" }, got " + describe(*an));
      const TomlTable a = top.sub(*at, prefix + ".actuation", "solid.actuation");
      a.allow();
      for (const char* k : {"stretch_x", "shear"}) {
        if (!a.has(k)) continue;
        const std::string text = expression_text(a, k);
        const bool stretch = std::string(k) == "stretch_x";
        Expression e;
        try {
          e = Expression(text);
        } catch (const std::invalid_argument& ex) {
          a.fail(k, "invalid expression " + dq(text) + ": " + ex.what());
        }
        const double v = e.eval(0.0, 0.0, cfg.t_start);
        if (stretch ? !(v > 0.0 && std::isfinite(v)) : !std::isfinite(v))
          a.fail(k, std::string("must be ") + (stretch ? "a finite number > 0" : "finite") + ", got " + fmt_num(v) +
                        " at t = " + fmt_num(cfg.t_start));
        (stretch ? spec.stretch_x : spec.shear) = std::move(e);
      }
      if (!spec.enabled()) s.fail("actuation", "give stretch_x and/or shear");
      any = true;
    }
    opt->per_solid.push_back(std::move(spec));
  }
  if (!any) return nullptr;
  return opt;
}

std::unique_ptr<Component> make_actuation(const ComponentOptions& o, Simulation& sim) {
  return ActuatedSolids::from_options(static_cast<const ActuationOptions&>(o), sim.config());
}

}  // namespace

ComponentKind actuation_kind() {
  using namespace keys;
  using KT = KeyType;
  ComponentKind k;
  k.name = "actuation";
  k.tables = {{{"solid.actuation", "`solid.actuation` as an inline table", false, false, true,
                "Expressions of `t` (see *Expressions*); the stress is that of the elastic part F A(t)^-1 of the "
                "deformation, so the solid relaxes towards its reference shape mapped by A(t) (docs/actuation.md)."},
               "solid"}};
  k.keys = {
      shown_default(key("solid", "actuation", KT::InlineTable, {}, {},
                        "inline table `{ stretch_x = \"...\", shear = \"...\" }`: a stress-free configuration that "
                        "changes in time (see `solid.actuation` below, docs/actuation.md)"),
                    "none"),
      shown_default(key("solid.actuation", "stretch_x", KT::Expression, {}, text_range("> 0 at every t"),
                        "s(t): the stress-free shape is the reference one stretched by s along x and by 1/s along y "
                        "(area kept)"),
                    "`1`"),
      shown_default(key("solid.actuation", "shear", KT::Expression, {}, {},
                        "g(t): then sheared, x += g y (A = diag(s, 1/s) [[1, g], [0, 1]])"),
                    "`0`"),
  };
  k.parse = parse_actuation;
  k.make = make_actuation;
  return k;
}

}  // namespace refmap
