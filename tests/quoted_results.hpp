#pragma once
// The numbers results/README.md quotes for the quick validation cases, read from the page
// itself, so that a test can compare what it has just measured with what the page says.
//
// The page's "## Validation" table has the columns `refmap` (the quoted number; the first
// token of the cell) and `test` (an id in backquotes, e.g. `CavityGhia.Re100/rms_u`, or a
// dash for rows no test reruns). expect_quoted(id, measured) fails unless the two agree to
// the digits quoted: |measured - quoted| <= one unit in the last quoted digit (e.g. 2.3e-3
// quotes to 1e-4, 5.433 to 1e-3). The runs are deterministic (the same bits on any thread
// count), so the only slack needed is the rounding of the quoted number, taken at a full
// unit so that a result on a rounding boundary does not flip with the last bits of the
// compiler's code; any change to the method that moves a result by more than that must
// update the table (and the study page the row links to).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace refmap::testing {

struct QuotedNumber {
  std::string text;  ///< the token as printed on the page
  double value = 0;
  double unit = 0;   ///< one unit in its last digit: the agreement asked for
};

inline std::string results_page_path() { return std::string(REFMAP_SOURCE_DIR) + "/results/README.md"; }

/// Splits a Markdown table row "| a | b |" into its trimmed cells.
inline std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::stringstream ss(line.substr(line.find('|') + 1));
  while (std::getline(ss, cell, '|')) {
    const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!cells.empty() && cells.back().empty() && line.back() == '|') cells.pop_back();
  return cells;
}

/// Parses a quoted number ("2.3e-3", "-0.016075", "4.02"); false if the token is not one.
inline bool parse_quoted(const std::string& token, QuotedNumber& q) {
  const char* s = token.c_str();
  char* end = nullptr;
  q.value = std::strtod(s, &end);
  if (end == s || (*end != '\0' && *end != ' ')) return false;
  const std::string num(s, static_cast<const char*>(end));
  const auto epos = num.find_first_of("eE");
  const std::string mant = num.substr(0, epos);
  const int exp10 = epos == std::string::npos ? 0 : std::atoi(num.c_str() + epos + 1);
  const auto dot = mant.find('.');
  const int decimals = dot == std::string::npos ? 0 : int(mant.size() - dot - 1);
  q.text = num;
  q.unit = std::pow(10.0, exp10 - decimals);
  return true;
}

/// id -> quoted number, for every row of the validation table with a test id. Rows with an id
/// whose `refmap` cell does not start with a number are returned with text = the cell and
/// unit = 0 (ResultsPage.QuotedNumbersParse reports them).
inline std::map<std::string, QuotedNumber> quoted_results() {
  std::ifstream in(results_page_path());
  std::map<std::string, QuotedNumber> out;
  std::string line;
  bool in_section = false;
  int col_refmap = -1, col_test = -1;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      in_section = line == "## Validation";
      continue;
    }
    if (!in_section || line.rfind("|", 0) != 0) continue;
    const auto cells = table_cells(line);
    if (col_refmap < 0) {  // the header row
      for (size_t c = 0; c < cells.size(); ++c) {
        if (cells[c] == "refmap") col_refmap = int(c);
        if (cells[c] == "test") col_test = int(c);
      }
      continue;
    }
    if (col_test < 0 || int(cells.size()) <= std::max(col_refmap, col_test)) continue;
    const std::string& id_cell = cells[col_test];
    if (id_cell.size() < 3 || id_cell.front() != '`') continue;  // no test reruns this row
    const std::string id = id_cell.substr(1, id_cell.find('`', 1) - 1);
    QuotedNumber q;
    std::string token = cells[col_refmap].substr(0, cells[col_refmap].find(' '));
    if (!parse_quoted(token, q)) q = QuotedNumber{cells[col_refmap], 0, 0};
    out[id] = q;
  }
  return out;
}

/// Fails unless `measured` agrees with the number results/README.md quotes for `id`.
inline void expect_quoted(const std::string& id, double measured) {
  static const std::map<std::string, QuotedNumber> quoted = quoted_results();
  const auto it = quoted.find(id);
  if (it == quoted.end() || it->second.unit == 0) {
    ADD_FAILURE() << "results/README.md's validation table has no number for `" << id << "` (this run: " << measured
                  << ")";
    return;
  }
  const QuotedNumber& q = it->second;
  EXPECT_LE(std::abs(measured - q.value), q.unit)
      << "results/README.md quotes " << q.text << " for `" << id << "`, this run gives " << measured
      << ": update the validation table and the study it links to, or find what changed";
}

}  // namespace refmap::testing
