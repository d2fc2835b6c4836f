#pragma once
// The shear stress the fluid exerts on the bottom and top walls, and the relative viscosity
// of a shear cell (output.wall_stress; a component, solver/model/component.hpp, whose key and
// parser are its kind in wall_stress.cpp).
//
// On a wall face the tangential stress is sigma_xy = mu (du/dy + dv/dx) with dv/dx = 0
// along a wall (v = 0 there), taken as the viscous kernel takes it: the difference of the
// first cell and its ghost (ghost = 2 U_wall - u, solver/model/boundary.hpp) over dx, times the
// cell's blended viscosity (eq. 3.6). Averaged along the wall:
//   wall_stress_bottom = <mu (u(i, 0) - u(i, -1)) / dx>_i        (x-force per area on the wall)
//   wall_stress_top    = <mu (u(i, ny) - u(i, ny - 1)) / dx>_i   (minus the x-force on it)
// both positive when u grows with y. In a shear cell (walls at +-U/2, periodic along x) the
// mean of the two over mu_f gamma, gamma = (U_top - U_bottom) / L_y, is the relative
// viscosity eta_r of the suspension (1 for the fluid alone; Einstein's 2-D dilute limit
// 1 + 2 phi for rigid discs at area fraction phi, Brady 1984). eta_r is 0 while gamma = 0.
#include <string>
#include <vector>

#include "solver/model/component.hpp"
#include "solver/model/config.hpp"

namespace refmap {

class WallStress : public Component {
 public:
  explicit WallStress(const Config& cfg) : bottom_(cfg.bc[Bottom]), top_(cfg.bc[Top]), mu_f_(cfg.mu_f) {}
  const char* name() const override { return "wall stress"; }
  std::vector<std::string> columns() const override { return {"wall_stress_bottom", "wall_stress_top", "eta_r"}; }
  void values(const Simulation& sim, std::vector<double>& out) const override;

 private:
  SideBc bottom_, top_;
  double mu_f_;
};

}  // namespace refmap
