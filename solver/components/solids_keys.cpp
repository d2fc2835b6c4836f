// The solids' kind (solver/model/component_kind.hpp): the keys of `[solids]` (the options
// every solid shares) and of `[[solid]]` (each solid's shape, material and initial velocity;
// a rigid body's keys in the same table are the rigid bodies' kind's,
// solver/components/rigid_bodies.cpp), the scene names of their options
// (solver/components/option_names.hpp), and the parser into Config::solid_opt and
// Config::solids, which the core reads too (the loader's start checks, contact, the markers,
// the Simulation). The loader calls it (ComponentKind::configure) after its own tables and
// after `[suspension]` has appended its particles to `[[solid]]` (solver/scene/scene.cpp).
// The Solids component itself is made by the Simulation (solver/components/solids.hpp).
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "solver/components/option_names.hpp"
#include "solver/components/rigid_bodies.hpp"
#include "solver/io/key_def.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/shape.hpp"

namespace refmap {

std::span<const OptionName<SolidVelocity>> option_names(SolidVelocity) {
  static const OptionName<SolidVelocity> n[] = {{SolidVelocity::Rigid, "rigid"}, {SolidVelocity::Fluid, "fluid"}};
  return name_list(n);
}

std::span<const OptionName<ExtrapolationMethod>> option_names(ExtrapolationMethod) {
  static const OptionName<ExtrapolationMethod> n[] = {{ExtrapolationMethod::Lsq, "lsq"},
                                                      {ExtrapolationMethod::Pde, "pde"}};
  return name_list(n);
}

std::span<const OptionName<ConstitutiveLaw>> option_names(ConstitutiveLaw) {
  static const OptionName<ConstitutiveLaw> n[] = {{ConstitutiveLaw::NeoHookean, "neo_hookean"},
                                                  {ConstitutiveLaw::StrainStiffening, "strain_stiffening"}};
  return name_list(n);
}

std::span<const OptionName<StressForm>> option_names(StressForm) {
  static const OptionName<StressForm> n[] = {{StressForm::Cell, "cell"}, {StressForm::Face, "face"},
                                              {StressForm::Variational, "variational"}};
  return name_list(n);
}

std::span<const OptionName<StressBlend>> option_names(StressBlend) {
  static const OptionName<StressBlend> n[] = {{StressBlend::Volume, "volume"}, {StressBlend::Specific, "specific"}};
  return name_list(n);
}

std::span<const OptionName<XiFlux>> option_names(XiFlux) {
  static const OptionName<XiFlux> n[] = {
      {XiFlux::Central, "central"}, {XiFlux::Superbee, "superbee"}, {XiFlux::VanLeer, "vanleer"},
      {XiFlux::Minmod, "minmod"}};
  return name_list(n);
}

std::span<const OptionName<XiVelocity>> option_names(XiVelocity) {
  static const OptionName<XiVelocity> n[] = {{XiVelocity::Face, "face"}, {XiVelocity::Cell, "cell"}};
  return name_list(n);
}

namespace {

using namespace toml_text;

void parse_solids_options(const TomlTable& top, Config& cfg) {
  const toml::table* tp = top.table("solids", false);
  if (!tp) return;
  const TomlTable s = top.sub(*tp, "solids", "solids");
  s.allow();
  SolidsOptions& o = cfg.solid_opt;
  o.extrapolation = s.option<ExtrapolationMethod>("extrapolation");
  o.lsq_radius = s.number("lsq_radius");
  o.band = s.number("band");
  o.transition = s.number("transition");
  if (!(o.transition < o.band - 1)) {
    // blame the key the user wrote (the transition if both are given)
    if (s.has("transition"))
      s.fail("transition", "must be < solids.band - 1 = " + fmt_num(o.band - 1) + " (the smoothed interface must lie "
                           "inside the extrapolated band), got " + fmt_num(o.transition));
    s.fail("band", "must be > solids.transition + 1 = " + fmt_num(o.transition + 1) +
                       " (the smoothed interface must lie inside the extrapolated band), got " + fmt_num(o.band));
  }
  o.conservative = s.boolean("conservative");
  o.stress_form = s.option<StressForm>("stress_discretisation");
  o.variational_width = s.number("variational_width");
  o.stress_blend = s.option<StressBlend>("stress_blend");
  s.require(o.stress_blend == StressBlend::Volume || (o.stress_form == StressForm::Cell && o.conservative),
            "stress_blend", "\"specific\" needs stress_discretisation = \"cell\" and conservative = true");
  o.xi_advection = s.option<XiFlux>("xi_advection");
  o.xi_velocity = s.option<XiVelocity>("xi_velocity");
  o.solid_cfl = s.number("solid_cfl");
  o.reinitialise = s.boolean("reinitialise");
  o.pde_tol = s.number("pde_tol");
  o.pde_max_iter = int(s.integer("pde_max_iter"));
}


/// time.elastic_coupling = "verlet" advects xi with a midpoint face velocity built from the
/// last two steps' projected face velocities (Simulation::drift_velocities): the cell
/// velocity of solids.xi_velocity = "cell" has no such history.
void check_elastic_coupling(const TomlTable& top, Config& cfg) {
  if (cfg.elastic_coupling == ElasticCoupling::SymplecticEuler || cfg.solid_opt.xi_velocity == XiVelocity::Face) return;
  const toml::table* time = top.table("time", false);
  if (!time || !time->contains("elastic_coupling")) {  // the default: falls back
    cfg.elastic_coupling = ElasticCoupling::SymplecticEuler;
    return;
  }
  const TomlTable t = top.sub(*time, "time", "time");  // the key was given
  t.fail("elastic_coupling", "\"verlet\" needs solids.xi_velocity = \"face\" (its midpoint velocity is built from the "
                             "face velocities)");
}

void parse_solids(const TomlTable& top, Config& cfg) {
  const toml::node* n = top.node("solid");
  if (!n) return;
  const toml::array* arr = n->as_array();
  if (!arr) top.fail("solid", "expected an array of tables ([[solid]] sections), got " + describe(*n));
  const Grid& g = cfg.grid;
  const std::filesystem::path scene_dir = std::filesystem::path(top.context().file).parent_path();
  // a prescribed flow moves the solids kinematically: their material is not used
  const bool need_material = cfg.flow == FlowMode::Solve;
  std::set<std::string> names;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string prefix = "solid[" + std::to_string(i) + "]";
    const toml::table* t = arr->get(i)->as_table();
    if (!t) top.context().fail(prefix, arr->get(i), "expected a table ([[solid]] section), got " + describe(*arr->get(i)));
    const TomlTable s = top.sub(*t, prefix, "solid");
    s.allow();
    SolidSpec sp;

    sp.name = s.has("name") ? s.string("name") : "solid" + std::to_string(i);
    bool ok = !sp.name.empty();
    for (char c : sp.name) ok = ok && (std::isalnum((unsigned char)c) || c == '_');
    s.require(ok, "name", "must be a non-empty name of letters, digits and '_', got " + dq(sp.name));
    s.require(names.insert(sp.name).second, "name", "duplicate solid name " + dq(sp.name));

    // ---- shape
    ShapeParams& sh = sp.shape;
    sh.kind = s.option<ShapeKind>("shape");
    const std::string kind = to_string(sh.kind);  // the canonical name (an alias may be written)
    if (const auto k = s.misplaced("shape", kind))
      s.fail(*k, "not a parameter of shape = " + dq(kind) + " (it takes " + join(s.keys_of("shape", kind), ", ") + ")");

    if (sh.kind != ShapeKind::Tabulated) {
      const auto c = s.vec2("center");
      sh.cx = c[0];
      sh.cy = c[1];
      sh.angle = sh.kind == ShapeKind::Circle ? 0.0 : s.number("angle");
    }
    if (sh.kind == ShapeKind::Circle || sh.kind == ShapeKind::Zalesak) {
      sh.radius = s.number("radius");
    }
    if (sh.kind == ShapeKind::Ellipse) {
      const auto ab = s.vec2("semi_axes");
      s.require(ab[0] > 0 && ab[1] > 0, "semi_axes",
                "both semi-axes must be > 0, got [" + fmt_num(ab[0]) + ", " + fmt_num(ab[1]) + "]");
      sh.a = ab[0];
      sh.b = ab[1];
    } else if (sh.kind == ShapeKind::RoundedRectangle) {
      const auto hs = s.vec2("half_size");
      s.require(hs[0] > 0 && hs[1] > 0, "half_size",
                "both half-sizes must be > 0, got [" + fmt_num(hs[0]) + ", " + fmt_num(hs[1]) + "]");
      sh.half_width = hs[0];
      sh.half_height = hs[1];
      sh.corner_radius = s.number("corner_radius");
      const double rmax = std::min(hs[0], hs[1]);
      s.require(sh.corner_radius >= 0 && sh.corner_radius <= rmax, "corner_radius",
                "must be in [0, min(half_size) = " + fmt_num(rmax) + "], got " + fmt_num(sh.corner_radius));
    } else if (sh.kind == ShapeKind::Zalesak) {
      sh.slot_half_width = s.number("slot_half_width");
      s.require(sh.slot_half_width > 0 && sh.slot_half_width < sh.radius, "slot_half_width",
                "must be in (0, radius = " + fmt_num(sh.radius) + "), got " + fmt_num(sh.slot_half_width));
      sh.slot_top = s.number("slot_top");
      const double h = std::sqrt(sh.radius * sh.radius - sh.slot_half_width * sh.slot_half_width);
      s.require(sh.slot_top > sh.cy - h && sh.slot_top < sh.cy + h, "slot_top",
                "must be strictly between the y where the slot walls meet the circle, (" + fmt_num(sh.cy - h) + ", " +
                    fmt_num(sh.cy + h) + "), got " + fmt_num(sh.slot_top));
    } else if (sh.kind == ShapeKind::Tabulated) {
      const std::string f = s.string("file");
      s.require(!f.empty(), "file", "must be a non-empty path");
      std::filesystem::path fp(f);
      if (fp.is_relative() && !scene_dir.empty()) fp = scene_dir / fp;
      sh.file = fp.lexically_normal().string();
      std::error_code ec;
      if (!std::filesystem::exists(sh.file, ec))
        s.fail("file", "cannot read " + dq(sh.file) + ": no such file" +
                           (std::filesystem::path(f).is_relative() ? " (relative paths are relative to the scene file's directory)"
                                                                   : ""));
      if (std::filesystem::is_directory(sh.file, ec)) s.fail("file", "cannot read " + dq(sh.file) + ": is a directory");
    }

    // build it now, so that bad geometry fails at load time
    const char* shape_key = sh.kind == ShapeKind::Tabulated ? "file" : "shape";
    std::unique_ptr<Shape> shape;
    try {
      shape = make_shape(sh);
    } catch (const std::exception& e) {
      s.fail(shape_key, std::string("invalid geometry: ") + e.what());
    }
    const BoundingBox bb = shape->bbox();
    const double X0 = g.x0, X1 = g.x0 + g.lx(), Y0 = g.y0, Y1 = g.y0 + g.ly();
    if (!(bb.xmax > X0 && bb.xmin < X1 && bb.ymax > Y0 && bb.ymin < Y1))
      s.fail(sh.kind == ShapeKind::Tabulated ? "file" : "center",
             "the solid lies outside the domain: its bounding box [" + fmt_num(bb.xmin) + ", " + fmt_num(bb.xmax) +
                 "] x [" + fmt_num(bb.ymin) + ", " + fmt_num(bb.ymax) + "] does not intersect the domain [" +
                 fmt_num(X0) + ", " + fmt_num(X1) + "] x [" + fmt_num(Y0) + ", " + fmt_num(Y1) + "]");

    // ---- motion: a soft solid, or a rigid body (the rigid bodies' keys: solver/components/rigid_bodies.cpp)
    parse_body_motion(s, sp);
    const std::string motion = to_string(sp.motion);
    const bool rigid = sp.rigid();
    // the point a rigid body's rotation refers to (as for the initial omega)
    const double ccx = sh.kind == ShapeKind::Tabulated ? 0.5 * (bb.xmin + bb.xmax) : sh.cx;
    const double ccy = sh.kind == ShapeKind::Tabulated ? 0.5 * (bb.ymin + bb.ymax) : sh.cy;

    // ---- material
    if (rigid && s.has("mu_s"))
      s.fail("mu_s", "not used with motion = \"" + motion + "\" (a rigid body has no elastic stress)");
    sp.mu_s = rigid ? 0.0 : s.number("mu_s", /*required=*/need_material);
    sp.density = s.number("density", /*required=*/need_material);
    // a rigid body's region blends to the fluid's viscosity unless told otherwise: its
    // velocity is imposed there, and a drop of mu across the interface would move the
    // effective no-slip surface
    sp.viscosity = rigid && !s.has("viscosity") ? cfg.mu_f : s.number("viscosity");
    // a grid-scale Kelvin-Voigt viscosity c dx rho_s c_s (c_s = sqrt(2 mu_s / rho_s), the
    // shear-wave speed at rest) on top of `viscosity`: the form of the peer code IncRMT's
    // extra viscosity (Rycroft et al. 2020; c = 0.4-0.8 in its examples), which vanishes as
    // the grid is refined
    sp.grid_viscosity = s.number("grid_viscosity");
    if (rigid && s.has("grid_viscosity"))
      s.fail("grid_viscosity", "not used with motion = \"" + motion + "\" (a rigid body has no elastic waves)");
    sp.viscosity += sp.grid_viscosity * g.dx * std::sqrt(sp.density * 2.0 * sp.mu_s);
    sp.model = s.option<ConstitutiveLaw>("model");
    if (const auto k = s.misplaced("model", to_string(sp.model)))
      s.fail(*k, "only used with model = \"strain_stiffening\"");
    if (sp.model == ConstitutiveLaw::StrainStiffening) {
      sp.c3 = s.number("c3");
      s.require(sp.mu_s > 0 || !need_material, "mu_s", "must be > 0 with model = \"strain_stiffening\" (it is c1)");
    }

    // ---- initial velocity
    sp.velocity = s.option<SolidVelocity>("velocity");
    if (const auto k = s.misplaced("velocity", to_string(sp.velocity)))
      s.fail(*k, "only used with velocity = \"rigid\" (velocity is \"fluid\": the solid keeps the fluid's velocity)");
    if (sp.velocity == SolidVelocity::Rigid) {
      sp.u = s.number("u");
      sp.v = s.number("v");
      sp.omega = s.number("omega");
    }
    parse_body_velocity(s, sp, cfg, ccx, ccy);

    cfg.solids.push_back(std::move(sp));
  }
  resolve_clamps(top, cfg.solids);
}

/// The solids' keys, into the Config the core reads (ComponentKind::configure).
void configure_solids(const TomlTable& top, Config& cfg) {
  parse_solids_options(top, cfg);  // the loader has read [solver]: the solids need cfg.flow
  check_elastic_coupling(top, cfg);  // the xi velocity against time.elastic_coupling
  parse_solids(top, cfg);
}

}  // namespace

ComponentKind solids_kind() {
  using namespace keys;
  using KT = KeyType;
  const SolidsOptions dso;  // the defaults (solver/model/config.hpp)
  const SolidSpec ds;
  const ShapeParams& dsh = ds.shape;
  const std::vector<std::string> kRectangle = {"rounded_rectangle"}, kNotTabulated = {"circle", "ellipse",
                                                                                       "rounded_rectangle", "zalesak"};
  ComponentKind k;
  k.name = "solids";
  k.tables = {{{"solids", "`[solids]`", false, false, false, "Options shared by all solids; widths are in cells."},
               "probe"},
              {{"solid", "`[[solid]]`", false, true, false,
                "A shape key that does not belong to the chosen `shape` is an error, as are `u`, `v`, `omega` with "
                "`velocity = \"fluid\"`."},
               "solids"}};
  // [solids], then [[solid]] to the initial velocity; the rigid bodies' keys follow `omega`
  // (solver/components/rigid_bodies.cpp)
  k.keys = {
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
  };
  k.configure = configure_solids;
  return k;
}

}  // namespace refmap
