// Actuated solids (kernels/constitutive_actuation.hpp, solver/components/actuation.hpp):
//  - the transform: b_e of grad xi = A^{-1} (the solid already in its actuated shape) is the
//    identity, so the stress vanishes; without actuation the same kernel arithmetic;
//  - a free disc in a quiescent viscous fluid whose stress-free shape is stretched by
//    s = 1.5 along x becomes the ellipse of semi-axes s R and R / s: aspect ratio s^2 = 2.25
//    from the second moments of the solid region, area kept;
//  - bad actuation values are scene errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "kernels/constitutive.hpp"
#include "solver/app/run.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/fixtures/scene_text.hpp"

using namespace refmap;
using namespace refmap::testing;

TEST(Actuation, StressFreeInTheActuatedShape) {
  // a solid stretched by A = [[s, s g], [0, 1/s]] (F = A, grad xi = A^{-1}) is at rest
  const double s = 1.3, g = 0.2;
  const Affine2 a{s, s * g, 0.0, 1.0 / s};
  // A^{-1} = [[1/s, -s g], [0, s]]
  const double gxx = 1.0 / s, gxy = -s * g, gyx = 0.0, gyy = s;
  const Actuated<NeoHookean> m{NeoHookean(1.0), a};
  const Sym2 st = m.stress(elastic_left_cauchy_green(m, gxx, gxy, gyx, gyy));
  EXPECT_NEAR(st.xx, 0.0, 1e-14);
  EXPECT_NEAR(st.xy, 0.0, 1e-14);
  EXPECT_NEAR(st.yy, 0.0, 1e-14);
  // the plain model sees the stretch: sigma_xx - sigma_yy = 2 mu_s (b_xx - b_yy) != 0
  const NeoHookean p(1.0);
  const Sym2 sp = p.stress(elastic_left_cauchy_green(p, gxx, gxy, gyx, gyy));
  const Sym2 b = left_cauchy_green(gxx, gxy, gyx, gyy);
  EXPECT_EQ(sp.xx, p.stress(b).xx);  // the same arithmetic as before actuation existed
  EXPECT_GT(std::abs(sp.xx - sp.yy), 0.1);
}

namespace {

struct Moments { double area, aspect; };

/// Area and aspect ratio sqrt(lambda_max / lambda_min) of the second-moment tensor of the
/// solid region (sub-cell fraction clamp(1/2 - phi/dx, 0, 1), as solid<i>_area); for an
/// ellipse of semi-axes a, b the eigenvalues are a^2/4 and b^2/4 per unit area.
Moments moments(const Solid& s, const Grid& g) {
  double m = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
  for (int j = 0; j < s.nj(); ++j)
    for (int i = 0; i < s.ni(); ++i) {
      const double f = std::clamp(0.5 - s.phi()(i, j) / g.dx, 0.0, 1.0);
      const double x = g.xc(s.i0() + i), y = g.yc(s.j0() + j);
      m += f; mx += f * x; my += f * y; mxx += f * x * x; mxy += f * x * y; myy += f * y * y;
    }
  const double cx = mx / m, cy = my / m;
  const double ixx = mxx / m - cx * cx, ixy = mxy / m - cx * cy, iyy = myy / m - cy * cy;
  const double mean = 0.5 * (ixx + iyy), d = std::sqrt(0.25 * (ixx - iyy) * (ixx - iyy) + ixy * ixy);
  return {m * g.dx * g.dx, std::sqrt((mean + d) / (mean - d))};
}

}  // namespace

TEST(ActuatedDisc, StretchGivesAspectRatioSquaredAndKeepsArea) {
  // disc R = 0.2 in a closed unit box, 48^2; s ramps 1 -> 1.5 over t in [0, 0.5], then holds;
  // the fluid (mu = 0.02) damps the elastic oscillation (shear-wave time R / sqrt(2 mu_s /
  // rho) = 0.14) by t = 2
  const std::string text = box_scene(48, kWalls,
                                     disc_toml("d", 0.5, 0.5, 0.2, 1.0,
                                               "actuation = { stretch_x = \"1 + 0.5*min(t/0.5, 1)\" }\n"),
                                     0.02, 2.0);
  Config cfg = load_scene_string(text, "actuated_disc_test.toml");
  Simulation sim(cfg);
  const Moments m0 = moments(*sim.solids()[0], cfg.grid);
  RunSummary r = run(sim, RunOptions::silent());
  ASSERT_FALSE(r.failed) << r.failure;
  const Moments m1 = moments(*sim.solids()[0], cfg.grid);
  std::printf("actuated disc 48^2: aspect %.4f -> %.4f (target 2.25), area %.5f -> %.5f (change %.2e)\n", m0.aspect,
              m1.aspect, m0.area, m1.area, m1.area / m0.area - 1);
  // tolerance: the minor semi-axis R/s is 6.4 cells; the sub-cell area fraction and the
  // smoothed interface (w_T = 3 cells) bias the moments by O(dx^2 / b^2) ~ 2.4 %; the
  // residual oscillation at t = 2 is damped below that. 3 % on the aspect ratio (measured:
  // 2.2412, 0.4 %).
  EXPECT_NEAR(m0.aspect, 1.0, 0.01);
  EXPECT_NEAR(m1.aspect, 2.25, 0.03 * 2.25);
  EXPECT_NEAR(m1.area / m0.area, 1.0, 0.01);  // incompressible: area drift of the level set < 1 %
}

TEST(Actuation, BadValuesAreSceneErrors) {
  auto error_of = [](const std::string& more) {
    try {
      load_scene_string(box_scene(16, kWalls, disc_toml("d", 0.5, 0.5, 0.2, 1.0, more)), "bad.toml");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("actuation = { stretch_x = \"0\" }\n").find("must be a finite number > 0"), std::string::npos);
  EXPECT_NE(error_of("actuation = { stretch_x = \"1 +\" }\n").find("invalid expression"), std::string::npos);
  EXPECT_NE(error_of("actuation = { stretch = \"1\" }\n").find("unknown key"), std::string::npos);
  EXPECT_NE(error_of("actuation = { }\n").find("give stretch_x"), std::string::npos);
  EXPECT_NE(error_of("actuation = 2\n").find("expected an inline table"), std::string::npos);
  EXPECT_EQ(error_of("actuation = { stretch_x = 1.2, shear = \"0.1*t\" }\n"), "");
}
