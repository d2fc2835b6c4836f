#pragma once
// Material points of the solids ([[solid]] markers / boundary_markers): a marker is a point
// X of the reference configuration; its current position x is where the reference map
// takes that value, xi(x) = X (eq. 2.1: xi is the inverse of the motion). Found by Newton's
// method on the bilinear interpolant of xi over the solid's window, started from the
// marker's previous position (it moves less than a cell per step). Written to markers.csv
// at every output frame (docs/tracers.md). An optional component: its keys, parser and
// factory are its kind (markers_kind in markers.cpp, registered in
// solver/model/component_kind.cpp).
#include <array>
#include <memory>
#include <vector>

#include "solver/model/component.hpp"
#include "solver/model/solid.hpp"

namespace refmap {

class CheckpointWriter;
class CheckpointReader;

/// The material points a [[solid]] asks for: `markers` (reference positions) and
/// `boundary_markers` (how many on the reference boundary).
struct SolidMarkers {
  std::vector<std::array<double, 2>> points;
  int boundary = 0;
};

/// The options of the kind "markers": one entry per solid, in scene order.
struct MarkerOptions : ComponentOptions {
  std::vector<SolidMarkers> per_solid;
};

/// The reference points of a solid: its `markers` list, then `boundary_markers` points on
/// phi0 = 0 at equal angles about the centre of the shape's bounding box (found by
/// bisection along each ray; the shape must contain that centre and be star-shaped about
/// it, which the loader checks for the centre).
std::vector<std::array<double, 2>> marker_reference_points(const SolidMarkers& m, const Shape& shape);

/// Solves xi(x) = X on a solid's window (bilinear interpolant of its xi, ghost layers
/// included) by Newton's method from (x, y); returns false if it did not converge to
/// 1e-10 dx in 50 iterations (x, y then hold the last iterate).
bool solve_material_point(const Solid& s, const Grid& g, double X, double Y, double& x, double& y);

/// A component (solver/model/component.hpp): the points move at the end of every step.
class Markers : public Component {
 public:
  Markers(const std::vector<std::unique_ptr<Solid>>& solids, const Grid& g, const MarkerOptions& opt);
  bool empty() const { return count_ == 0; }
  /// New positions from the current xi of every solid.
  void update(const std::vector<std::unique_ptr<Solid>>& solids);

  struct Point {
    int solid = 0, id = 0;
    double X = 0, Y = 0;  ///< reference position
    double x = 0, y = 0;  ///< current position
  };
  const std::vector<Point>& points() const { return pts_; }

  void save_state(CheckpointWriter& w) const;
  void load_state(CheckpointReader& r);

  // Component
  const char* name() const override { return "markers"; }
  void register_state(StateRegistry& reg) override;
  void at(StepPoint p, Simulation& sim, double dt) override;
  /// markers.csv: frame, t, solid, id, x, y (one row per marker and frame).
  std::vector<ComponentFile> files() const override;

 private:
  Grid g_;
  std::vector<Point> pts_;
  int count_ = 0;
};

}  // namespace refmap
