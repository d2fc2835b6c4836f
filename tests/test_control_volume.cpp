// The control-volume sums of kernels/control_volume.hpp on fields where the discrete sums
// are exact (the face values are means of two cells and the tangential derivatives central
// differences, exact for linear fields; the surface and volume sums are midpoint rules,
// exact for linear integrands), so each check is to round-off:
//  - a linear pressure p = a x + b y: force -A (a, b), torque -A ((xc - xr) b - (yc - yr) a);
//  - a simple shear u = g y with a constant viscosity: a divergence-free symmetric stress,
//    no force and no torque (its traction is mu g on every face);
//  - a rigid rotation u = Omega x (x - c) of density rho: no viscous stress, and the
//    momentum flux gives -oint rho u (u . n) = -int rho (u . grad) u = rho Omega^2 int (x - c);
//  - the volume sums of a uniform flow with a fluid fraction.
// The forces of the solver's bodies from these sums are checked against the forcing's
// (Cylinder.*) and against analytic values (Bodies.*) in test_cylinder.cpp, test_bodies.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "core/field.hpp"
#include "kernels/control_volume.hpp"

using namespace refmap;

namespace {

constexpr int kN = 16;
constexpr double kDx = 0.1, kX0 = -0.3, kY0 = 0.2;

struct Fields {
  Field u{kN, kN}, v{kN, kN}, p{kN, kN}, mu{kN, kN}, rho{kN, kN}, uf{kN + 1, kN}, vf{kN, kN + 1};
  template <class F>
  void set(F f) {  // f(x, y, u, v, p) at cell centres (ghosts too) and faces
    double a, b, c;
    for (int j = -2; j < kN + 2; ++j)
      for (int i = -2; i < kN + 2; ++i) f(kX0 + (i + 0.5) * kDx, kY0 + (j + 0.5) * kDx, u(i, j), v(i, j), p(i, j));
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i <= kN; ++i) f(kX0 + i * kDx, kY0 + (j + 0.5) * kDx, uf(i, j), b, c);
    for (int j = 0; j <= kN; ++j)
      for (int i = 0; i < kN; ++i) f(kX0 + (i + 0.5) * kDx, kY0 + j * kDx, a, vf(i, j), c);
  }
  SurfaceFields view() const { return {u.cview(), v.cview(), p.cview(), mu.cview(), rho.cview(), uf.cview(), vf.cview(), {}, {}, {}}; }
};

BoxFrame frame(double xr, double yr) {
  BoxFrame fr;
  fr.dx = kDx;
  fr.x0 = kX0;
  fr.y0 = kY0;
  fr.nx = fr.ny = kN;
  fr.xr = xr;
  fr.yr = yr;
  return fr;
}

const ControlBox kBox{3, 5, 11, 14};  // 8 x 9 cells
constexpr double kArea = 8 * 9 * kDx * kDx;
const double kXc = kX0 + 7 * kDx, kYc = kY0 + 9.5 * kDx;  // its centre

}  // namespace

TEST(ControlVolume, LinearPressureGivesMinusAreaTimesGradient) {
  Fields f;
  const double a = 2.0, b = -3.0;
  f.set([&](double x, double y, double& u, double& v, double& p) { u = v = 0.0; p = a * x + b * y; });
  f.mu.fill(0.7);
  f.rho.fill(1.3);
  const double xr = 0.1, yr = 0.4;
  const auto F = box_surface_force(f.view(), kBox, frame(xr, yr));
  EXPECT_NEAR(F[0], -kArea * a, 1e-12);
  EXPECT_NEAR(F[1], -kArea * b, 1e-12);
  EXPECT_NEAR(F[2], -kArea * ((kXc - xr) * b - (kYc - yr) * a), 1e-12);
}

TEST(ControlVolume, SimpleShearHasNoForceNorTorque) {
  Fields f;
  const double g = 1.7, mu = 0.3;
  f.set([&](double, double y, double& u, double& v, double& p) { u = g * y; v = 0.0; p = 0.0; });
  f.mu.fill(mu);
  f.rho.fill(0.0);  // no momentum flux: the viscous traction alone
  const auto F = box_surface_force(f.view(), kBox, frame(0.05, 0.3));
  EXPECT_NEAR(F[0], 0.0, 1e-12);
  EXPECT_NEAR(F[1], 0.0, 1e-12);
  EXPECT_NEAR(F[2], 0.0, 1e-12);
}

TEST(ControlVolume, RigidRotationMomentumFlux) {
  Fields f;
  const double Om = 1.5, cx = 0.2, cy = 0.7, rho = 2.0;
  f.set([&](double x, double y, double& u, double& v, double& p) {
    u = -Om * (y - cy);
    v = Om * (x - cx);
    p = 0.0;
  });
  f.mu.fill(0.9);  // grad u + grad u^T = 0: no viscous force whatever mu
  f.rho.fill(rho);
  const auto F = box_surface_force(f.view(), kBox, frame(cx, cy));
  EXPECT_NEAR(F[0], rho * Om * Om * kArea * (kXc - cx), 1e-12);
  EXPECT_NEAR(F[1], rho * Om * Om * kArea * (kYc - cy), 1e-12);
  // r x (rho Omega^2 r) = 0 pointwise: the flux of angular momentum about the axis vanishes
  EXPECT_NEAR(F[2], 0.0, 1e-12);
}

TEST(ControlVolume, MomentumOfTheFluidFraction) {
  Field u(kN, kN, 2, 0.5), v(kN, kN, 2, -0.25), w(kN, kN, 2, 1.0);
  for (int j = kBox.j0; j < kBox.j1; ++j) w(kBox.i0, j) = 0.25;  // a column three quarters solid
  w(kBox.i0 + 1, kBox.j0) = 1.5;                                  // clamped to 1
  const double rho = 3.0, da = kDx * kDx;
  const auto s = box_momentum(u.cview(), v.cview(), w.cview(), rho, kBox, frame(kXc, kYc));
  const double solid = 9 * 0.75 * da, fluid = kArea - solid;
  EXPECT_NEAR(s[0], rho * 0.5 * fluid, 1e-12);
  EXPECT_NEAR(s[1], -rho * 0.25 * fluid, 1e-12);
  EXPECT_NEAR(s[3], solid, 1e-12);
  const double rx = kX0 + (kBox.i0 + 0.5) * kDx - kXc;  // the solid column's offset; centred in y
  EXPECT_NEAR(s[4], solid * rx, 1e-12);
  EXPECT_NEAR(s[5], 0.0, 1e-12);
  // angular momentum of the uniform flow about the centre: minus that of the missing column
  EXPECT_NEAR(s[2], -rho * 0.75 * 9 * da * (rx * -0.25), 1e-12);
}
