#pragma once
// Everything a scene file says, after validation: plain data (it includes only io/, pressure/
// and model/ headers: tests/test_layout.cpp). solver/scene/scene.cpp fills it from TOML, with
// the kinds that configure it (the solids' and the implicit step's keys, solver/components/);
// the time loop (solver/model/simulation.cpp) only reads it. The member initialisers below are
// the defaults of the scene keys: the key tables (solver/scene/scene_keys.cpp, the components' kinds) read them from a
// default-constructed Config, so the loader and scenes/README.md use these values.
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "kernels/boundary_kind.hpp"
#include "kernels/advection.hpp"
#include "kernels/reference_map.hpp"
#include "kernels/constitutive.hpp"
#include "core/grid.hpp"
#include "solver/io/expression.hpp"
#include "solver/pressure/poisson.hpp"
#include "solver/model/shape_params.hpp"

namespace refmap {

enum class BcType { NoSlip, MovingWall, FreeSlip, Periodic, Inflow, Outflow };

// Physics options are enums from the moment the scene is loaded; their scene-file names
// are in solver/scene/option_names.hpp (to_string / parse_option of solver/io/enum_names.hpp).

/// Config::flow: solve Navier-Stokes, or impose the initial velocity field at every step.
enum class FlowMode { Solve, Prescribed };
/// InitialVelocity::kind.
enum class InitialKind { Zero, Uniform, TaylorGreen, Expression };
/// SolidSpec::velocity: initial velocity inside a solid.
enum class SolidVelocity { Rigid, Fluid };
/// SolidSpec::motion: a soft solid moved by the flow (Free), or a rigid body held still,
/// moved on a prescribed path or pinned at a point (solver/model/rigid_body.hpp, docs/bodies.md).
enum class SolidMotion { Free, Fixed, Prescribed, Pinned };
/// SolidSpec::forcing: how a rigid body's velocity is imposed (solver/model/rigid_body.hpp):
/// Diffuse, relaxed by the sub-cell fraction chi; Interpolated, sharp (cells inside take the
/// body's velocity, the fluid cells next to the surface a value interpolated along the normal);
/// Sharp, Interpolated with the cells inside cut out of the pressure solve (their faces carry
/// the body's velocity and are not corrected).
enum class BodyForcing { Diffuse, Interpolated, Sharp };
/// SolidSpec::forcing_interpolation: the profile along the normal through which the
/// interpolated and sharp forcings set a fluid cell next to the surface (rigid_body.cpp):
/// Linear, between the surface and one image point; Quadratic, through the surface and two.
enum class ForcingInterpolation { Linear, Quadratic };
/// SolidSpec::forcing_faces (forcing = "sharp"): the faces of the cells inside. Staircase,
/// closed (beta = 0, the body's velocity: the normal flux stops on the staircase of inside
/// cells); Aperture, a cut cell's face: beta times the face's open (phi > 0) fraction a and
/// the mean velocity a u_open + (1 - a) u_body, u_open from the forced cells' normal profile
/// (the normal flux stops on phi = 0; rigid_body.cpp).
enum class CutFaces { Staircase, Aperture };
/// SolidsOptions::extrapolation: Algorithm 2 (least squares) or the PDE baseline.
enum class ExtrapolationMethod { Lsq, Pde };
/// SolidsOptions::stress_form: discretisation of the solid stress divergence. Variational:
/// the energy-consistent force of kernels/variational_stress.hpp (docs/implicit.md).
enum class StressForm { Cell, Face, Variational };
/// SolidsOptions::stress_blend: the weight of a solid's stress in the mixture (eq. 3.6):
/// Volume, the paper's 1 - H; Specific, (1 - H) rho_b / rho_s for a solid heavier than the
/// fluid (rho_b = (1 - H) rho_s + H rho_f): the stress per unit mass blended by volume
/// fraction, so the light cells of the blend are not driven harder than the solid
/// (docs/density_ratio.md). The same as Volume when rho_s <= rho_f.
enum class StressBlend { Volume, Specific };
/// Config::viscous_time: the viscous stress forward Euler (eq. 5.2) or backward Euler in
/// its compact part (solver/model/implicit_step.hpp, docs/implicit.md).
enum class ViscousTime { Explicit, Implicit };
/// Config::splitting (time.splitting): how the substeps of a step (advection, viscous step,
/// projection) share the work. Split: Algorithm 1 as published -- the advection and the
/// viscous step act on the velocity without the pressure gradient, which the projection
/// applies whole, so a steady state of the scheme moves with dt. Increment: the advection
/// carries the last pressure gradient and viscous force as sources and the viscous step
/// solves for the change of the viscous force only, so in a steady state every substep
/// leaves the velocity unchanged (docs/method.md, "Splitting").
enum class Splitting { Split, Increment };
/// Config::solid_time: the solid stress explicit, or explicit plus the stabilising implicit
/// isotropic term eta = k G dt (1 - H) minus its explicit counterpart, or the
/// upper-convected stress increment 2 mu_s dt (1 - H)(L b + b L^T) implicit (docs/implicit.md).
enum class SolidStressTime { Explicit, SemiImplicit, UpperConvected };
/// Config::elastic_coupling (time.elastic_coupling): how the explicit solid stress and the xi
/// advection take turns in a step. SymplecticEuler: Algorithm 1 -- xi advected with the
/// velocity of the step's start, then the stress of the new xi applied whole (drift, kick):
/// the stored velocity runs half a step ahead of xi, so the total energy is off by O(dt).
/// Verlet: velocity Verlet -- xi advected with the midpoint velocity u^n + dt/2 a^n, the
/// stress applied as the mean of the old and new xi's forces (half kick, drift, half kick):
/// second order, same stress evaluations per step (docs/method.md, "Time step").
enum class ElasticCoupling { SymplecticEuler, Verlet };
/// Config::solid_picard_force (time.solid_picard_force): the solid force of a pass of
/// time.solid_picard_iterations. New: the force of the pass's xi^{n+1,(k)} applied whole (the
/// fixed point damps like backward Euler). Trapezoidal: the mean of the step's starting force
/// F(xi^n) and the pass's, (F^n + F^{n+1,(k)}) / 2 (with theta = 1/2 the fixed point is the
/// trapezoidal rule: energy-neutral for the linear oscillator; solver/model/solid_picard.cpp).
enum class PicardForce { New, Trapezoidal };
/// Config::jump_flux: the momentum's face values where the density is not one value in a
/// face's stencil (a density jump), with central advection: Superbee-limited (default) or
/// the same central values as elsewhere (docs/density_ratio.md).
enum class JumpFlux { Superbee, Same };

/// Boundary condition of one side. `velocity` is the tangential wall speed of a moving
/// wall (u on bottom/top, v on left/right); the normal velocity at a wall is always 0.
/// Periodic must be set on both sides of a direction. Inflow: the velocity (inflow_u,
/// inflow_v) on the side is prescribed as expressions of x, y, t (docs/boundaries.md);
/// Outflow: p = 0 and zero normal derivative of the velocity.
struct SideBc {
  BcType type = BcType::NoSlip;
  double velocity = 0.0;
  Expression inflow_u, inflow_v;  ///< Inflow only: u(x, y, t), v(x, y, t) on the side
  /// Optional time dependence of a moving wall: speed = velocity * sin(omega t + phase)
  /// when `oscillating` is true (the elastic-layer Couette flow needs it).
  bool oscillating = false;
  double omega = 0.0, phase = 0.0;
  double speed(double t) const;  ///< defined in solver/model/boundary.cpp
};

/// A named line probe: `points` samples from (x0,y0) to (x1,y1) of a cell field
/// ("u", "v", "p", "speed", "vorticity", "density"), bilinear from cell centres.
struct ProbeSpec {
  std::string name, field;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int points = 2;
};

struct InitialVelocity {
  InitialKind kind = InitialKind::Zero;
  double u = 0.0, v = 0.0;    ///< uniform velocity
  double amplitude = 1.0;     ///< Taylor-Green: u = A sin(k(x-x0)) cos(k(y-y0)), v = -A cos sin
  double wavenumber = 0.0;    ///< k; 0 means 2 pi / lx
  std::string u_expr, v_expr; ///< expression kind: functions of x, y (and pi)
};

/// One solid of a scene ([[solid]] tables).
struct SolidSpec {
  std::string name;
  ShapeParams shape;          ///< reference configuration, phi0 of eq. (3.2)
  double mu_s = 0.0;          ///< the paper's mu^s: sigma = 2 mu_s b, shear modulus G = 2 mu_s
  /// constitutive law (kernels/constitutive.hpp): neo-Hookean (eq. 2.9) or strain-stiffening
  /// W = mu_s (I1 - 3) + c3 (I1 - 3)^2
  ConstitutiveLaw model = ConstitutiveLaw::NeoHookean;
  double c3 = 0.0;            ///< strain-stiffening coefficient (model StrainStiffening only)
  double density = 1.0;       ///< rho_s
  double viscosity = 0.0;     ///< Kelvin-Voigt solid viscosity (0: no viscous stress in the solid), grid part included
  /// c of the grid-scale part c dx rho_s c_s that the scene adds to `viscosity` (c_s the
  /// shear-wave speed at rest; 0: none)
  double grid_viscosity = 0.0;
  /// Rigid: u = (u, v) + omega x (x - centre); Fluid: keep the fluid's
  SolidVelocity velocity = SolidVelocity::Rigid;
  double u = 0.0, v = 0.0, omega = 0.0;
  /// Free: a soft solid (the paper's); otherwise a rigid body whose velocity is imposed in
  /// its region (solver/model/rigid_body.hpp). A rigid body has no elastic stress (mu_s = 0).
  SolidMotion motion = SolidMotion::Free;
  BodyForcing forcing = BodyForcing::Diffuse;  ///< rigid bodies only
  /// forcing = "sharp" only: the cells the forcing sets are held at their values of the
  /// step's start through the advection and the viscous step (solver/model/rigid_body.hpp)
  bool forcing_hold = false;
  /// forcing = "interpolated" or "sharp": the normal profile of the cells next to the surface
  ForcingInterpolation forcing_interpolation = ForcingInterpolation::Linear;
  /// forcing = "sharp": closed cut faces or cut-cell apertures (rigid_body.cpp)
  CutFaces forcing_faces = CutFaces::Staircase;
  /// Prescribed: the centre's path x(t), y(t) and the rotation rate omega(t) (expressions
  /// of t; the path starts at the shape's centre).
  std::string path_x, path_y, rotation_rate;
  double pivot_x = 0.0, pivot_y = 0.0;  ///< Pinned: the fixed point it rotates about
  /// A soft solid clamped to a rigid one: its reference map is held at the rigid motion
  /// where it overlaps that body ("" = not clamped); clamp_index is its index.
  std::string clamp;
  int clamp_index = -1;
  bool rigid() const { return motion != SolidMotion::Free; }
};

/// Options shared by all solids ([solids] table).
struct SolidsOptions {
  ExtrapolationMethod extrapolation = ExtrapolationMethod::Lsq;  ///< Algorithm 2, or the Aslam 2004 PDE baseline
  /// Lsq: radius of the plane fit, in cells; the known cells with offsets di^2 + dj^2 <=
  /// floor(lsq_radius^2) enter it. Default 2 sqrt(2) (a 5 x 5 block), half the paper's
  /// 4 sqrt(2): with the paper's radius a stiff solid translating through an inviscid
  /// fluid gains energy without bound and impacts gain energy (docs/reference_map.md; the
  /// numbers in results/methods.md, "Least-squares fit radius"; why the wider fit feeds it is
  /// not established). Both radii are exact for affine xi.
  double lsq_radius = 2.0 * 1.4142135623730951;
  double band = 6.0;        ///< w_E, width of the extrapolated band, in cells
  double transition = 3.0;  ///< w_T, half-width of the smoothed Heaviside (eq. 3.5), in cells
  bool conservative = true; ///< divergence of the blended stress (true) or blend of divergences
  /// Cell (default, the paper's discretisation): divergence of the cell-centred stress of
  /// eqs. (2.9), (3.1); Face: compact face-based stress (couples the odd-even mode that
  /// the 2 dx-wide cell form leaves undamped in an inviscid solid, but was seen to gain
  /// energy in the disc-in-Taylor-Green case; see kernels/solid_stress.hpp)
  StressForm stress_form = StressForm::Cell;
  /// StressForm::Variational: half-width w_V of the energy's weight 1 - H(phi + w_V + dx, w_V),
  /// in cells (zero where a cell's stencil reaches an extrapolated cell, phi >= -dx)
  double variational_width = 1.0;
  StressBlend stress_blend = StressBlend::Volume;  ///< solids.stress_blend (cell, conservative form)
  /// face values of xi in its advection (eq. 3.3): Central (the paper's), VanLeer, Superbee
  /// or Minmod (limited upwind: damp grid-scale xi oscillations where the solid moves; all
  /// four exact for an affine xi; see docs/reference_map.md)
  XiFlux xi_advection = XiFlux::VanLeer;
  /// the velocity that carries xi (eq. 3.3): Face, the projected face velocities (default),
  /// or Cell, the cell-centred velocity the solid stress accelerates: with face velocities
  /// the solid's shortest waves have (almost) no restoring force (kernels/reference_map.hpp);
  /// Cell is an experiment: on the Turek & Hron flag it fails sooner (results/fsi.md)
  XiVelocity xi_velocity = XiVelocity::Face;
  double solid_cfl = 0.5;   ///< P of section 4: dt <= P dx / sqrt(2 mu_s / rho_s)
  bool reinitialise = true; ///< fast-marching reinitialisation of phi0(xi)
  double pde_tol = 1e-8;    ///< PDE baseline: stop when max |change| per iteration < tol * (largest known |xi|)
  int pde_max_iter = 1000;
};

/// The options of an optional component, parsed by its kind from the component's own
/// keys (solver/model/component_kind.hpp); each kind derives its own.
struct ComponentOptions {
  virtual ~ComponentOptions() = default;
};

struct Config {
  std::string scene_path;  ///< the file it came from (for messages)
  std::string name;        ///< scene name (file stem unless set)

  Grid grid;
  double rho_f = 1.0;  ///< fluid density
  double mu_f = 0.0;   ///< fluid dynamic viscosity
  std::array<SideBc, 4> bc{};
  InitialVelocity init;
  double gx = 0.0, gy = 0.0;  ///< gravity; acts on rho - rho_f (balanced-force, Algorithm 1 step 5)

  // time
  double t_start = 0.0, t_end = 1.0;
  double cfl = 0.5;          ///< advective Courant number: dt (|u|+|v|)_max / dx <= cfl
  double visc_safety = 0.9;  ///< fraction of the forward-Euler viscous bound rho dx^2/(6 mu)
  double dt_fixed = 0.0;     ///< > 0 forces this dt
  double dt_max = 1e30;
  long max_steps = 0;        ///< 0 = unlimited
  double steady_tol = 0.0;   ///< > 0: stop when max|u^{n+1}-u^n|/dt < steady_tol
  ViscousTime viscous_time = ViscousTime::Explicit;        ///< time.viscous
  Splitting splitting = Splitting::Split;                  ///< time.splitting
  /// time.rhie_chow_dt: the time tau of the Rhie-Chow term of the face velocities, which in a
  /// steady state are <u> + tau (<G_c> - G_f); 0: the step's dt (Algorithm 1). With tau != dt
  /// the projection corrects the faces by tau grad dp (the pressure relaxes by dt/tau per step).
  double rhie_chow_dt = 0.0;
  SolidStressTime solid_time = SolidStressTime::Explicit;  ///< time.solid_stress
  /// time.elastic_coupling; Verlet acts only with the explicit stress and face transport of
  /// xi (verlet_coupling()): symplectic Euler otherwise
  ElasticCoupling elastic_coupling = ElasticCoupling::Verlet;
  /// time.verlet_project_drift: the drift's correction (F^n - F^{n-1}) dt / (4 rho) projected
  /// (one more pressure-operator solve per step) so that the face velocity that carries xi
  /// stays divergence-free (kernels/verlet.hpp; results/fsi.md, "What compresses the flag's map")
  bool verlet_project_drift = false;
  double solid_implicit_k = 0.5;  ///< time.solid_implicit_k: k of eta = k G dt (stable for k >= 1/4)
  /// time.solid_implicit_reach: cells by which the implicit solid coefficient's blend
  /// 1 - H(phi - reach dx) reaches further into the fluid than the stress's (docs/implicit.md)
  double solid_implicit_reach = 0.0;
  /// time.solid_implicit_cfl: P of dt <= P dx sqrt(rho_s / G) for the implicit solid stress
  /// (0: no solid limit; with the reach a disc in a fluid stays bounded to P ~ 8)
  double solid_implicit_cfl = 0.0;
  /// time.solid_picard_iterations: fixed-point iterations of the whole step with xi advanced by
  /// the latest end-of-step velocity (0: Algorithm 1's step, xi moved by u^n; docs/implicit.md,
  /// "The implicit step in xi")
  int solid_picard = 0;
  double solid_picard_theta = 0.5;  ///< time.solid_picard_theta: xi moves with (1 - theta) u^n + theta u^{n+1}
  /// time.solid_picard_defect: the iterations correct the last one's velocity change through
  /// the stabilising operator (its term vanishes at convergence) instead of repeating the step
  bool solid_picard_defect = true;
  PicardForce solid_picard_force = PicardForce::New;  ///< time.solid_picard_force
  /// time.solid_picard_tol: the relative tolerance of the pressure and velocity solves in every
  /// pass but the last (never tighter than solver.tol and implicit_tol; 0: those in every pass)
  double solid_picard_tol = 1e-4;
  /// time.solid_picard_anderson: history depth of the Anderson acceleration of the passes
  /// (solver/model/picard_anderson.hpp; 0: none, each pass starts from the last one's result)
  int solid_picard_anderson = 0;
  int solid_rate_sweeps = 1;  ///< time.solid_rate_sweeps: outer block Gauss-Seidel sweeps of the upper-convected step (1: cross terms lagged)
  /// time.implicit_tol: relative residual of the implicit velocity solve (the velocity
  /// change d over a step; solver/model/implicit_step.hpp); looser than the pressure's solver.tol
  double implicit_tol = 1e-5;

  // numerics
  FluxScheme advection = FluxScheme::Central;  ///< momentum fluxes of eq. (5.1)
  JumpFlux jump_flux = JumpFlux::Superbee;      ///< solver.density_jump_flux
  PoissonOptions poisson;

  // output
  double output_interval = 0.0;  ///< simulated time between VTK frames; 0 = first and last only
  bool write_vtk = true;
  /// a checkpoint (DIR/checkpoint.bin, solver/model/checkpoint.cpp) with every VTK frame
  bool checkpoint_frames = true;
  /// and every this many wall minutes (0: not by wall time); refmap run --checkpoint-minutes
  double checkpoint_minutes = 30.0;
  int diagnostics_every = 1;     ///< steps between rows of diagnostics.csv
  double log_interval_s = 2.0;   ///< wall seconds between log lines when not on a terminal
  std::vector<ProbeSpec> probes;

  // solids
  std::vector<SolidSpec> solids;
  SolidsOptions solid_opt;
  /// Solve (Navier-Stokes) or Prescribed: the initial velocity field (an expression,
  /// possibly of t) is imposed at every step and no flow is solved (kinematic tests such
  /// as the Zalesak disk).
  FlowMode flow = FlowMode::Solve;

  /// The optional components the scene uses (tracers, markers, actuation, ...;
  /// solver/model/component_kind.hpp), in registration order: the kind's name and the options
  /// its parser read from the component's own keys. A kind the scene leaves off is absent.
  std::vector<std::pair<std::string, std::shared_ptr<const ComponentOptions>>> components;
  /// The options of component kind `kind` (null: the scene does not use it).
  template <class T>
  const T* component_options(const std::string& kind) const {
    for (const auto& [name, o] : components)
      if (name == kind) return dynamic_cast<const T*>(o.get());
    return nullptr;
  }
};

/// Whether the solids' explicit stress is coupled by velocity Verlet: time.elastic_coupling
/// = "verlet" (the default) with the explicit stress and xi moved by the face velocities,
/// from which its midpoint velocity is built (docs/method.md, "Time step").
inline bool verlet_coupling(const Config& c) {
  return c.elastic_coupling == ElasticCoupling::Verlet && c.solid_time == SolidStressTime::Explicit &&
         c.solid_opt.xi_velocity == XiVelocity::Face && c.flow != FlowMode::Prescribed;
}

}  // namespace refmap
