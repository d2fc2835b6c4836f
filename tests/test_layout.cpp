// The source tree's layers (docs/layout.md): every #include "..." of refmap's own code
// points to the same layer or one below it, never up. From the bottom:
//   core < kernels < solver/io < solver/pressure < solver/model = solver/components
//        < solver/scene < solver/app
// (the model and its components use each other: a component reads the Simulation, and
// Simulation::add_components is the one place that lists them).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::vector<std::pair<std::string, int>> kLayers = {
    {"core/", 0},          {"kernels/", 1},         {"solver/io/", 2},    {"solver/pressure/", 3},
    {"solver/model/", 4},  {"solver/components/", 4}, {"solver/scene/", 5}, {"solver/app/", 6},
};

/// The layer of a path relative to the source root, -1 if it is in none.
int layer_of(const std::string& rel) {
  for (const auto& [prefix, rank] : kLayers)
    if (rel.rfind(prefix, 0) == 0) return rank;
  return -1;
}

// Includes that still run up, each with the reason it is allowed for now.
// (none today: keep it that way)
const std::set<std::pair<std::string, std::string>> kKnownUpward = {};

TEST(Layout, NoIncludeRunsUpTheLayers) {
  const fs::path root(REFMAP_SOURCE_DIR);
  const std::regex include_re("#include \"([^\"]+)\"");
  std::vector<std::string> upward;
  int files = 0;
  for (const char* top : {"core", "kernels", "solver"}) {
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      if (!e.is_regular_file()) continue;
      const std::string ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".hpp") continue;
      const std::string rel = fs::relative(e.path(), root).generic_string();
      const int from = layer_of(rel);
      EXPECT_GE(from, 0) << rel << " is in no layer: put it in one of solver/{io,pressure,model,components,scene,app}";
      ++files;
      std::ifstream in(e.path());
      std::stringstream text;
      text << in.rdbuf();
      const std::string s = text.str();
      for (std::sregex_iterator it(s.begin(), s.end(), include_re), end; it != end; ++it) {
        const std::string inc = (*it)[1].str();
        const int to = layer_of(inc);
        if (to > from && !kKnownUpward.count({rel, inc})) upward.push_back(rel + " includes " + inc);
      }
    }
  }
  EXPECT_GT(files, 100);  // the walk found the tree
  for (const std::string& u : upward) ADD_FAILURE() << u << " (an include running up the layers)";
}

}  // namespace
