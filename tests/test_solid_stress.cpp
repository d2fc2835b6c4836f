// Neo-Hookean stress of eq. (2.9) for homogeneous deformations, where central
// differences of an affine reference map are exact: the kernel must reproduce the closed
// form sigma_s = 2 mu_s (b - I), b = F F^T, to round-off inside the solid.
//   simple shear     F = [[1, g], [0, 1]]: b - I = [[g^2, g], [g, 0]]
//   equibiaxial      F = diag(l, 1/l) (det F = 1): b - I = diag(l^2 - 1, l^-2 - 1)
// Also the smoothed Heaviside of eq. (3.5) at its defining points.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/solid_stress.hpp"
#include "core/field.hpp"

using namespace refmap;

namespace {

struct Stress { double xx, xy, yy; };

// xi = F^{-1} x on a 12 x 10 window, every cell inside (phi = -1)
Stress stress_of(double f11, double f12, double f21, double f22, double mu_s, double dx = 0.03) {
  const int ni = 12, nj = 10;
  Field xi_x(ni, nj), xi_y(ni, nj), phi(ni, nj, 2, -1.0), sxx(ni, nj), sxy(ni, nj), syy(ni, nj);
  const double det = f11 * f22 - f12 * f21;
  const double a11 = f22 / det, a12 = -f12 / det, a21 = -f21 / det, a22 = f11 / det;
  for (int j = -2; j < nj + 2; ++j)
    for (int i = -2; i < ni + 2; ++i) {
      const double x = 0.3 + (i + 0.5) * dx, y = -0.1 + (j + 0.5) * dx;
      xi_x(i, j) = a11 * x + a12 * y;
      xi_y(i, j) = a21 * x + a22 * y;
    }
  cell_stress(NeoHookean(mu_s), xi_x.view(), xi_y.view(), phi.view(), ni, nj, dx, 0.5,
              sxx.view(), sxy.view(), syy.view());
  // every cell must agree; return the worst deviation from cell (0,0) folded into the value
  Stress s{sxx(0, 0), sxy(0, 0), syy(0, 0)};
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      EXPECT_NEAR(sxx(i, j), s.xx, 1e-12 * (1 + std::abs(s.xx)));
      EXPECT_NEAR(sxy(i, j), s.xy, 1e-12 * (1 + std::abs(s.xy)));
      EXPECT_NEAR(syy(i, j), s.yy, 1e-12 * (1 + std::abs(s.yy)));
    }
  return s;
}

}  // namespace

TEST(SolidStress, SimpleShearMatchesClosedForm) {
  const double mu = 2.5;
  for (double g : {0.1, 0.43, 1.0, 2.5}) {
    Stress s = stress_of(1.0, g, 0.0, 1.0, mu);
    EXPECT_NEAR(s.xy, 2 * mu * g, 1e-12 * 2 * mu * (1 + g));        // shear stress G gamma
    EXPECT_NEAR(s.xx, 2 * mu * g * g, 1e-12 * 2 * mu * (1 + g * g)); // normal-stress difference
    EXPECT_NEAR(s.yy, 0.0, 1e-12 * 2 * mu);
  }
}

TEST(SolidStress, EquibiaxialStretchMatchesClosedForm) {
  const double mu = 100.0;
  for (double l : {0.5, 0.9, 1.0, 1.3, 2.0}) {
    Stress s = stress_of(l, 0.0, 0.0, 1.0 / l, mu);
    EXPECT_NEAR(s.xx, 2 * mu * (l * l - 1), 1e-12 * 2 * mu * l * l);
    EXPECT_NEAR(s.yy, 2 * mu * (1 / (l * l) - 1), 1e-12 * 2 * mu / (l * l));
    EXPECT_NEAR(s.xy, 0.0, 1e-12 * 2 * mu);
  }
}

TEST(SolidStress, RotationIsStressFree) {
  const double th = 0.7;  // a rigid rotation: b = I
  Stress s = stress_of(std::cos(th), -std::sin(th), std::sin(th), std::cos(th), 10.0);
  EXPECT_NEAR(s.xx, 0.0, 1e-12);
  EXPECT_NEAR(s.xy, 0.0, 1e-12);
  EXPECT_NEAR(s.yy, 0.0, 1e-12);
}

TEST(SolidStress, SmoothedHeavisideEq35) {
  const double w = 3.0;
  EXPECT_EQ(smoothed_heaviside(-w, w), 0.0);
  EXPECT_EQ(smoothed_heaviside(w, w), 1.0);
  EXPECT_DOUBLE_EQ(smoothed_heaviside(0.0, w), 0.5);
  EXPECT_NEAR(smoothed_heaviside(1.5, w), 0.5 * (1 + 0.5 + 1 / M_PI), 1e-15);
  // symmetric: H(x) + H(-x) = 1
  for (double x : {0.3, 1.1, 2.9}) EXPECT_NEAR(smoothed_heaviside(x, w) + smoothed_heaviside(-x, w), 1.0, 1e-15);
}
