#pragma once
// The error of an input file (a scene): one line naming the file, the position when known
// and the dotted key,
//
//     <file>:<line>:<column>: <dotted.key>: <what is wrong>
//
// thrown by the TOML reader (solver/io/toml_reader.hpp) and the scene loader
// (solver/scene/scene.hpp); `refmap` exits 2 on it.
#include <stdexcept>
#include <string>

namespace refmap {

struct SceneError : std::runtime_error {
  SceneError(const std::string& file, const std::string& key, const std::string& what,
             long line = 0, long column = 0);
  std::string file;  ///< scene path as given
  std::string key;   ///< dotted key ("fluid.viscosity", "probe[1].start"), "" for file-level errors
  long line = 0, column = 0;  ///< 1-based position in the file, 0 if unknown
};

}  // namespace refmap
