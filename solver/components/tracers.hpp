#pragma once
// Passive fluid tracers ([[tracers]] tables): points seeded on a line or a box of the scene
// and carried by the cell velocity, dx/dt = u(x, t), with the RK-4 step of the rest of the
// code (kernels/rk4.hpp) and the bilinear interpolation of the line probes
// (solver/model/probes.hpp). Written to tracers.csv at every output frame (docs/tracers.md).
// An optional component: its keys, parser and factory are its kind (tracers_kind,
// registered in solver/model/component_kind.cpp).
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/model/component.hpp"
#include "solver/model/config.hpp"

namespace refmap {

/// A [[tracers]] table: `n` points on the segment (x0,y0)-(x1,y1), ends included (line),
/// or nx x ny points on the lattice of the box with corners (x0,y0), (x1,y1) (box).
struct TracerSeed {
  bool box = false;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int n = 0, nx = 0, ny = 0;
};

/// The scene's [[tracers]] tables, in order (the options of the kind "tracers",
/// solver/model/component_kind.hpp; its keys and parser are in tracers.cpp).
struct TracerOptions : ComponentOptions {
  std::vector<TracerSeed> seeds;
};

class CheckpointWriter;
class CheckpointReader;

/// The seed points of the scene's [[tracers]] tables, in table order: a line gives n
/// evenly spaced points, ends included; a box nx x ny points on a lattice, corners
/// included (one point along a direction of size 1: the middle of the box).
std::vector<std::array<double, 2>> tracer_seeds(const std::vector<TracerSeed>& seeds);

/// A component (solver/model/component.hpp): it keeps the velocity of the step's start and moves
/// the points at the step's end.
class Tracers : public Component {
 public:
  /// periodic_x/y: positions are wrapped into the domain; otherwise clamped onto the walls
  /// (the interpolated normal velocity vanishes there, so only round-off reaches them).
  Tracers(const Grid& g, const std::vector<std::array<double, 2>>& points, bool periodic_x, bool periodic_y);

  /// The velocity at the start of the step (cell fields with their ghosts filled).
  void begin_step(const Field& u, const Field& v);
  /// One RK-4 step over [t, t + dt]: the velocity between the start of the step and its
  /// end (u1, v1, ghosts filled) is linear in time, so stages 2-3 see the mean of the two
  /// and stage 4 the end. Exact in time for a steady flow up to the RK-4 error O(dt^4);
  /// second order for an unsteady one (the flow solver's own order).
  void advance(const Field& u1, const Field& v1, double dt);

  int size() const { return n_; }
  double x(int k) const { return x_(k, 0); }
  double y(int k) const { return y_(k, 0); }

  void save_state(CheckpointWriter& w) const;
  void load_state(CheckpointReader& r);

  // Component
  const char* name() const override { return "tracers"; }
  void register_state(StateRegistry& reg) override;
  void at(StepPoint p, Simulation& sim, double dt) override;
  /// tracers.csv: frame, t, id, x, y (one row per tracer and frame).
  std::vector<ComponentFile> files() const override;

 private:
  double wrap_x(double x) const;
  double wrap_y(double y) const;
  Grid g_;
  bool px_, py_;
  int n_ = 0;
  Field x_, y_;                          // positions, n x 1
  Field sx_, sy_, accx_, accy_, kx_, ky_;  // RK-4 work (kernels/rk4.hpp)
  Field u0_, v0_;                         // velocity at the start of the step
  Field u1_, v1_;                         // and at its end (with ghosts)
};

}  // namespace refmap
