// Problems of a scene that used to surface only after the output directory was made
// (exit 1, or a run full of non-finite values) are load-time SceneErrors (exit 2) that
// name the key and its line: non-finite initial-velocity expressions, solids outside
// the walls, too wide for a periodic direction, overlapping at the start (also across a
// periodic side), a band wider than the grid, a grid larger than the machine's memory.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "solver/scene/scene.hpp"
#include "tests/fixtures/scene_text.hpp"

using refmap::load_scene_string;
using refmap::SceneError;
using namespace refmap::testing;

namespace {

std::string scene(const std::string& boundary, const std::string& extra, int n = 32) {
  return box_scene(n, boundary, extra);
}

std::string disc(const std::string& name, double cx, double cy, double r) { return disc_toml(name, cx, cy, r); }

/// The message of the SceneError that loading `text` throws ("" if it loads).
std::string error_of(const std::string& text) {
  try {
    load_scene_string(text, "start.toml", {});
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

/// The 1-based line of the first line of `text` that starts with `prefix`.
int line_of(const std::string& text, const std::string& prefix) {
  int line = 1;
  for (std::size_t p = 0; p < text.size(); p = text.find('\n', p) + 1, ++line) {
    if (text.compare(p, prefix.size(), prefix) == 0) return line;
    if (text.find('\n', p) == std::string::npos) break;
  }
  return -1;
}

/// ":N:" of a message's file:line:column position.
std::string line_tag(int line) {
  std::ostringstream o;
  o << ':' << line << ':';
  return o.str();
}

}  // namespace

TEST(StartChecks, ValidScenesStillLoad) {
  EXPECT_EQ(error_of(scene(kWalls, disc("a", 0.3, 0.5, 0.1) + disc("b", 0.7, 0.5, 0.1))), "");
  // a layer spanning the periodic direction (the elastic Couette case) may cross it
  EXPECT_EQ(error_of(scene("left = \"periodic\"\nright = \"periodic\"\nbottom = \"no_slip\"\ntop = \"no_slip\"\n",
                           "[[solid]]\nname = \"layer\"\nshape = \"rounded_rectangle\"\ncenter = [0.5, 0.25]\n"
                           "half_size = [0.6, 0.1]\nmu_s = 1.0\ndensity = 1.0\n")),
            "");
}

TEST(StartChecks, NonFiniteExpressionNamesKeyLineAndPoint) {
  for (const char* expr : {"1/(x-x)", "sqrt(-1)", "1/(y - 0.515625)"}) {
    const std::string text =
        scene(kWalls, "[initial]\nvelocity = \"expression\"\nu_expr = \"0\"\nv_expr = \"" + std::string(expr) + "\"\n");
    const std::string msg = error_of(text);
    EXPECT_NE(msg.find("start.toml:" + std::to_string(line_of(text, "v_expr")) + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find("initial.v_expr"), std::string::npos) << msg;
    EXPECT_NE(msg.find("must be finite over the whole grid"), std::string::npos) << msg;
  }
}

TEST(StartChecks, SolidOutsideTheWalls) {
  const std::string text = scene(kWalls, disc("big", 0.5, 0.5, 0.55));
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find("solid[0].center"), std::string::npos) << msg;
  EXPECT_NE(msg.find("does not fit inside the walls"), std::string::npos) << msg;
  EXPECT_NE(msg.find(line_tag(line_of(text, "center"))), std::string::npos) << msg;
}

TEST(StartChecks, SolidAcrossAPeriodicSide) {
  // a disc across a periodic side loads (its window wraps, solver/model/periodic_window.hpp)
  EXPECT_EQ(error_of(scene(kPeriodic, disc("edge", 0.05, 0.5, 0.1))), "");
  EXPECT_EQ(error_of(scene(kPeriodic, disc("corner", 0.0, 1.0, 0.1))), "");
  // with walls on the other sides: across the periodic side yes, across a wall no
  const std::string channel =
      "left = \"periodic\"\nright = \"periodic\"\nbottom = \"no_slip\"\ntop = \"no_slip\"\n";
  EXPECT_EQ(error_of(scene(channel, disc("edge", 0.02, 0.5, 0.1))), "");
  const std::string msg = error_of(scene(channel, disc("low", 0.5, 0.05, 0.1)));
  EXPECT_NE(msg.find("solid[0].center"), std::string::npos) << msg;
  EXPECT_NE(msg.find("does not fit inside the walls"), std::string::npos) << msg;
  // narrower than the period but too wide for a window that does not span it: the band
  // (6 cells) and the margin (3 + 1 cells) either side must fit in the 32 cells
  const std::string wide = error_of(scene(kPeriodic, disc("wide", 0.5, 0.5, 0.3)));
  EXPECT_NE(wide.find("solid[0].center"), std::string::npos) << wide;
  EXPECT_NE(wide.find("too wide for the periodic direction x"), std::string::npos) << wide;
  // two discs that overlap across the seam (their nearest images do) are refused
  const std::string ov = error_of(scene(kPeriodic, disc("a", 0.05, 0.5, 0.1) + disc("b", 0.9, 0.5, 0.1)));
  EXPECT_NE(ov.find("overlaps solid 'a'"), std::string::npos) << ov;
  EXPECT_EQ(error_of(scene(kPeriodic, disc("a", 0.05, 0.5, 0.1) + disc("b", 0.8, 0.5, 0.1))), "");
}

TEST(StartChecks, OverlappingSolids) {
  const std::string msg = error_of(scene(kWalls, disc("a", 0.4, 0.5, 0.15) + disc("b", 0.6, 0.5, 0.15)));
  EXPECT_NE(msg.find("solid[1].center"), std::string::npos) << msg;
  EXPECT_NE(msg.find("overlaps solid 'a'"), std::string::npos) << msg;
  // touching bounding boxes, disjoint discs: fine
  EXPECT_EQ(error_of(scene(kWalls, disc("a", 0.3, 0.5, 0.15) + disc("b", 0.65, 0.5, 0.15))), "");
}

TEST(StartChecks, BandWiderThanTheGrid) {
  const std::string msg = error_of(scene(kWalls, "[solids]\nband = 12.0\ntransition = 3.0\n" + disc("a", 0.5, 0.5, 0.2), 12));
  EXPECT_NE(msg.find("solids.band"), std::string::npos) << msg;
  EXPECT_NE(msg.find("wider than the grid"), std::string::npos) << msg;
}

TEST(StartChecks, GridLargerThanMemory) {
  // 40000^2 cells need about 300 GB: refused at load time, naming grid.nx, not bad_alloc
  const std::string text = scene(kWalls, "", 40000);
  const std::string msg = error_of(text);
  EXPECT_NE(msg.find("grid.nx"), std::string::npos) << msg;
  EXPECT_NE(msg.find("of memory"), std::string::npos) << msg;
  EXPECT_NE(msg.find(line_tag(line_of(text, "nx"))), std::string::npos) << msg;
}
