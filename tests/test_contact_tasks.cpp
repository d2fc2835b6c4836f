// The contact force is computed as tasks (solver/contact.hpp, THREADS): per pair and per
// wall, only over the cells that can contribute, concurrently, then applied in a fixed
// order. Neither the narrowed cell boxes nor the number of threads may change a bit of the
// face forces or of the contact energy.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "solver/contact.hpp"
#include "solver/scene.hpp"
#include "solver/simulation.hpp"
#include "tests/fixtures/scene_text.hpp"

using namespace refmap;

namespace {

struct Forces {
  std::vector<double> fx, fy;
  double energy = 0.0;
};

Forces forces(const Config& cfg, const Simulation& sim, bool narrow, int threads) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Contact c(cfg, 1.0);  // velocity scale unused: the scene sets contact.velocity_scale
  c.set_narrow_boxes(narrow);
  const Grid& g = cfg.grid;
  Field fx(g.nx + 1, g.ny, 1), fy(g.nx, g.ny + 1, 1);
  fx.fill(0.0);
  fy.fill(0.0);
  c.add_force(sim.solids(), fx, fy);
  omp_set_num_threads(saved);
  return {{fx.raw(), fx.raw() + fx.raw_size()}, {fy.raw(), fy.raw() + fy.raw_size()}, c.energy()};
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

// Nine discs on a 3 x 3 lattice with gaps of one cell, pressed together by their initial
// velocities and against the walls, 64^2: every step the forces from the narrowed boxes
// on 1 and 2 threads must be bitwise those of every cell of the overlapping windows on 1.
TEST(ContactTasks, NarrowedBoxesAndThreadsChangeNoBit) {
  std::string solids;
  const double r = 0.14, step = 2 * r + 1.0 / 64;
  int k = 0;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i, ++k) {
      // towards the centre, the corner discs also towards the walls' neighbours
      char more[96];
      std::snprintf(more, sizeof more, "velocity = \"rigid\"\nu = %g\nv = %g\nomega = %g\n", -0.5 * i, -0.5 * j,
                    k % 2 ? 2.0 : -2.0);
      solids += refmap::testing::disc_toml("d" + std::to_string(k), 0.5 + i * step, 0.5 + j * step, r, 5.0, more);
    }
  const Config cfg = load_scene_string(
      refmap::testing::box_scene(64, refmap::testing::kWalls, "[contact]\nenabled = true\nvelocity_scale = 1.0\n" + solids, 0.01, 0.2),
      "nine_discs.toml");
  Simulation sim(cfg);
  ASSERT_TRUE(sim.contact() && sim.contact()->force_enabled());
  int with_force = 0;
  for (int n = 0; n < 12; ++n) {
    const Forces ref = forces(cfg, sim, false, 1);
    double fmax = 0.0;
    for (double f : ref.fx) fmax = std::max(fmax, std::abs(f));
    with_force += fmax > 0.0;
    for (int threads : {1, 2}) {
      const Forces f = forces(cfg, sim, true, threads);
      EXPECT_TRUE(same_bits(ref.fx, f.fx)) << "step " << n << ", " << threads << " threads";
      EXPECT_TRUE(same_bits(ref.fy, f.fy)) << "step " << n << ", " << threads << " threads";
      EXPECT_EQ(std::memcmp(&ref.energy, &f.energy, sizeof(double)), 0) << "step " << n;
    }
    sim.step();
  }
  EXPECT_GE(with_force, 10);  // the discs (and walls) really push: the comparison is not of zeros
}
