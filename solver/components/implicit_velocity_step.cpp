#include "solver/components/implicit_velocity_step.hpp"

#include <algorithm>
#include <limits>

#include "kernels/constitutive.hpp"
#include "kernels/solid_stress.hpp"
#include "solver/components/option_names.hpp"
#include "solver/io/key_def.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/model/boundary.hpp"
#include "solver/model/component_kind.hpp"
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

std::span<const OptionName<PicardForce>> option_names(PicardForce) {
  static const OptionName<PicardForce> n[] = {{PicardForce::New, "new"}, {PicardForce::Trapezoidal, "trapezoidal"}};
  return name_list(n);
}

namespace {

using namespace toml_text;

/// The implicit step's [time] keys, into the Config (the Simulation reads them for its limits
/// and its passes). After the core's [time] (they need time.solid_stress) and the solids' keys
/// (the reach is checked against the band).
void configure_implicit_step(const TomlTable& top, Config& cfg) {
  const TomlTable t = top.sub(*top.table("time", true), "time", "time");
  cfg.solid_implicit_k = t.number("solid_implicit_k");
  cfg.solid_implicit_reach = t.number("solid_implicit_reach");
  cfg.solid_implicit_cfl = t.number("solid_implicit_cfl");
  // the two act on the implicit solid term only: with the explicit stress they would do nothing
  const bool implicit_solid = cfg.solid_time != SolidStressTime::Explicit;
  t.require(implicit_solid || cfg.solid_implicit_reach == 0.0, "solid_implicit_reach",
            "needs solid_stress = \"semi_implicit\" or \"upper_convected\"");
  t.require(implicit_solid || cfg.solid_implicit_cfl == 0.0, "solid_implicit_cfl",
            "needs solid_stress = \"semi_implicit\" or \"upper_convected\" (the explicit stress has solids.solid_cfl)");
  cfg.solid_picard = int(t.integer("solid_picard_iterations"));
  cfg.solid_picard_theta = t.number("solid_picard_theta");
  cfg.solid_picard_defect = t.boolean("solid_picard_defect");
  t.require(cfg.solid_picard == 0 || cfg.solid_time != SolidStressTime::UpperConvected, "solid_picard_iterations",
            "is not offered with solid_stress = \"upper_convected\" (docs/implicit.md)");
  t.require(cfg.solid_picard == 0 || !cfg.solid_picard_defect || cfg.solid_time == SolidStressTime::SemiImplicit,
            "solid_picard_defect", "needs solid_stress = \"semi_implicit\" (it corrects through its operator); "
            "set it false for plain repetitions of the step");
  cfg.solid_picard_force = t.option<PicardForce>("solid_picard_force");
  cfg.solid_picard_tol = t.number("solid_picard_tol");
  cfg.solid_picard_anderson = int(t.integer("solid_picard_anderson"));
  t.require(cfg.solid_picard_anderson == 0 || cfg.solid_picard >= 2, "solid_picard_anderson",
            "needs solid_picard_iterations >= 2 (the first mixed pass is the second)");
  t.require(cfg.solid_picard_force == PicardForce::New ||
                (cfg.solid_picard > 0 && cfg.solid_time == SolidStressTime::SemiImplicit),
            "solid_picard_force", "\"trapezoidal\" needs solid_picard_iterations > 0 and solid_stress = "
            "\"semi_implicit\" (with the explicit stress the default Verlet coupling already applies the mean force)");
  cfg.solid_rate_sweeps = t.integer("solid_rate_sweeps");
  cfg.implicit_tol = t.number("implicit_tol");
  // the implicit solid coefficient's blend 1 - H(phi - reach dx) must vanish where phi is
  // capped at the band's edge (phi = band), or it would reach cells whose phi is unknown
  const double limit = cfg.solid_opt.band - cfg.solid_opt.transition;
  if (cfg.solid_implicit_reach > limit)
    t.fail("solid_implicit_reach", "must be <= solids.band - solids.transition = " + fmt_num(limit) +
                                       " cells (the implicit blend must end inside the extrapolated band), got " +
                                       fmt_num(cfg.solid_implicit_reach));
}

}  // namespace

ComponentKind implicit_velocity_step_kind() {
  using namespace keys;
  const Config d;  // the defaults (solver/model/config.hpp)
  ComponentKind k;
  k.name = "implicit_velocity_step";
  k.after = "time.verlet_project_drift";  // after the core's choice of the step (time.viscous, time.solid_stress)
  // read into the Config (configure); the component is made by the Simulation when the
  // scene takes the implicit step (ImplicitVelocityStep::needed)
  k.keys = {
      num("time", "solid_implicit_k", d.solid_implicit_k, gt(0),
          "k of the semi-implicit solid stress: eta = k G dt (stable for k >= 1/4, docs/implicit.md)"),
      num("time", "solid_implicit_reach", d.solid_implicit_reach, ge(0, "cells"),
          "cells by which the implicit solid term (semi_implicit or upper_convected) reaches further into the "
          "fluid than the stress: its coefficient is blended with 1 - H(phi - reach dx) instead of 1 - H(phi); at "
          "most solids.band - solids.transition. 2 keeps a disc in a fluid bounded to about 8x (semi_implicit) "
          "or 4x (upper_convected) the explicit step, at some cost in accuracy (docs/implicit.md)"),
      num("time", "solid_implicit_cfl", d.solid_implicit_cfl, ge(0, "0 = none"),
          "P of a solid time-step limit dt <= P dx sqrt(rho_s / G) for the implicit solid stress (semi_implicit or "
          "upper_convected), which has none by default (0); with solid_implicit_reach = 2 a disc in a fluid stays "
          "bounded to P ~ 8, less through an impact (docs/implicit.md)"),
      integer("time", "solid_picard_iterations", d.solid_picard, in(0, false, 50, false),
              "fixed-point iterations of the whole step in which xi is advanced with (1 - solid_picard_theta) u^n + "
              "solid_picard_theta u^{n+1} of the last iterate and the step re-solved (0: xi moved by u^n, Algorithm 1); "
              "each costs a whole step (experimental; docs/implicit.md)"),
      num("time", "solid_picard_theta", d.solid_picard_theta, in(0, false, 1, false),
          "weight of the new velocity in the transport of xi of solid_picard_iterations (1/2: midpoint, 1: backward "
          "Euler)"),
      boolean("time", "solid_picard_defect", d.solid_picard_defect,
              "the iterations of solid_picard_iterations correct the last velocity change through the "
              "semi-implicit operator, (rho/dt - A(eta)) (d - d_last) = f - rho d_last / dt, so that its term vanishes "
              "at convergence; false: each iteration repeats the semi-implicit step with the new xi"),
      choice<PicardForce>("time", "solid_picard_force", d.solid_picard_force,
                          "solid force of each pass of solid_picard_iterations: `\"new\"`, the force of the pass's "
                          "xi^{n+1} applied whole (its fixed point damps like backward Euler); `\"trapezoidal\"`, the "
                          "mean of the step's starting force F(xi^n) and the pass's (with solid_picard_theta = 1/2 the "
                          "trapezoidal rule; the defect iteration converges in one pass in the solid's interior at "
                          "solid_implicit_k = solid_picard_theta / 2); `\"trapezoidal\"` needs solid_stress = "
                          "\"semi_implicit\" and solid_picard_iterations > 0 (docs/implicit.md)"),
      num("time", "solid_picard_tol", d.solid_picard_tol, in(0, false, 1, true),
          "relative tolerance of the pressure and velocity solves in every pass of solid_picard_iterations but the "
          "last, never tighter than solver.tol and implicit_tol (0: those in every pass); the earlier passes only "
          "give the velocity that moves xi in the next, the last solves to the full tolerances (docs/implicit.md)"),
      integer("time", "solid_picard_anderson", d.solid_picard_anderson, in(0, false, 10, false),
              "history depth m of an Anderson acceleration of the passes of solid_picard_iterations: each pass "
              "from the combination of the last m + 1 passes' results that minimises their residual (0: none, "
              "each pass from the last one's result; docs/implicit.md)"),
      integer("time", "solid_rate_sweeps", d.solid_rate_sweeps, in(1, false, 100, false),
              "outer block Gauss-Seidel sweeps (u, then v) of solid_stress = \"upper_convected\": the first "
              "without its cross terms (b_xy and the other component's derivatives: lagged), each further "
              "one with them at the last sweep's solution (docs/implicit.md)"),
      num("time", "implicit_tol", d.implicit_tol, in(0, true, 1, true),
          "relative residual of the implicit velocity solve (time.viscous = \"implicit\" or "
          "solid_stress = \"semi_implicit\"): its unknown is the velocity change over a step, so it "
          "needs far less than the pressure's solver.tol (docs/implicit.md)"),
  };
  k.configure = configure_implicit_step;
  return k;
}

}  // namespace refmap
