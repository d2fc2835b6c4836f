#pragma once
// The parameters of a solid's reference shape as a scene gives them: plain data, so the
// configuration (solver/model/config.hpp) holds them without the shapes' code
// (solver/model/shape.hpp builds a Shape from them: make_shape).
#include <span>
#include <string>

#include "solver/io/enum_names.hpp"

namespace refmap {

/// Which shape ShapeParams describe (scene names and aliases: option_names below, defined in
/// solver/model/shape.cpp).
enum class ShapeKind { Circle, Ellipse, RoundedRectangle, Zalesak, Tabulated };

/// Parameters of any shape, as a scene file gives them. `kind` selects which fields
/// are used:
///   Circle:           cx, cy, radius
///   Ellipse:          cx, cy, a, b, angle
///   RoundedRectangle: cx, cy, half_width, half_height, corner_radius, angle
///   Zalesak:          cx, cy, radius, slot_half_width, slot_top, angle
///   Tabulated:        file
struct ShapeParams {
  ShapeKind kind = ShapeKind::Circle;
  double cx = 0.0, cy = 0.0;
  double radius = 0.0;
  double a = 0.0, b = 0.0;
  double half_width = 0.0, half_height = 0.0, corner_radius = 0.0;
  double slot_half_width = 0.0, slot_top = 0.0;
  double angle = 0.0;  ///< radians, counter-clockwise
  std::string file;
};

std::span<const OptionName<ShapeKind>> option_names(ShapeKind);

}  // namespace refmap
