#pragma once
// The explicit time-step limits that do not depend on the flow: the viscous one (explicit
// viscous term) and a solid's shear-wave one (explicit solid stress). One home for both
// formulas: the adaptive step (Simulation::stable_dt, Solid::min_dt) takes them every step,
// and the scene loader (solver/scene/scene.cpp) refuses a fixed time.dt above them at load.
#include <cmath>

#include "kernels/constitutive.hpp"
#include "solver/model/config.hpp"

namespace refmap {

/// Forward Euler on the viscous term is stable for dt <= rho dx^2 / (6 mu): the discrete
/// operator of kernels/viscous.cpp (full stress mu (grad u + grad u^T), needed for the
/// blended viscosity) has its largest eigenvalue 12 mu / (rho dx^2) (the checkerboard mode:
/// 8 from the compact normal stress 2 mu u_xx, 4 from mu u_yy). The paper's 0.5 rho dx^2 / mu
/// is the bound of the 1-D Laplacian. `safety` is time.viscous_safety, `nu_max` the largest
/// mu / rho over the grid (> 0).
inline double viscous_dt_limit(double safety, double dx, double nu_max) {
  return safety * dx * dx / (6.0 * nu_max);
}

/// Section 4: dt <= P dx sqrt(rho_s / G), shear-wave speed sqrt(G / rho_s); G the tangent
/// shear modulus (kernels/constitutive.hpp, wave_modulus; 2 mu_s at rest). `p` is
/// solids.solid_cfl (or time.solid_implicit_cfl).
inline double shear_wave_dt_limit(double p, double dx, double wave_modulus, double density) {
  return p * dx / std::sqrt(wave_modulus / density);
}

/// A solid's tangent shear modulus at rest (b = I): 2 mu_s for neo-Hookean. The step's own
/// bound takes the larger of it and the largest in the strained solid (Solid::wave_modulus),
/// so the limit at rest is the largest the solid's limit can be.
inline double rest_wave_modulus(const SolidSpec& s) {
  if (s.mu_s <= 0.0) return 0.0;
  return with_constitutive_model(s, [](const auto& m) { return m.wave_modulus({1.0, 0.0, 1.0}); });
}

}  // namespace refmap
