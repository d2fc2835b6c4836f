// time.solid_picard_iterations (solver/model/solid_picard.cpp; docs/implicit.md, "The
// implicit step in xi"): the whole step repeated from a snapshot of the state at t^n with xi
// moved by the blend of u^n and the last pass's u^{n+1}.
//  - ThetaZeroRepeatsTheStepBitForBit: with theta = 0 and no defect correction every pass
//    recomputes the same step from the same state, so the result must be the plain step's
//    bits: the snapshot restores everything a step reads.
//  - TrapezoidalRestoresTheStartForce: the same with time.solid_picard_force = "trapezoidal"
//    (the snapshot must restore the stored F^n, or pass 2 kicks with pass 1's force).
//  - TrapezoidalKeepsTheShearWaveEnergy: the 1-D analysis of solid_picard.cpp's header on
//    the periodic shear wave at 2x and 4x the explicit limit: the trapezoidal fixed point keeps
//    the energy, today's ("new") loses the factor 1 / (1 + theta w) per step.
//  - the keys' errors.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "solver/model/picard_anderson.hpp"
#include "solver/model/rigid_body.hpp"
#include "solver/model/simulation.hpp"
#include "solver/model/solid.hpp"
#include "solver/scene/scene.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

std::vector<std::string> semi_case() {
  // disc_tgv 32^2 at mu_s / rho_s = 100, P = 2 (past the explicit limit, P = 1)
  return {"grid.nx=32", "grid.ny=32", "time.end=100", "time.viscous=\"implicit\"",
          "time.solid_stress=\"semi_implicit\"", "solid.0.mu_s=100", "output.vtk=false",
          "time.dt_max=" + std::to_string(2.0 / 32.0 / std::sqrt(200.0))};
}

/// The two runs' cell velocities agree to the bit.
void expect_same_velocity(const Simulation& a, const Simulation& b) {
  const Grid& g = a.grid();
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      ASSERT_EQ(a.u()(i, j), b.u()(i, j)) << i << " " << j;
      ASSERT_EQ(a.v()(i, j), b.v()(i, j)) << i << " " << j;
    }
}

/// The scene with `sets` (a) and with two more plain passes at theta = 0 (b), each run 5 steps:
/// every pass of b is its first again.
struct RepeatedPasses {
  std::unique_ptr<Simulation> a, b;
};
RepeatedPasses run_repeated_passes(const std::string& scene, const std::vector<std::string>& sets) {
  std::vector<std::string> picard = sets;
  // every pass to the full tolerances (time.solid_picard_tol = 0), so that every pass is the first
  for (const char* s : {"time.solid_picard_iterations=2", "time.solid_picard_theta=0", "time.solid_picard_defect=false",
                        "time.solid_picard_tol=0"})
    picard.push_back(s);
  RepeatedPasses r{std::make_unique<Simulation>(load_scene(scene_path(scene), sets)),
                   std::make_unique<Simulation>(load_scene(scene_path(scene), picard))};
  for (int n = 0; n < 5; ++n) {
    r.a->step();
    r.b->step();
  }
  return r;
}

}  // namespace

TEST(SolidPicard, ThetaZeroRepeatsTheStepBitForBit) {
  const RepeatedPasses r = run_repeated_passes("disc_tgv.toml", semi_case());
  const Simulation &a = *r.a, &b = *r.b;
  expect_same_velocity(a, b);
  const Solid &sa = *a.solids().at(0), &sb = *b.solids().at(0);
  ASSERT_EQ(sa.ni(), sb.ni());
  ASSERT_EQ(sa.nj(), sb.nj());
  for (int j = 0; j < sa.nj(); ++j)
    for (int i = 0; i < sa.ni(); ++i) ASSERT_EQ(sa.xi_x()(i, j), sb.xi_x()(i, j)) << i << " " << j;
  EXPECT_EQ(b.picard_change(), 0.0);  // the passes agree exactly
  EXPECT_GT(b.picard_cycles(), a.last_poisson_iterations());  // three passes' cycles
}

// The same with rigid bodies: a repeated pass starts from the step's snapshot, which holds the
// bodies' state (poses, last loads, held momentum) through the state registry, so with
// theta = 0 and plain repetition every pass is the first one again, bit for bit. The flag
// clamped behind a fixed cylinder (scenes/flag_clamped.toml), with the diffuse forcing and the
// sharp forcing with held cells (its cut faces and held rates are rebuilt in each pass).
TEST(SolidPicard, ThetaZeroRepeatsTheStepBitForBitWithRigidBodies) {
  for (const bool sharp : {false, true}) {
    std::vector<std::string> base{"output.vtk=false", "time.viscous=\"implicit\"",
                                  "time.solid_stress=\"semi_implicit\""};
    if (sharp) {
      base.push_back("solid[0].forcing=\"sharp\"");
      base.push_back("solid[0].forcing_hold=true");
      base.push_back("time.splitting=\"increment\"");
    }
    const RepeatedPasses r = run_repeated_passes("flag_clamped.toml", base);
    const Simulation &a = *r.a, &b = *r.b;
    expect_same_velocity(a, b);
    ASSERT_NE(a.bodies(), nullptr);
    EXPECT_EQ(a.bodies()->load(0).fx, b.bodies()->load(0).fx) << "sharp = " << sharp;
    EXPECT_EQ(a.bodies()->load(0).fy, b.bodies()->load(0).fy) << "sharp = " << sharp;
    EXPECT_EQ(b.picard_change(), 0.0);
  }
}

TEST(SolidPicard, TrapezoidalRestoresTheStartForce) {
  // theta = 0, plain repetition: every pass is the same step from the same state, its kick
  // (F^n + F^{n+1}) / 2 with F^n restored from the snapshot; one pass and three must agree
  // to the bit (pass k reading pass k-1's force as F^n would move u by dt |F^{n+1} - F^n| / 2)
  auto with = [](int n) {
    std::vector<std::string> sets = semi_case();
    for (const std::string& s : {std::string("time.solid_picard_iterations=") + std::to_string(n),
                                 std::string("time.solid_picard_theta=0"), std::string("time.solid_picard_defect=false"),
                                 std::string("time.solid_picard_force=\"trapezoidal\""), std::string("time.solid_picard_tol=0")})
      sets.push_back(s);
    return sets;
  };
  Simulation a(load_scene(scene_path("disc_tgv.toml"), with(1)));
  Simulation b(load_scene(scene_path("disc_tgv.toml"), with(3)));
  for (int n = 0; n < 5; ++n) {
    a.step();
    b.step();
  }
  expect_same_velocity(a, b);
  EXPECT_EQ(b.picard_change(), 0.0);
  EXPECT_GT(a.elastic_energy(), 0.0);  // the disc is strained: the two forces differ
}

// time.solid_picard_tol: the passes before the last solve only to 1e-4 (the default), the last
// to the full tolerances. The fixed point is the same; what moves is the last pass's input, by
// the earlier passes' solve errors (about 1e-4 of their velocity changes) times the iteration's
// contraction. disc_tgv 32^2 at P = 2 (semi_case), two defect passes at theta = 1/2, reach 2,
// 5 steps: a solve error of at most tol |d| per pass, |d| < max |u| and a contracting iteration
// move the velocity by less than tol max |u| against the run with every pass at full
// tolerance (measured 1.9e-6 of max |u|, while the iteration's own last change is 3.1e-2),
// with fewer cycles (183 -> 149; at 1e-3: 2.6e-4 and 123).
TEST(SolidPicard, LooseEarlierPassesKeepTheVelocity) {
  auto with = [](const char* tol) {
    std::vector<std::string> sets = semi_case();
    for (const char* s : {"time.solid_picard_iterations=2", "time.solid_picard_theta=0.5", "time.solid_implicit_reach=2"})
      sets.push_back(s);
    if (tol) sets.push_back(std::string("time.solid_picard_tol=") + tol);
    return sets;
  };
  Simulation a(load_scene(scene_path("disc_tgv.toml"), with("0")));
  Simulation b(load_scene(scene_path("disc_tgv.toml"), with(nullptr)));
  long ca = 0, cb = 0;
  for (int n = 0; n < 5; ++n) {
    a.step();
    b.step();
    ca += a.picard_cycles();
    cb += b.picard_cycles();
  }
  const Grid& g = a.grid();
  double dmax = 0.0, umax = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      dmax = std::max({dmax, std::abs(a.u()(i, j) - b.u()(i, j)), std::abs(a.v()(i, j) - b.v()(i, j))});
      umax = std::max({umax, std::abs(a.u()(i, j)), std::abs(a.v()(i, j))});
    }
  std::printf("  loose earlier passes: max |du| / max |u| = %.3g, cycles %ld -> %ld, last change %.3g\n",
              dmax / umax, ca, cb, a.picard_change());
  EXPECT_LT(dmax / umax, 1e-4);
  EXPECT_LT(cb, ca);
}

// AndersonMixer (time.solid_picard_anderson) on a linear map g(x) = A x + b in 3 unknowns (three
// cells of one field), A non-symmetric, eigenvalues near 0.9, -0.8 and 0.3: with a window that keeps the whole
// history Anderson's update is GMRES's on (I - A) x = b (Walker & Ni 2011, section 4), so once
// the residual differences span the 3 dimensions the next input is the fixed point
// x* = (I - A)^{-1} b, up to the bias of the mixer's Tikhonov shift (1e-13 of the normal
// matrix's trace: 2e-11 here, 2e-8 with a shift of 1e-10); the plain iteration is far from it
// after as many maps.
TEST(SolidPicard, AndersonReachesTheFixedPointOfALinearMap) {
  const double A[3][3] = {{0.9, 0.1, 0.0}, {-0.1, -0.8, 0.1}, {0.05, 0.0, 0.3}};
  const double b[3] = {1.0, -0.5, 0.25};
  auto apply = [&](const Field& x, Field& g) {
    for (int i = 0; i < 3; ++i) {
      double s = b[i];
      for (int j = 0; j < 3; ++j) s += A[i][j] * x(j, 0);
      g(i, 0) = s;
    }
  };
  // the fixed point by Cramer's rule on (I - A) x = b
  double M[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) M[i][j] = (i == j ? 1.0 : 0.0) - A[i][j];
  auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  double xs[3];
  for (int c = 0; c < 3; ++c) {
    double Mc[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Mc[i][j] = j == c ? b[i] : M[i][j];
    xs[c] = det3(Mc) / det3(M);
  }
  auto error = [&](const Field& x) {
    double e = 0.0;
    for (int i = 0; i < 3; ++i) e = std::max(e, std::abs(x(i, 0) - xs[i]));
    return e;
  };
  Field x, g, r, xp, gp;
  for (Field* f : {&x, &g, &r, &xp, &gp}) f->resize(3, 1, 0);
  AndersonMixer mix(3);
  for (int k = 0; k < 4; ++k) {
    apply(x, g);
    for (int i = 0; i < 3; ++i) r(i, 0) = g(i, 0) - x(i, 0);
    mix.next({&g}, {&r}, {&x});
    apply(xp, gp);  // the plain iteration alongside
    xp = gp;
  }
  std::printf("  Anderson(3) after 4 evaluations: error %.3g; plain iteration %.3g\n", error(x), error(xp));
  EXPECT_LT(error(x), 1e-10);
  EXPECT_GT(error(xp), 1e-2);
}

// time.solid_picard_anderson on the solver: disc_tgv 32^2 at P = 8, the trapezoidal force
// (k = 1/4, reach 2), eight passes of the first step from the same state. The plain iteration
// contracts slowly at the interface (its last pass still moves the velocity by 1.9 % of
// max |u|); Anderson with depth 2 over the same passes must leave less than half that
// (measured 0.67 %; at N = 4 / 6: 4.3 / 2.7 % plain, 2.6 / 1.2 % with depth 2). The disc_tgv
// 64^2 runs: results/implicit.md, "Anderson acceleration of the passes".
TEST(SolidPicard, AndersonConvergesTheTrapezoidalPasses) {
  auto with = [](int depth) {
    std::vector<std::string> sets = semi_case();
    for (const char* s : {"time.solid_picard_iterations=8", "time.solid_picard_theta=0.5", "time.solid_implicit_k=0.25",
                          "time.solid_implicit_reach=2", "time.solid_picard_force=\"trapezoidal\""})
      sets.push_back(s);
    sets.push_back("time.solid_picard_anderson=" + std::to_string(depth));
    sets.push_back("time.dt_max=" + std::to_string(8.0 / 32.0 / std::sqrt(200.0)));  // P = 8
    return sets;
  };
  Simulation a(load_scene(scene_path("disc_tgv.toml"), with(0)));
  Simulation b(load_scene(scene_path("disc_tgv.toml"), with(2)));
  a.step();
  b.step();
  std::printf("  trapezoidal, 8 passes, P = 8: last-pass change %.3g plain, %.3g Anderson(2)\n", a.picard_change(),
              b.picard_change());
  EXPECT_LT(b.picard_change(), 0.5 * a.picard_change());
}

namespace {

/// The shear wave of scenes/shear_wave.toml (32^2, all solid, c = 1, inviscid, E0 = U0^2 / 4)
/// over one period at dt with the semi-implicit step and two defect passes, theta = 1/2: the
/// total energy at t = 1 over E0.
double shear_wave_energy(double dt, const char* force, double k) {
  Config cfg = load_scene(scene_path("shear_wave.toml"),
                          {"time.dt=" + std::to_string(dt), "time.solid_stress=\"semi_implicit\"",
                           "time.solid_picard_iterations=2", "time.solid_picard_theta=0.5",
                           "time.solid_implicit_k=" + std::to_string(k),
                           std::string("time.solid_picard_force=\"") + force + "\"", "output.vtk=false"});
  Simulation sim(cfg);
  const double e0 = sim.kinetic_energy() + sim.elastic_energy();
  while (sim.time() < 1.0 - 1e-9) sim.step(dt);
  return (sim.kinetic_energy() + sim.elastic_energy()) / e0;
}

}  // namespace

TEST(SolidPicard, TrapezoidalKeepsTheShearWaveEnergy) {
  // The wave is linear in this geometry (the neo-Hookean shear stress is G gamma, and
  // xi_x = x - s(y, t) advects linearly), all solid (eta everywhere), so each pass is the 1-D
  // model of solid_picard.cpp's header for the mode kappa = 2 pi: x1 = x0 + h ((1 - theta) v0 +
  // theta v1), v1 = v0 - h omega^2 ((1 - a) x0 + a x1), a = 1/2 ("trapezoidal") or 1 ("new"),
  // omega = c kappa_h, kappa_h = 2 sin(kappa dx / 2) / dx the compact face stress's wave number;
  // with k = theta / 2 resp. theta one defect pass reaches the fixed point (the second is a
  // check). The energy v^2 + omega^2 x^2 of that recurrence after one period is the expectation:
  // 1 for the trapezoidal rule at any dt, (1 + theta w)^{-1} per step on average for "new"
  // (0.31 and 0.13 here). Measured: within 0.003 % / 0.2 % (trapezoidal, dt = 1/16 / 1/8) and
  // 0.01 % / 0.3 % ("new"); the tolerance 1 % leaves room for the discrete energy's quadratic
  // form (cell gradients, not the face operator's) and the velocity solve's tolerance, and is
  // far below the gap between the two forces (a factor 3 .. 8).
  const double dx = 1.0 / 32, kh = 2.0 * std::sin(M_PI * dx) / dx;
  for (double dt : {1.0 / 16, 1.0 / 8}) {  // c dt / dx = 2 and 4: the explicit step blows up at 2
    for (double a : {0.5, 1.0}) {
      const double h = dt, om2 = kh * kh, th = 0.5;
      double x = 0.0, v = 1.0;
      for (int n = 0; n < int(std::lround(1.0 / dt)); ++n) {
        // [1, -h th; h a om2, 1] (x1, v1) = (x + h (1 - th) v, v - h (1 - a) om2 x)
        const double b0 = x + h * (1.0 - th) * v, b1 = v - h * (1.0 - a) * om2 * x;
        const double det = 1.0 + h * th * h * a * om2;
        x = (b0 + h * th * b1) / det;
        v = (b1 - h * a * om2 * b0) / det;
      }
      const double expected = v * v + om2 * x * x;
      const double got = a == 0.5 ? shear_wave_energy(dt, "trapezoidal", 0.25) : shear_wave_energy(dt, "new", 0.5);
      std::printf("[picard shear wave] dt %.4f, %s: E(1)/E0 %.5f, 1-D recurrence %.5f\n", dt,
                  a == 0.5 ? "trapezoidal" : "new", got, expected);
      EXPECT_NEAR(got / expected, 1.0, 0.01) << dt << " " << a;
    }
  }
}

TEST(SolidPicard, KeysErrors) {
  const std::string base = "[domain]\nlx = 1\nly = 1\n[grid]\nnx = 16\nny = 16\n[fluid]\ndensity = 1\nviscosity = 0.01\n"
                           "[boundary]\nleft = \"no_slip\"\nright = \"no_slip\"\nbottom = \"no_slip\"\ntop = \"no_slip\"\n";
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 2\nsolid_stress = \"upper_convected\"\n")
                .find("time.solid_picard_iterations: is not offered with solid_stress = \"upper_convected\""),
            std::string::npos);
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 2\n")
                .find("time.solid_picard_defect: needs solid_stress = \"semi_implicit\""),
            std::string::npos);
  EXPECT_EQ(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 2\nsolid_picard_defect = false\n"), "");
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_theta = 1.5\n").find("time.solid_picard_theta"), std::string::npos);
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_force = \"trapezoidal\"\nsolid_stress = \"semi_implicit\"\n")
                .find("time.solid_picard_force: \"trapezoidal\" needs solid_picard_iterations > 0"),
            std::string::npos);
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 2\nsolid_picard_defect = false\n"
                               "solid_picard_force = \"trapezoidal\"\n")
                .find("time.solid_picard_force"),
            std::string::npos);
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_force = \"midpoint\"\n").find("time.solid_picard_force"),
            std::string::npos);
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_iterations = 1\nsolid_picard_defect = false\n"
                               "solid_picard_anderson = 2\n")
                .find("time.solid_picard_anderson: needs solid_picard_iterations >= 2"),
            std::string::npos);
  EXPECT_NE(scene_error(base + "[time]\nend = 1\nsolid_picard_tol = 1\n").find("time.solid_picard_tol"), std::string::npos);
}
