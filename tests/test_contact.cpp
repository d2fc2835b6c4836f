// Solid-solid and solid-wall contact (solver/model/contact.hpp):
//  - the pair force is equal and opposite to round-off, so two discs colliding in a
//    periodic box (rho_s = rho_f) keep the total momentum to round-off;
//  - the gap diagnostic of two discs / a disc and a wall at known separations is right to
//    0.1 dx;
//  - two soft discs in a Taylor-Green vortex collide and separate without their zero
//    level sets crossing, areas within 1%;
//  - a disc thrown at a wall without gravity comes to rest (kinetic energy < 1% of its
//    start) without crossing the wall, area within 1%;
//  - a disc falling onto a wall bounces (0 < e < 1), without energy gain through the
//    contact or during the rebound (beyond 8% of the energy the fall released), and the
//    softer disc deforms more (light, squeeze-film dominated setting);
//  - in the bounce scenes as shipped (heavy discs, inertia-dominated impact) the softer disc
//    has the lower restitution, as in the paper (in the light setting it is the opposite).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/components/contact_component.hpp"
#include "solver/model/contact.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/fixtures/scene_text.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

const char* kPeriodicPair = R"(
name = "periodic_pair"
[domain]
lx = 1.0
[grid]
nx = 64
ny = 64
[fluid]
density = 1.0
viscosity = 0.01
[boundary]
left = "periodic"
right = "periodic"
bottom = "periodic"
top = "periodic"
[initial]
velocity = "zero"
[time]
end = 10.0
[solver]
tol = 1e-12
[[solid]]
name = "a"
shape = "circle"
center = [0.3, 0.5]
radius = 0.1
mu_s = 10.0
density = 1.0
u = 1.5
v = 0.1
[[solid]]
name = "b"
shape = "ellipse"
center = [0.53, 0.53]
semi_axes = [0.1, 0.08]
angle = 0.4
mu_s = 10.0
density = 1.0
)";

const char* kGapScene = R"(
name = "gaps"
[domain]
lx = 1.0
[grid]
nx = 64
ny = 64
[fluid]
viscosity = 0.01
[boundary]
left = "no_slip"
right = "free_slip"
bottom = "no_slip"
top = { type = "moving_wall", velocity = 1.0 }
[initial]
velocity = "zero"
[time]
end = 1.0
[[solid]]
name = "a"
shape = "circle"
center = [0.3, 0.4]
radius = 0.15
mu_s = 10.0
density = 1.0
[[solid]]
name = "b"
shape = "circle"
center = [0.7, 0.5]
radius = 0.12
mu_s = 10.0
density = 1.0
)";

double area(const Simulation& sim, int k) {
  return sim.solids()[k]->diagnostics(sim.u(), sim.v()).area;
}

// aspect ratio of solid k from the eigenvalues of its second-moment tensor
double aspect_ratio(const Simulation& sim, int k) {
  const Solid& s = *sim.solids().at(k);
  const Grid& g = sim.grid();
  double w = 0, mx = 0, my = 0, sxx = 0, sxy = 0, syy = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j < s.nj(); ++j)
      for (int i = 0; i < s.ni(); ++i) {
        const double f = std::clamp(0.5 - s.phi()(i, j) / g.dx, 0.0, 1.0);
        const double x = g.xc(s.i0() + i), y = g.yc(s.j0() + j);
        if (pass == 0) { w += f; mx += f * x; my += f * y; continue; }
        const double X = x - mx / w, Y = y - my / w;
        sxx += f * X * X; sxy += f * X * Y; syy += f * Y * Y;
      }
  const double tr = sxx + syy, det = sxx * syy - sxy * sxy;
  const double d = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
  return std::sqrt((0.5 * tr + d) / (0.5 * tr - d));
}

}  // namespace

TEST(ContactForce, PairForceEqualAndOppositeMomentumToRoundOff) {
  Config cfg = load_scene_string(kPeriodicPair, "periodic_pair.toml");
  Simulation sim(cfg);
  ASSERT_TRUE(sim.contact() && sim.contact()->force_enabled());
  auto [mx0, my0] = sim.momentum();
  const double p0 = std::hypot(mx0, my0);
  double drift = 0.0, worst_pair = 0.0, max_force = 0.0, min_gap = 1e9;
  int active = 0;
  for (int n = 0; n < 400 && sim.time() < 0.5; ++n) {
    sim.step();
    auto [mx, my] = sim.momentum();
    drift = std::max(drift, std::hypot(mx - mx0, my - my0) / p0);
    const auto& t = sim.contact()->last_pair_totals();
    if (!t.empty()) {
      ++active;
      const double fa = std::hypot(t[0], t[1]);
      max_force = std::max(max_force, fa);
      worst_pair = std::max(worst_pair, std::hypot(t[0] + t[2], t[1] + t[3]) / fa);
    }
    min_gap = std::min(min_gap, sim.contact()->gap_solid(0));
  }
  // the whole face force field sums to zero too
  const Grid& g = sim.grid();
  const Field &fx = sim.component<ContactComponent>()->force_x(), &fy = sim.component<ContactComponent>()->force_y();
  double sx = 0, sy = 0, ax = 0, ay = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i) { sx += fx(i, j); ax += std::abs(fx(i, j)); }
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) { sy += fy(i, j); ay += std::abs(fy(i, j)); }
  std::printf("[contact momentum] %d steps with contact force (t = %.3f), max |F_pair| = %.3e, "
              "max |F_a + F_b| / |F_a| = %.3e, max |P - P0| / |P0| = %.3e, min gap = %.3f dx\n",
              active, sim.time(), max_force, worst_pair, drift, min_gap / g.dx);
  EXPECT_GT(active, 20);             // the discs really were in contact
  EXPECT_GT(max_force, 0.0);
  EXPECT_LT(worst_pair, 1e-12);      // equal and opposite
  EXPECT_LT(drift, 1e-12);           // total momentum to round-off
  EXPECT_LE(std::abs(sx), 1e-12 * std::max(ax, 1e-300) + 1e-300);
  EXPECT_LE(std::abs(sy), 1e-12 * std::max(ay, 1e-300) + 1e-300);
  EXPECT_GE(min_gap, 0.0);
}

TEST(ContactGap, KnownSeparationsToWithinTenthOfCell) {
  const double dx = 1.0 / 64;
  for (double gap_cells : {0.3, 1.7, 3.2, 5.0}) {
    // disc b placed at a known gap from disc a along a direction not aligned with the grid
    const double gap = gap_cells * dx, theta = 0.37;
    const double D = 0.15 + 0.12 + gap;
    const double bx = 0.3 + D * std::cos(theta), by = 0.4 + D * std::sin(theta);
    char c[128];
    std::snprintf(c, sizeof c, "solid[1].center=[%.17g, %.17g]", bx, by);
    Config cfg = load_scene_string(kGapScene, "gaps.toml", {c});
    Simulation sim(cfg);
    const double gs = sim.contact()->gap_solid(0), gs1 = sim.contact()->gap_solid(1);
    // walls: a is 0.15 from the left wall (its nearest); b's nearest is the top or right
    const double wall_a = 0.3 - 0.15;
    const double wall_b = std::min({1.0 - by, 1.0 - bx, bx, by}) - 0.12;
    const double ga = sim.contact()->gap_wall(0), gb = sim.contact()->gap_wall(1);
    std::printf("[gap] %.1f dx: solid gap error %.3f dx, wall gap errors %.3f dx, %.3f dx\n", gap_cells,
                (gs - gap) / dx, (ga - wall_a) / dx, (gb - wall_b) / dx);
    EXPECT_NEAR(gs, gap, 0.1 * dx);
    EXPECT_EQ(gs, gs1);
    EXPECT_NEAR(ga, wall_a, 0.1 * dx);
    EXPECT_NEAR(gb, wall_b, 0.1 * dx);
  }
  // no other solid within reach: the sentinel (domain diagonal)
  Config cfg = load_scene_string(kGapScene, "gaps.toml", {"solid[1].center=[0.8, 0.8]"});
  Simulation sim(cfg);
  EXPECT_DOUBLE_EQ(sim.contact()->gap_solid(0), std::sqrt(2.0));
}

TEST(ContactCollision, TwoSolidsInTaylorGreenCollideAndSeparate) {
  // the scene on 48^2 (coarse), to its end (t = 1.2)
  Config cfg = load_scene(scene_path("two_solids_tgv.toml"), {"grid.nx=48", "grid.ny=48"});
  Simulation sim(cfg);
  const double a0 = area(sim, 0), a1 = area(sim, 1);
  const double range = sim.contact()->range();
  double min_gap = 1e9, t_min = 0, max_area_dev = 0, gap_before_end = -1;
  while (sim.time() < cfg.t_end - 1e-12) {
    sim.step();
    const double gp = sim.contact()->gap_solid(0);
    if (gp < min_gap) { min_gap = gp; t_min = sim.time(); }
    if (gap_before_end < 0 && sim.time() >= cfg.t_end - 0.2) gap_before_end = gp;
    max_area_dev = std::max({max_area_dev, std::abs(area(sim, 0) - a0) / a0, std::abs(area(sim, 1) - a1) / a1});
  }
  const double gap_end = sim.contact()->gap_solid(0);
  int ends = 0;
  for (const auto& e : sim.contact()->events()) ends += e.event == "contact_end";
  std::printf("[two solids tgv 48^2] min gap %.4f (%.2f dx) at t = %.3f, gap %.4f at t = %.2f and %.4f "
              "(%.2f dx) at the end, max area deviation %.3e\n",
              min_gap, min_gap / sim.grid().dx, t_min, gap_before_end, cfg.t_end - 0.2, gap_end,
              gap_end / sim.grid().dx, max_area_dev);
  EXPECT_LT(min_gap, range);        // they did come into contact
  EXPECT_GE(min_gap, 0.0);          // without the zero level sets crossing
  EXPECT_LT(max_area_dev, 1e-2);
  // and separated: the contact ended (one contact_end per solid), the gap ends more than
  // twice the contact range beyond its minimum and is still growing
  EXPECT_EQ(ends, 2);
  EXPECT_GT(gap_end, min_gap + 2.0 * range);
  EXPECT_GT(gap_end, gap_before_end + 0.5 * range);
}

TEST(ContactWall, MicrogravityImpactComesToRest) {
  // the scene's 64^2 (on 48^2 the kinetic energy at t = 3 is 0.66% of its start, not
  // monotonically falling: too close to the 1% bound to say "at rest")
  Config cfg = load_scene(scene_path("wall_microgravity.toml"));
  Simulation sim(cfg);
  const double a0 = area(sim, 0), ke0 = sim.kinetic_energy();
  double min_gap = 1e9, max_area_dev = 0;
  while (sim.time() < cfg.t_end - 1e-12) {
    sim.step();
    min_gap = std::min(min_gap, sim.contact()->gap_wall(0));
    max_area_dev = std::max(max_area_dev, std::abs(area(sim, 0) - a0) / a0);
  }
  const double ke = sim.kinetic_energy();
  std::printf("[wall microgravity 64^2] KE(t=%.2f)/KE0 = %.3e, min wall gap %.4f (%.2f dx), max area "
              "deviation %.3e\n", sim.time(), ke / ke0, min_gap, min_gap / sim.grid().dx, max_area_dev);
  EXPECT_LT(min_gap, sim.contact()->range());  // it reached the wall
  EXPECT_GE(min_gap, 0.0);
  EXPECT_LT(ke, 1e-2 * ke0);
  EXPECT_LT(max_area_dev, 1e-2);
}

namespace {

struct Bounce {
  double restitution = -1, max_aspect = 1, min_gap = 1e9, energy_gain = 0, contact_gain = 1e9, pressure = 0;
  double max_rise = 0, released = 0;  // largest rise of E + elastic energy above its running minimum; E0 - min E
};

// A bounce scene to t_end with --set overrides. Energy E: kinetic + gravitational
// ((rho_s - rho_f) |g| area * height of the centroid) + contact potential. With the viscous
// fluid the mechanical energy E + elastic can only fall; max_rise measures how far the scheme
// breaks that, against the energy the fall released.
Bounce run_bounce(const std::string& scene, const std::vector<std::string>& sets, double t_end) {
  std::vector<std::string> all(sets);
  all.push_back("time.end=" + std::to_string(t_end));
  Config cfg = load_scene(scene_path(scene), all);
  Simulation sim(cfg);
  const double drho = cfg.solids[0].density - cfg.rho_f, g = std::abs(cfg.gy);
  auto energy = [&]() {
    const SolidDiagnostics d = sim.solids()[0]->diagnostics(sim.u(), sim.v());
    return sim.kinetic_energy() + drho * g * d.area * d.cy + sim.contact()->energy();
  };
  Bounce b;
  b.pressure = sim.contact()->pressure();
  const double e0 = energy();
  double e_start = 0, e_min = e0, running_min = e0;
  size_t seen = 0;
  while (sim.time() < cfg.t_end - 1e-12) {
    sim.step();
    const double e = energy();
    b.energy_gain = std::max(b.energy_gain, (e - e0) / e0);
    const double total = e + sim.elastic_energy();
    b.max_rise = std::max(b.max_rise, total - running_min);
    running_min = std::min(running_min, total);
    e_min = std::min(e_min, e);
    b.min_gap = std::min(b.min_gap, sim.contact()->gap_wall(0));
    b.max_aspect = std::max(b.max_aspect, aspect_ratio(sim, 0));
    const auto& ev = sim.contact()->events();
    for (; seen < ev.size(); ++seen) {
      if (ev[seen].event == "contact_start" && e_start == 0) e_start = e;
      if (ev[seen].event == "contact_end" && e_start > 0 && b.contact_gain == 1e9)
        b.contact_gain = (e - e_start) / e_start;  // the first contact
    }
  }
  for (const auto& c : sim.components()) c->finish(sim, "");  // as at the end of a run, without files
  b.released = e0 - e_min;
  for (const auto& e : sim.contact()->events())
    if (e.event == "restitution" && b.restitution < 0) b.restitution = e.value;
  std::printf("[bounce %s %dx%d rho_s %g g %g] contact pressure P = %.4g, restitution %.4f, min wall gap %.4f (%.2f dx), "
              "max aspect ratio %.4f, max energy rise above start %.2e, relative energy change across the first contact %.3e, "
              "max rise of the total energy above its running minimum %.3e = %.4f of the released %.4f\n",
              scene.c_str(), cfg.grid.nx, cfg.grid.ny, cfg.solids[0].density, g, b.pressure, b.restitution, b.min_gap,
              b.min_gap / sim.grid().dx, b.max_aspect, b.energy_gain, b.contact_gain, b.max_rise,
              b.max_rise / b.released, b.released);
  return b;
}

}  // namespace

// The bounce scenes in the lighter, squeeze-film dominated setting (rho_s = 2, g = 10, central
// momentum fluxes, 64^2; Stokes number 11) to the end of the first rebound (t = 0.92: the
// contacts start at t ~ 0.52 and the rebounds are over by t ~ 0.8): the energy budget of a
// bounce, where it is cleanest.
const std::vector<std::string> kLightBounce{"solid[0].density=2.0", "gravity.g=[0.0, -10.0]",
                                            "solver.advection=central", "grid.nx=64", "grid.ny=64"};

TEST(ContactWall, BounceUnderGravity) {
  const Bounce soft = run_bounce("bounce_soft.toml", kLightBounce, 0.92);
  const Bounce stiff = run_bounce("bounce_stiff.toml", kLightBounce, 0.92);
  EXPECT_EQ(soft.pressure, stiff.pressure);  // the contact law does not depend on mu_s
  for (const Bounce* b : {&soft, &stiff}) {
    EXPECT_LT(b->min_gap, 2.5 / 64.0);  // fell under gravity into contact range (2.5 cells of 64)
    EXPECT_GT(b->restitution, 0.1);  // it bounced (the heavier solid fell, hit and came back)
    EXPECT_LT(b->restitution, 1.0);
    EXPECT_GE(b->min_gap, 0.0);
    EXPECT_LE(b->energy_gain, 1e-3);   // never above the initial energy
    EXPECT_LT(b->contact_gain, 0.0);   // no energy gain through the (first) contact
    // nor during the rebound: measured 0.45 % (soft) and 4.0 % (stiff) of the energy released
    // by the fall; with the paper's least-squares fit radius (solids.lsq_radius = 5.66) the
    // rebound gained 22 % and 17 % of it (results/methods.md, "Least-squares fit radius")
    EXPECT_LT(b->max_rise, 0.08 * b->released);
  }
  // the softer solid deforms more
  EXPECT_GT(soft.max_aspect - 1.0, 2.0 * (stiff.max_aspect - 1.0));
}

// The paper (Figs. 11-12): the softer solid has the lower restitution. The scenes as shipped
// (rho_s = 10, g = 20: Stokes number ~180, the soft disc's impact speed 0.59 of its shear-wave
// speed) on 96^2 instead of 128^2, to t = 0.45 (first contacts from t ~ 0.19, rebounds over by
// t ~ 0.40). Measured 0.70 (soft) and 0.82 (stiff); 0.69 and 0.81 on the scenes' 128^2. In the
// lighter setting of BounceUnderGravity the order is the opposite (0.56 vs 0.49; docs/contact.md, results/methods.md "Restitution regime").
TEST(ContactWall, StifferSolidHasHigherRestitution) {
  const std::vector<std::string> sets{"grid.nx=96", "grid.ny=96"};
  const Bounce soft = run_bounce("bounce_soft.toml", sets, 0.45);
  const Bounce stiff = run_bounce("bounce_stiff.toml", sets, 0.45);
  for (const Bounce* b : {&soft, &stiff}) {
    EXPECT_GT(b->restitution, 0.1);  // both bounced
    EXPECT_LT(b->restitution, 1.0);
    EXPECT_GE(b->min_gap, 0.0);
  }
  EXPECT_GT(stiff.restitution, soft.restitution);
  EXPECT_GT(soft.max_aspect - 1.0, 2.0 * (stiff.max_aspect - 1.0));  // the softer deforms more
}

TEST(ContactScene, KeysAreValidatedWithOneLineErrors) {
  auto message = [](const std::vector<std::string>& sets) {
    try {
      load_scene_string(kGapScene, "gaps.toml", sets);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // without a [contact] table the kind returns no options and the component takes the
  // defaults (solver/components/contact_component.cpp)
  const Config def = load_scene_string(kGapScene, "gaps.toml");
  EXPECT_EQ(def.component_options<ContactOptions>("contact"), nullptr);
  const ContactOptions d;
  EXPECT_TRUE(d.enabled);
  EXPECT_TRUE(d.walls);
  EXPECT_DOUBLE_EQ(d.range, 2.5);
  EXPECT_DOUBLE_EQ(d.stiffness, 20.0);
  Simulation sim(def);
  ASSERT_NE(sim.contact(), nullptr);
  EXPECT_TRUE(sim.contact()->force_enabled());
  EXPECT_DOUBLE_EQ(sim.contact()->range(), 2.5 * def.grid.dx);
  const Config c = load_scene_string(kGapScene, "gaps.toml",
                                     {"contact.range=3", "contact.stiffness=50", "contact.walls=false"});
  const ContactOptions* co = c.component_options<ContactOptions>("contact");
  ASSERT_NE(co, nullptr);
  EXPECT_DOUBLE_EQ(co->range, 3.0);
  EXPECT_DOUBLE_EQ(co->stiffness, 50.0);
  EXPECT_FALSE(co->walls);
  EXPECT_TRUE(co->enabled);
  EXPECT_NE(message({"contact.range=6"}).find("contact.range: must be in (0, solids.band = 6)"), std::string::npos);
  EXPECT_NE(message({"contact.range=0"}).find("contact.range"), std::string::npos);
  EXPECT_NE(message({"contact.stiffness=-1"}).find("contact.stiffness: must be >= 0"), std::string::npos);
  EXPECT_NE(message({"contact.velocity_scale=-1"}).find("contact.velocity_scale"), std::string::npos);
  EXPECT_NE(message({"contact.cfl=0"}).find("contact.cfl: must be > 0"), std::string::npos);
  EXPECT_NE(message({"contact.stifness=1"}).find("contact.stifness: unknown key"), std::string::npos);
  EXPECT_NE(message({"contact.enabled=1"}).find("contact.enabled: expected true or false"), std::string::npos);
}

// The contact strength, hence the contact limit of the time step, does not depend on the
// run's length (solver/model/contact.hpp): a soft disc in a lid-driven box starting from rest (no
// initial speed, no gravity) took U = l_x / (t_end - t_start), so two runs differing only in
// time.end had first steps in the ratio of their lengths (here 10: the contact limit is the
// smallest at end = 1). Now U = 0 in both until the disc moves (no initial speed, no gravity).
TEST(ContactTimeStep, FirstStepDoesNotDependOnTheEndTime) {
  double dt[2], U[2];
  const double ends[2] = {1.0, 10.0};
  for (int k = 0; k < 2; ++k) {
    Config cfg = load_scene_string(box_scene(32, kLidDriven, disc_toml("disc", 0.5, 0.5, 0.2), 0.01, ends[k]),
                                   "lid_disc.toml");
    Simulation sim(cfg);
    ASSERT_NE(sim.contact(), nullptr);
    U[k] = sim.contact()->velocity_scale();
    dt[k] = sim.step();
  }
  std::printf("first dt %.6g (end = 1), %.6g (end = 10); U = %.3g, %.3g\n", dt[0], dt[1], U[0], U[1]);
  EXPECT_EQ(dt[0], dt[1]);
  EXPECT_EQ(U[0], 0.0);
  EXPECT_EQ(U[1], 0.0);
}

// The spring's time-step limit (solver/model/contact.hpp) applies only in a step that can bring a
// surface into the contact range d: far from contact the step is set by the other limits
// (here the viscous one, 2.3x the spring's), near contact by the spring.
TEST(ContactTimeStep, SpringLimitOnlyInStepsThatCanCloseAGap) {
  const double dx = 1.0 / 64;
  auto scene_with_gap = [&](double gap_cells, const char* extra = "contact.cfl=0.5") {
    // disc b at a known gap from disc a (as in ContactGap above), both soft enough that
    // their own limit does not bind; a fixed contact velocity scale, so the spring is on
    const double D = 0.15 + 0.12 + gap_cells * dx, theta = 0.37;
    char c[128];
    std::snprintf(c, sizeof c, "solid[1].center=[%.17g, %.17g]", 0.3 + D * std::cos(theta), 0.4 + D * std::sin(theta));
    return load_scene_string(kGapScene, "gaps.toml",
                             {c, "solid[0].mu_s=1", "solid[1].mu_s=1", "contact.velocity_scale=1", extra});
  };
  {
    Simulation sim(scene_with_gap(5.0));  // d = 2.5 dx: 2.5 dx to spare (+-0.1 dx sampling)
    const Contact& c = *sim.contact();
    // closing 2 speed dt + dx: 2 dx at dt = dx / 2 (clear), 3 dx at dt = dx (not)
    EXPECT_TRUE(c.clear_of_contact(1.0, 0.5 * dx));
    EXPECT_FALSE(c.clear_of_contact(1.0, 1.0 * dx));
    const double spring = c.min_dt(1.0);
    const double dt = sim.step();  // the moving lid: (|u| + |v|)_max = 1
    std::printf("far: dt %.6g, spring limit %.6g\n", dt, spring);
    EXPECT_GT(dt, 2.0 * spring);
    EXPECT_DOUBLE_EQ(dt, 0.9 * dx * dx / (6.0 * 0.01));  // the viscous limit
  }
  {
    Simulation sim(scene_with_gap(3.0));  // 0.5 dx to spare: a step of 0.004 can close it
    const double dt = sim.step();
    EXPECT_DOUBLE_EQ(dt, sim.contact()->min_dt(1.0));
  }
}

// With gravity the advective bound uses the speed at the step's end, dt (umax + a dt) <=
// cfl dx, a = |g| max(1, |rho_s - rho_f| / rho_s) (docs/method.md): a step from rest is
// sqrt(cfl dx / a), not unbounded (the spring's limit, which capped it before, no longer
// applies far from contact). A light disc (rho_s = 0.25) rises at up to 3 |g|.
TEST(ContactTimeStep, StepFromRestUnderGravityIsBounded) {
  const double dx = 1.0 / 64;
  for (double rho : {10.0, 0.25}) {
    const std::string r = std::to_string(rho);
    Config cfg = load_scene_string(kGapScene, "gaps.toml",
                                   {"boundary.top=\"no_slip\"", "gravity.g=[0.0, -10.0]", "fluid.viscosity=1e-5",
                                    "solid[1].center=[0.7, 0.7]", "solid[0].mu_s=1e-4", "solid[1].mu_s=1e-4",
                                    "solid[0].density=" + r, "solid[1].density=" + r});
    Simulation sim(cfg);
    const double dt = sim.step();
    const double a = 10.0 * std::max(1.0, std::abs(rho - 1.0) / rho);
    std::printf("rho_s %g: first dt %.6g\n", rho, dt);
    EXPECT_NEAR(dt, std::sqrt(0.5 * dx / a), 1e-12);
  }
}
