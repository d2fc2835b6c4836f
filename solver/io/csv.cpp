#include "solver/io/csv.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

namespace refmap {

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> header, const std::string& comment_header)
    : path_(path), header_(std::move(header)) {
  if (header_.empty()) throw std::invalid_argument("CsvWriter: " + path + ": empty header");
  errno = 0;
  file_.reset(std::fopen(path.c_str(), "w"));
  if (!file_)
    throw std::runtime_error("cannot open " + path + " for writing: " + (errno ? std::strerror(errno) : "open failed"));
  std::setvbuf(file_.get(), nullptr, _IONBF, 0);  // rows are buffered in buf_ (flush() relies on it)
  if (!comment_header.empty()) {
    std::size_t start = 0;
    while (start <= comment_header.size()) {
      std::size_t nl = comment_header.find('\n', start);
      if (nl == std::string::npos) nl = comment_header.size();
      const std::string line = comment_header.substr(start, nl - start);
      if (!(nl == comment_header.size() && line.empty())) {  // no empty line for a trailing '\n'
        buf_ += (!line.empty() && line[0] == '#') ? line : (line.empty() ? "#" : "# " + line);
        buf_ += '\n';
      }
      start = nl + 1;
    }
  }
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (i) buf_ += ',';
    buf_ += header_[i];
  }
  buf_ += '\n';
  flush();
}

CsvWriter CsvWriter::resume(const std::string& path, std::vector<std::string> header, std::size_t bytes, long rows) {
  CsvWriter w;
  w.path_ = path;
  w.header_ = std::move(header);
  std::error_code ec;
  if (std::filesystem::file_size(path, ec) < bytes || ec)
    throw std::runtime_error(path + " is shorter than when the checkpoint was written (" + std::to_string(bytes) +
                             " bytes): it cannot be continued");
  std::filesystem::resize_file(path, bytes, ec);
  if (ec) throw std::runtime_error("cannot cut " + path + " back to its checkpoint: " + ec.message());
  errno = 0;
  w.file_.reset(std::fopen(path.c_str(), "a"));
  if (!w.file_)
    throw std::runtime_error("cannot open " + path + " for appending: " + (errno ? std::strerror(errno) : "open failed"));
  std::setvbuf(w.file_.get(), nullptr, _IONBF, 0);
  w.committed_ = bytes;
  w.rows_ = rows;
  w.last_flush_ = std::chrono::steady_clock::now();
  return w;
}

CsvWriter::~CsvWriter() {
  try {
    flush();
  } catch (...) {
  }
}

CsvWriter::CsvWriter(CsvWriter&&) noexcept = default;
CsvWriter& CsvWriter::operator=(CsvWriter&& o) noexcept {
  if (this != &o) {
    try { flush(); } catch (...) {}
    path_ = std::move(o.path_);
    header_ = std::move(o.header_);
    file_ = std::move(o.file_);
    buf_ = std::move(o.buf_);
    last_flush_ = o.last_flush_;
    rows_ = o.rows_;
    committed_ = o.committed_;
  }
  return *this;
}

void CsvWriter::append(const std::vector<double>& values) {
  if (values.size() != header_.size())
    throw std::invalid_argument("CsvWriter: " + path_ + ": row has " + std::to_string(values.size()) +
                                " values, the header has " + std::to_string(header_.size()) + " columns");
  char num[40];
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) buf_ += ',';
    const int n = std::snprintf(num, sizeof num, "%.10g", values[i]);
    buf_.append(num, std::size_t(n));
  }
  buf_ += '\n';
  ++rows_;
}

void CsvWriter::flush_if_due() {
  if (buf_.size() > (1u << 20) ||
      std::chrono::steady_clock::now() - last_flush_ >= std::chrono::seconds(1))
    flush();
}

void CsvWriter::row(const std::vector<double>& values) {
  append(values);
  flush_if_due();
}

void CsvWriter::rows(const std::vector<std::vector<double>>& block) {
  for (const auto& values : block) append(values);
  flush_if_due();
}

void CsvWriter::flush() {
  if (!file_) return;
  last_flush_ = std::chrono::steady_clock::now();
  if (buf_.empty()) return;
  // buf_ holds whole rows only; the stream is unbuffered (see the constructor), so what
  // reached the file is known: on a short write (full disk, file size limit) the file is
  // cut back to the end of the last whole row and the writer stops, rather than leave a
  // half row that a later, successful write would glue to the next one.
  errno = 0;
  const std::size_t n = std::fwrite(buf_.data(), 1, buf_.size(), file_.get());
  if (n != buf_.size() || std::fflush(file_.get()) != 0) {
    const int err = errno;
    if (::ftruncate(::fileno(file_.get()), off_t(committed_)) != 0) { /* the message below still holds */ }
    file_.reset();
    buf_.clear();
    throw std::runtime_error("write error on " + path_ + ": " + (err ? std::strerror(err) : "short write") +
                             " (the file ends on its last whole row)");
  }
  committed_ += buf_.size();
  buf_.clear();
}

}  // namespace refmap
