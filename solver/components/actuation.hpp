#pragma once
// The actuation map A(t) of a solid (a [[solid]]'s `actuation`) from its expressions of t;
// the stress kernels apply it (kernels/constitutive_actuation.hpp). docs/actuation.md. An
// optional component: its keys, parser and factory are its kind (actuation_kind in
// actuation.cpp, registered in solver/model/component_kind.cpp).
#include <memory>
#include <string>
#include <vector>

#include "kernels/constitutive_actuation.hpp"
#include "solver/model/component.hpp"
#include "solver/model/config.hpp"
#include "solver/io/expression.hpp"

namespace refmap {

/// `actuation` of a [[solid]] (docs/actuation.md): its stress-free configuration is the
/// reference one mapped by A(t) = diag(s, 1/s) [[1, g], [0, 1]] (det A = 1), s = stretch_x(t),
/// g = shear(t), expressions of t (kernels/constitutive_actuation.hpp), parsed by the loader.
/// Empty: not given (s = 1, g = 0); both empty: not actuated.
struct ActuationSpec {
  Expression stretch_x, shear;
  bool enabled() const { return !stretch_x.empty() || !shear.empty(); }
};

/// The options of the kind "actuation": one entry per solid, in scene order.
struct ActuationOptions : ComponentOptions {
  std::vector<ActuationSpec> per_solid;
};

class Actuation {
 public:
  Actuation(const ActuationSpec& spec, const std::string& solid_name);
  /// A(t) = diag(s, 1/s) [[1, g], [0, 1]] = [[s, s g], [0, 1/s]]: det A = 1 (the area is kept).
  /// Throws std::runtime_error when s(t) is not a finite number > 0 or g(t) not finite.
  Affine2 at(double t) const;

 private:
  Expression stretch_, shear_;  ///< empty: not given
  bool has_stretch_, has_shear_;
  std::string name_;
};

/// The actuated solids of a scene as a component (solver/model/component.hpp): before each step
/// every actuated solid gets A(t + dt), so the stress of the step is that of the
/// configuration at its end. Stateless: A is a function of t.
class ActuatedSolids : public Component {
 public:
  /// Null when no solid of the scene is actuated.
  static std::unique_ptr<ActuatedSolids> from_options(const ActuationOptions& opt, const Config& cfg);
  const char* name() const override { return "actuation"; }
  void at(StepPoint p, Simulation& sim, double dt) override;

 private:
  std::vector<std::unique_ptr<Actuation>> per_solid_;  ///< null: that solid is not actuated
};

}  // namespace refmap
