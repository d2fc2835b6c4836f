#pragma once
// VTK XML output for ParaView/VisIt: one ImageData (.vti) file per frame with the interior
// cells of cell-centred fields as CellData (Float64, raw appended binary, UInt64 block
// headers), the simulated time as a FieldData TIME value, and a .pvd collection that
// lists the frames with their times.
#include <string>
#include <utility>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"

namespace refmap {

struct VtkScalar {
  std::string name;
  const Field* f;  ///< cell-centred, nx x ny
};
struct VtkVector {
  std::string name;
  const Field* fx;  ///< x component, cell-centred
  const Field* fy;  ///< y component, cell-centred (z is written as 0)
};

/// Writes `path` (.vti). The file is written to `path + ".tmp"` and renamed, so a reader
/// never sees a half-written frame. Throws std::runtime_error on I/O failure and
/// std::invalid_argument if a field's size does not match the grid.
void write_vti(const std::string& path, const Grid& g, const std::vector<VtkScalar>& scalars,
               const std::vector<VtkVector>& vectors, double time);

/// A ParaView .pvd time series. Every add() rewrites the complete file (via a temporary
/// and a rename), so the series on disk is valid at any moment, even after a crash.
class PvdSeries {
 public:
  PvdSeries() = default;
  explicit PvdSeries(std::string pvd_path);
  /// Appends a frame; `file_relative_to_pvd` is the .vti path relative to the .pvd's folder.
  void add(double time, const std::string& file_relative_to_pvd);
  const std::string& path() const { return path_; }
  std::size_t size() const { return entries_.size(); }
  /// The frames listed so far (for a checkpoint); restore() rewrites the series with them.
  std::vector<std::pair<double, std::string>> entries() const;
  void restore(const std::vector<std::pair<double, std::string>>& entries);

 private:
  void write() const;
  struct Entry { double time; std::string file; };
  std::string path_;
  std::vector<Entry> entries_;
};

/// XML attribute escaping (& < > " ').
std::string xml_escape(const std::string& s);

}  // namespace refmap
