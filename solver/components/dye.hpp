#pragma once
// A passive dye carried by the flow ([dye]; docs/components.md): a cell field c obeying
//     dc/dt + div(u_f c) = 0,
// the conservative form of dc/dt + u . grad c = 0 (the face velocities u_f are
// divergence-free after the projection, eq. 5.6). Space: the flux form of
// kernels/advection.hpp with Superbee-limited face values (bounded: no new extrema).
// Time: the three-stage strong-stability-preserving Runge-Kutta step of Shu & Osher (1988,
// J. Comput. Phys. 77, 439, eq. 2.18), which keeps the bound of the forward-Euler step
// under the same step limit; the face velocity of its stages at t, t + dt, t + dt/2 is
// u_f^n, u_f^{n+1} and their mean, each divergence-free, so a uniform dye stays uniform.
// The total sum c dx^2 is conserved to round-off: each face's flux leaves one cell and
// enters its neighbour. An optional component: its key, parser and factory are its kind
// (dye_kind in dye.cpp).
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/field.hpp"
#include "solver/model/component.hpp"
#include "solver/model/config.hpp"
#include "solver/io/expression.hpp"

namespace refmap {

/// The options of the kind "dye": the initial concentration c(x, y) at the start time.
struct DyeOptions : ComponentOptions {
  Expression initial;
};

class Dye : public Component {
 public:
  Dye(const Simulation& sim, const Expression& initial);
  /// The concentration (nx x ny cells; ghosts filled at the last stage only).
  const Field& field() const { return c_; }

  /// One SSP-RK3 step over [t, t + dt] with the face velocities at its two ends.
  void advance(const Field& uf0, const Field& vf0, const Field& uf1, const Field& vf1, double dt);

  // Component
  const char* name() const override { return "dye"; }
  void register_state(StateRegistry& reg) override;
  /// The bound of the limited scheme: (|u_f| + |v_f|)_max dt / dx <= 1/2 over the cells.
  double max_dt(const Simulation& sim) const override;
  void at(StepPoint p, Simulation& sim, double dt) override;
  std::vector<std::string> columns() const override { return {"dye_total", "dye_min", "dye_max"}; }
  void values(const Simulation& sim, std::vector<double>& out) const override;
  void frame_fields(FrameFields& out) const override { out.scalars.emplace_back("dye", &c_); }

 private:
  /// r = -div(u_f q) of q (its ghosts filled first).
  void rate(Field& q, const Field& uf, const Field& vf, Field& r);
  Grid g_;
  std::array<SideBc, 4> bc_;
  Field c_, c1_, r_, scratch_;
  Field uf0_, vf0_, ufm_, vfm_;  ///< face velocities at the step's start and the mean
};

}  // namespace refmap
