#include "solver/components/rigid_bodies.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "solver/components/option_names.hpp"
#include "solver/io/checkpoint_io.hpp"
#include "solver/io/key_def.hpp"
#include "solver/io/toml_reader.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/model/implicit_step.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {

void RigidBodiesComponent::register_state(StateRegistry& reg) {
  // the poses, the last loads and forcing regions, the held momentum (solver/model/rigid_body.hpp)
  reg.add_record(
      "bodies", [this](CheckpointWriter& w) { bodies_.save_state(w); },
      [this](CheckpointReader& r) { bodies_.load_state(r); });
}

void RigidBodiesComponent::solid_values(const Simulation&, int k, std::vector<double>& out) const {
  // a soft solid's rows (a clamped one, or a free one beside the bodies) have no rotation
  const bool body = bodies_.rigid(k);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.push_back(body ? bodies_.pose(k).theta : nan);
  out.push_back(body ? bodies_.pose(k).omega : nan);
}

void RigidBodiesComponent::at(StepPoint p, Simulation& sim, double dt) {
  const Grid& g = sim.grid();
  switch (p) {
    case StepPoint::Begin:  // from t to t + dt, before the solids are moved
      bodies_.advance(sim.time(), dt);
      break;
    case StepPoint::PoissonCoefficients:  // forcing = "sharp": no pressure coupling across a cut face
      if (cuts_) bodies_.clear_cut_faces(sim.solids(), sim.beta_x_mut(), sim.beta_y_mut(), g);
      break;
    case StepPoint::FaceAccelerations:  // forcing = "sharp": G_f of the cut faces (face_accel left -g there)
      if (cuts_) bodies_.cut_face_accel(sim.solids(), sim.face_accel_x_mut(), sim.face_accel_y_mut(), g);
      break;
    case StepPoint::BeforePredictor:
      // with the face accelerations the predictor will subtract: the forcing aims at
      // u_body + dt G_c so that the predicted face velocities inside a body are its velocity
      bodies_.force(sim.solids(), sim.u_mut(), sim.v_mut(), sim.rho(), sim.face_accel_x(), sim.face_accel_y(),
                    sim.p(), g, dt);
      break;
    case StepPoint::Predicted:  // forcing = "sharp": the cut faces carry the body's velocity
      if (cuts_) bodies_.impose_cut_faces(sim.solids(), sim.uf_mut(), sim.vf_mut(), g);
      break;
    case StepPoint::PressureUpdated:  // cut out of the solve: the fluid's pressure inside
      if (cuts_) bodies_.fill_inside_pressure(sim.solids(), sim.p_mut(), g);
      break;
    case StepPoint::Substeps:  // forcing_hold: the cells held through the substeps
      if (holds_) bodies_.held_cells(sim.solids(), g, held_);
      break;
    case StepPoint::Rates:  // an RK-4 stage's or the explicit stress step's rate
      if (holds_) hold_rates(sim.rate_x_mut(), sim.rate_y_mut(), sim.rate_weight(), g);
      break;
    case StepPoint::HeldSolved:  // the implicit solve's rates at the held cells (held exactly)
      if (holds_) {
        const auto& r = sim.implicit_velocity()->held_rate();
        for (std::size_t n = 0; n < held_.size(); ++n)
          bodies_.add_held(held_[n][2], held_[n][0], held_[n][1], dt * r[n][0], dt * r[n][1], g);
      }
      break;
    default:
      break;
  }
}

void RigidBodiesComponent::hold_rates(View kx, View ky, double w, const Grid& g) {
  for (const auto& c : held_) {
    const int i = c[0], j = c[1];
    bodies_.add_held(c[2], i, j, w * kx(i, j), w * ky(i, j), g);
    kx(i, j) = 0.0;
    ky(i, j) = 0.0;
  }
}

std::span<const OptionName<SolidMotion>> option_names(SolidMotion) {
  static const OptionName<SolidMotion> n[] = {{SolidMotion::Free, "free"},
                                              {SolidMotion::Fixed, "fixed"},
                                              {SolidMotion::Prescribed, "prescribed"},
                                              {SolidMotion::Pinned, "pinned"}};
  return name_list(n);
}

std::span<const OptionName<BodyForcing>> option_names(BodyForcing) {
  static const OptionName<BodyForcing> n[] = {{BodyForcing::Diffuse, "diffuse"},
                                              {BodyForcing::Interpolated, "interpolated"},
                                              {BodyForcing::Sharp, "sharp"}};
  return name_list(n);
}

std::span<const OptionName<ForcingInterpolation>> option_names(ForcingInterpolation) {
  static const OptionName<ForcingInterpolation> n[] = {{ForcingInterpolation::Linear, "linear"},
                                                       {ForcingInterpolation::Quadratic, "quadratic"}};
  return name_list(n);
}

std::span<const OptionName<CutFaces>> option_names(CutFaces) {
  static const OptionName<CutFaces> n[] = {{CutFaces::Staircase, "staircase"}, {CutFaces::Aperture, "aperture"}};
  return name_list(n);
}

using namespace toml_text;

void parse_body_motion(const TomlTable& s, SolidSpec& sp) {
  sp.motion = s.option<SolidMotion>("motion");
  const std::string motion = to_string(sp.motion);
  if (const auto k = s.misplaced("motion", motion))
    s.fail(*k, "only used with motion = \"" + s.entry(*k).only.front() + "\" (motion is \"" + motion + "\")");
  const bool rigid = sp.rigid();
  if (rigid) sp.forcing = s.option<BodyForcing>("forcing");
  if (rigid) sp.forcing_hold = s.boolean("forcing_hold");
  if (sp.forcing_hold && sp.forcing != BodyForcing::Sharp)
    s.fail("forcing_hold", "only with forcing = \"sharp\" (forcing is \"" + std::string(to_string(sp.forcing)) + "\")");
  if (rigid) sp.forcing_interpolation = s.option<ForcingInterpolation>("forcing_interpolation");
  if (sp.forcing_interpolation != ForcingInterpolation::Linear && sp.forcing == BodyForcing::Diffuse)
    s.fail("forcing_interpolation", "only with forcing = \"interpolated\" or \"sharp\" (forcing is \"diffuse\")");
  if (rigid) sp.forcing_faces = s.option<CutFaces>("forcing_faces");
  if (sp.forcing_faces != CutFaces::Staircase && sp.forcing != BodyForcing::Sharp)
    s.fail("forcing_faces", "only with forcing = \"sharp\" (forcing is \"" + std::string(to_string(sp.forcing)) + "\")");
  // measured on a fixed body only: a disc translating and turning (prescribed) ran with wrong
  // forces (c_D -33 against the staircase's 5.9 on the cylinder at 10 cells per diameter)
  if (sp.forcing_faces != CutFaces::Staircase && sp.motion != SolidMotion::Fixed)
    s.fail("forcing_faces", "\"aperture\" only with motion = \"fixed\" (motion is \"" + motion + "\")");
  // "sharp" cuts the inside cells out of the pressure solve: the pressure acts on the body
  // through its cut faces only, which a pinned body's rotation rate (the angular momentum
  // of the inside cells) does not see
  if (rigid && sp.forcing == BodyForcing::Sharp && sp.motion == SolidMotion::Pinned)
    s.fail("forcing", "\"sharp\" is not offered with motion = \"pinned\" (the pressure torque would not turn "
                      "it); use \"interpolated\" or \"diffuse\"");
}

void parse_body_velocity(const TomlTable& s, SolidSpec& sp, const Config& cfg, double ccx, double ccy) {
  const bool rigid = sp.rigid();
  const std::string motion = to_string(sp.motion);
  const Grid& g = cfg.grid;
  // a rigid body's initial velocity is its motion's
  if (rigid)
    for (const char* k : {"velocity", "u", "v", "omega"}) {
      if (sp.motion == SolidMotion::Pinned && std::string(k) == "omega") continue;
      if (s.has(k))
        s.fail(k, "not used with motion = \"" + motion + "\" (the motion sets the body's velocity" +
                      (sp.motion == SolidMotion::Pinned ? std::string("; a pinned body takes `omega` only)") : ")"));
    }
  if (sp.motion == SolidMotion::Fixed) {
    sp.velocity = SolidVelocity::Rigid;
    sp.u = sp.v = sp.omega = 0.0;
  } else if (sp.motion == SolidMotion::Prescribed) {
    char buf[2][40];
    std::snprintf(buf[0], sizeof buf[0], "%.17g", ccx);
    std::snprintf(buf[1], sizeof buf[1], "%.17g", ccy);
    sp.path_x = s.has("path_x") ? expression_text(s, "path_x") : std::string(buf[0]);
    sp.path_y = s.has("path_y") ? expression_text(s, "path_y") : std::string(buf[1]);
    sp.rotation_rate = s.has("rotation_rate") ? expression_text(s, "rotation_rate") : std::string("0");
    const RigidPath path(sp.path_x, sp.path_y, sp.rotation_rate);
    const double t0 = cfg.t_start, tol = 1e-9 * g.dx;
    const auto c0 = path.centre(t0);
    for (int d = 0; d < 2; ++d) {
      const double want = d == 0 ? ccx : ccy, got = c0[std::size_t(d)];
      if (!std::isfinite(got) || std::abs(got - want) > tol)
        s.fail(d == 0 ? "path_x" : "path_y",
               "must start at the centre: it is " + fmt_num(got) + " at t = " + fmt_num(t0) + ", the centre " +
                   (d == 0 ? "x" : "y") + " is " + fmt_num(want));
    }
    const auto v0 = path.velocity(t0);
    sp.velocity = SolidVelocity::Rigid;
    sp.u = v0[0];
    sp.v = v0[1];
    sp.omega = path.rate(t0);
    if (!std::isfinite(sp.u) || !std::isfinite(sp.v) || !std::isfinite(sp.omega))
      s.fail(s.has("rotation_rate") ? "rotation_rate" : "path_x", "the motion's velocity is not finite at the start");
  } else if (sp.motion == SolidMotion::Pinned) {
    const auto p = s.has("pivot") ? s.vec2("pivot") : std::array<double, 2>{ccx, ccy};
    sp.pivot_x = p[0];
    sp.pivot_y = p[1];
    sp.velocity = SolidVelocity::Rigid;
    sp.omega = s.number("omega");
    // rotation about the pivot, written as a translation plus the rotation about the centre
    sp.u = -sp.omega * (ccy - sp.pivot_y);
    sp.v = sp.omega * (ccx - sp.pivot_x);
  }
  if (s.has("clamp")) sp.clamp = s.string("clamp");

}

void resolve_clamps(const TomlTable& top, std::vector<SolidSpec>& solids) {
  const toml::node* n = top.node("solid");
  if (!n) return;
  const toml::array* arr = n->as_array();  // the solids' parser checked it is one
for (std::size_t i = 0; i < solids.size(); ++i) {
  SolidSpec& sp = solids[i];
  if (sp.clamp.empty()) continue;
  const TomlTable s = top.sub(*arr->get(i)->as_table(), "solid[" + std::to_string(i) + "]", "solid");
  for (std::size_t k = 0; k < solids.size(); ++k)
    if (solids[k].name == sp.clamp) sp.clamp_index = int(k);
  if (sp.clamp_index < 0) s.fail("clamp", "no solid is named " + dq(sp.clamp));
  if (!solids[std::size_t(sp.clamp_index)].rigid())
    s.fail("clamp", "solid " + dq(sp.clamp) + " is not rigid (a soft solid is clamped to a body with motion = "
                    "\"fixed\", \"prescribed\" or \"pinned\")");
}
}

ComponentKind rigid_bodies_kind() {
  using namespace keys;
  using KT = KeyType;
  const SolidSpec ds;  // the defaults (solver/model/config.hpp)
  ComponentKind k;
  k.name = "rigid_bodies";
  k.after = "solid.omega";  // after a solid's initial velocity, which a rigid body's motion replaces
  // read by the solids' parser (configure: solver/components/solids_keys.cpp); the
  // component is made by the Simulation whenever a solid is rigid
  k.keys = {
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
      only(choice<CutFaces>(
               "solid", "forcing_faces", ds.forcing_faces,
               "`forcing = \"sharp\"` only: the faces of the cells inside. `\"staircase\"`: closed (the normal "
               "flux stops on the staircase of inside cells, up to dx/2 from the surface); `\"aperture\"`: cut-cell "
               "faces, the Poisson coefficient times the face's open fraction and the flux of its open part from "
               "the forced cells' profile (the normal flux stops on the surface; docs/bodies.md); `\"aperture\"` "
               "with `motion = \"fixed\"` only"),
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
  };
  return k;
}

}  // namespace refmap
