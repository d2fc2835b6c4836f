#pragma once
// The byte format of a checkpoint file: a header (magic "REFMAPCK", format version,
// payload size, FNV-1a 64 checksum of the payload) followed by tagged records. Writing
// goes to PATH.tmp, is flushed to disk and renamed over PATH, so a checkpoint is either
// the old one or the new one, never half of each. Reading checks the magic, the version,
// the size and the checksum before anything is used, so a truncated or corrupted file is
// refused whole with a message naming the file and what is wrong.
//
// Records are read back in the order they were written; each carries a tag that the
// reader checks, so a file written by another layout fails with the tag it expected.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/field.hpp"

namespace refmap {

/// A checkpoint that cannot be used (missing, truncated, corrupted, other version).
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class CheckpointWriter {
 public:
  void put_bytes(const std::string& tag, const void* data, std::size_t n);
  void put_f64(const std::string& tag, double v) { put_bytes(tag, &v, sizeof v); }
  void put_i64(const std::string& tag, std::int64_t v) { put_bytes(tag, &v, sizeof v); }
  void put_string(const std::string& tag, const std::string& s) { put_bytes(tag, s.data(), s.size()); }
  void put_f64s(const std::string& tag, const std::vector<double>& v) {
    put_bytes(tag, v.data(), v.size() * sizeof(double));
  }
  /// Shape (nx, ny, ng) and every stored element, ghosts and padding included.
  void put_field(const std::string& tag, const Field& f);
  void put_mask(const std::string& tag, const Mask& m);

  /// Writes the file atomically (PATH.tmp, fsync, rename). Throws std::runtime_error.
  void save(const std::string& path) const;
  /// The records written so far (an in-memory snapshot: CheckpointReader::from_payload).
  const std::vector<unsigned char>& payload() const { return payload_; }

 private:
  std::vector<unsigned char> payload_;
};

class CheckpointReader {
 public:
  /// Reads and verifies the whole file; throws CheckpointError.
  explicit CheckpointReader(const std::string& path);
  /// Reads the records of an in-memory snapshot (CheckpointWriter::payload; no header, no
  /// checksum: it never left the process). `name` stands for the path in error messages.
  static CheckpointReader from_payload(const std::vector<unsigned char>& payload, const std::string& name);

  std::vector<unsigned char> get_bytes(const std::string& tag);
  double get_f64(const std::string& tag);
  std::int64_t get_i64(const std::string& tag);
  std::string get_string(const std::string& tag);
  std::vector<double> get_f64s(const std::string& tag);
  void get_field(const std::string& tag, Field& f);
  void get_mask(const std::string& tag, Mask& m);
  bool at_end() const { return pos_ == payload_.size(); }
  const std::string& path() const { return path_; }

 private:
  CheckpointReader() = default;
  [[noreturn]] void fail(const std::string& what) const;
  std::string path_;
  std::vector<unsigned char> payload_;
  std::size_t pos_ = 0;
};

}  // namespace refmap
