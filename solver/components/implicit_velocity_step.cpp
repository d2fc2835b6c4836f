#include "solver/components/implicit_velocity_step.hpp"

#include <algorithm>
#include <limits>

#include "kernels/constitutive.hpp"
#include "kernels/solid_stress.hpp"
#include "solver/model/boundary.hpp"
#include "solver/model/periodic_window.hpp"
#include "solver/model/simulation.hpp"
#include "solver/model/solid.hpp"

namespace refmap {

ImplicitVelocityStep::ImplicitVelocityStep(const Config& cfg)
    : cfg_(cfg), solids_(!cfg.solids.empty()), solver_(cfg) {
  const int nx = cfg_.grid.nx, ny = cfg_.grid.ny, ng = Grid::ng;
  mimp_.resize(nx, ny, ng);
  if (cfg_.solid_time == SolidStressTime::UpperConvected)
    for (Field* f : {&qxx_, &qxy_, &qyy_}) f->resize(nx, ny, ng);
}

void ImplicitVelocityStep::velocity_step(Simulation& sim, double dt) {
  implicit_viscosity(sim, dt);
  if (cfg_.solid_time == SolidStressTime::UpperConvected) {
    rate_coefficients(sim, dt);
    solver_.apply_rate(sim.u_mut(), sim.v_mut(), sim.step_force_x(), sim.step_force_y(), sim.rho(), mimp_, qxx_,
                       qxy_, qyy_, dt);
  } else {
    // (the Simulation refuses held cells with the upper-convected stress)
    solver_.set_held(sim.held_cells());
    solver_.apply(sim.u_mut(), sim.v_mut(), sim.step_force_x(), sim.step_force_y(), sim.rho(), mimp_, dt);
  }
}

double ImplicitVelocityStep::velocity_step_dt(const Simulation& sim) const {
  // the implicit stress's own cap on the shear-wave limit it lifts (docs/implicit.md)
  double dt = std::numeric_limits<double>::infinity();
  if (cfg_.solid_time != SolidStressTime::Explicit && cfg_.solid_implicit_cfl > 0.0)
    for (const auto& s : sim.solids()) dt = std::min(dt, s->min_dt(cfg_.solid_implicit_cfl));
  return dt;
}

void ImplicitVelocityStep::add_solid_viscosity(const Simulation& sim, Field& m, double dt) const {
  for (const auto& s : sim.solids())  // blended like the stress, eq. (3.6), reaching reach cells further out
    if (s->spec().mu_s > 0.0)
      s->add_blend(m, cfg_.solid_implicit_k * s->wave_modulus() * dt, 0.0, cfg_.solid_implicit_reach * cfg_.grid.dx);
}

void ImplicitVelocityStep::implicit_viscosity(const Simulation& sim, double dt) {
  if (cfg_.viscous_time == ViscousTime::Implicit) mimp_ = sim.viscosity();
  else mimp_.fill(0.0);
  if (cfg_.solid_time == SolidStressTime::SemiImplicit) add_solid_viscosity(sim, mimp_, dt);
  fill_scalar_ghosts(mimp_, cfg_.bc);
}

void ImplicitVelocityStep::rate_coefficients(const Simulation& sim, double dt) {
  // q = 2 mu_s dt (1 - H) b of every elastic solid (the upper-convected step's tensor,
  // kernels/helmholtz.hpp), b from the stress just computed from the advected xi
  for (Field* f : {&qxx_, &qxy_, &qyy_}) f->fill(0.0);
  for (const auto& s : sim.solids()) {
    if (s->spec().mu_s <= 0.0) continue;
    // per piece of the window that does not cross a periodic side (solver/model/periodic_window.hpp)
    s->for_each_piece([&](const WindowPiece& p) {
      auto at = [&](const Field& f) { return shifted_view(f.cview(), p.li, p.lj); };
      with_constitutive_model(s->spec(), [&](const auto& model) {
        blend_rate_coefficients(model, at(s->stress_xx()), at(s->stress_xy()), at(s->stress_yy()), at(s->phi()),
                                p.ni, p.nj, s->transition(), cfg_.solid_implicit_reach * cfg_.grid.dx, dt,
                                qxx_.view(), qxy_.view(), qyy_.view(), p.gi, p.gj);
      });
    });
  }
  for (Field* f : {&qxx_, &qxy_, &qyy_}) fill_scalar_ghosts(*f, cfg_.bc);
}

}  // namespace refmap
