// Passive tracers (solver/components/tracers.hpp) and solid material points (solver/components/markers.hpp):
//  - tracers in a solid-body rotation: the cell velocity is linear, so the bilinear
//    interpolation is exact and the only error is RK-4's; after one revolution it must be
//    within the RK-4 phase error and fall by ~2^4 when dt is halved;
//  - tracers in a steady Taylor-Green flow keep their stream function to the O(dx^2) of the
//    interpolation (second order under refinement);
//  - markers of a disc moved by a uniform flow / a rotation follow the exact rigid motion;
//  - a run saved and restored half-way continues tracers and markers bit for bit;
//  - bad [[tracers]] / markers values are scene errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "solver/io/checkpoint_io.hpp"
#include "solver/components/markers.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "solver/components/tracers.hpp"
#include "tests/fixtures/scene_text.hpp"
#include "test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

const double kPi = std::acos(-1.0);

/// A prescribed flow (u_expr, v_expr) on the unit box, n x n cells, fixed dt, `extra` tables.
Config prescribed(int n, const std::string& boundary, const std::string& u, const std::string& v, double dt,
                  double end, const std::string& extra) {
  const std::string text = box_scene(n, boundary,
                                     "dt = " + std::to_string(dt) + "\n[solver]\nflow = \"prescribed\"\n[initial]\n"
                                     "velocity = \"expression\"\nu_expr = \"" + u + "\"\nv_expr = \"" + v + "\"\n" + extra,
                                     0.0, end);
  return load_scene_string(text, "tracers_test.toml");
}

void run_to_end(Simulation& sim, double dt) {
  const double end = sim.config().t_end;
  while (sim.time() < end - 1e-12) sim.step(std::min(dt, end - sim.time()));
}

/// Largest distance of the tracers after one revolution (omega = 2 pi, period 1) from their seeds.
double rotation_error(double dt) {
  Config cfg = prescribed(16, kWalls, "-2*pi*(y-0.5)", "2*pi*(x-0.5)", dt, 1.0,
                          "[[tracers]]\nline = [[0.5, 0.5], [0.8, 0.5]]\nn = 4\n");
  Simulation sim(cfg);
  run_to_end(sim, dt);
  double e = 0.0;
  for (int k = 0; k < 4; ++k) e = std::max(e, std::hypot(sim.component<Tracers>()->x(k) - (0.5 + 0.1 * k), sim.component<Tracers>()->y(k) - 0.5));
  return e;
}

}  // namespace

TEST(Tracers, Rk4ErrorInSolidBodyRotation) {
  // RK-4 on dz/dt = i omega z multiplies z by 1 + h + ... + h^4/24 (h = i omega dt): per
  // step a phase error of (omega dt)^5 / 120 and a modulus error of (omega dt)^6 / 144, so
  // after T = 1 (2 pi / (omega dt) steps) the distance is r (2 pi) (omega dt)^4 / 120.
  const double e1 = rotation_error(1.0 / 40), e2 = rotation_error(1.0 / 80);
  const double bound = [](double dt) { const double h = 2 * kPi * dt; return 0.3 * 2 * kPi * std::pow(h, 4) / 120; }(1.0 / 40);
  std::printf("rotation: error %.3e (dt 1/40), %.3e (dt 1/80), ratio %.2f, RK-4 estimate %.3e\n", e1, e2, e1 / e2, bound);
  EXPECT_LT(e1, 1.05 * bound);
  EXPECT_GT(e1, 0.9 * bound);       // it is the RK-4 error, not something smaller by luck
  EXPECT_NEAR(e1 / e2, 16.0, 1.0);  // fourth order in time
}

TEST(Tracers, StreamFunctionKeptInTaylorGreen) {
  // steady u = sin(2 pi x) cos(2 pi y), v = -cos(2 pi x) sin(2 pi y): psi = sin sin / (2 pi)
  // is constant along a trajectory. The bilinear interpolation errs by dx^2/8 |u''| ~
  // (2 pi)^2 dx^2 / 8 in velocity, so psi drifts at second order in dx (dt small enough
  // that RK-4's share is negligible).
  auto drift = [](int n) {
    Config cfg = prescribed(n, kPeriodic, "sin(2*pi*x)*cos(2*pi*y)", "-cos(2*pi*x)*sin(2*pi*y)", 0.005, 0.5,
                            "[[tracers]]\nbox = [[0.1, 0.1], [0.4, 0.4]]\nnx = 3\nny = 3\n");
    Simulation sim(cfg);
    auto psi = [](double x, double y) { return std::sin(2 * kPi * x) * std::sin(2 * kPi * y) / (2 * kPi); };
    std::vector<double> p0;
    for (int k = 0; k < sim.component<Tracers>()->size(); ++k) p0.push_back(psi(sim.component<Tracers>()->x(k), sim.component<Tracers>()->y(k)));
    run_to_end(sim, 0.005);
    double d = 0.0;
    for (int k = 0; k < sim.component<Tracers>()->size(); ++k) d = std::max(d, std::abs(psi(sim.component<Tracers>()->x(k), sim.component<Tracers>()->y(k)) - p0[k]));
    return d;
  };
  const double d32 = drift(32), d64 = drift(64);
  std::printf("Taylor-Green: max |psi drift| %.3e (32^2), %.3e (64^2), ratio %.2f\n", d32, d64, d32 / d64);
  // bound: velocity error (2 pi)^2 dx^2 / 8 times |u| <= 1 over T = 0.5
  EXPECT_LT(d32, 0.5 * std::pow(2 * kPi / 32, 2) / 8);
  EXPECT_GT(d32 / d64, 3.0);  // second order in dx
}

TEST(Markers, FollowATranslatingDisc) {
  // uniform flow: xi stays affine, every stage of its advection is exact, so the markers
  // are at X + U t to round-off (tolerance 1e-9 dx)
  Config cfg = prescribed(32, kWalls, "0.5", "0.25", 0.01, 0.4,
                          disc_toml("d", 0.35, 0.35, 0.15, 0.0, "markers = [[0.35, 0.35], [0.4, 0.3]]\nboundary_markers = 8\n"));
  Simulation sim(cfg);
  run_to_end(sim, 0.01);
  ASSERT_NE(sim.component<Markers>(), nullptr);
  ASSERT_EQ(sim.component<Markers>()->points().size(), 10u);
  double e = 0.0;
  for (const auto& p : sim.component<Markers>()->points()) e = std::max(e, std::hypot(p.x - (p.X + 0.2), p.y - (p.Y + 0.1)));
  std::printf("translating disc: max marker error %.3e (dx = %.3e)\n", e, cfg.grid.dx);
  EXPECT_LT(e, 1e-9 * cfg.grid.dx);
  // the boundary markers are on the reference circle
  for (std::size_t k = 2; k < 10; ++k) {
    const auto& p = sim.component<Markers>()->points()[k];
    EXPECT_NEAR(std::hypot(p.X - 0.35, p.Y - 0.35), 0.15, 1e-12);
  }
}

TEST(Markers, FollowARotatingDisc) {
  // a quarter turn about the disc's centre: xi is affine at all times and its advection's
  // only error is RK-4's in time, the tracers' phase error r (omega T) (omega dt)^4 / 120
  // (2.5e-9 for r = 0.25, omega T = pi/2, omega dt = pi/100); twice that is the tolerance
  const double dt = 1.0 / 200;
  Config cfg = prescribed(32, kWalls, "-2*pi*(y-0.5)", "2*pi*(x-0.5)", dt, 0.25,
                          disc_toml("d", 0.5, 0.5, 0.25, 0.0, "markers = [[0.6, 0.5], [0.5, 0.7]]\nboundary_markers = 6\n"));
  Simulation sim(cfg);
  run_to_end(sim, dt);
  double e = 0.0;
  for (const auto& p : sim.component<Markers>()->points()) {
    // a quarter turn counter-clockwise about (0.5, 0.5)
    const double xe = 0.5 - (p.Y - 0.5), ye = 0.5 + (p.X - 0.5);
    e = std::max(e, std::hypot(p.x - xe, p.y - ye));
  }
  std::printf("rotating disc: max marker error %.3e (dx = %.3e)\n", e, cfg.grid.dx);
  EXPECT_LT(e, 2 * 0.25 * (kPi / 2) * std::pow(2 * kPi * dt, 4) / 120);
}

TEST(Tracers, RestoredStateContinuesBitForBit) {
  // a solved flow (Taylor-Green around a soft disc), 12 steps straight through, against 6
  // steps, a checkpoint, a new Simulation loading it and 6 more steps
  const std::string text = box_scene(32, kPeriodic,
                                     "dt = 0.002\n[initial]\nvelocity = \"taylor_green\"\n"
                                     "[[tracers]]\nline = [[0.05, 0.1], [0.95, 0.2]]\nn = 7\n"
                                     "[[tracers]]\nbox = [[0.1, 0.6], [0.3, 0.9]]\nnx = 2\nny = 3\n" +
                                         disc_toml("d", 0.5, 0.5, 0.15, 0.5, "boundary_markers = 5\n"),
                                     0.01, 1.0);
  Config cfg = load_scene_string(text, "resume_test.toml");
  Simulation a(cfg);
  for (int k = 0; k < 12; ++k) a.step(0.002);
  Simulation b(cfg);
  for (int k = 0; k < 6; ++k) b.step(0.002);
  const std::string path = (std::filesystem::temp_directory_path() / "refmap_tracers_resume.ck").string();
  CheckpointWriter w;
  b.save_state(w);
  w.save(path);
  Simulation c(cfg);
  CheckpointReader r(path);
  c.load_state(r);
  EXPECT_TRUE(r.at_end());
  for (int k = 0; k < 6; ++k) c.step(0.002);
  ASSERT_EQ(a.component<Tracers>()->size(), 13);
  for (int k = 0; k < a.component<Tracers>()->size(); ++k) {
    EXPECT_EQ(a.component<Tracers>()->x(k), c.component<Tracers>()->x(k)) << k;
    EXPECT_EQ(a.component<Tracers>()->y(k), c.component<Tracers>()->y(k)) << k;
    EXPECT_NE(a.component<Tracers>()->x(k), b.component<Tracers>()->x(k)) << k;  // they did move after the checkpoint
  }
  for (std::size_t k = 0; k < a.component<Markers>()->points().size(); ++k) {
    EXPECT_EQ(a.component<Markers>()->points()[k].x, c.component<Markers>()->points()[k].x) << k;
    EXPECT_EQ(a.component<Markers>()->points()[k].y, c.component<Markers>()->points()[k].y) << k;
  }
  std::filesystem::remove(path);
}

TEST(Tracers, BadValuesAreSceneErrors) {
  auto error_of = [](const std::string& extra) { return refmap::testing::scene_error(box_scene(16, kWalls, extra)); };
  EXPECT_NE(error_of("[[tracers]]\nline = [[0.1, 0.1], [1.5, 0.1]]\nn = 3\n").find("outside the domain"), std::string::npos);
  EXPECT_NE(error_of("[[tracers]]\nline = [[0.1, 0.1]]\nn = 3\n").find("expected two points"), std::string::npos);
  EXPECT_NE(error_of("[[tracers]]\nline = [[0.1, 0.1], [0.2, 0.2]]\nbox = [[0.1, 0.1], [0.2, 0.2]]\nn = 3\n").find("not both"),
            std::string::npos);
  EXPECT_NE(error_of("[[tracers]]\nn = 3\n").find("needs `line`"), std::string::npos);
  EXPECT_NE(error_of("[[tracers]]\nline = [[0.1, 0.1], [0.2, 0.2]]\nn = 0\n").find("tracers[0].n"), std::string::npos);
  EXPECT_NE(error_of(disc_toml("d", 0.5, 0.5, 0.2, 1.0, "markers = [[0.9, 0.5]]\n")).find("reference configuration"),
            std::string::npos);
  EXPECT_NE(error_of(disc_toml("d", 0.5, 0.5, 0.2, 1.0, "markers = [0.5, 0.5]\n")).find("list of points"),
            std::string::npos);
}
