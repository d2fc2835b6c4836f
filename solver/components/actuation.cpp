#include "solver/components/actuation.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "solver/model/simulation.hpp"

namespace refmap {

Actuation::Actuation(const ActuationSpec& spec, const std::string& solid_name)
    : has_stretch_(!spec.stretch_x.empty()), has_shear_(!spec.shear.empty()), name_(solid_name) {
  if (has_stretch_) stretch_ = Expression(spec.stretch_x);
  if (has_shear_) shear_ = Expression(spec.shear);
}

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

std::unique_ptr<ActuatedSolids> ActuatedSolids::from_scene(const Config& cfg) {
  std::unique_ptr<ActuatedSolids> a;
  for (std::size_t k = 0; k < cfg.solids.size(); ++k)
    if (cfg.solids[k].actuation.enabled()) {
      if (!a) {
        a = std::make_unique<ActuatedSolids>();
        a->per_solid_.resize(cfg.solids.size());
      }
      a->per_solid_[k] = std::make_unique<Actuation>(cfg.solids[k].actuation, cfg.solids[k].name);
    }
  return a;
}

void ActuatedSolids::at(StepPoint p, Simulation& sim, double dt) {
  if (p != StepPoint::Begin) return;
  auto& solids = sim.solids_mut();
  for (std::size_t k = 0; k < per_solid_.size(); ++k)
    if (per_solid_[k]) solids[k]->set_actuation(per_solid_[k]->at(sim.time() + dt));
}

}  // namespace refmap
