// The key table of solver/scene/scene_keys.cpp: scenes/README.md holds exactly its generated
// reference, and the loader enforces what the table says (ranges, choices, key lists).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "solver/scene/option_names.hpp"
#include "solver/scene/scene.hpp"
#include "tests/fixtures/scene_text.hpp"
#include "solver/scene/scene_keys.hpp"

namespace refmap {
namespace {

const char* kBegin = "<!-- keys:begin -->\n";
const char* kEnd = "<!-- keys:end -->";

const std::string kBase = testing::box_scene(16, testing::kLidDriven);

std::string error_of(const std::vector<std::string>& sets) {
  try {
    load_scene_string(kBase, "scene.toml", sets);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

/// Tables whose keys can be set on kBase alone (no array of tables, no inline table).
bool settable(const KeyDef& k) {
  for (const auto& t : scene_tables())
    if (t.name == k.table) return !t.name.empty() && !t.repeatable && !t.nested;
  return false;
}

/// The --set that selects the variant a key belongs to (initial.velocity = "taylor_green"
/// for initial.wavenumber), if any.
std::vector<std::string> with_selector(const KeyDef& k, std::string set) {
  std::vector<std::string> sets;
  if (!k.selector.empty()) sets.push_back(k.table + "." + k.selector + "=\"" + k.only.front() + "\"");
  sets.push_back(std::move(set));
  return sets;
}

TEST(SceneKeys, ReadmeIsGenerated) {
  const std::string path = std::string(REFMAP_SOURCE_DIR) + "/scenes/README.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << "cannot read " << path;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const auto b = text.find(kBegin);
  const auto e = text.find(kEnd);
  ASSERT_NE(b, std::string::npos) << path << " has no line " << kBegin;
  ASSERT_NE(e, std::string::npos) << path << " has no line " << kEnd;
  ASSERT_LT(b, e);
  const std::string have = text.substr(b + std::string(kBegin).size(), e - b - std::string(kBegin).size());
  const std::string want = scene_keys_markdown();
  if (have != want && std::getenv("REFMAP_WRITE_README")) {  // opt-in regeneration
    std::ofstream out(path, std::ios::trunc);
    out << text.substr(0, b + std::string(kBegin).size()) << want << text.substr(e);
    ADD_FAILURE() << "rewrote the key reference of " << path << "; check the diff and commit it";
    return;
  }
  EXPECT_EQ(have, want)
      << "the key reference in scenes/README.md differs from the key table (solver/scene/scene_keys.cpp). Regenerate "
         "it: replace the lines between '<!-- keys:begin -->' and '<!-- keys:end -->' by the output of "
         "`build/refmap keys --markdown`, or run this test once with REFMAP_WRITE_README=1 "
         "(build/tests/refmap_tests --gtest_filter=SceneKeys.ReadmeIsGenerated).";
}

TEST(SceneKeys, EntriesAreUniqueAndDescribed) {
  for (std::size_t i = 0; i < scene_keys().size(); ++i) {
    const KeyDef& k = scene_keys()[i];
    EXPECT_FALSE(k.description.empty()) << k.dotted();
    EXPECT_EQ(k.description.find('|'), std::string::npos) << k.dotted() << ": '|' breaks the markdown table";
    EXPECT_EQ(k.description.find('\n'), std::string::npos) << k.dotted() << ": one line";
    if (k.type == KeyType::Choice) {
      EXPECT_FALSE(k.choices.empty()) << k.dotted();
    }
    for (std::size_t j = i + 1; j < scene_keys().size(); ++j)
      EXPECT_FALSE(k.table == scene_keys()[j].table && k.name == scene_keys()[j].name) << "duplicate " << k.dotted();
    bool table_known = false;
    for (const auto& t : scene_tables()) table_known = table_known || t.name == k.table;
    EXPECT_TRUE(table_known) << k.dotted();
  }
}

// Every numeric range of the table is enforced by the loader, with the table's phrase.
TEST(SceneKeys, LoaderEnforcesEveryRange) {
  int checked = 0;
  for (const KeyDef& k : scene_keys()) {
    if (!settable(k) || (!k.range.lo && !k.range.hi)) continue;
    const bool integer = k.type == KeyType::Integer;
    std::vector<double> outside;
    if (k.range.lo) outside.push_back(k.range.lo_open ? *k.range.lo : (integer ? *k.range.lo - 1 : std::nextafter(*k.range.lo, -1e300)));
    if (k.range.hi) outside.push_back(k.range.hi_open ? *k.range.hi : (integer ? *k.range.hi + 1 : std::nextafter(*k.range.hi, 1e300)));
    for (double v : outside) {
      const std::string value = integer ? std::to_string(long(v)) : num(v);
      const std::string m = error_of(with_selector(k, k.dotted() + "=" + value));
      EXPECT_NE(m.find(k.dotted() + ": must be " + k.range.phrase()), std::string::npos)
          << k.dotted() << " = " << value << ": " << m;
      ++checked;
    }
    // and the default is inside its own range
    if (const double* d = std::get_if<double>(&k.def)) {
      EXPECT_TRUE(k.range.contains(*d)) << k.dotted();
    }
    if (const long* d = std::get_if<long>(&k.def)) {
      EXPECT_TRUE(k.range.contains(double(*d))) << k.dotted();
    }
  }
  EXPECT_GE(checked, 25);  // the ranges of [grid], [fluid], [time], [solver], [output], [solids], [contact], ...
}

// Every choice of the table is accepted, a wrong one is rejected with the list.
TEST(SceneKeys, LoaderAcceptsEveryChoice) {
  int checked = 0;
  for (const KeyDef& k : scene_keys()) {
    if (!settable(k) || k.type != KeyType::Choice) continue;
    for (const auto& c : k.choices) {
      std::vector<std::string> sets = with_selector(k, k.dotted() + "=\"" + c + "\"");
      if (k.dotted() == "initial.velocity" && c == "expression")  // its required keys
        for (const char* e : {"initial.u_expr=\"x\"", "initial.v_expr=\"-y\""}) sets.push_back(e);
      if (k.dotted() == "time.solid_picard_force" && c == "trapezoidal")  // its prerequisites
        for (const char* e : {"time.solid_picard_iterations=1", "time.solid_stress=\"semi_implicit\""}) sets.push_back(e);
      EXPECT_EQ(error_of(sets), "") << k.dotted() << " = " << c;
      ++checked;
    }
    std::string list;
    for (const auto& c : k.choices) list += (list.empty() ? "\"" : ", \"") + c + "\"";
    const std::string m = error_of({k.dotted() + "=\"no_such_choice\""});
    EXPECT_NE(m.find(k.dotted() + ": unknown value \"no_such_choice\""), std::string::npos) << m;
    EXPECT_NE(m.find("(expected one of " + list + ")"), std::string::npos) << m;
  }
  EXPECT_GE(checked, 20);
}

// The allowed-key list of an unknown-key message is the table's.
TEST(SceneKeys, UnknownKeyListsTheTable) {
  for (const auto& t : scene_tables()) {
    if (t.name.empty() || t.repeatable || t.nested) continue;
    std::string list;
    for (const auto& n : scene_key_names(t.name)) list += (list.empty() ? "" : ", ") + n;
    const std::string m = error_of({t.name + ".qqqqqqqqqqqq=1"});
    EXPECT_NE(m.find(t.name + ".qqqqqqqqqqqq: unknown key (allowed: " + list + ")"), std::string::npos) << m;
  }
}

// Shape aliases are accepted by the loader and stored as the kind.
TEST(SceneKeys, ShapeAliases) {
  const std::string solid = std::string(kBase) +
                            "[[solid]]\nshape = \"rectangle\"\ncenter = [0.5, 0.5]\nhalf_size = [0.1, 0.1]\n"
                            "mu_s = 1.0\ndensity = 1.0\n";
  const Config c = load_scene_string(solid, "scene.toml");
  ASSERT_EQ(c.solids.size(), 1u);
  EXPECT_EQ(c.solids[0].shape.kind, ShapeKind::RoundedRectangle);
  EXPECT_STREQ(to_string(ShapeKind::Zalesak), "zalesak");
  EXPECT_EQ(parse_option<ShapeKind>("slotted_disk"), ShapeKind::Zalesak);
}

}  // namespace
}  // namespace refmap
