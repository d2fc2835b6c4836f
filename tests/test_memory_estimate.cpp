// The memory estimate (solver/scene/memory_estimate.hpp) against what a constructed
// Simulation really holds: the resident set grows by the estimate within 25% (the
// estimate counts every array the solver allocates up front; allocations of a few KiB and
// the Poisson solver's method-dependent vectors are what the margin covers).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "solver/scene/memory_estimate.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "tests/fixtures/scene_text.hpp"

using namespace refmap;
using namespace refmap::testing;

namespace {

std::size_t resident_bytes() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      std::size_t kb;
      in >> kb;
      return kb * 1024;
    }
    std::getline(in, key);
  }
  return 0;
}

}  // namespace

TEST(MemoryEstimate, FieldBytesMatchTheFieldLayout) {
  for (int nx : {1, 7, 8, 9, 100, 1023})
    for (int ny : {1, 5, 64}) {
      Field f(nx, ny, Grid::ng);
      EXPECT_EQ(field_bytes(nx, ny, Grid::ng), f.raw_size() * sizeof(double)) << nx << " x " << ny;
    }
}

TEST(MemoryEstimate, MatchesTheResidentMemoryOfASimulation) {
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer's redzones and shadow memory change the resident set";
#endif
  // a 512^2 cavity with one elastic disc: about 80 MB, far above allocator noise
  const std::string scene = box_scene(512, kLidDriven, disc_toml("disc", 0.5, 0.5, 0.2));
  Config cfg = load_scene_string(scene, "memory.toml", {});
  const MemoryEstimate est = estimate_memory(cfg);
  const std::size_t before = resident_bytes();
  ASSERT_GT(before, 0u);
  Simulation sim(cfg);
  const std::size_t used = resident_bytes() - before;
  const double ratio = double(est.total() - est.output) / double(used);
  std::printf("estimate %s, resident growth %s\n", est.summary().c_str(), format_bytes(used).c_str());
  EXPECT_GT(ratio, 0.75) << "estimate " << est.summary() << ", resident growth " << format_bytes(used);
  EXPECT_LT(ratio, 1.25) << "estimate " << est.summary() << ", resident growth " << format_bytes(used);
}
