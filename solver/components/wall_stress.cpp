#include "solver/components/wall_stress.hpp"

#include "solver/model/simulation.hpp"

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

}  // namespace refmap
