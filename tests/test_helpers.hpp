#pragma once
// Small helpers shared by the tests: reading reference CSVs, scene paths, scene errors.
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/io/input_error.hpp"
#include "solver/scene/scene.hpp"

namespace refmap::testing {

inline std::string scene_path(const std::string& name) {
  return std::string(REFMAP_SOURCE_DIR) + "/scenes/" + name;
}
inline std::string data_path(const std::string& name) {
  return std::string(REFMAP_DATA_DIR) + "/" + name;
}

/// The message of the SceneError that loading the scene `text` throws ("" if it loads).
inline std::string scene_error(const std::string& text) {
  try {
    load_scene_string(text, "bad.toml", {});
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

/// A CSV with one header line: columns by name.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(const std::string& name) const {
    for (size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) {
        std::vector<double> out;
        for (const auto& r : rows) out.push_back(r.at(c));
        return out;
      }
    throw std::runtime_error("no column " + name);
  }
  /// The rows whose column `name` equals `value` (one solid's rows of solids.csv).
  Csv where(const std::string& name, double value) const {
    Csv out{header, {}};
    const std::vector<double> c = column(name);
    for (size_t k = 0; k < rows.size(); ++k)
      if (c[k] == value) out.rows.push_back(rows[k]);
    return out;
  }
};

inline Csv read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Csv csv;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (csv.header.empty()) {
      csv.header = cells;
    } else {
      std::vector<double> r;
      for (auto& c : cells) r.push_back(std::stod(c));
      csv.rows.push_back(r);
    }
  }
  return csv;
}

}  // namespace refmap::testing
