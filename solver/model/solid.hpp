#pragma once
// One reference-map solid (Jain & Mani, sections 2-3; Algorithm 1 steps 1-3).
//
// Storage follows the solid: xi, phi, the known-mask and the solid stress live on a
// rectangular WINDOW of the global grid that covers the solid, its extrapolation band
// Omega_E and a margin. The window moves and grows with the solid (re-windowing copies
// the overlap), so memory and work scale with the solid's size, not with the grid.
//
// A solid that spans a periodic direction completely (the elastic layer of the Couette
// test) gets a window of the full width in that direction, with ghost cells wrapped and
// the reference map shifted by the period: xi_x(x + L) = xi_x(x) + L. Any other solid may
// cross a periodic side: its window is in unwrapped index space and only the global
// fields are read and written modulo the period (solver/model/periodic_window.hpp).
#include <memory>
#include <string>

#include "kernels/boundary_kind.hpp"
#include "kernels/extrapolate.hpp"
#include "kernels/fast_marching.hpp"
#include "solver/model/config.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/model/periodic_window.hpp"
#include "solver/model/shape.hpp"

namespace refmap {

class CheckpointWriter;
class CheckpointReader;

struct ExtrapolationCounters {
  long calls = 0;
  long cells_filled = 0;
  long fallbacks = 0;
  long iterations = 0;  ///< PDE pseudo-time iterations (0 for least squares)
  double seconds = 0.0; ///< wall time spent in the extrapolation kernels
};

struct SolidDiagnostics {
  double area = 0.0;        ///< sum of clamp(1/2 - phi/dx, 0, 1) dx^2 (sub-cell area of phi < 0)
  double cx = 0.0, cy = 0.0;///< centroid of that area
  double u = 0.0, v = 0.0;  ///< mean velocity over it
  double sigma_max = 0.0;   ///< max |normal stress (sxx + syy)/2| inside the solid
};

class Solid {
 public:
  /// sides: which directions are periodic (a solid spanning one gets a wrapped window of
  /// the full width; any other may cross its sides: solver/model/periodic_window.hpp).
  /// rho_f: the fluid's density (solids.stress_blend = "specific" weighs the stress by it).
  Solid(const SolidSpec& spec, const SolidsOptions& opt, const Grid& g, Sides sides, double rho_f = 1.0);

  const SolidSpec& spec() const { return spec_; }
  const Shape& shape() const { return *shape_; }

  // --- Algorithm 1, steps 1-2 -------------------------------------------------------
  /// Eq. (3.3), RK-4 in time with the velocity frozen over the step, H = 1 only where
  /// phi < 0; the band is re-extrapolated before the right-hand side of stages 2-4. The
  /// face velocities (uf, vf) carry xi, or the cell velocities (u, v) with
  /// solids.xi_velocity = "cell" (kernels/reference_map.hpp).
  void advect(const Field& uf, const Field& vf, const Field& u, const Field& v, double dt);
  /// Fills xi in the band from the cells advected (phi < 0) by the method of
  /// solids.extrapolation (least squares or the PDE; kernels/extrapolate.hpp).
  void extrapolate() { extrapolate_layers(0); }
  /// phi = phi0(xi) (eq. 3.2) on the band, reinitialised by fast marching; moves/grows
  /// the window when the band comes near its edge.
  void rebuild_level_set();

  /// Lets f(x, y, xi_x, xi_y) overwrite the reference map at every window cell (cell
  /// centre (x, y)); f returns true where it set xi, and those cells count as known when
  /// the level set is rebuilt. Ghosts are refilled. For rigid and clamped solids
  /// (solver/model/rigid_body.hpp), between extrapolate() and rebuild_level_set().
  template <class F>
  void overwrite_reference_map(F&& f) {
    for (int j = 0; j < nj_; ++j)
      for (int i = 0; i < ni_; ++i) {
        double X = xi_x_(i, j), Y = xi_y_(i, j);
        if (!f(grid_.xc(i0_ + i), grid_.yc(j0_ + j), X, Y)) continue;
        xi_x_(i, j) = X;
        xi_y_(i, j) = Y;
        known_(i, j) = 1;
      }
    fill_ghosts(xi_x_, 0);
    fill_ghosts(xi_y_, 1);
  }

  // --- mixture ---------------------------------------------------------------------
  /// Adds (1 - H) (q_s - q_f) to `out` over the window (density or viscosity blending,
  /// eq. 3.6: q = q_f + sum_i (1 - H_i)(q_s,i - q_f)). reach > 0 (a length) blends with
  /// 1 - H(phi - reach) instead: the semi-implicit solid coefficient (docs/implicit.md).
  void add_blend(Field& out, double q_s, double q_f, double reach = 0.0) const;
  /// Stress of the solid's constitutive model (kernels/constitutive.hpp) on its window;
  /// conservative: adds (1-H) sigma_s to the global tensor (sxx, sxy, syy); non-conservative: adds (1-H) div sigma_s to the
  /// force (fx, fy). Returns the elastic energy.
  /// compute_stress() then blend_stress_into().
  double add_stress(Field& sxx, Field& sxy, Field& syy, Field& fx, Field& fy);
  /// The first half of add_stress: the stress on the window and the largest tangent
  /// modulus (min_dt); writes only this solid's state, so solids may run concurrently.
  void compute_stress();
  /// The second half: adds the last computed stress to the global fields (they overlap
  /// where windows do: call it for the solids one after another, in solid order, for
  /// sums with the same bits for any number of threads). Returns the elastic energy.
  double blend_stress_into(Field& sxx, Field& sxy, Field& syy, Field& fx, Field& fy) const;

  /// The actuation map A of the next stress evaluations (kernels/constitutive_actuation.hpp;
  /// the identity unless the scene actuates the solid).
  void set_actuation(const Affine2& a) { actuation_ = a; actuated_ = true; }

  /// Sets the initial velocity inside the solid (rigid motion) blended with (1 - H).
  void impose_initial_velocity(Field& u, Field& v) const;

  SolidDiagnostics diagnostics(const Field& u, const Field& v) const;
  double min_dt() const { return min_dt(opt_.solid_cfl); }  ///< shear-wave limit of section 4
  double min_dt(double p) const;  ///< the same with the factor P = p
  /// The shear modulus min_dt() uses: the model's at rest (G = 2 mu_s for neo-Hookean) or
  /// the largest tangent modulus at the last stress evaluation, whichever is larger.
  double wave_modulus() const;

  // --- window and fields (window-local, (i, j) <-> global (i0 + i, j0 + j)) ----------
  // i0 + i is UNWRAPPED in a periodic direction (it may lie outside [0, nx)): positions are
  // grid.xc(i0 + i); the global fields are indexed at (wrap().i(i0 + i), wrap().j(j0 + j))
  // or, for a kernel, per piece (for_each_piece; solver/model/periodic_window.hpp).
  int i0() const { return i0_; }
  int j0() const { return j0_; }
  int ni() const { return ni_; }
  int nj() const { return nj_; }
  const Field& xi_x() const { return xi_x_; }
  const Field& xi_y() const { return xi_y_; }
  const Field& phi() const { return phi_; }
  const Field& stress_xx() const { return sxx_; }
  const Field& stress_xy() const { return sxy_; }
  const Field& stress_yy() const { return syy_; }
  Field& xi_x_mut() { return xi_x_; }
  Field& xi_y_mut() { return xi_y_; }
  const PeriodicWrap& wrap() const { return wrap_; }
  /// f(WindowPiece) for each part of the window that does not cross a periodic side (the
  /// whole window, once, unless it crosses one).
  template <class F>
  void for_each_piece(F&& f) const {
    refmap::for_each_piece(wrap_, i0_, j0_, ni_, nj_, f);
  }
  /// phi at a global cell (any image of it in a periodic direction): the window's value,
  /// +band outside the window.
  double phi_global(int i, int j) const {
    int li = i - i0_, lj = j - j0_;
    if (wrap_.px) li = PeriodicWrap::mod(li, wrap_.nx);  // the window is at most nx wide
    if (wrap_.py) lj = PeriodicWrap::mod(lj, wrap_.ny);
    if (li < 0 || li >= ni_ || lj < 0 || lj >= nj_) return band_;
    return phi_(li, lj);
  }
  const ExtrapolationCounters& extrapolation_counters() const { return counters_; }
  long rewindows() const { return rewindows_; }
  /// Bytes held by the solid's window arrays (every Field and the mask, ghosts and row
  /// padding included) plus its fast-marching workspace (capacity).
  std::size_t storage_bytes() const;
  double band() const { return band_; }  ///< w_E in length units
  double transition() const { return wt_; }

  /// The solid's evolving state (window, xi, phi, stress, counters) for a checkpoint
  /// (solver/model/checkpoint.cpp); `tag` prefixes the records.
  void save_state(CheckpointWriter& w, const std::string& tag) const;
  void load_state(CheckpointReader& r, const std::string& tag);

 private:
  void initialise();
  /// extrapolate(); layers > 0: only the cells within `layers` of Omega_S are needed
  /// (Extrapolator::extrapolate_layers).
  void extrapolate_layers(int layers);
  /// Chooses the window for the current band (plus margin) and copies the overlap.
  void fit_window(bool force);
  /// The window [lo, hi) of one direction for a band over cells [a, b) (n cells, periodic
  /// or not, spanned or not): the band plus the margin m, inside the grid unless the band
  /// reaches a periodic side, never wider than the period.
  void window_range(int a, int b, int m, int n, bool periodic, bool spans, const char* axis, int& lo,
                    int& hi) const;
  /// Window ghosts: wrapped (+ the period for the matching xi component: component 0 =
  /// xi_x, 1 = xi_y, 2 = neither) across a spanned periodic direction, else linear
  /// extrapolation.
  void fill_ghosts(Field& f, int component) const;
  void compute_phi_from_xi();
  /// compute_stress / blend_stress_into for one constitutive model (solver/model/solid.cpp).
  template <class Model>
  void compute_model_stress(const Model& model);
  template <class Model>
  double blend_model_stress(const Model& model, Field& sxx, Field& sxy, Field& syy, Field& fx,
                            Field& fy) const;

  SolidSpec spec_;
  SolidsOptions opt_;
  Grid grid_;
  Sides sides_;
  bool wrap_x_ = false, wrap_y_ = false;  ///< window spans a periodic direction
  PeriodicWrap wrap_;  ///< global index of an unwrapped one (solver/model/periodic_window.hpp)
  std::unique_ptr<Shape> shape_;
  double band_, wt_;
  double light_ratio_ = 1.0;  ///< rho_f / rho_s of solids.stress_blend = "specific" (1: volume blend)
  int i0_ = 0, j0_ = 0, ni_ = 0, nj_ = 0;
  Field xi_x_, xi_y_, phi_, kx_, ky_, k2x_, k2y_, xs_, ys_, x0x_, x0y_;
  Field sxx_, sxy_, syy_;
  /// solids.stress_discretisation = "variational": P = w dW/dA (kernels/variational_stress.hpp)
  /// of the last stress evaluation and the energy it derives from (recomputed every step)
  Field pxx_, pxy_, pyx_, pyy_;
  double variational_energy_ = 0.0;
  Mask known_;
  FmmWorkspace fmm_ws_;
  std::unique_ptr<Extrapolator> extrapolator_;  ///< solids.extrapolation, owns its workspace
  ExtrapolationCounters counters_;
  long rewindows_ = 0;
  /// the constitutive model of spec_, wrapped in Actuated when set_actuation was called:
  /// f(model), the one dispatch of compute_stress and blend_stress_into
  template <class F>
  decltype(auto) with_model(F&& f) const;
  Affine2 actuation_;
  bool actuated_ = false;
  double max_wave_modulus_ = 0.0;  ///< largest tangent shear modulus in the solid at the last stress evaluation (0: none yet)
};

}  // namespace refmap
