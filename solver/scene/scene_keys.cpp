// The scene-file schema (see solver/scene/scene_keys.hpp). One entry per key; the order here is
// the order of the reference in scenes/README.md. The optional components' keys are in
// their own files (solver/model/component_kind.hpp); a comment marks where each goes.
#include "solver/scene/scene_keys.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "solver/model/component_kind.hpp"
#include "solver/model/config.hpp"
#include "solver/scene/option_names.hpp"
#include "solver/scene/suspension.hpp"

namespace refmap {

namespace {

/// A float as a scene file would write it: 1 -> "1.0", 0.5 -> "0.5", 1e-8 -> "1e-8".
std::string float_text(double v) {
  std::string s = key_number_text(v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// the entry builders (solver/io/key_def.hpp)
using namespace keys;

std::vector<KeyDef> build_keys() {
  const Config d;  // the defaults (solver/model/config.hpp)
  const SolidSpec ds;
  const ShapeParams& dsh = ds.shape;
  const PoissonOptions& dp = d.poisson;
  const SolidsOptions& dso = d.solid_opt;
  const InitialVelocity& di = d.init;
  const SideBc db;
  const SuspensionSpec dsu;
  using KT = KeyType;
  const std::vector<std::string> kRectangle = {"rounded_rectangle"}, kNotTabulated = {"circle", "ellipse",
                                                                                       "rounded_rectangle", "zalesak"};
  std::vector<KeyDef> k = {
      shown_default(str("", "name", std::nullopt,
                        "name of the scene; the default output directory is `out/<name>`. Must not contain `/`"),
                    "file stem"),

      num("domain", "x0", d.grid.x0, {}, "x of the lower-left corner"),
      num("domain", "y0", d.grid.y0, {}, "y of the lower-left corner"),
      num("domain", "lx", std::nullopt, gt(0), "width of the domain"),
      shown_default(num("domain", "ly", std::nullopt, gt(0),
                        "height of the domain; cells are square, so it must equal `lx * ny / nx` (to 1e-12 "
                        "relative) and may be omitted"),
                    "`lx * ny / nx`"),

      integer("grid", "nx", std::nullopt, ge(8, "the multigrid solver needs at least 8 cells per direction"),
              "cells in x"),
      integer("grid", "ny", std::nullopt, ge(8, "the multigrid solver needs at least 8 cells per direction"),
              "cells in y"),

      num("fluid", "density", d.rho_f, gt(0), "fluid density rho_f"),
      num("fluid", "viscosity", std::nullopt, ge(0),
          "fluid dynamic viscosity mu_f (the kinematic viscosity is `viscosity / density`)"),

      key("boundary", "left", KT::Boundary, {}, {}, "boundary condition of the side x = x0"),
      key("boundary", "right", KT::Boundary, {}, {}, "boundary condition of the side x = x0 + lx"),
      key("boundary", "bottom", KT::Boundary, {}, {}, "boundary condition of the side y = y0"),
      key("boundary", "top", KT::Boundary, {}, {}, "boundary condition of the side y = y0 + ly"),

      choice<BcType>("boundary.side", "type", std::nullopt, "kind of the boundary condition"),
      only(num("boundary.side", "velocity", std::nullopt, {},
               "tangential wall speed U (u on bottom/top, v on left/right); the normal velocity is 0"),
           "type", {"moving_wall"}),
      only(shown_default(num("boundary.side", "omega", std::nullopt, gt(0),
                             "oscillating wall: speed U sin(omega t + phase)"),
                         "steady wall"),
           "type", {"moving_wall"}),
      only(num("boundary.side", "phase", db.phase, {}, "phase of the oscillating wall (needs `omega`)"), "type",
           {"moving_wall"}),
      only(shown_default(key("boundary.side", "u", KT::Expression, {}, {},
                             "x velocity u(x, y, t) on the side (see *Expressions*); required on the left and "
                             "right sides (the normal velocity)"),
                         "`0`"),
           "type", {"inflow"}),
      only(shown_default(key("boundary.side", "v", KT::Expression, {}, {},
                             "y velocity v(x, y, t) on the side; required on the bottom and top sides"),
                         "`0`"),
           "type", {"inflow"}),

      choice<InitialKind>("initial", "velocity", di.kind, "initial velocity field"),
      only(num("initial", "u", di.u, {}, "constant x velocity"), "velocity", {"uniform"}),
      only(num("initial", "v", di.v, {}, "constant y velocity"), "velocity", {"uniform"}),
      only(num("initial", "amplitude", di.amplitude, {},
               "A in u = A sin(k(x-x0)) cos(k(y-y0)), v = -A cos(k(x-x0)) sin(k(y-y0))"),
           "velocity", {"taylor_green"}),
      only(num("initial", "wavenumber", di.wavenumber, ge(0, "0 means 2 pi / domain.lx"), "k; 0 means 2 pi / lx"),
           "velocity", {"taylor_green"}),
      only(key("initial", "u_expr", KT::Expression, {}, {},
               "u(x, y, t) (see *Expressions*); checked when the scene is loaded"),
           "velocity", {"expression"}),
      only(key("initial", "v_expr", KT::Expression, {}, {},
               "v(x, y, t) (see *Expressions*); checked when the scene is loaded"),
           "velocity", {"expression"}),

      vec2("gravity", "g", std::array<double, 2>{d.gx, d.gy},
           "gravitational acceleration (gx, gy), e.g. `[0.0, -9.81]`; acts on rho - rho_f"),

      num("time", "start", d.t_start, {}, "initial time"),
      num("time", "end", std::nullopt, text_range("> start"), "final time"),
      num("time", "cfl", d.cfl, in(0, true, 2.5, false),
          "advective Courant number: dt (abs(u) + abs(v))_max / dx <= cfl"),
      num("time", "viscous_safety", d.visc_safety, in(0, true, 1, false),
          "fraction of the explicit viscous limit rho dx^2 / (6 mu) (the full-stress operator's stability bound)"),
      num("time", "dt", d.dt_fixed, ge(0, "0 = adaptive"),
          "fixed time step if > 0 (0: adaptive from the limits); refused above the explicit viscous limit "
          "(time.viscous = \"explicit\") or a solid's limit at rest (time.solid_stress = \"explicit\")"),
      shown_default(num("time", "dt_max", d.dt_max, gt(0), "upper bound of the adaptive time step"), "unlimited"),
      integer("time", "max_steps", d.max_steps, ge(0, "0 = unlimited"), "stop after this many steps (0: unlimited)"),
      num("time", "steady_tol", d.steady_tol, ge(0, "0 = off"),
          "stop when max abs(u^{n+1} - u^n) / dt < steady_tol (0: off)"),
      choice<ViscousTime>("time", "viscous", d.viscous_time,
                          "`\"explicit\"`: forward Euler (eq. 5.2; dt <= viscous_safety rho dx^2 / (6 mu)); "
                          "`\"implicit\"`: backward Euler in the compact part, solved by the pressure solver's "
                          "method with a sink term; no viscous time-step limit (docs/implicit.md)"),
      num("time", "rhie_chow_dt", d.rhie_chow_dt, ge(0, "0 = dt"),
          "the time tau of the Rhie-Chow term of the face velocities (eq. 5.3): a steady state's face "
          "velocities are <u> + tau (<G_c> - G_f), so a fixed tau keeps it from moving with dt; the "
          "projection then corrects the faces by tau grad dp and the pressure relaxes by dt / tau per step "
          "(tau <= 4 dt advised; 0: tau = dt, Algorithm 1; docs/method.md)"),
      choice<Splitting>("time", "splitting", d.splitting,
                        "`\"split\"`: Algorithm 1 (the advection and the viscous step act without the pressure "
                        "gradient, the projection applies it whole: a steady state moves with dt); `\"increment\"`: "
                        "the advection carries the last pressure gradient and viscous force as sources, the "
                        "viscous step only their change, so a steady state does not depend on dt "
                        "(docs/method.md, \"Splitting\")"),
      choice<SolidStressTime>("time", "solid_stress", d.solid_time,
                              "`\"explicit\"`: dt <= solid_cfl dx sqrt(rho_s / G); `\"semi_implicit\"`: an "
                              "implicit isotropic term eta = k G dt (1 - H) added and its explicit counterpart "
                              "subtracted (first order in dt); `\"upper_convected\"`: the stress increment 2 mu_s dt (L b + b L^T) "
                              "of the new velocity (upper-convected rate of b, blended with 1 - H) implicit in the "
                              "velocity solve, its explicit counterpart subtracted (first order in dt); no solid "
                              "time-step limit (docs/implicit.md)"),
      choice<ElasticCoupling>("time", "elastic_coupling", d.elastic_coupling,
                              "order of the explicit solid stress and the ξ advection in a step: "
                              "`\"symplectic_euler\"`, Algorithm 1 (ξ advected with the step's starting velocity, then "
                              "the new ξ's stress applied whole: the velocity runs half a step ahead of ξ and the total "
                              "energy is off by O(dt)); `\"verlet\"`, velocity Verlet (ξ advected with the midpoint velocity "
                              "u + dt a / 2, a the last step's acceleration, and the mean of the old and new ξ's stress "
                              "forces applied: second order, no extra stress evaluation); `\"verlet\"` needs time.solid_stress = "
                              "\"explicit\" and solids.xi_velocity = \"face\": given with others it is refused, "
                              "as the default it falls back to `\"symplectic_euler\"` there (docs/method.md, \"Time step\")"),
      boolean("time", "verlet_project_drift", d.verlet_project_drift,
              "with elastic_coupling = `\"verlet\"`: project the drift's stress correction (F^n - F^{n-1}) dt / (4 rho) "
              "onto divergence-free face velocities (one more solve of the pressure operator per step, to 1e-6 "
              "relative) so that xi is carried by a divergence-free velocity; unprojected it compresses thin solids' "
              "maps (results/fsi.md, \"What compresses the flag's map\")"),
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

      choice<FlowMode>("solver", "flow", d.flow,
                       "`\"solve\"`: the Navier-Stokes equations; `\"prescribed\"`: no flow solve, the initial "
                       "velocity (e.g. an expression of t) is imposed at every step and only the solids move"),
      choice<FluxScheme>("solver", "advection", d.advection,
                         "momentum advection scheme: second-order central or Superbee-limited upwind (TVD)"),
      choice<JumpFlux>("solver", "density_jump_flux", d.jump_flux,
                       "with `advection = \"central\"` and a density contrast: the momentum's face values where "
                       "the density varies in the flux stencil, Superbee-limited (stable to ratio 100, "
                       "docs/density_ratio.md) or `\"same\"` central ones (the paper's; blows up from ratio 100)"),
      choice<PoissonMethod>("solver", "poisson", dp.method,
                            "pressure solver: multigrid, conjugate gradients, or multigrid-preconditioned CG"),
      choice<MgCycle>("solver", "cycle", dp.cycle, "multigrid cycle"),
      choice<MgSmoother>("solver", "smoother", dp.smoother,
                         "multigrid smoother: red-black Gauss-Seidel or weighted Jacobi"),
      choice<MgCoarseOperator>("solver", "coarse_operator", dp.coarse_operator,
                               "multigrid coarse coefficients: restriction-weighted mean of beta, or fine faces "
                               "in series normal to the coarse face, or Galerkin P^T L P with operator-dependent "
                               "prolongation (9-point coarse levels; robust to density contrast)"),
      integer("solver", "pre_smooth", dp.pre_smooth, in(1, false, 100, false),
              "smoothing sweeps before coarse-grid correction"),
      integer("solver", "post_smooth", dp.post_smooth, in(1, false, 100, false),
              "smoothing sweeps after coarse-grid correction"),
      num("solver", "tol", dp.tol, in(0, true, 1, true),
          "relative residual norm(r) / norm(rhs) at which the pressure solve stops"),
      integer("solver", "max_iter", dp.max_iter, in(1, false, 1000000, false), "iteration limit of the pressure solve"),
      integer("solver", "coarse_cells", dp.coarse_cells, in(1, false, 1000000, false),
              "multigrid stops coarsening at or below this many cells"),

      num("output", "interval", d.output_interval, ge(0, "0 = first and last frame only"),
          "simulated time between VTK frames (0: first and last frame only)"),
      boolean("output", "vtk", d.write_vtk, "write VTK frames (`.vti` files and a `.pvd` series for ParaView)"),
      boolean("output", "checkpoint", d.checkpoint_frames,
              "write a checkpoint (`checkpoint.bin`, for `refmap resume`) with every VTK frame"),
      num("output", "checkpoint_minutes", d.checkpoint_minutes, ge(0, "0 = not by wall time"),
          "also write a checkpoint every this many wall minutes (`--checkpoint-minutes` overrides)"),
      integer("output", "diagnostics_every", d.diagnostics_every, ge(1), "steps between rows of `diagnostics.csv`"),
      // output.wall_stress: solver/components/wall_stress.cpp (wall_stress_kind)
      // output.body_force: solver/components/control_volume_forces.cpp (control_volume_forces_kind)
      num("output", "log_interval", d.log_interval_s, gt(0, "seconds"),
          "wall seconds between progress log lines when stderr is not a terminal"),

      str("probe", "name", std::nullopt, "unique name of letters, digits and `_` (names the output file)"),
      [] {  // output field names, not a physics option
        KeyDef f = key("probe", "field", KT::Choice, {}, {}, "the sampled cell field");
        f.choices = {"u", "v", "p", "speed", "vorticity", "density"};
        return f;
      }(),
      vec2("probe", "start", std::nullopt, "first point (x, y), inside the domain (walls included)"),
      vec2("probe", "end", std::nullopt, "last point (x, y), inside the domain (walls included)"),
      integer("probe", "points", std::nullopt, in(2, false, 10000000, false), "number of samples"),

      // [[tracers]]: solver/components/tracers.cpp (tracers_kind)

      choice<ExtrapolationMethod>("solids", "extrapolation", dso.extrapolation,
                                  "extrapolation of the reference map into the band: least squares (the paper's "
                                  "Algorithm 2) or the PDE baseline (Aslam 2004)"),
      only(shown_default(num("solids", "lsq_radius", dso.lsq_radius,
                             // r^2 in [8, 33): the 5 x 5 block (2 sqrt(2)) to the paper's 4 sqrt(2)
                             KeyRange{std::sqrt(8.0 - 1e-6), std::sqrt(33.0), false, true,
                                      "cells: from the 5 x 5 block, 2 sqrt(2), to the paper's 4 sqrt(2) = 5.66",
                                      "in [2.83, 5.74]"},
                             "radius of the least-squares plane fit in cells (cells with di² + dj² ≤ "
                             "⌊lsq_radius²⌋ enter it); the paper's is 4√2 = `5.66`"),
                         "`2.83` (2√2)"),
           "extrapolation", {"lsq"}),
      num("solids", "band", dso.band, gt(1, "cells"), "width w_E of the extrapolated band, in cells"),
      num("solids", "transition", dso.transition, gt(0, "cells"),
          "half-width w_T of the smoothed Heaviside that blends solid and fluid (eq. 3.5), in cells; "
          "must be < `band - 1`"),
      boolean("solids", "conservative", dso.conservative,
              "`true`: divergence of the blended stress; `false`: blend of the divergences"),
      choice<StressForm>("solids", "stress_discretisation", dso.stress_form,
                         "solid stress divergence: `\"cell\"`, the paper's cell-centred stress (eqs. 2.9, 3.1), "
                         "`\"face\"`, a compact face-based form, or `\"variational\"`, the force that is the "
                         "derivative of the stored energy of the cells whose ξ is advected (weight moved inward "
                         "by w_V + 1 cells, `variational_width`; docs/implicit.md)"),
      num("solids", "variational_width", dso.variational_width, gt(0, "cells"),
          "with `stress_discretisation = \"variational\"`: half-width w_V of the stored energy's weight "
          "1 - H(phi + (w_V + 1) dx) (eq. 3.5 moved inward so that no weighted cell differences an extrapolated ξ), "
          "in cells"),
      choice<StressBlend>("solids", "stress_blend", dso.stress_blend,
                          "weight of a solid's stress in the mixture: `\"volume\"`, the paper's 1 - H (eq. 3.6), or "
                          "`\"specific\"`, (1 - H) rho_b / rho_s for a solid heavier than the fluid (the stress per unit "
                          "mass blended by volume; removes most of a heavy solid's energy gain, docs/density_ratio.md); "
                          "cell stress in the conservative form only"),
      choice<XiFlux>("solids", "xi_advection", dso.xi_advection,
                     "face values of ξ in its advection (eq. 3.3): second-order central (the paper's) or "
                     "Superbee / van Leer / minmod limited upwind"),
      choice<XiVelocity>("solids", "xi_velocity", dso.xi_velocity,
                         "the velocity that carries ξ (eq. 3.3): the projected face velocities, or the cell-centred "
                         "velocity the solid stress accelerates (with face velocities the velocity's shortest waves "
                         "strain ξ little or not at all, so the solid has no restoring force for them: "
                         "docs/reference_map.md)"),
      num("solids", "solid_cfl", dso.solid_cfl, in(0, true, 8, false),  // above ~1 only for the stability study (bench/stability.py)
          "P of the solid time-step limit dt <= P dx / sqrt(2 mu_s / rho_s) (explicit stress; a fixed `time.dt` above "
          "it is refused); with Algorithm 1's coupling stiff solids fail from about 0.75, with the default Verlet coupling and the cell stress P = 1 is stable at every stiffness (docs/stability.md)"),
      boolean("solids", "reinitialise", dso.reinitialise, "reinitialise phi0(xi) by fast marching every step"),
      only(num("solids", "pde_tol", dso.pde_tol, gt(0),
               "stop when the largest change in the band per iteration is below pde_tol times the largest "
               "known value"),
           "extrapolation", {"pde"}),
      only(integer("solids", "pde_max_iter", dso.pde_max_iter, in(1, false, 1000000000, false), "iteration limit"),
           "extrapolation", {"pde"}),

      shown_default(str("solid", "name", std::nullopt,
                        "unique name of letters, digits and `_` (`solid0`, `solid1`, ... by index)"),
                    "`\"solid<i>\"`"),
      choice<ShapeKind>("solid", "shape", std::nullopt, "reference shape phi0 (eq. 3.2); its keys follow"),
      only(vec2("solid", "center", std::nullopt, "centre (x, y)"), "shape", kNotTabulated),
      only(num("solid", "radius", std::nullopt, gt(0), "radius (of the disk, for `zalesak`)"), "shape",
           {"circle", "zalesak"}),
      only(key("solid", "semi_axes", KT::Vec2, {}, text_range("both > 0"), "semi-axes (a, b), a along the rotated x axis"),
           "shape", {"ellipse"}),
      only(key("solid", "half_size", KT::Vec2, {}, text_range("both > 0"), "half-width and half-height (hw, hh)"),
           "shape", kRectangle),
      only(key("solid", "corner_radius", KT::Float, dsh.corner_radius, text_range("in [0, min(hw, hh)]"),
               "radius of the rounded corners (0: sharp)"),
           "shape", kRectangle),
      only(key("solid", "slot_half_width", KT::Float, {}, text_range("in (0, radius)"),
               "half-width of the slot cut from the bottom of the disk"),
           "shape", {"zalesak"}),
      only(num("solid", "slot_top", std::nullopt, {},
               "y of the top of the slot (unrotated); strictly between the y values where the slot walls meet the "
               "circle"),
           "shape", {"zalesak"}),
      only(num("solid", "angle", dsh.angle, {}, "rotation, radians counter-clockwise about `center`"), "shape",
           {"ellipse", "rounded_rectangle", "zalesak"}),
      only(str("solid", "file", std::nullopt,
               "text file with a sampled phi0 (negative inside), relative to the scene file's directory (format: "
               "`solver/model/shape.hpp`)"),
           "shape", {"tabulated"}),
      shown_default(num("solid", "mu_s", ds.mu_s, ge(0),
                        "the paper's mu^s: solid stress sigma = 2 mu_s b (shear modulus 2 mu_s); 0 gives a "
                        "stress-free solid"),
                    "required (`0.0` with `flow = \"prescribed\"`)"),
      choice<ConstitutiveLaw>("solid", "model", ds.model,
                              "constitutive law (kernels/constitutive.hpp): the paper's neo-Hookean sigma = 2 mu_s b, or "
                              "strain-stiffening W = mu_s (I1 - 3) + c3 (I1 - 3)^2"),
      only(num("solid", "c3", std::nullopt, ge(0), "stiffening coefficient of W = mu_s (I1 - 3) + c3 (I1 - 3)^2; strong stiffening (c3 = 4 mu_s in "
               "`disc_tgv`) blows up with the cell stress form, `solids.stress_discretisation = \"face\"` stays stable"),
           "model", {"strain_stiffening"}),
      shown_default(num("solid", "density", ds.density, gt(0), "solid density rho_s"),
                    "required (`1.0` with `flow = \"prescribed\"`)"),
      num("solid", "viscosity", ds.viscosity, ge(0),
          "Kelvin-Voigt solid viscosity (0: no viscous stress in the solid beyond the fluid's)"),
      num("solid", "grid_viscosity", ds.grid_viscosity, ge(0),
          "c of a grid-scale Kelvin-Voigt viscosity c dx rho_s c_s added to `viscosity` (c_s = sqrt(2 mu_s / "
          "rho_s)); vanishes as the grid is refined (the peer code IncRMT's extra viscosity has c = 0.4-0.8)"),
      choice<SolidVelocity>("solid", "velocity", ds.velocity,
                            "initial velocity inside the solid: rigid (from `u`, `v`, `omega`) or the fluid's"),
      only(num("solid", "u", ds.u, {}, "initial translation velocity, x"), "velocity", {"rigid"}),
      only(num("solid", "v", ds.v, {}, "initial translation velocity, y"), "velocity", {"rigid"}),
      only(num("solid", "omega", ds.omega, {},
               "initial rotation rate (counter-clockwise) about `center` (the bounding-box centre for `tabulated`)"),
           "velocity", {"rigid"}),
      choice<SolidMotion>("solid", "motion", ds.motion,
                          "`\"free\"`: a soft solid moved by the flow; a rigid body (docs/bodies.md) held still "
                          "(`\"fixed\"`), moved on a path (`\"prescribed\"`) or pinned at a point and free to rotate "
                          "(`\"pinned\"`); its velocity is imposed in its region and the force on it reported in "
                          "`solids.csv`. A rigid body takes no `mu_s`; its `viscosity` defaults to the fluid's"),
      only(choice<BodyForcing>("solid", "forcing", ds.forcing,
                               "how a rigid body's velocity is imposed (docs/bodies.md): `\"diffuse\"` relaxes the "
                               "cells by their sub-cell fraction (its surface slips by O(dt)); `\"interpolated\"` is "
                               "sharp: cells inside take the body's velocity, the fluid cells next to the surface the "
                               "value interpolated along the normal between the surface and an image point; `\"sharp\"` is "
                               "`\"interpolated\"` with the cells inside cut out of the pressure solve (their faces "
                               "carry the body's velocity, not corrected by the projection); not for a pinned body"),
           "motion", {"fixed", "prescribed", "pinned"}),
      only(boolean("solid", "forcing_hold", ds.forcing_hold,
                   "`forcing = \"sharp\"` only: hold the cells the forcing sets (inside and next to the surface) "
                   "at their values of the step's start through the advection and the viscous step, the momentum "
                   "they would have taken counted in the force (docs/bodies.md)"),
           "motion", {"fixed", "prescribed", "pinned"}),
      only(choice<ForcingInterpolation>(
               "solid", "forcing_interpolation", ds.forcing_interpolation,
               "`forcing = \"interpolated\"` or `\"sharp\"`: the velocity of a fluid cell next to the surface "
               "from the profile along the normal through the surface (the body's velocity) and one image point "
               "(`\"linear\"`) or two (`\"quadratic\"`: the linear chord's O(dx^2) curvature error, which moves "
               "the effective wall outward, removed; docs/bodies.md)"),
           "motion", {"fixed", "prescribed", "pinned"}),
      only(shown_default(key("solid", "path_x", KT::Expression, {}, {},
                             "x of the centre as an expression of t; must equal `center` at the start time"),
                         "`center` (still)"),
           "motion", {"prescribed"}),
      only(shown_default(key("solid", "path_y", KT::Expression, {}, {},
                             "y of the centre as an expression of t; must equal `center` at the start time"),
                         "`center` (still)"),
           "motion", {"prescribed"}),
      only(shown_default(key("solid", "rotation_rate", KT::Expression, {}, {},
                             "rotation rate omega(t) about the centre, counter-clockwise, an expression of t"),
                         "`0`"),
           "motion", {"prescribed"}),
      only(shown_default(vec2("solid", "pivot", std::nullopt,
                              "the fixed point (x, y) a pinned body rotates about; its initial rate is `omega`"),
                         "`center`"),
           "motion", {"pinned"}),
      only(shown_default(str("solid", "clamp", std::nullopt,
                             "name of a rigid solid this soft solid is clamped to: where it overlaps that body its "
                             "reference map moves with it, and contact between the two is off"),
                         "not clamped"),
           "motion", {"free"}),
      // solid.markers, solid.boundary_markers: solver/components/markers.cpp (markers_kind)

      // solid.actuation and its table: solver/components/actuation.cpp (actuation_kind)

      integer("suspension", "count", dsu.count, ge(0, "0: from `area_fraction`"),
              "number of particles; give this or `area_fraction`"),
      num("suspension", "area_fraction", dsu.area_fraction, in(0, false, 0.9069, false),
          "sum of the particle areas over the domain's area; the count that comes closest is placed (within half "
          "a particle's area); give this or `count`"),
      num("suspension", "radius", std::nullopt, gt(0), "particle radius (of the first size)"),
      num("suspension", "radius2", dsu.radius2, ge(0, "0: one size"), "radius of the second size (0: one size)"),
      num("suspension", "fraction2", dsu.fraction2, in(0, false, 1, false),
          "share of the particles, by number, of the second size"),
      num("suspension", "aspect", dsu.aspect, ge(1),
          "a / b: ellipses of the disc's area (a = r sqrt(aspect), b = r / sqrt(aspect)) at random angles; 1: discs"),
      integer("suspension", "seed", dsu.seed, ge(0), "seed of the placement: the same seed gives the same particles"),
      num("suspension", "gap", dsu.gap, ge(0),
          "least distance between particle surfaces, and from a wall, in units of `radius` (across the periodic "
          "sides too)"),
      integer("suspension", "attempts", dsu.attempts, ge(1),
              "random positions tried per particle before the placement gives up (exit 2 with the fraction reached)"),
      str("suspension", "name", dsu.name, "particle i is the solid named <name><i>"),
      num("suspension", "mu_s", std::nullopt, ge(0), "each particle's `mu_s` (shear modulus G = 2 mu_s)"),
      num("suspension", "density", std::nullopt, gt(0), "each particle's `density`"),
      num("suspension", "viscosity", dsu.viscosity, ge(0), "each particle's (Kelvin-Voigt) `viscosity`"),


      // [contact]: solver/components/contact_component.cpp (contact_kind)
  };
  return k;
}

std::string join(const std::vector<std::string>& v, const std::string& sep, const std::string& last_sep,
                 const char* quote) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += i + 1 == v.size() ? last_sep : sep;
    s += quote + v[i] + quote;
  }
  return s;
}

}  // namespace

namespace {

/// The core's tables (the components' are merged in by scene_catalog).
std::vector<TableDef> core_tables() {
  return {
      {"", "Top level", false, false, false, ""},
      {"domain", "`[domain]`", true, false, false, ""},
      {"grid", "`[grid]`", true, false, false, ""},
      {"fluid", "`[fluid]`", true, false, false, ""},
      {"boundary", "`[boundary]`", true, false, false,
       "All four sides are required; each is a string or an inline table (see *Boundary conditions* below)."},
      {"boundary.side", "`boundary.<side>` as an inline table", false, false, true,
       "`{ type = \"moving_wall\", velocity = U }` or `{ type = \"inflow\", u = \"...\", v = \"...\" }`; "
       "the other kinds take no further keys. An inflow needs an `\"outflow\"` side (p = 0, zero normal "
       "derivative of the velocity); see docs/boundaries.md."},
      {"initial", "`[initial]`", false, false, false,
       "A key of another kind (e.g. `u` with `velocity = \"zero\"`) is an error."},
      {"gravity", "`[gravity]`", false, false, false, ""},
      {"time", "`[time]`", true, false, false, ""},
      {"solver", "`[solver]`", false, false, false, ""},
      {"output", "`[output]`", false, false, false, ""},
      {"probe", "`[[probe]]`", false, true, false, ""},
      // [[tracers]]: solver/components/tracers.cpp
      {"solids", "`[solids]`", false, false, false, "Options shared by all solids; widths are in cells."},
      {"solid", "`[[solid]]`", false, true, false,
       "A shape key that does not belong to the chosen `shape` is an error, as are `u`, `v`, `omega` with "
       "`velocity = \"fluid\"`."},
      // solid.actuation: solver/components/actuation.cpp
      {"suspension", "`[suspension]`", false, false, false,
       "Particles at random positions without overlap (random sequential addition, solver/scene/suspension.hpp), "
       "expanded at load into soft `[[solid]]` tables named `<name><i>` (circles, or ellipses with `aspect` > 1) "
       "that start with the fluid's velocity. Deterministic from `seed`. A fraction the placement cannot reach "
       "in `attempts` tries per particle is an error (exit 2) naming the fraction reached."},
      // [contact]: solver/components/contact_component.cpp
  };
}

/// The core's tables and keys with every component kind's merged in, where each says
/// (solver/model/component_kind.hpp).
KeyCatalog with_components(std::vector<TableDef> tables, std::vector<KeyDef> all) {
  for (const ComponentKind& kind : component_kinds()) {
    for (const auto& t : kind.tables) {
      auto it = std::find_if(tables.begin(), tables.end(), [&](const TableDef& d) { return d.name == t.after; });
      tables.insert(it == tables.end() ? it : it + 1, t.def);
    }
    std::size_t pos = all.size();  // after the kind's anchor key, in a table of the core
    for (std::size_t i = 0; i < all.size(); ++i)
      if (!kind.after.empty() && all[i].dotted() == kind.after) pos = i + 1;
    for (const KeyDef& k : kind.keys) {
      if (pos < all.size() && pos > 0 && all[pos - 1].table == k.table)
        all.insert(all.begin() + std::ptrdiff_t(pos++), k);
      else
        all.push_back(k);
    }
  }
  // grouped by table in the tables' order (`refmap keys` lists them in this order; the
  // core's entries already are), each table's keys in the order above
  auto table_index = [&](const KeyDef& k) {
    for (std::size_t i = 0; i < tables.size(); ++i)
      if (tables[i].name == k.table) return i;
    return tables.size();
  };
  std::stable_sort(all.begin(), all.end(),
                   [&](const KeyDef& a, const KeyDef& b) { return table_index(a) < table_index(b); });
  return {std::move(tables), std::move(all)};
}

}  // namespace

const KeyCatalog& scene_catalog() {
  static const KeyCatalog c = with_components(core_tables(), build_keys());
  return c;
}

const std::vector<TableDef>& scene_tables() { return scene_catalog().tables; }

const std::vector<KeyDef>& scene_keys() { return scene_catalog().keys; }

const KeyDef& scene_key(const std::string& table, const std::string& name) { return scene_catalog().key(table, name); }

std::vector<std::string> scene_key_names(const std::string& table) { return scene_catalog().key_names(table); }

std::vector<std::string> scene_top_level_names() { return scene_catalog().top_level_names(); }

std::string key_type_text(const KeyDef& k) {
  std::string t;
  switch (k.type) {
    case KeyType::Float: t = "float"; break;
    case KeyType::Integer: t = "integer"; break;
    case KeyType::Bool: t = "boolean"; break;
    case KeyType::String: t = "string"; break;
    case KeyType::Choice: {
      std::vector<std::string> q;
      for (const auto& c : k.choices) q.push_back("`\"" + c + "\"`");
      return join(q, ", ", " or ", "");
    }
    case KeyType::Vec2: t = "[float, float]"; break;
    case KeyType::Points: t = "[[float, float], ...]"; break;
    case KeyType::InlineTable: t = "inline table"; break;
    case KeyType::Expression: t = "expression (string or number)"; break;
    case KeyType::Boundary: t = "boundary condition"; break;
  }
  const std::string r = k.range.phrase();
  return r.empty() ? t : t + " " + r;
}

std::string key_default_text(const KeyDef& k) {
  if (!k.default_text.empty()) return k.default_text;
  struct V {
    const KeyDef& k;
    std::string operator()(std::monostate) const { return "required"; }
    std::string operator()(double v) const { return "`" + float_text(v) + "`"; }
    std::string operator()(long v) const { return "`" + std::to_string(v) + "`"; }
    std::string operator()(bool v) const { return v ? "`true`" : "`false`"; }
    std::string operator()(const std::string& s) const { return "`\"" + s + "\"`"; }
    std::string operator()(const std::array<double, 2>& a) const {
      return "`[" + float_text(a[0]) + ", " + float_text(a[1]) + "]`";
    }
  };
  return std::visit(V{k}, k.def);
}

namespace {
std::string only_text(const KeyDef& k) {
  if (k.only.empty()) return "";
  std::vector<std::string> q;
  for (const auto& o : k.only) q.push_back("`" + o + "`");
  return join(q, ", ", " or ", "") + " only: ";
}
}  // namespace

std::string scene_keys_markdown() {
  std::ostringstream o;
  bool first = true;
  for (const auto& t : scene_tables()) {
    if (!first) o << "\n";
    first = false;
    o << "### " << t.heading;
    if (!t.name.empty() && !t.nested)
      o << " (" << (t.required ? "required" : "optional") << (t.repeatable ? ", repeatable" : "") << ")";
    o << "\n\n";
    if (!t.intro.empty()) o << t.intro << "\n\n";
    o << "| key | type | default | meaning |\n| --- | --- | --- | --- |\n";
    for (const auto& k : scene_keys())
      if (k.table == t.name)
        o << "| `" << k.name << "` | " << key_type_text(k) << " | " << key_default_text(k) << " | " << only_text(k)
          << k.description << " |\n";
  }
  return o.str();
}

std::string scene_keys_text() {
  std::ostringstream o;
  for (const auto& k : scene_keys()) {
    std::string name = k.table == "boundary.side" ? "boundary.<side>." + k.name : k.dotted();
    auto plain = [](std::string t) {
      std::string r;
      for (char c : t)
        if (c != '`') r += c;
      return r;
    };
    o << name << "  (" << plain(key_type_text(k)) << "; default " << plain(key_default_text(k)) << ")  "
      << plain(only_text(k) + k.description) << "\n";
  }
  return o.str();
}

}  // namespace refmap
