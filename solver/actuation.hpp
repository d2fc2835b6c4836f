#pragma once
// The actuation map A(t) of a solid (ActuationSpec, solver/config.hpp) from its expressions
// of t; the stress kernels apply it (kernels/constitutive_actuation.hpp). docs/actuation.md.
#include <string>

#include "kernels/constitutive_actuation.hpp"
#include "solver/config.hpp"
#include "solver/expression.hpp"

namespace refmap {

class Actuation {
 public:
  /// Throws std::invalid_argument for an expression that does not parse.
  Actuation(const ActuationSpec& spec, const std::string& solid_name);
  /// A(t) = diag(s, 1/s) [[1, g], [0, 1]] = [[s, s g], [0, 1/s]]: det A = 1 (the area is kept).
  /// Throws std::runtime_error when s(t) is not a finite number > 0 or g(t) not finite.
  Affine2 at(double t) const;

 private:
  Expression stretch_, shear_;
  bool has_stretch_, has_shear_;
  std::string name_;
};

}  // namespace refmap
