#pragma once
// A buffered CSV writer for time series (diagnostics.csv, ...).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace refmap {

class CsvWriter {
 public:
  /// Creates (truncates) `path` and writes the optional comment header (every line
  /// prefixed with "# " unless it already starts with '#'; multi-line OK) and the column
  /// header, and flushes them. Throws std::runtime_error if the file cannot be opened.
  CsvWriter(const std::string& path, std::vector<std::string> header, const std::string& comment_header = "");
  /// Continues `path` from a checkpoint: the file is cut back to `bytes` (the whole rows
  /// written when the checkpoint was taken; rows written after it are dropped, the resumed
  /// run writes them again) and rows are appended from there.
  static CsvWriter resume(const std::string& path, std::vector<std::string> header, std::size_t bytes, long rows);
  ~CsvWriter();  ///< flushes
  CsvWriter(CsvWriter&&) noexcept;
  CsvWriter& operator=(CsvWriter&&) noexcept;
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  /// One row, numbers as %.10g. Throws std::invalid_argument if values.size() differs
  /// from the number of columns. Rows are buffered and reach the file at least once a
  /// second of wall time (checked on each row), on flush() and on destruction.
  void row(const std::vector<double>& values);
  /// Several rows that reach the file together (one output step of a long-format file,
  /// solids.csv): the file is only flushed after the last, and a failed write cuts it back
  /// to the end of an earlier flush, so it always ends on a whole block.
  void rows(const std::vector<std::vector<double>>& block);
  /// Throws std::runtime_error on a write error, after cutting the file back to its last
  /// whole row; the writer then writes nothing more.
  void flush();

  const std::string& path() const { return path_; }
  std::size_t columns() const { return header_.size(); }
  long rows() const { return rows_; }
  /// Bytes in the file after flush() (whole rows only).
  std::size_t bytes() const { return committed_; }

 private:
  CsvWriter() = default;
  void append(const std::vector<double>& values);  ///< one row into buf_
  void flush_if_due();  ///< flush() once a second of wall time or past 1 MiB of rows
  struct Closer { void operator()(std::FILE* f) const { if (f) std::fclose(f); } };
  std::string path_;
  std::vector<std::string> header_;
  std::unique_ptr<std::FILE, Closer> file_;
  std::string buf_;
  std::chrono::steady_clock::time_point last_flush_;
  long rows_ = 0;
  std::size_t committed_ = 0;  ///< bytes known to be in the file (always whole lines)
};

}  // namespace refmap
