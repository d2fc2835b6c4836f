#pragma once
// The implicit part of the split stress step of eq. (5.2) (time.viscous = "implicit",
// time.solid_stress = "semi_implicit"; docs/implicit.md).
//
// The explicit step is u** = u* + (dt/rho) f with f = div tau(u*) + div sigma_s (the
// forces of kernels/viscous.cpp and kernels/solid_stress.hpp). The implicit step solves
// for the change d = u** - u*, per component,
//
//     (rho/dt) d - div(m grad d)_compact = f,      m = mu_impl + eta,
//
// with the compact normal part of the full stress (2 m d_xx + m d_yy for u, m d_xx +
// 2 m d_yy for v: kernels/helmholtz.hpp) and homogeneous wall conditions (the wall values
// are already in f, which was evaluated at u* with the walls at t + dt). Then
//  * with mu_impl = mu: (rho/dt)(u** - u*) = A(mu) u** + C(mu) u* + div sigma_s, i.e.
//    backward Euler in the compact part A and the cross-derivative part C (u_y in the
//    v-equation, v_x in the u-equation) lagged at u*. For constant mu and a
//    divergence-free field C is mu grad(div u) = 0; it matters only where mu varies
//    (the fluid-solid blend). First order in time.
//  * with eta = k G dt (1 - H(phi)) (G the solid's shear modulus, blended like the stress,
//    eq. 3.6): the stabilised splitting "add an implicit isotropic viscosity, subtract its
//    explicit counterpart": the term added, A(eta)(u** - u*), is O(dt^2) per step and
//    vanishes as dt -> 0 (first-order consistent). For the 1-D shear wave the scheme is
//    u^{n+1} - 2u^n + u^{n-1} = -w/(1 + k w) u^n with w = (c dt kappa)^2 (wave number
//    kappa, c^2 = G/rho), stable for all dt when k >= 1/4.
// Backward Euler rather than Crank-Nicolson: at dt far above the explicit limit the
// CN amplification of the stiff (grid-scale) modes tends to -1 (undamped ringing), while BE
// damps them (L-stable); and the lagged cross term and the stabilised solid splitting are
// first order anyway, so CN would not give second order.
#include <array>
#include <memory>
#include <vector>

#include "core/field.hpp"
#include "solver/model/config.hpp"
#include "solver/pressure/poisson.hpp"
#include "solver/io/state_registry.hpp"

namespace refmap {

class ImplicitVelocity {
 public:
  explicit ImplicitVelocity(const Config& cfg);

  /// u += d_u, v += d_v with d solving the problem above for the force (fx, fy), density
  /// rho and implicit viscosity m (cell field; ghosts filled as fill_scalar_ghosts does).
  void apply(Field& u, Field& v, const Field& fx, const Field& fy, const Field& rho,
             const Field& m, double dt);

  /// Cells held fixed by the next apply() (a rigid body's forcing_hold, solver/model/rigid_body.hpp):
  /// d = 0 there (Dirichlet: their faces leave the operator, each face's coefficient moves
  /// to the neighbour's sink), and held_rate() then gives, per held cell and component, the
  /// force per volume the step would have put into it, f_P + (1/dx^2) sum_f beta_f d_nb
  /// (the momentum the hold takes out, over dt). Cell (i, j, tag): the tag is not read.
  /// An empty list holds nothing. Not with apply_rate.
  void set_held(const std::vector<std::array<int, 3>>* cells) { held_ = cells; }
  const std::vector<std::array<double, 2>>& held_rate() const { return held_rate_; }

  /// time.solid_stress = "upper_convected" (docs/implicit.md): the same step with the solid
  /// stress increment tau = 2 mu_s dt (1 - H)(L b + b L^T), L = grad d, implicit: per
  /// component (rho/dt) d - div(k grad d)_compact = f + cross(d), the compact coefficients
  /// k from m and the tensor q = 2 mu_s dt (1 - H) b (kernels/helmholtz.hpp: 2 m + 2 q_xx on
  /// x faces and m + q_yy on y faces for u; m + q_xx and 2 m + 2 q_yy for v), the cross
  /// terms of tau at the latest iterate, time.solid_rate_sweeps outer block Gauss-Seidel
  /// sweeps (u, then v; the first without the cross terms, i.e. lagged at u*, each further
  /// one with those of the latest iterate). m, q need one ghost layer.
  void apply_rate(Field& u, Field& v, const Field& fx, const Field& fy, const Field& rho,
                  const Field& m, const Field& qxx, const Field& qxy, const Field& qyy, double dt);
  /// max |d change in the last outer sweep| / max |d| of the last apply_rate (0 with one sweep).
  double last_sweep_change() const { return sweep_change_; }

  /// The relative tolerance of the next solves (time.implicit_tol until called; the
  /// earlier passes of time.solid_picard_iterations loosen it, solver/model/solid_picard.cpp).
  void set_tol(double tol);
  double tol() const { return tol_; }

  /// The velocity change of component comp (0: u, 1: v) of the last apply().
  const Field& last_change(int comp) const { return comp == 0 ? du_ : dv_; }
  /// (ou, ov) = A(m) (du, dv): the compact operator of apply() without its rho/dt sink,
  /// with the same homogeneous wall conditions (time.solid_picard_defect moves A(eta) of the
  /// last iterate's change to the right-hand side; docs/implicit.md). m needs one ghost layer.
  void compact_operator(const Field& m, const Field& du, const Field& dv, Field& ou, Field& ov);

  /// Iterations of the last solve (u and v summed) and the worse relative residual.
  int last_iterations() const { return iterations_; }
  double last_residual() const { return residual_; }
  long total_iterations() const { return total_iterations_; }

  /// Registers what the next step reads of the last ones: the last two changes and steps
  /// (the initial guesses extrapolate them, so a resumed run needs them to continue bit for
  /// bit), the step count and the solve statistics the diagnostics report.
  void register_state(StateRegistry& reg);

 private:
  SolveStats solve(int comp, const Field& f, const Field& rho, const Field& m, double dt, Field& d);
  /// The initial guesses du_, dv_ for this step (extrapolated from the last two).
  void predict_changes(double dt);
  /// Ghosts of a change d of component comp: the homogeneous wall condition (fixed: -d,
  /// free: +d) or the periodic wrap; corners included (for the tangential differences).
  void change_ghosts(Field& d, int comp) const;

  /// Held cells (set_held): their faces out of the operator of component comp, their
  /// neighbours' sinks raised; the faces' coefficients before, per cell (left, right,
  /// bottom, top), into held_beta_[comp].
  void hold_cells(int comp, double dx);
  /// f_P + (1/dx^2) sum_f beta_f d_nb at the held cells into held_rate_[.][comp].
  void held_rates(int comp, const Field& f, const Field& d, bool solved);

  Config cfg_;
  Sides sides_;
  double tol_;  ///< the solves' relative tolerance (time.implicit_tol; set_tol)
  const std::vector<std::array<int, 3>>* held_ = nullptr;
  std::array<std::vector<std::array<double, 4>>, 2> held_beta_;
  std::vector<std::array<double, 2>> held_rate_;
  Field held_mark_;  ///< 1 at the held cells while a component is set up
  std::array<std::array<bool, 4>, 2> fixed_{};  ///< per component, per side: Dirichlet
  // per component: face coefficients, sink and the solver (the pressure solver's method
  // and options with tol = time.implicit_tol, solver/pressure/poisson.hpp, with the sink term), set
  // up anew every step (rho, m and dt change)
  std::array<Field, 2> bx_, by_, c_;
  std::array<std::unique_ptr<PoissonSolver>, 2> solver_;
  Field rhs_;
  Field du_, dv_;    ///< the last step's changes (then this step's initial guesses)
  Field du2_, dv2_;  ///< the changes of the step before (the guess extrapolates the two)
  std::array<Field, 2> kx_, ky_;  ///< upper-convected: cell coefficients of the compact part
  Field opx_, opy_, opc_, zero_, dtmp_;  ///< compact_operator's scratch
  Field cx_, cy_, dprev_;          ///< upper-convected: cross force, the last sweep's d
  double sweep_change_ = 0.0;
  double dt1_ = 0.0, dt2_ = 0.0;  ///< the last two steps' dt
  long steps_ = 0;
  int iterations_ = 0;
  double residual_ = 0.0;
  long total_iterations_ = 0;
};

}  // namespace refmap
