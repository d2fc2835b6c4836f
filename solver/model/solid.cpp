#include "solver/model/solid.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "kernels/loop.hpp"
#include "kernels/reference_map.hpp"
#include "kernels/rk4.hpp"
#include "kernels/solid_stress.hpp"
#include "kernels/variational_stress.hpp"
#include "solver/model/extrapolation.hpp"
#include "solver/model/time_step_limits.hpp"

namespace refmap {

namespace {
constexpr int kMarginMin = 3;  // cells between the band and the window edge before re-windowing
constexpr int kMarginNew = 8;  // margin given to a new window (hysteresis)
}  // namespace

Solid::Solid(const SolidSpec& spec, const SolidsOptions& opt, const Grid& g, Sides sides, double rho_f)
    : spec_(spec), opt_(opt), grid_(g), sides_(sides) {
  // rho_f / rho_s of the specific stress blend (1: the volume blend, bit for bit)
  if (opt_.stress_blend == StressBlend::Specific && spec_.density > rho_f) light_ratio_ = rho_f / spec_.density;
  shape_ = make_shape(spec_.shape);
  band_ = opt_.band * g.dx;
  wt_ = opt_.transition * g.dx;
  extrapolator_ = make_extrapolator(opt_);
  initialise();
}

void Solid::initialise() {
  const Grid& g = grid_;
  const BoundingBox bb = shape_->bbox();
  wrap_x_ = sides_.periodic_x() && (bb.xmax - bb.xmin + 2.0 * band_ >= g.lx());
  wrap_y_ = sides_.periodic_y() && (bb.ymax - bb.ymin + 2.0 * band_ >= g.ly());
  wrap_ = PeriodicWrap{g.nx, g.ny, sides_.periodic_x(), sides_.periodic_y()};
  // initial window: the reference bounding box plus band and margin, in cells
  auto lo = [&](double x, double x0) { return int(std::floor((x - x0) / g.dx)); };
  auto hi = [&](double x, double x0) { return int(std::ceil((x - x0) / g.dx)); };
  int a, b, c, d;
  window_range(lo(bb.xmin - band_, g.x0), hi(bb.xmax + band_, g.x0), kMarginNew, g.nx, sides_.periodic_x(),
               wrap_x_, "x", a, b);
  window_range(lo(bb.ymin - band_, g.y0), hi(bb.ymax + band_, g.y0), kMarginNew, g.ny, sides_.periodic_y(),
               wrap_y_, "y", c, d);
  if (b <= a || d <= c)
    throw std::invalid_argument("solid '" + spec_.name + "' lies outside the domain");
  i0_ = a; j0_ = c; ni_ = b - a; nj_ = d - c;
  for (Field* f : {&xi_x_, &xi_y_, &phi_, &sxx_, &sxy_, &syy_}) f->resize(ni_, nj_, Grid::ng);
  known_.resize(ni_, nj_, Grid::ng);
  for (int j = 0; j < nj_; ++j)
    for (int i = 0; i < ni_; ++i) {
      const double x = g.xc(i0_ + i), y = g.yc(j0_ + j);
      xi_x_(i, j) = x;  // reference configuration: xi = x
      xi_y_(i, j) = y;
      phi_(i, j) = std::min(shape_->phi0(x, y), band_);
    }
  fill_ghosts(xi_x_, 0);
  fill_ghosts(xi_y_, 1);
  if (opt_.reinitialise) reinitialise_fmm(phi_.view(), ni_, nj_, g.dx, band_, fmm_ws_);
  fill_ghosts(phi_, 2);
}

void Solid::fill_ghosts(Field& f, int component) const {
  const int ng = f.ng();
  const bool is_xi_x = component == 0, is_xi_y = component == 1;
  // x direction
  for (int j = 0; j < nj_; ++j)
    for (int k = 1; k <= ng; ++k) {
      if (wrap_x_) {
        const double shift = is_xi_x ? grid_.lx() : 0.0;
        f(-k, j) = f(ni_ - k, j) - shift;
        f(ni_ - 1 + k, j) = f(k - 1, j) + shift;
      } else {  // linear extrapolation (exact for the affine reference configuration)
        f(-k, j) = 2.0 * f(-k + 1, j) - f(-k + 2, j);
        f(ni_ - 1 + k, j) = 2.0 * f(ni_ - 2 + k, j) - f(ni_ - 3 + k, j);
      }
    }
  for (int k = 1; k <= ng; ++k)
    for (int i = -ng; i < ni_ + ng; ++i) {
      if (wrap_y_) {
        const double shift = is_xi_y ? grid_.ly() : 0.0;
        f(i, -k) = f(i, nj_ - k) - shift;
        f(i, nj_ - 1 + k) = f(i, k - 1) + shift;
      } else {
        f(i, -k) = 2.0 * f(i, -k + 1) - f(i, -k + 2);
        f(i, nj_ - 1 + k) = 2.0 * f(i, nj_ - 2 + k) - f(i, nj_ - 3 + k);
      }
    }
}

void Solid::advect(const Field& uf, const Field& vf, const Field& u, const Field& v, double dt) {
  // RK-4 for eq. (3.3). H (phi < 0) and the face velocities are frozen over the step.
  // Outside Omega_S, xi is not advected (H = 0) but is the extrapolation of the values
  // inside: the right-hand side of every stage is evaluated on the extrapolation of that
  // stage's xi (stages 2-4 re-extrapolate; stage 1 uses the previous step's band). Without
  // that, cells at the interface would difference stage values against the band's
  // start-of-step values, an O(dt) inconsistency per step.
  const int ni = ni_, nj = nj_;
  if (x0x_.nx() != ni || x0x_.ny() != nj)
    for (Field* f : {&kx_, &ky_, &k2x_, &k2y_, &x0x_, &x0y_}) f->resize(ni, nj, Grid::ng);
  x0x_ = xi_x_;
  x0y_ = xi_y_;
  const XiFlux flux = opt_.xi_advection;
  // stages 2-4 re-extrapolate the band only as far as the right-hand side reads it (one or
  // two cells beyond Omega_S): those cells get the bits of a whole-band fill (least squares
  // fills layer by layer), and the rest of the band is not read before the extrapolation
  // after the step refills it
  const int reach = reference_map_rhs_reach(flux);
  // The RK-4 loops then run over the box of Omega_S grown by the cells the stages write:
  // outside it k = 0 (H = 0) in every stage, so there the stage state and the result are
  // xi^n, which those cells hold already (a method that writes anywhere in its band, the
  // PDE, gets the whole window: its stage values there must be reset to xi^n as before).
  const int written = extrapolator_->layers_written(reach);
  int b0 = 0, b1 = ni, c0 = 0, c1 = nj;  // box [b0, b1) x [c0, c1), window-local
  if (written >= 0) {
    const int grow = std::max(reach, written);
    b0 = c0 = 1 << 30;
    b1 = c1 = -(1 << 30);
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i)
        if (phi_(i, j) < 0.0) {
          b0 = std::min(b0, i); b1 = std::max(b1, i + 1);
          c0 = std::min(c0, j); c1 = std::max(c1, j + 1);
        }
    if (b1 <= b0) {  // no cell to advect: xi stays xi^n (k = 0 everywhere)
      fill_ghosts(xi_x_, 0);
      fill_ghosts(xi_y_, 1);
      return;
    }
    b0 = std::max(b0 - grow, 0); b1 = std::min(b1 + grow, ni);
    c0 = std::max(c0 - grow, 0); c1 = std::min(c1 + grow, nj);
  }
  // xi itself is the stage state (the extrapolation and phi read it); x0 keeps xi^n
  auto box = [&](Field& fld) { return shifted_view(fld.view(), b0, c0); };
  Rk4Fields f;
  f.q0x = box(x0x_);
  f.q0y = box(x0y_);
  f.sx = f.outx = box(xi_x_);
  f.sy = f.outy = box(xi_y_);
  f.accx = box(kx_);  // k1 + 2 k2 + 2 k3 + k4
  f.accy = box(ky_);
  f.kx = box(k2x_);
  f.ky = box(k2y_);
  f.ni = b1 - b0;
  f.nj = c1 - c0;
  fill_ghosts(xi_x_, 0);
  fill_ghosts(xi_y_, 1);
  rk4_step(f, dt, [&](int stage, View kx, View ky) {  // kx, ky: views of the box
    if (stage > 1) extrapolate_layers(reach);
    // per piece of the window that does not cross a periodic side (the face velocities are
    // read at the grid cells it covers; one piece, the whole window, unless it crosses one),
    // within the box
    for_each_piece([&](const WindowPiece& p) {
      const int li = std::max(p.li, b0), lj = std::max(p.lj, c0);
      const int mi = std::min(p.li + p.ni, b1) - li, mj = std::min(p.lj + p.nj, c1) - lj;
      if (mi <= 0 || mj <= 0) return;
      auto at = [&](View v) { return shifted_view(v, li, lj); };
      auto atk = [&](View v) { return shifted_view(v, li - b0, lj - c0); };
      if (opt_.xi_velocity == XiVelocity::Cell)
        reference_map_rhs_cell(at(xi_x_.view()), at(xi_y_.view()), at(phi_.view()), u.view(), v.view(), mi, mj,
                               p.gi + (li - p.li), p.gj + (lj - p.lj), grid_.dx, atk(kx), atk(ky), flux);
      else
        reference_map_rhs(at(xi_x_.view()), at(xi_y_.view()), at(phi_.view()), uf.view(), vf.view(), mi, mj,
                          p.gi + (li - p.li), p.gj + (lj - p.lj), grid_.dx, atk(kx), atk(ky), flux);
    });
  });
  fill_ghosts(xi_x_, 0);
  fill_ghosts(xi_y_, 1);
}

void Solid::extrapolate_layers(int layers) {
  // known = Omega_S of the current level set (the cells eq. 3.3 advects)
  known_.fill(0);
  for (int j = 0; j < nj_; ++j)
    for (int i = 0; i < ni_; ++i) known_(i, j) = phi_(i, j) < 0.0 ? 1 : 0;
  const auto t0 = std::chrono::steady_clock::now();
  const ExtrapStats st =
      layers > 0 ? extrapolator_->extrapolate_layers(xi_x_.view(), xi_y_.view(), known_.view(), phi_.view(), ni_,
                                                     nj_, Grid::ng, grid_.dx, layers)
                 : extrapolator_->extrapolate(xi_x_.view(), xi_y_.view(), known_.view(), phi_.view(), ni_, nj_,
                                              Grid::ng, grid_.dx);
  counters_.calls += 1;
  counters_.cells_filled += st.cells_filled;
  counters_.fallbacks += st.fallbacks;
  counters_.iterations += st.iterations;
  fill_ghosts(xi_x_, 0);
  fill_ghosts(xi_y_, 1);
  counters_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void Solid::compute_phi_from_xi() {
  // eq. (3.2): phi(x, t) = phi0(xi(x, t)) wherever xi is valid; +band elsewhere
  const Shape& s = *shape_;
  const double cap = band_;
  parallel_rows(0, nj_, ni_, [&](int j) {
    for (int i = 0; i < ni_; ++i)
      phi_(i, j) = known_(i, j) ? std::clamp(s.phi0(xi_x_(i, j), xi_y_(i, j)), -cap, cap) : cap;
  });
}

void Solid::rebuild_level_set() {
  compute_phi_from_xi();
  if (opt_.reinitialise) reinitialise_fmm(phi_.view(), ni_, nj_, grid_.dx, band_, fmm_ws_);
  fit_window(false);
  fill_ghosts(phi_, 2);
}

void Solid::window_range(int a, int b, int m, int n, bool periodic, bool spans, const char* axis, int& lo,
                         int& hi) const {
  if (spans) {  // the full width, ghosts wrapped (fill_ghosts)
    lo = 0;
    hi = n;
    return;
  }
  lo = a - m;
  hi = b + m;
  // inside the grid while the band keeps kMarginMin cells off its sides (always at a wall);
  // across a periodic side the window extends past it in unwrapped indices
  if (!periodic || (a - kMarginMin >= 0 && b + kMarginMin <= n)) {
    lo = std::max(lo, 0);
    hi = std::min(hi, n);
    return;
  }
  // never wider than the period (two window cells would be one grid cell): the margin
  // shrinks, down to kMarginMin
  if (b - a + 2 * kMarginMin > n)
    throw std::runtime_error("solid '" + spec_.name + "' is too wide for the periodic direction " + axis +
                             ": its band covers " + std::to_string(b - a) + " of the " + std::to_string(n) +
                             " cells of the period, which leaves less than " + std::to_string(kMarginMin) +
                             " cells on either side (a solid may span a periodic direction only from the start)");
  const int mm = std::min(m, (n - (b - a)) / 2);
  lo = a - mm;
  hi = b + mm;
}

void Solid::fit_window(bool force) {
  const Grid& g = grid_;
  // extent of the band (phi < band) in global cells (unwrapped)
  int a = 1 << 30, b = -(1 << 30), c = 1 << 30, d = -(1 << 30);
  for (int j = 0; j < nj_; ++j)
    for (int i = 0; i < ni_; ++i)
      if (phi_(i, j) < band_) {
        a = std::min(a, i0_ + i); b = std::max(b, i0_ + i + 1);
        c = std::min(c, j0_ + j); d = std::max(d, j0_ + j + 1);
      }
  if (b <= a) throw std::runtime_error("solid '" + spec_.name + "' has vanished (no cell with phi < band)");
  // the band keeps kMarginMin cells from the window's edges, except at a wall (a window
  // there stays at the domain's edge); across a periodic side the window follows it
  auto inside = [&](int lo, int hi, int w0, int wn, int n, bool periodic) {
    return (lo - kMarginMin >= w0 || (!periodic && w0 == 0)) &&
           (hi + kMarginMin <= w0 + wn || (!periodic && w0 + wn == n));
  };
  bool ok_x = wrap_x_ || inside(a, b, i0_, ni_, g.nx, sides_.periodic_x());
  bool ok_y = wrap_y_ || inside(c, d, j0_, nj_, g.ny, sides_.periodic_y());
  if (!force && ok_x && ok_y) return;
  int na, nb, nc, nd;
  window_range(a, b, kMarginNew, g.nx, sides_.periodic_x(), wrap_x_, "x", na, nb);
  window_range(c, d, kMarginNew, g.ny, sides_.periodic_y(), wrap_y_, "y", nc, nd);
  const int nni = nb - na, nnj = nd - nc;
  Field nx_x(nni, nnj, Grid::ng), nx_y(nni, nnj, Grid::ng), nphi(nni, nnj, Grid::ng, band_);
  for (int j = 0; j < nnj; ++j)
    for (int i = 0; i < nni; ++i) {
      const int oi = na + i - i0_, oj = nc + j - j0_;
      if (oi >= 0 && oi < ni_ && oj >= 0 && oj < nj_) {
        nx_x(i, j) = xi_x_(oi, oj);
        nx_y(i, j) = xi_y_(oi, oj);
        nphi(i, j) = phi_(oi, oj);
      } else {  // outside the band: xi will be extrapolated before it is used
        nx_x(i, j) = g.xc(na + i);
        nx_y(i, j) = g.yc(nc + j);
      }
    }
  xi_x_ = std::move(nx_x);
  xi_y_ = std::move(nx_y);
  phi_ = std::move(nphi);
  i0_ = na; j0_ = nc; ni_ = nni; nj_ = nnj;
  for (Field* f : {&sxx_, &sxy_, &syy_}) f->resize(ni_, nj_, Grid::ng);
  known_.resize(ni_, nj_, Grid::ng);
  fill_ghosts(xi_x_, 0);
  fill_ghosts(xi_y_, 1);
  ++rewindows_;
}

void Solid::add_blend(Field& out, double q_s, double q_f, double reach) const {
  const double dq = q_s - q_f;
  if (dq == 0.0) return;
  // per piece of the window that does not cross a periodic side (the whole window unless it
  // crosses one): the grid cells of a row are contiguous, so the loop vectorises as it did
  // before windows could cross (a wrapped index per cell would not, and the vector and
  // scalar sin differ in the last bit)
  for_each_piece([&](const WindowPiece& p) {
    parallel_rows(0, p.nj, p.ni, [&](int j) {
      for (int i = 0; i < p.ni; ++i) {
        const double ph = phi_(p.li + i, p.lj + j) - reach;
        if (ph >= wt_) continue;
        out(p.gi + i, p.gj + j) += (1.0 - smoothed_heaviside(ph, wt_)) * dq;
      }
    });
  });
}

template <class Model>
void Solid::compute_model_stress(const Model& model) {
  // cell-centred stress (eq. 2.9 with eq. 3.1), one cell beyond the transition zone so the
  // non-conservative cell divergence at its edge sees valid neighbours; blended into the
  // global tensor it is the output field and gives the elastic energy
  cell_stress(model, xi_x_.view(), xi_y_.view(), phi_.view(), ni_, nj_, grid_.dx,
              wt_ + 1.5 * grid_.dx, sxx_.view(), sxy_.view(), syy_.view());
  // largest tangent shear modulus in the solid, for the time step
  max_wave_modulus_ = max_wave_modulus(model, sxx_.view(), sxy_.view(), syy_.view(), phi_.view(),
                                       ni_, nj_, wt_);
  if (opt_.stress_form == StressForm::Variational) {
    // the weight 1 - H(phi + w_V + dx, w_V) is zero wherever eq. (3.1) would read an
    // extrapolated xi (docs/implicit.md, "The variational force")
    if (pxx_.nx() != ni_ || pxx_.ny() != nj_)
      for (Field* f : {&pxx_, &pxy_, &pyx_, &pyy_}) f->resize(ni_, nj_, Grid::ng);  // zero ghosts
    const double wv = opt_.variational_width * grid_.dx;
    variational_energy_ = variational_stress_tensor(model, xi_x_.view(), xi_y_.view(), phi_.view(), ni_, nj_,
                                                    grid_.dx, wv, wv + grid_.dx, pxx_.view(), pxy_.view(),
                                                    pyx_.view(), pyy_.view());
  }
  if (opt_.stress_form == StressForm::Cell && !opt_.conservative)
    for (Field* f : {&sxx_, &sxy_, &syy_})  // ghosts are outside the band: zero stress
      for (int j = -Grid::ng; j < nj_ + Grid::ng; ++j)
        for (int i = -Grid::ng; i < ni_ + Grid::ng; ++i)
          if (i < 0 || j < 0 || i >= ni_ || j >= nj_) (*f)(i, j) = 0.0;
}

template <class Model>
double Solid::blend_model_stress(const Model& model, Field& sxx, Field& sxy, Field& syy, Field& fx,
                                 Field& fy) const {
  // (blend_stress reads the window's interior only: the ghosts zeroed above do not matter).
  // Per piece of the window that does not cross a periodic side (solver/model/periodic_window.hpp;
  // the whole window unless it crosses one): the stencils read the window's own cells.
  double energy = 0.0;
  for_each_piece([&](const WindowPiece& p) {
    auto at = [&](const Field& f) { return shifted_view(f.view(), p.li, p.lj); };
    energy += blend_stress(model, at(sxx_), at(sxy_), at(syy_), at(phi_), p.ni, p.nj, grid_.dx, wt_, sxx.view(),
                           sxy.view(), syy.view(), p.gi, p.gj, light_ratio_);
    if (opt_.stress_form == StressForm::Variational) {
      add_variational_force(at(xi_x_), at(xi_y_), at(pxx_), at(pxy_), at(pyx_), at(pyy_), p.ni, p.nj, grid_.dx,
                            fx.view(), fy.view(), p.gi, p.gj);
    } else if (opt_.stress_form == StressForm::Face) {
      add_face_stress_force(model, at(xi_x_), at(xi_y_), at(phi_), p.ni, p.nj, grid_.dx, wt_, opt_.conservative,
                            fx.view(), fy.view(), p.gi, p.gj);
    } else if (!opt_.conservative) {
      blend_stress_divergence(at(sxx_), at(sxy_), at(syy_), at(phi_), p.ni, p.nj, grid_.dx, wt_, fx.view(),
                              fy.view(), p.gi, p.gj);
    }
  });
  // Cell + conservative: the caller takes the divergence of the global blended tensor.
  // Variational: the blended tensor is output only; the energy is the one the force derives from
  if (opt_.stress_form == StressForm::Variational) return variational_energy_;
  return energy;
}

template <class F>
decltype(auto) Solid::with_model(F&& f) const {
  return with_constitutive_model(spec_, [&](const auto& model) {
    if (actuated_) return f(Actuated<std::decay_t<decltype(model)>>{model, actuation_});
    return f(model);
  });
}

void Solid::compute_stress() {
  if (spec_.mu_s <= 0.0) return;
  // one dispatch on the constitutive law per call: the kernels are templates on the model
  with_model([&](const auto& model) { compute_model_stress(model); });
}

double Solid::blend_stress_into(Field& sxx, Field& sxy, Field& syy, Field& fx, Field& fy) const {
  if (spec_.mu_s <= 0.0) return 0.0;
  return with_model([&](const auto& model) {
    return blend_model_stress(model, sxx, sxy, syy, fx, fy);
  });
}

double Solid::add_stress(Field& sxx, Field& sxy, Field& syy, Field& fx, Field& fy) {
  compute_stress();
  return blend_stress_into(sxx, sxy, syy, fx, fy);
}

void Solid::impose_initial_velocity(Field& u, Field& v) const {
  if (spec_.velocity == SolidVelocity::Fluid) return;
  const BoundingBox bb = shape_->bbox();
  const double cx = spec_.shape.kind == ShapeKind::Tabulated ? 0.5 * (bb.xmin + bb.xmax) : spec_.shape.cx;
  const double cy = spec_.shape.kind == ShapeKind::Tabulated ? 0.5 * (bb.ymin + bb.ymax) : spec_.shape.cy;
  // per piece of the window that does not cross a periodic side, positions unwrapped
  for_each_piece([&](const WindowPiece& p) {
    for (int j = 0; j < p.nj; ++j)
      for (int i = 0; i < p.ni; ++i) {
        const double ph = phi_(p.li + i, p.lj + j);
        if (ph >= wt_) continue;
        const double s = 1.0 - smoothed_heaviside(ph, wt_);
        const int gi = p.gi + i, gj = p.gj + j;
        const double ur = spec_.u - spec_.omega * (grid_.yc(j0_ + p.lj + j) - cy);
        const double vr = spec_.v + spec_.omega * (grid_.xc(i0_ + p.li + i) - cx);
        u(gi, gj) = (1.0 - s) * u(gi, gj) + s * ur;
        v(gi, gj) = (1.0 - s) * v(gi, gj) + s * vr;
      }
  });
}

SolidDiagnostics Solid::diagnostics(const Field& u, const Field& v) const {
  SolidDiagnostics d;
  const double dx = grid_.dx, a = dx * dx;
  double w = 0, wx = 0, wy = 0, wu = 0, wv = 0, smax = 0;
  for (int j = 0; j < nj_; ++j)
    for (int i = 0; i < ni_; ++i) {
      const double ph = phi_(i, j);
      const double f = std::clamp(0.5 - ph / dx, 0.0, 1.0);  // sub-cell fraction of phi < 0
      if (f <= 0.0) continue;
      // the centroid from the unwrapped positions (continuous across a periodic side), the
      // velocity from the grid cell
      const int gi = wrap_.i(i0_ + i), gj = wrap_.j(j0_ + j);
      w += f;
      wx += f * grid_.xc(i0_ + i);
      wy += f * grid_.yc(j0_ + j);
      wu += f * u(gi, gj);
      wv += f * v(gi, gj);
      if (ph < 0.0) smax = std::max(smax, std::abs(0.5 * (sxx_(i, j) + syy_(i, j))));
    }
  d.area = w * a;
  if (w > 0) { d.cx = wx / w; d.cy = wy / w; d.u = wu / w; d.v = wv / w; }
  d.sigma_max = smax;
  return d;
}

double Solid::wave_modulus() const {
  if (spec_.mu_s <= 0.0) return 0.0;
  return std::max(rest_wave_modulus(spec_), max_wave_modulus_);
}

double Solid::min_dt(double p) const {
  if (spec_.mu_s <= 0.0) return 1e300;
  // section 4 (solver/model/time_step_limits.hpp): at finite strain the wave speed is
  // sqrt(G_t / rho_s) with the model's tangent shear modulus G_t (kernels/constitutive.hpp;
  // neo-Hookean: G lambda_max(b)), the largest in the solid at the last stress evaluation;
  // at rest this is the paper's bound, G = 2 mu_s.
  return shear_wave_dt_limit(p, grid_.dx, wave_modulus(), spec_.density);
}

std::size_t Solid::storage_bytes() const {
  std::size_t b = 0;
  for (const Field* f : {&xi_x_, &xi_y_, &phi_, &kx_, &ky_, &k2x_, &k2y_, &xs_, &ys_, &x0x_, &x0y_,
                         &sxx_, &sxy_, &syy_, &pxx_, &pxy_, &pyx_, &pyy_})
    b += f->raw_size() * sizeof(double);
  b += known_.raw_size() * sizeof(std::uint8_t);
  b += fmm_ws_.upos.capacity() * sizeof(double) + fmm_ws_.uneg.capacity() * sizeof(double) +
       fmm_ws_.state.capacity() + fmm_ws_.heap.capacity() * sizeof(FmmHeapEntry) +
       (fmm_ws_.pos.capacity() + fmm_ws_.init_cells.capacity() + fmm_ws_.accepted.capacity()) * sizeof(int);
  return b;
}

}  // namespace refmap
