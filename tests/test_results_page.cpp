// results/README.md, the page of headline results: its validation table is machine-readable
// (tests/quoted_results.hpp), and the validation tests compare their runs with it. These
// checks keep that link honest without running anything: every quoted number parses, every
// test id of the table is used by some test source (a row whose id no test checks would go
// stale silently), and the page stays a short summary (at most 16 kB; the studies live on
// the topic pages it links to).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/quoted_results.hpp"

using namespace refmap::testing;

TEST(ResultsPage, QuotedNumbersParse) {
  const auto quoted = quoted_results();
  // the quick cases: cavity (2 Re x u, v), Taylor-Green, Zalesak, Couette, cylinder
  EXPECT_GE(quoted.size(), 10u) << "the validation table of results/README.md was not found or lost its rows";
  for (const auto& [id, q] : quoted) EXPECT_GT(q.unit, 0.0) << "`" << id << "`: not a number: " << q.text;
  QuotedNumber q;
  ASSERT_TRUE(parse_quoted("2.3e-3", q));
  EXPECT_DOUBLE_EQ(q.value, 2.3e-3);
  EXPECT_NEAR(q.unit, 1e-4, 1e-18);
  ASSERT_TRUE(parse_quoted("-0.016075", q));
  EXPECT_NEAR(q.unit, 1e-6, 1e-20);
  ASSERT_TRUE(parse_quoted("5", q));
  EXPECT_DOUBLE_EQ(q.unit, 1.0);
  EXPECT_FALSE(parse_quoted("—", q));
}

TEST(ResultsPage, EveryQuotedIdIsCheckedByATest) {
  std::string sources;
  for (const auto& e : std::filesystem::directory_iterator(std::string(REFMAP_SOURCE_DIR) + "/tests")) {
    if (e.path().extension() != ".cpp" || e.path().filename() == "test_results_page.cpp") continue;
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    sources += ss.str();
  }
  for (const auto& [id, q] : quoted_results())
    EXPECT_NE(sources.find("\"" + id + "\""), std::string::npos)
        << "results/README.md quotes `" << id << "` but no test calls expect_quoted(\"" << id << "\", ...)";
}

TEST(ResultsPage, AtMost16kB) {
  EXPECT_LE(std::filesystem::file_size(results_page_path()), 16u * 1024u)
      << "results/README.md is the summary: move study text to the topic pages under results/";
}
