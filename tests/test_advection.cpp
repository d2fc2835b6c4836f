// The advection kernel (kernels/advection.hpp): the division-free Superbee face value against
// the limiter's textbook definition, and the flux-form right-hand side against exact
// derivatives where the schemes must be exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "kernels/advection.hpp"
#include "core/field.hpp"

using namespace refmap;

namespace {

// q_f = qu + 0.5 psi(r) (qd - qu), r = (qu - quu) / (qd - qu),
// psi(r) = max(0, min(2r, 1), min(r, 2)) (Roe 1986); qu when qd = qu.
double superbee_reference(double quu, double qu, double qd) {
  const double d = qd - qu;
  if (d == 0.0) return qu;
  const double r = (qu - quu) / d;
  const double psi = std::max({0.0, std::min(2.0 * r, 1.0), std::min(r, 2.0)});
  return qu + 0.5 * psi * d;
}

}  // namespace

TEST(Advection, SuperbeeFaceMatchesLimiterDefinition) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double a = U(rng), b = U(rng);
    // mix in equal neighbours and exact ratios 1/2, 1, 2 (the limiter's kinks)
    double c = U(rng);
    if (k % 7 == 0) c = b;
    if (k % 11 == 0) c = b + 2.0 * (b - a);
    if (k % 13 == 0) c = b + (b - a);
    if (k % 17 == 0) c = b + 0.5 * (b - a);
    const double f = superbee_face(a, b, c), g = superbee_reference(a, b, c);
    worst = std::max(worst, std::abs(f - g));
    // TVD: the face value lies between the upwind and downwind cell values
    ASSERT_GE(f, std::min(b, c) - 1e-15);
    ASSERT_LE(f, std::max(b, c) + 1e-15);
  }
  // the two forms differ only by the rounding of (du / d) * d against du: a few ulps of
  // values of size <= 2 (ulp 4.4e-16)
  EXPECT_LT(worst, 2e-15);
  EXPECT_EQ(superbee_face(0.3, 0.7, 0.7), 0.7);          // flat downwind: upwind value
  EXPECT_NEAR(superbee_face(0.9, 0.7, 0.5), 0.6, 1e-15); // smooth monotone, r = 1: central
  EXPECT_EQ(superbee_face(0.5, 0.7, 0.3), 0.7);          // local extremum: first-order upwind
}

// A linear field q = c0 + cx x + cy y advected by a uniform velocity (U, V): the flux
// divergence is -(U cx + V cy) exactly for central fluxes and, where the limiter is at
// r = 1 (every cell of a linear field), for Superbee too.
TEST(Advection, LinearFieldUniformVelocityIsExact) {
  const int nx = 37, ny = 23;  // not powers of two, not square
  const double dx = 0.05, U = 0.8, V = -1.3, cx = 2.0, cy = -0.7;
  Field a(nx, ny), b(nx, ny), uf(nx + 1, ny), vf(nx, ny + 1), ra(nx, ny), rb(nx, ny);
  for (int j = -2; j < ny + 2; ++j)
    for (int i = -2; i < nx + 2; ++i) {
      const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
      a(i, j) = 1.0 + cx * x + cy * y;
      b(i, j) = -3.0 * x + 0.25 * y;
    }
  uf.fill(U);
  vf.fill(V);
  for (FluxScheme s : {FluxScheme::Central, FluxScheme::Superbee}) {
    advect_rhs2(a.view(), b.view(), uf.view(), vf.view(), ra.view(), rb.view(), nx, ny, dx, s);
    double ea = 0.0, eb = 0.0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        ea = std::max(ea, std::abs(ra(i, j) + (U * cx + V * cy)));
        eb = std::max(eb, std::abs(rb(i, j) + (U * -3.0 + V * 0.25)));
      }
    EXPECT_LT(ea, 1e-11) << int(s);
    EXPECT_LT(eb, 1e-11) << int(s);
  }
}

// The momentum flux at a density jump (advect_rhs2_hybrid): with no face flagged it is the
// central scheme, with every face flagged the Superbee one, bit for bit (both evaluate the
// same expressions); flag_density_jump_faces flags exactly the faces whose 4-cell stencil
// straddles a density step (two faces each side of it, in either of the two fields).
TEST(Advection, HybridFluxIsCentralOrSuperbeePerFace) {
  const int nx = 19, ny = 13;
  const double dx = 0.1;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Field a(nx, ny), b(nx, ny), uf(nx + 1, ny), vf(nx, ny + 1), ra(nx, ny), rb(nx, ny), ha(nx, ny), hb(nx, ny);
  Field lx(nx + 1, ny), ly(nx, ny + 1);
  for (int j = -2; j < ny + 2; ++j)
    for (int i = -2; i < nx + 2; ++i) {
      a(i, j) = U(rng);
      b(i, j) = U(rng);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i) uf(i, j) = U(rng);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) vf(i, j) = U(rng);
  for (double flag : {0.0, 1.0}) {
    lx.fill(flag);
    ly.fill(flag);
    const FluxScheme s = flag != 0.0 ? FluxScheme::Superbee : FluxScheme::Central;
    advect_rhs2(a.view(), b.view(), uf.view(), vf.view(), ra.view(), rb.view(), nx, ny, dx, s);
    advect_rhs2_hybrid(a.view(), b.view(), uf.view(), vf.view(), lx.view(), ly.view(), ha.view(), hb.view(), nx,
                       ny, dx);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        ASSERT_EQ(ha(i, j), ra(i, j)) << flag << " " << i << " " << j;
        ASSERT_EQ(hb(i, j), rb(i, j)) << flag << " " << i << " " << j;
      }
  }
  // a density step between columns 8 and 9 (at time 0) and a uniform field (time 1)
  Field r0(nx, ny), r1(nx, ny);
  r1.fill(1.0);
  for (int j = -2; j < ny + 2; ++j)
    for (int i = -2; i < nx + 2; ++i) r0(i, j) = i <= 8 ? 100.0 : 1.0;
  flag_density_jump_faces(r0.view(), r1.view(), lx.view(), ly.view(), nx, ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i)  // x-face i sees cells i-2 .. i+1: the step is inside for i = 8, 9, 10
      EXPECT_EQ(lx(i, j), i >= 8 && i <= 10 ? 1.0 : 0.0) << i;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) EXPECT_EQ(ly(i, j), 0.0);  // y-stencils are one column: uniform
}

// The reference-map advection (kernels/reference_map.hpp, eq. 3.3) with central, Superbee,
// van Leer and minmod face values: all exact for an affine xi under a non-uniform but divergence-free
// face velocity (rigid rotation sampled on the faces); on an odd-even perturbation of xi the
// central form has no effect (its increments cancel), while the limited ones remove variance:
// sum_i delta_i k_i < 0, i.e. d/dt of sum delta^2 is negative at first order.
#include "kernels/reference_map.hpp"

TEST(ReferenceMapAdvection, AffineExactAndLimitedFluxesDampOddEvenMode) {
  const int n = 24;
  const double dx = 1.0 / n, om = 0.7, xc = 0.5, yc = 0.5;
  Field xi_x(n, n), xi_y(n, n), phi(n, n), uf(n + 1, n), vf(n, n + 1), kx(n, n), ky(n, n);
  phi.fill(-1.0);  // everything inside the solid
  for (int j = 0; j < n; ++j)
    for (int i = 0; i <= n; ++i) uf(i, j) = -om * ((j + 0.5) * dx - yc);  // x-faces at x = i dx
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i < n; ++i) vf(i, j) = om * ((i + 0.5) * dx - xc);
  auto affine = [&](int i, int j, double& a, double& b) {
    const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
    a = 0.3 + 1.2 * x - 0.4 * y;
    b = -0.1 + 0.5 * x + 0.9 * y;
  };
  for (XiFlux fl : {XiFlux::Central, XiFlux::Superbee, XiFlux::VanLeer, XiFlux::Minmod}) {
    const bool sb = fl != XiFlux::Central;
    const char* name = fl == XiFlux::Central    ? "central"
                       : fl == XiFlux::Superbee ? "superbee"
                       : fl == XiFlux::VanLeer  ? "van Leer"
                                                : "minmod";
    for (int j = -2; j < n + 2; ++j)
      for (int i = -2; i < n + 2; ++i) affine(i, j, xi_x(i, j), xi_y(i, j));
    reference_map_rhs(xi_x.view(), xi_y.view(), phi.view(), uf.view(), vf.view(), n, n, 0, 0, dx,
                      kx.view(), ky.view(), fl);
    double err = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
        const double u = -om * (y - yc), v = om * (x - xc);
        err = std::max(err, std::abs(kx(i, j) + (1.2 * u - 0.4 * v)));
        err = std::max(err, std::abs(ky(i, j) + (0.5 * u + 0.9 * v)));
      }
    EXPECT_LT(err, 1e-12) << name;
    // odd-even perturbation on the affine field
    const double eps = 1e-3;
    for (int j = -2; j < n + 2; ++j)
      for (int i = -2; i < n + 2; ++i) {
        affine(i, j, xi_x(i, j), xi_y(i, j));
        xi_x(i, j) += eps * (((i + j) % 2 == 0) ? 1.0 : -1.0);
      }
    reference_map_rhs(xi_x.view(), xi_y.view(), phi.view(), uf.view(), vf.view(), n, n, 0, 0, dx,
                      kx.view(), ky.view(), fl);
    // production of the perturbation's variance, interior cells (away from the ghosts)
    double prod = 0.0, scale = 0.0;
    for (int j = 2; j < n - 2; ++j)
      for (int i = 2; i < n - 2; ++i) {
        double a, b;
        affine(i, j, a, b);
        const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
        const double k_aff = -(1.2 * (-om * (y - yc)) - 0.4 * (om * (x - xc)));
        const double delta = xi_x(i, j) - a;
        prod += delta * (kx(i, j) - k_aff);
        scale += delta * delta * (std::abs(uf(i, j)) + std::abs(vf(i, j))) / dx;
      }
    std::printf("[xi advection %s] odd-even variance production %.3e (scale %.3e)\n",
                name, prod, scale);
    if (sb) {
      EXPECT_LT(prod, -0.1 * scale);  // a first-order upwind damping rate at least
    } else {
      EXPECT_LT(std::abs(prod), 1e-9 * scale);  // central: no damping at all
    }
  }
}

// XiVelocity::Cell (kernels/reference_map.hpp): xi carried by the cell-centred velocity. Exact
// for an affine xi under a rigid rotation sampled at the cells, like the face form above; and
// the velocity's odd-even mode along its own direction, u_P = eps (-1)^i, strains xi = x at
// exactly the rate -u_P, where the face velocities of the projection's predictor,
// u_f = (u_W + u_P) / 2 (eq. 5.3 without the pressure), are zero and leave xi unchanged: the
// mode the solid stress cannot restore when xi follows the faces.
TEST(ReferenceMapAdvection, CellVelocityExactForAffineAndSeesTheOddEvenVelocity) {
  const int n = 24;
  const double dx = 1.0 / n, om = 0.7, xc = 0.5, yc = 0.5;
  Field xi_x(n, n), xi_y(n, n), phi(n, n), u(n, n), v(n, n), uf(n + 1, n), vf(n, n + 1), kx(n, n), ky(n, n);
  phi.fill(-1.0);  // everything inside the solid
  for (int j = -2; j < n + 2; ++j)
    for (int i = -2; i < n + 2; ++i) {
      u(i, j) = -om * ((j + 0.5) * dx - yc);
      v(i, j) = om * ((i + 0.5) * dx - xc);
    }
  auto affine = [&](int i, int j, double& a, double& b) {
    const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
    a = 0.3 + 1.2 * x - 0.4 * y;
    b = -0.1 + 0.5 * x + 0.9 * y;
  };
  for (XiFlux fl : {XiFlux::Central, XiFlux::Superbee, XiFlux::VanLeer, XiFlux::Minmod}) {
    for (int j = -2; j < n + 2; ++j)
      for (int i = -2; i < n + 2; ++i) affine(i, j, xi_x(i, j), xi_y(i, j));
    reference_map_rhs_cell(xi_x.view(), xi_y.view(), phi.view(), u.view(), v.view(), n, n, 0, 0, dx, kx.view(),
                           ky.view(), fl);
    double err = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        err = std::max(err, std::abs(kx(i, j) + (1.2 * u(i, j) - 0.4 * v(i, j))));
        err = std::max(err, std::abs(ky(i, j) + (0.5 * u(i, j) + 0.9 * v(i, j))));
      }
    EXPECT_LT(err, 1e-12) << int(fl);  // round-off of O(1) values
  }
  // the odd-even velocity mode along x on the identity map xi = x
  const double eps = 1e-3;
  for (int j = -2; j < n + 2; ++j)
    for (int i = -2; i < n + 2; ++i) {
      xi_x(i, j) = (i + 0.5) * dx;
      xi_y(i, j) = (j + 0.5) * dx;
      u(i, j) = eps * ((i % 2 + 2) % 2 == 0 ? 1.0 : -1.0);
      v(i, j) = 0.0;
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i <= n; ++i) uf(i, j) = 0.5 * (u(i - 1, j) + u(i, j));  // = 0
  vf.fill(0.0);
  for (XiFlux fl : {XiFlux::Central, XiFlux::Superbee, XiFlux::VanLeer, XiFlux::Minmod}) {
    reference_map_rhs_cell(xi_x.view(), xi_y.view(), phi.view(), u.view(), v.view(), n, n, 0, 0, dx, kx.view(),
                           ky.view(), fl);
    double err = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) err = std::max({err, std::abs(kx(i, j) + u(i, j)), std::abs(ky(i, j))});
    EXPECT_LT(err, 1e-15) << int(fl);  // d xi_x / dt = -u_P, round-off of eps-sized values
    reference_map_rhs(xi_x.view(), xi_y.view(), phi.view(), uf.view(), vf.view(), n, n, 0, 0, dx, kx.view(),
                      ky.view(), fl);
    double face = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) face = std::max({face, std::abs(kx(i, j)), std::abs(ky(i, j))});
    EXPECT_EQ(face, 0.0) << int(fl);  // the face velocities carry none of the mode
  }
}
