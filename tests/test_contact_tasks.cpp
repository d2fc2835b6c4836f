// The contact force is computed as tasks (solver/model/contact.hpp, THREADS): per pair and per
// wall, only over the cells that can contribute, concurrently, then applied in a fixed
// order. Neither the narrowed cell boxes, nor the number of threads, nor the broad phase
// (cell lists instead of every pair, solver/model/contact_pairs.hpp) may change a bit of the
// face forces, of the contact energy, of the gaps or of the contact events.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include <unistd.h>

#include "solver/io/checkpoint_io.hpp"
#include "solver/model/contact.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/fixtures/scene_text.hpp"

using namespace refmap;

namespace {

struct Forces {
  std::vector<double> fx, fy;
  double energy = 0.0;
};

Forces forces(const Config& cfg, const Simulation& sim, bool narrow, int threads, bool broad = true) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Contact c(cfg, contact_options(cfg), 1.0);  // velocity scale unused: the scene sets contact.velocity_scale
  c.set_narrow_boxes(narrow);
  c.set_broad_phase(broad);
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
    const Forces ref = forces(cfg, sim, false, 1, false);
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

namespace {

/// `n` discs of radii in [0.03, 0.06] at random places of the unit square (seeded), none
/// overlapping; every third placed just beside an earlier one (a gap of 0 to 2 cells of
/// 1/96), so that many pairs are within the contact range; random rigid velocities.
std::string random_discs(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  struct D { double x, y, r; };
  std::vector<D> d;
  std::string out;
  const double dx = 1.0 / 96;
  for (int tries = 0; int(d.size()) < n && tries < 100000; ++tries) {
    D c{0, 0, 0.03 + 0.03 * U(rng)};
    if (d.size() % 3 == 2) {  // beside disc k
      const D& o = d[std::size_t(rng() % d.size())];
      const double a = 2 * M_PI * U(rng), s = o.r + c.r + 2 * dx * U(rng);
      c.x = o.x + s * std::cos(a);
      c.y = o.y + s * std::sin(a);
    } else {
      c.x = U(rng);
      c.y = U(rng);
    }
    // clear of the sides by more than the band and 3 cells (a solid may not come nearer a
    // periodic side, solver/model/solid.cpp fit_window), apart from the others
    if (c.x - c.r < 0.16 || c.x + c.r > 0.84 || c.y - c.r < 0.16 || c.y + c.r > 0.84) continue;
    bool ok = true;
    for (const D& o : d) ok = ok && std::hypot(c.x - o.x, c.y - o.y) > o.r + c.r;
    if (!ok) continue;
    d.push_back(c);
    char more[96];
    std::snprintf(more, sizeof more, "velocity = \"rigid\"\nu = %.3f\nv = %.3f\n", U(rng) - 0.5, U(rng) - 0.5);
    out += refmap::testing::disc_toml("r" + std::to_string(d.size()), c.x, c.y, c.r, 5.0, more);
  }
  return out;
}

}  // namespace

// A random configuration of 24 discs on 96^2, many within the contact range of each other,
// with walls and with every side periodic: for several steps the forces, the contact
// energy, the gaps and the events of the broad phase are bitwise those of every pair.
TEST(ContactTasks, BroadPhaseChangesNoBitOnRandomDiscs) {
  for (const char* boundary : {refmap::testing::kWalls, refmap::testing::kPeriodic}) {
    const Config cfg = load_scene_string(
        refmap::testing::box_scene(96, boundary, "[contact]\nenabled = true\nvelocity_scale = 1.0\n" + random_discs(24, 2027),
                                   0.01, 0.2),
        "random_discs.toml");
    ASSERT_EQ(cfg.solids.size(), 24u);
    Simulation sim(cfg);
    Contact all(cfg, contact_options(cfg), 1.0), cells(cfg, contact_options(cfg), 1.0);
    all.set_broad_phase(false);
    int with_force = 0;
    std::size_t max_touching = 0;
    for (int n = 0; n < 6; ++n) {
      const Forces ref = forces(cfg, sim, true, 1, false), f = forces(cfg, sim, true, 1, true);
      double fmax = 0.0;
      for (double v : ref.fx) fmax = std::max(fmax, std::abs(v));
      with_force += fmax > 0.0;
      EXPECT_TRUE(same_bits(ref.fx, f.fx)) << "step " << n;
      EXPECT_TRUE(same_bits(ref.fy, f.fy)) << "step " << n;
      EXPECT_EQ(std::memcmp(&ref.energy, &f.energy, sizeof(double)), 0) << "step " << n;
      all.observe(sim.time(), sim.solids(), sim.solid_diagnostics());
      cells.observe(sim.time(), sim.solids(), sim.solid_diagnostics());
      for (std::size_t k = 0; k < cfg.solids.size(); ++k) {
        const double a = all.gap_solid(int(k)), b = cells.gap_solid(int(k));
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "step " << n << ", solid " << k;
      }
      EXPECT_EQ(all.touching_pairs(), cells.touching_pairs()) << "step " << n;
      max_touching = std::max(max_touching, cells.touching_pairs().size());
      sim.step();
    }
    ASSERT_EQ(all.events().size(), cells.events().size());
    for (std::size_t k = 0; k < all.events().size(); ++k) {
      const ContactEvent &a = all.events()[k], &b = cells.events()[k];
      EXPECT_TRUE(a.time == b.time && a.solid == b.solid && a.event == b.event && a.with == b.with &&
                  std::memcmp(&a.value, &b.value, sizeof(double)) == 0)
          << "event " << k;
    }
    // the configuration really is in contact: forces at every step, several pairs touching
    EXPECT_EQ(with_force, 6);
    EXPECT_GE(max_touching, 4u);
  }
}

// The pairs in contact are kept as a list and saved in a checkpoint (contact.touching): a
// tracker restored from one, while pairs are in contact, must go on exactly as the one that
// was saved -- the same gaps, pairs and events (bits) at every later step.
TEST(ContactTasks, TouchingPairsSurviveACheckpoint) {
  const Config cfg = load_scene_string(
      refmap::testing::box_scene(96, refmap::testing::kWalls,
                                 "[contact]\nenabled = true\nvelocity_scale = 1.0\n" + random_discs(24, 2027), 0.01, 0.2),
      "random_discs.toml");
  Simulation sim(cfg);
  Contact a(cfg, contact_options(cfg), 1.0);
  int n = 0;
  for (; n < 12 && a.touching_pairs().empty(); ++n) {
    a.observe(sim.time(), sim.solids(), sim.solid_diagnostics());
    sim.step();
  }
  ASSERT_FALSE(a.touching_pairs().empty()) << "no pair in contact: the checkpoint would hold an empty list";
  const std::string path =
      (std::filesystem::temp_directory_path() / ("refmap_touching_" + std::to_string(::getpid()) + ".bin")).string();
  CheckpointWriter w;
  a.save_state(w);
  w.save(path);
  Contact b(cfg, contact_options(cfg), 1.0);
  CheckpointReader r(path);
  b.load_state(r);
  std::filesystem::remove(path);
  EXPECT_EQ(b.touching_pairs(), a.touching_pairs());
  for (int k = 0; k < 6; ++k) {
    a.observe(sim.time(), sim.solids(), sim.solid_diagnostics());
    b.observe(sim.time(), sim.solids(), sim.solid_diagnostics());
    EXPECT_EQ(a.touching_pairs(), b.touching_pairs()) << "step " << k;
    for (std::size_t i = 0; i < cfg.solids.size(); ++i) {
      const double ga = a.gap_solid(int(i)), gb = b.gap_solid(int(i));
      EXPECT_EQ(std::memcmp(&ga, &gb, sizeof ga), 0) << "step " << k << ", solid " << i;
    }
    sim.step();
  }
  ASSERT_EQ(a.events().size(), b.events().size());
  for (std::size_t k = 0; k < a.events().size(); ++k)
    EXPECT_TRUE(a.events()[k].event == b.events()[k].event && a.events()[k].solid == b.events()[k].solid &&
                std::memcmp(&a.events()[k].value, &b.events()[k].value, sizeof(double)) == 0)
        << "event " << k;
}
