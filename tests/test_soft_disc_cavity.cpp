// Soft disc in a lid-driven cavity (Zhao, Freund & Moser 2008; Sugiyama et al. 2011;
// docs/references.md#soft-disc-in-a-lid-driven-cavity): scenes/soft_disc_cavity.toml at a coarse grid. The centroid path
// (area-weighted over phi < 0, recorded after every step) is compared, without time stamps,
// with the digitised path of Sugiyama et al. (2011, 1024^2; tests/data, see README there):
// the distance from each of our centroids to the nearest point of the reference polyline
// must stay below a bound, the disc must actually travel along the path (otherwise a disc
// that never moved would pass), and the area of the incompressible disc must be conserved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/quoted_results.hpp"
#include "tests/test_helpers.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

struct Pt { double x, y; };

double dist_to_polyline(Pt p, const std::vector<Pt>& poly) {
  double best = INFINITY;
  for (size_t k = 0; k + 1 < poly.size(); ++k) {
    const double ax = poly[k].x, ay = poly[k].y;
    const double bx = poly[k + 1].x - ax, by = poly[k + 1].y - ay;
    const double l2 = bx * bx + by * by;
    const double s = l2 > 0 ? std::clamp(((p.x - ax) * bx + (p.y - ay) * by) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(p.x - ax - s * bx, p.y - ay - s * by));
  }
  return best;
}

std::vector<Pt> read_path(const std::string& file) {
  Csv c = read_csv(data_path(file));
  auto xs = c.column("x_centroid"), ys = c.column("y_centroid");
  std::vector<Pt> p;
  for (size_t k = 0; k < xs.size(); ++k) p.push_back({xs[k], ys[k]});
  return p;
}

}  // namespace

TEST(SoftDiscCavity, CentroidFollowsSugiyamaPathAndAreaIsConserved) {
  // 64^2 to t = 20 (the scene stops at 8, one loop): the Sugiyama path's end time is not
  // recorded, but our 128^2 centroid reaches its last point (to 0.007) at t = 20, so over
  // [0, 20] both distances are meaningful: from each of our centroids to the reference
  // polyline, and from each reference point to our path (the inner spiral is reached).
  constexpr double kEnd = 20.0;
  Config cfg = load_scene(scene_path("soft_disc_cavity.toml"),
                          {"grid.nx=64", "grid.ny=64", "time.end=20", "output.vtk=false"});
  Simulation sim(cfg);
  const std::vector<Pt> sugiyama = read_path("sugiyama2011_disc_centroid_path.csv");
  const std::vector<Pt> kolahdouz = read_path("kolahdouz2023_disc_centroid_path.csv");
  ASSERT_GT(sugiyama.size(), 50u);

  const double a0 = sim.solids()[0]->diagnostics(sim.u(), sim.v()).area;
  double max_d_sug = 0.0, max_d_kol = 0.0, max_area_dev = 0.0;
  double min_x = 1.0, max_y = 0.0, length = 0.0;
  const Pt start{sim.solids()[0]->diagnostics(sim.u(), sim.v()).cx,
                 sim.solids()[0]->diagnostics(sim.u(), sim.v()).cy};
  Pt prev = start;
  std::vector<Pt> path{prev};
  while (sim.time() < cfg.t_end - 1e-12) {
    sim.step(std::min(sim.stable_dt(), cfg.t_end - sim.time()));
    const SolidDiagnostics d = sim.solids()[0]->diagnostics(sim.u(), sim.v());
    ASSERT_TRUE(std::isfinite(d.cx) && std::isfinite(d.cy)) << "t = " << sim.time();
    const Pt p{d.cx, d.cy};
    max_d_sug = std::max(max_d_sug, dist_to_polyline(p, sugiyama));
    max_d_kol = std::max(max_d_kol, dist_to_polyline(p, kolahdouz));
    max_area_dev = std::max(max_area_dev, std::abs(d.area - a0) / a0);
    min_x = std::min(min_x, p.x);
    max_y = std::max(max_y, p.y);
    length += std::hypot(p.x - prev.x, p.y - prev.y);
    prev = p;
    path.push_back(p);
  }
  std::vector<Pt> ours;
  ours.swap(path);
  double back_sug = 0.0, back_kol = 0.0;  // from each reference point to our path
  for (const Pt& p : sugiyama) back_sug = std::max(back_sug, dist_to_polyline(p, ours));
  for (const Pt& p : kolahdouz) back_kol = std::max(back_kol, dist_to_polyline(p, ours));
  std::printf("[soft-disc-cavity 64^2] t = %.3f, %ld steps: max distance of our centroids to the Sugiyama "
              "path %.4f (Kolahdouz %.4f), of the reference points to our path %.4f (Kolahdouz %.4f); "
              "path length %.3f, min x %.4f, max y %.4f; max |A - A0|/A0 %.3e\n",
              sim.time(), sim.steps(), max_d_sug, max_d_kol, back_sug, back_kol, length, min_x, max_y,
              max_area_dev);
  EXPECT_NEAR(sim.time(), kEnd, 1e-9);
  // Measured when written (64^2, t = 20): 0.0143 and 0.0140 (128^2: 0.0134 and 0.0103); the
  // two published paths differ from each other by up to 0.042 (Kolahdouz to ours: 0.037).
  EXPECT_LT(max_d_sug, 0.025);
  EXPECT_LT(back_sug, 0.025);
  expect_quoted("SoftDiscCavity/max_distance_to_sugiyama", max_d_sug);  // as results/README.md quotes
  expect_quoted("SoftDiscCavity/max_distance_from_sugiyama", back_sug);
  // the disc must make the loop, not stay near the start of the path: measured min x
  // 0.289, max y 0.872 (Sugiyama: 0.289, 0.868), path length 2.12 (Sugiyama polyline: 2.02)
  EXPECT_LT(min_x, 0.33);
  EXPECT_GT(max_y, 0.82);
  EXPECT_GT(length, 1.8);
  // Area of the incompressible disc: measured max deviation 2.5% at 64^2 (above 1% first
  // for t = 3.7-7.5, while the disc passes under the lid with 1-2 cells of gap), and 0.58%
  // at 128^2.
  EXPECT_LT(max_area_dev, 4e-2);
}
