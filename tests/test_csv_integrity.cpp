// A full disk must leave diagnostics.csv ending on a whole row (README.md, exit status 3: runs that
// survive). The file size limit (RLIMIT_FSIZE) stands in for a full disk: a write past it
// fails with EFBIG exactly as one past the free space fails with ENOSPC.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include "solver/io/csv.hpp"

namespace fs = std::filesystem;

namespace {

struct FileSizeLimit {
  rlimit old{};
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, SIG_IGN);  // else the kernel kills the process at the limit
    rlimit lim = old;
    lim.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lim);
  }
  ~FileSizeLimit() { setrlimit(RLIMIT_FSIZE, &old); }
};

/// The text of a CSV file after a full disk: it must end on a newline; returns its data
/// lines (not the '#' comment, not the header, which starts with `header`), each checked
/// to hold `commas` commas (a whole row).
long whole_data_lines(const fs::path& f, char header, long commas, std::string* text_out = nullptr) {
  std::ifstream in(f);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  EXPECT_FALSE(text.empty());
  if (!text.empty()) {
    EXPECT_EQ(text.back(), '\n') << "the file ends inside a row";
  }
  std::istringstream lines(text);
  std::string line;
  long data = 0;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#' || line[0] == header) continue;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), commas) << line;
    ++data;
  }
  if (text_out) *text_out = text;
  return data;
}

}  // namespace

TEST(CsvIntegrity, FullDiskLeavesWholeRows) {
  const fs::path f = fs::temp_directory_path() / ("refmap_csv_full_" + std::to_string(::getpid()) + ".csv");
  std::string error;
  long rows_given = 0;
  {
    FileSizeLimit limit(1000);  // the 8-column rows below are ~100 bytes: the limit falls mid-row
    refmap::CsvWriter w(f.string(), {"a", "b", "c", "d", "e", "f", "g", "h"}, "scene: full disk");
    try {
      for (int k = 0; k < 200; ++k) {
        w.row({k * 1.0, 0.1 * k, 1.0 / 3.0, 2.0 / 7.0, 1e-9 * k, 3.14159, 2.71828, -k * 1.25});
        ++rows_given;
        w.flush();  // every row reaches the file: the limit is hit on a row boundary-free write
      }
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
  }
  ASSERT_FALSE(error.empty()) << "the file size limit was never reached";
  EXPECT_NE(error.find("last whole row"), std::string::npos) << error;
  // every data line is whole: 8 fields
  std::string text;
  const long data = whole_data_lines(f, 'a', 7, &text);
  EXPECT_LE(text.size(), 1000u);
  EXPECT_GT(data, 3);
  EXPECT_LT(data, rows_given + 1);
  fs::remove(f);
}

// solids.csv writes one block of rows per output step (CsvWriter::rows): a full disk must
// leave it ending on a whole block -- every solid of the last step present -- not only on
// a whole row. Blocks of 3 rows of ~60 bytes, a limit of 1000 bytes: the limit falls inside
// a block (1000 is no multiple of a block's ~180 bytes), and the file must be cut back to
// the block before it.
TEST(CsvIntegrity, FullDiskLeavesWholeBlocks) {
  const fs::path f = fs::temp_directory_path() / ("refmap_csv_blocks_" + std::to_string(::getpid()) + ".csv");
  std::string error;
  {
    FileSizeLimit limit(1000);
    refmap::CsvWriter w(f.string(), {"step", "time", "solid", "a", "b"}, "scene: full disk, blocks");
    try {
      for (int k = 0; k < 200; ++k) {
        std::vector<std::vector<double>> block;
        for (int s = 0; s < 3; ++s) block.push_back({double(k), 0.1 * k, double(s), 1.0 / 3.0, 2.0 / 7.0});
        w.rows(block);
        w.flush();
      }
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
  }
  ASSERT_FALSE(error.empty()) << "the file size limit was never reached";
  const long data = whole_data_lines(f, 's', 4);
  EXPECT_GT(data, 3);
  EXPECT_EQ(data % 3, 0) << "the file ends inside a block: " << data << " rows";
  fs::remove(f);
}
