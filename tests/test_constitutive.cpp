// Constitutive models of kernels/constitutive.hpp against closed forms for a uniform simple
// shear xi = (x - g y, y), i.e. F = [[1, g], [0, 1]], b = [[1 + g^2, g], [g, 1]], det b = 1,
// I1 - 3 = g^2 (plane strain). Central differences of an affine xi are exact, so the kernels
// must reproduce the closed forms to round-off:
//   neo-Hookean           sigma_xy = 2 mu_s g,             sigma_xx - sigma_yy = 2 mu_s g^2
//   strain-stiffening     sigma_xy = 2 (c1 + 2 c3 g^2) g,  sigma_xx - sigma_yy = 2 (c1 + 2 c3 g^2) g^2
//   energy (isochoric invariant tr b / sqrt(det b) - 2 = g^2):  W = c1 g^2 + c3 g^4
// and the time-step modulus of the stiffening law grows with g as its tangent modulus does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "kernels/constitutive.hpp"
#include "kernels/solid_stress.hpp"
#include "core/field.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/solid.hpp"
#include "tests/fixtures/scene_text.hpp"

using namespace refmap;

namespace {

constexpr double kC1 = 0.7, kC3 = 1.3;

/// Closed-form simple-shear values of the law W = c1 (I1 - 3) + c3 (I1 - 3)^2.
struct Shear {
  double c1, c3, g;
  double w1() const { return c1 + 2 * c3 * g * g; }
  double sxy() const { return 2 * w1() * g; }
  double n1() const { return 2 * w1() * g * g; }  // sigma_xx - sigma_yy
  double energy() const { return c1 * g * g + c3 * g * g * g * g; }
  Sym2 b() const { return {1 + g * g, g, 1}; }
};

/// Affine simple-shear window: xi = (x - g y, y) on ni x nj cells (ghosts too), phi = -1.
struct ShearWindow {
  static constexpr int ni = 11, nj = 9;
  double dx = 0.05;
  Field xi_x{ni, nj}, xi_y{ni, nj}, phi{ni, nj, 2, -1.0}, sxx{ni, nj}, sxy{ni, nj}, syy{ni, nj};
  explicit ShearWindow(double g) {
    for (int j = -2; j < nj + 2; ++j)
      for (int i = -2; i < ni + 2; ++i) {
        const double x = 0.2 + (i + 0.5) * dx, y = -0.3 + (j + 0.5) * dx;
        xi_x(i, j) = x - g * y;
        xi_y(i, j) = y;
      }
  }
  template <class M>
  void stress(const M& m) {
    cell_stress(m, xi_x.view(), xi_y.view(), phi.view(), ni, nj, dx, 0.5, sxx.view(), sxy.view(),
                syy.view());
  }
};

template <class M>
void expect_cell_stress(const M& m, const Shear& c) {
  ShearWindow w(c.g);
  w.stress(m);
  const double tol = 1e-12 * (1 + c.sxy() + c.n1());
  for (int j = 0; j < w.nj; ++j)
    for (int i = 0; i < w.ni; ++i) {
      EXPECT_NEAR(w.sxy(i, j), c.sxy(), tol) << "g = " << c.g;
      EXPECT_NEAR(w.sxx(i, j) - w.syy(i, j), c.n1(), tol) << "g = " << c.g;
    }
  // the face form evaluates the same law on faces (compact normal + averaged tangential
  // differences, also exact for an affine xi)
  double fxx = 0, fxy = 0, fyx = 0, fyy = 0;
  detail::x_face_flux(m, w.xi_x.view(), w.xi_y.view(), 4, 4, 1.0 / w.dx, fxx, fxy);
  detail::y_face_flux(m, w.xi_x.view(), w.xi_y.view(), 4, 4, 1.0 / w.dx, fyx, fyy);
  EXPECT_NEAR(fxy, c.sxy(), tol);
  EXPECT_NEAR(fyx, c.sxy(), tol);
  EXPECT_NEAR(fxx - fyy, c.n1(), tol);
}

}  // namespace

TEST(Constitutive, SimpleShearStressNeoHookean) {
  for (double g : {0.1, 0.5, 1.0, 2.0}) expect_cell_stress(NeoHookean(kC1), Shear{kC1, 0.0, g});
}

TEST(Constitutive, SimpleShearStressStrainStiffening) {
  for (double g : {0.1, 0.5, 1.0, 2.0}) expect_cell_stress(StrainStiffening(kC1, kC3), Shear{kC1, kC3, g});
  // c3 = 0 is the neo-Hookean solid
  ShearWindow a(0.8), b(0.8);
  a.stress(StrainStiffening(kC1, 0.0));
  b.stress(NeoHookean(kC1));
  EXPECT_NEAR(a.sxx(3, 3), b.sxx(3, 3), 1e-14);
  EXPECT_NEAR(a.sxy(3, 3), b.sxy(3, 3), 1e-14);
  EXPECT_NEAR(a.syy(3, 3), b.syy(3, 3), 1e-14);
}

TEST(Constitutive, StrainInvertsStress) {
  // the energy and the time step read b back from the stored stress
  // (the last one has tr b < 2: a volume-drifted state, where W1 is held at c1)
  const Sym2 bs[] = {{1.0, 0.0, 1.0}, {2.25, 1.5, 1.0}, {0.8, -0.3, 1.4}, {4.0, 0.0, 0.25}, {0.9, 0.1, 0.95}};
  for (const Sym2& b : bs) {
    for (const Sym2 r : {NeoHookean(kC1).strain(NeoHookean(kC1).stress(b)),
                         StrainStiffening(kC1, kC3).strain(StrainStiffening(kC1, kC3).stress(b))}) {
      EXPECT_NEAR(r.xx, b.xx, 1e-13);
      EXPECT_NEAR(r.xy, b.xy, 1e-13);
      EXPECT_NEAR(r.yy, b.yy, 1e-13);
    }
  }
}

TEST(Constitutive, StiffeningNeverSoftensBelowC1) {
  // tr b < 2 (det b < 1 of a volume-drifted discrete map): the unclamped W1 = c1 + 2 c3
  // (tr b - 2) would be negative here (tr b - 2 = -0.4 < -c1 / (2 c3) = -0.27); the law
  // keeps the neo-Hookean stress instead
  const Sym2 b{0.8, 0.05, 0.8};
  const Sym2 s = StrainStiffening(kC1, kC3).stress(b), n = NeoHookean(kC1).stress(b);
  EXPECT_DOUBLE_EQ(s.xx, n.xx);
  EXPECT_DOUBLE_EQ(s.xy, n.xy);
  EXPECT_DOUBLE_EQ(s.yy, n.yy);
  EXPECT_GT(StrainStiffening(kC1, kC3).wave_modulus(b), 0.0);
}

TEST(Constitutive, EnergyDensityOfSimpleShear) {
  // blend_stress with (1 - H) = 1 everywhere returns W(g) times the window area; W uses the
  // isochoric invariant tr b / sqrt(det b) - 2, here equal to I1 - 3 = g^2 (det b = 1)
  for (double g : {0.1, 0.5, 1.0, 2.0}) {
    for (double c3 : {0.0, kC3}) {
      const Shear c{kC1, c3, g};
      ShearWindow w(g);
      Field gxx(w.ni, w.nj), gxy(w.ni, w.nj), gyy(w.ni, w.nj);
      auto total = [&](const auto& m) {
        w.stress(m);
        return blend_stress(m, w.sxx.view(), w.sxy.view(), w.syy.view(), w.phi.view(), w.ni, w.nj,
                            w.dx, 0.5, gxx.view(), gxy.view(), gyy.view(), 0, 0);
      };
      const double area = w.ni * w.nj * w.dx * w.dx;
      EXPECT_NEAR(total(StrainStiffening(kC1, c3)) / area, c.energy(), 1e-12 * c.energy()) << g;
      if (c3 == 0.0) {
        EXPECT_NEAR(total(NeoHookean(kC1)) / area, c.energy(), 1e-12 * c.energy()) << g;
      }
    }
  }
}

TEST(Constitutive, WaveModulusOfSimpleShear) {
  const NeoHookean nh(kC1);
  const StrainStiffening ss(kC1, kC3), ss0(kC1, 0.0);
  // at rest both give the paper's G = 2 mu_s
  EXPECT_DOUBLE_EQ(nh.wave_modulus({1, 0, 1}), 2 * kC1);
  EXPECT_DOUBLE_EQ(ss.wave_modulus({1, 0, 1}), 2 * kC1);
  double prev = 0.0;
  for (double g : {0.0, 0.25, 0.5, 1.0, 2.0, 4.0}) {
    const Shear c{kC1, kC3, g};
    const Sym2 b = c.b();
    const double l2 = 1 + g * g / 2 + g * std::sqrt(1 + g * g / 4);  // lambda_max(b)
    // neo-Hookean: 2 mu_s lambda_max(b); the stiffening law with c3 = 0 agrees
    EXPECT_NEAR(nh.wave_modulus(b), 2 * kC1 * l2, 1e-12 * 2 * kC1 * l2);
    EXPECT_NEAR(ss0.wave_modulus(b), nh.wave_modulus(b), 1e-12 * nh.wave_modulus(b));
    // stiffening law: closed form of the bound max(a, (a + beta)/2) with W1 = c1 + 2 c3 g^2,
    // a = 2 W1 lambda_max, beta = W1 tr b + 4 c3 (tr b^2 - 4 det b) = W1 (2 + g^2) + 4 c3 g^2 (4 + g^2)
    const double a = 2 * c.w1() * l2, beta = c.w1() * (2 + g * g) + 4 * kC3 * g * g * (4 + g * g);
    const double gt = std::max(a, 0.5 * (a + beta));
    EXPECT_NEAR(ss.wave_modulus(b), gt, 1e-12 * gt) << g;
    // it bounds rho c^2 of every in-plane shear wave (Ogden's incremental moduli of W(I1))
    const double l1 = l2, l2b = 1.0 / l2, W11 = 2 * kC3;  // principal stretches squared
    const double A1 = 2 * c.w1() * l1, A2 = 2 * c.w1() * l2b;
    const double B = c.w1() * (l1 + l2b) + 2 * W11 * (l1 - l2b) * (l1 - l2b);
    double fmax = 0.0;
    for (int k = 0; k <= 180; ++k) {
      const double th = M_PI * k / 360.0, co = std::cos(th), si = std::sin(th);
      fmax = std::max(fmax, A1 * co * co * co * co + 2 * B * co * co * si * si + A2 * si * si * si * si);
    }
    EXPECT_GE(ss.wave_modulus(b), fmax * (1 - 1e-12)) << g;
    // it grows with the strain, at least as fast as the secant factor W1 / c1 times the
    // neo-Hookean value
    EXPECT_GE(ss.wave_modulus(b), nh.wave_modulus(b) * c.w1() / kC1 * (1 - 1e-12)) << g;
    EXPECT_GT(ss.wave_modulus(b), prev);
    prev = ss.wave_modulus(b);
    // the kernel reads it back from the stored stress of the sheared window
    ShearWindow w(g);
    w.stress(ss);
    EXPECT_NEAR(max_wave_modulus(ss, w.sxx.view(), w.sxy.view(), w.syy.view(), w.phi.view(), w.ni,
                                 w.nj, 0.5),
                gt, 1e-12 * gt)
        << g;
  }
}

namespace {

const std::string kDiscScene = refmap::testing::box_scene(
    32, refmap::testing::kWalls,
    refmap::testing::disc_toml("soft", 0.28, 0.5, 0.15, 0.7) +
        refmap::testing::disc_toml("stiffening", 0.72, 0.5, 0.15, 0.7, "model = \"strain_stiffening\"\nc3 = 1.3\n"));

}  // namespace

TEST(Constitutive, SceneKeySelectsStrainStiffening) {
  const Config cfg = load_scene_string(kDiscScene, "disc.toml");
  ASSERT_EQ(cfg.solids.size(), 2u);
  EXPECT_EQ(cfg.solids[0].model, ConstitutiveLaw::NeoHookean);
  EXPECT_EQ(cfg.solids[1].model, ConstitutiveLaw::StrainStiffening);
  EXPECT_EQ(cfg.solids[1].c3, 1.3);
  // a solid sheared uniformly (xi = (x - g y, y)): the stiffening disc's stress is the
  // neo-Hookean one times W1 / c1 = 1 + 2 c3 g^2 / c1, and its time step is shorter
  const double g = 0.4;
  double sxy[2], dt[2];
  for (int k = 0; k < 2; ++k) {
    Solid s(cfg.solids[std::size_t(k)], cfg.solid_opt, cfg.grid, Sides::walls_or_periodic(false, false));
    for (int j = -Grid::ng; j < s.nj() + Grid::ng; ++j)
      for (int i = -Grid::ng; i < s.ni() + Grid::ng; ++i) {
        const double y = cfg.grid.yc(s.j0() + j);
        s.xi_x_mut()(i, j) = cfg.grid.xc(s.i0() + i) - g * y;
        s.xi_y_mut()(i, j) = y;
      }
    const Grid& gr = cfg.grid;
    Field gxx(gr.nx, gr.ny), gxy(gr.nx, gr.ny), gyy(gr.nx, gr.ny), fx(gr.nx, gr.ny), fy(gr.nx, gr.ny);
    const double e = s.add_stress(gxx, gxy, gyy, fx, fy);
    EXPECT_GT(e, 0.0);
    const SolidSpec& sp = cfg.solids[std::size_t(k)];  // the cell at the disc centre
    const int ci = int((sp.shape.cx - gr.x0) / gr.dx) - s.i0(), cj = int((sp.shape.cy - gr.y0) / gr.dx) - s.j0();
    sxy[k] = s.stress_xy()(ci, cj);
    dt[k] = s.min_dt();
  }
  EXPECT_NEAR(sxy[0], 2 * 0.7 * g, 1e-12);
  EXPECT_NEAR(sxy[1] / sxy[0], 1 + 2 * 1.3 * g * g / 0.7, 1e-12);
  EXPECT_LT(dt[1], dt[0]);
}

TEST(Constitutive, SceneKeyErrors) {
  const std::string base = kDiscScene;
  auto fails = [&](const std::string& text) {
    try {
      load_scene_string(text, "disc.toml");
    } catch (const SceneError&) {
      return true;
    }
    return false;
  };
  auto without = [&](std::string s, const std::string& what) { return s.replace(s.find(what), what.size(), ""); };
  EXPECT_TRUE(fails(without(base, "c3 = 1.3\n")));                       // c3 required
  EXPECT_TRUE(fails(without(base, "model = \"strain_stiffening\"\n")));  // c3 without the model
  std::string neg = base;
  neg.replace(neg.find("c3 = 1.3"), 8, "c3 = -1.0");
  EXPECT_TRUE(fails(neg));
  std::string bad = base;
  bad.replace(bad.find("strain_stiffening"), 17, "mooney");
  EXPECT_TRUE(fails(bad));
}
