// The variational solid force (kernels/variational_stress.hpp, docs/implicit.md): it must be
// exactly the negative derivative of the discrete stored energy along the reference map's
// transport, sum_k f_k . v_k dx^2 = -d/de E_h(xi - e A v) at e = 0, with
// E_h = sum_c w_c W'(A_c) dx^2 and W' = mu_s (tr b - 2) + 2 mu_s ln det A (the energy whose
// derivative -A^-T sigma(b) the kernel uses; equal to mu_s (tr b - 2) where det A = 1), for any
// velocity v and any (non-affine) xi: no work without stored energy behind it. And for an
// affine xi (homogeneous strain) the force vanishes in every cell whose stencil sees only
// full weight (the divergence of a constant stress).
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/variational_stress.hpp"
#include "core/field.hpp"

using namespace refmap;

namespace {

constexpr int ni = 24, nj = 22;
constexpr double dx = 0.05, mu_s = 3.0;

/// A disc of radius 8 dx (phi a signed distance) with a smooth non-affine xi.
void setup(Field& xi_x, Field& xi_y, Field& phi, double e, const Field* vx, const Field* vy) {
  for (int j = -2; j < nj + 2; ++j)
    for (int i = -2; i < ni + 2; ++i) {
      const double x = (i - ni / 2 + 0.5) * dx, y = (j - nj / 2 + 0.5) * dx;
      phi(i, j) = std::hypot(x, y) - 8 * dx;
      xi_x(i, j) = x + 0.1 * x * y + 0.05 * std::sin(3 * y);
      xi_y(i, j) = y - 0.08 * x * x + 0.03 * std::cos(2 * x);
    }
  if (!vx) return;
  // xi - e A v with A the central-difference gradient of the unperturbed xi (the transport
  // eq. 3.3 with the cell velocity v), at every cell (ghosts: the kernel never reads them
  // for a disc this far inside)
  Field ax(ni, nj), ay(ni, nj);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const double a = (xi_x(i + 1, j) - xi_x(i - 1, j)) / (2 * dx), b = (xi_x(i, j + 1) - xi_x(i, j - 1)) / (2 * dx);
      const double c = (xi_y(i + 1, j) - xi_y(i - 1, j)) / (2 * dx), d = (xi_y(i, j + 1) - xi_y(i, j - 1)) / (2 * dx);
      ax(i, j) = a * (*vx)(i, j) + b * (*vy)(i, j);
      ay(i, j) = c * (*vx)(i, j) + d * (*vy)(i, j);
    }
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      xi_x(i, j) -= e * ax(i, j);
      xi_y(i, j) -= e * ay(i, j);
    }
}

/// E_h with W' (see the file comment) and the kernel's weight.
double energy(const Field& xi_x, const Field& xi_y, const Field& phi, double wv) {
  double e = 0.0;
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const double ph = phi(i, j) + wv + dx;
      if (!(ph < wv)) continue;
      const double w = 1.0 - smoothed_heaviside(ph, wv);
      const double a = (xi_x(i + 1, j) - xi_x(i - 1, j)) / (2 * dx), b = (xi_x(i, j + 1) - xi_x(i, j - 1)) / (2 * dx);
      const double c = (xi_y(i + 1, j) - xi_y(i - 1, j)) / (2 * dx), d = (xi_y(i, j + 1) - xi_y(i, j - 1)) / (2 * dx);
      const Sym2 b2 = left_cauchy_green(a, b, c, d);
      e += w * (mu_s * (b2.xx + b2.yy - 2.0) + 2.0 * mu_s * std::log(a * d - b * c));
    }
  return e * dx * dx;
}

}  // namespace

TEST(VariationalStress, ForceIsMinusTheEnergyDerivativeAlongTheTransport) {
  const double wv = 1.0 * dx;
  Field xi_x(ni, nj), xi_y(ni, nj), phi(ni, nj), vx(ni, nj), vy(ni, nj);
  Field pxx(ni, nj), pxy(ni, nj), pyx(ni, nj), pyy(ni, nj), fx(ni, nj), fy(ni, nj);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {  // a velocity with grid-scale content
      vx(i, j) = std::sin(0.7 * i + 1.3 * j) + 0.3 * ((i + j) % 2);
      vy(i, j) = std::cos(1.1 * i - 0.4 * j);
    }
  setup(xi_x, xi_y, phi, 0.0, nullptr, nullptr);
  variational_stress_tensor(NeoHookean(mu_s), xi_x.view(), xi_y.view(), phi.view(), ni, nj, dx, wv, wv + dx,
                            pxx.view(), pxy.view(), pyx.view(), pyy.view());
  add_variational_force(xi_x.view(), xi_y.view(), pxx.view(), pxy.view(), pyx.view(), pyy.view(), ni, nj, dx,
                        fx.view(), fy.view(), 0, 0);
  double work = 0.0, outside = 0.0;
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      work += (fx(i, j) * vx(i, j) + fy(i, j) * vy(i, j)) * dx * dx;
      if (phi(i, j) >= 0.0) outside = std::max({outside, std::abs(fx(i, j)), std::abs(fy(i, j))});
    }
  // central difference in e of the energy: O(h^2) with h = 1e-5 relative to the O(1) strain
  const double h = 1e-5;
  Field x1(ni, nj), y1(ni, nj), x2(ni, nj), y2(ni, nj), ph(ni, nj);
  setup(x1, y1, ph, h, &vx, &vy);
  setup(x2, y2, ph, -h, &vx, &vy);
  const double dedt = (energy(x1, y1, ph, wv) - energy(x2, y2, ph, wv)) / (2 * h);
  std::printf("[variational] work %.12g, -dE/de %.12g\n", work, -dedt);
  ASSERT_GT(std::abs(work), 1e-3);  // a real test: the force does work on this velocity
  EXPECT_NEAR(work, -dedt, 1e-5 * std::abs(work));  // finite-difference error (measured 3e-7); a sign or factor error is O(1)
  EXPECT_EQ(outside, 0.0);  // no force where xi is extrapolated (phi >= 0)
}

TEST(VariationalStress, HomogeneousStrainGivesNoForceInside) {
  // xi = F^-1 x, simple shear g = 0.2: constant P, so div_h P = 0 wherever the weight is 1
  // over the stencil (phi + 2 dx + 1 dx < -w_V, i.e. phi < -4 dx here)
  const double wv = 1.0 * dx, g = 0.2;
  Field xi_x(ni, nj), xi_y(ni, nj), phi(ni, nj);
  Field pxx(ni, nj), pxy(ni, nj), pyx(ni, nj), pyy(ni, nj), fx(ni, nj), fy(ni, nj);
  for (int j = -2; j < nj + 2; ++j)
    for (int i = -2; i < ni + 2; ++i) {
      const double x = (i - ni / 2 + 0.5) * dx, y = (j - nj / 2 + 0.5) * dx;
      phi(i, j) = std::hypot(x, y) - 8 * dx;
      xi_x(i, j) = x - g * y;
      xi_y(i, j) = y;
    }
  variational_stress_tensor(NeoHookean(mu_s), xi_x.view(), xi_y.view(), phi.view(), ni, nj, dx, wv, wv + dx,
                            pxx.view(), pxy.view(), pyx.view(), pyy.view());
  add_variational_force(xi_x.view(), xi_y.view(), pxx.view(), pxy.view(), pyx.view(), pyy.view(), ni, nj, dx,
                        fx.view(), fy.view(), 0, 0);
  double inside = 0.0, edge = 0.0;
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const double m = std::max(std::abs(fx(i, j)), std::abs(fy(i, j)));
      if (phi(i, j) < -4 * dx) inside = std::max(inside, m);
      else edge = std::max(edge, m);
    }
  EXPECT_LT(inside, 1e-9 * mu_s / dx);  // round-off of a difference of equal values
  EXPECT_GT(edge, 0.1 * mu_s * g * g / dx);  // the surface traction is where the weight falls
}
