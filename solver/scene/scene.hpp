#pragma once
// Scene files: TOML in, a validated Config out. The complete key reference is
// scenes/README.md; every problem with a scene (syntax, unknown or missing key, wrong
// type, out-of-range value, unreadable file) is reported as a SceneError whose message is
// one line:
//
//     <file>:<line>:<column>: <dotted.key>: <what is wrong>
//
// (":<line>:<column>" is present when the offending value came from the file and toml++
// knows where it is; values from --set overrides are marked "(from --set)").
#include <string>
#include <vector>

#include "solver/model/config.hpp"
#include "solver/io/input_error.hpp"

namespace refmap {

/// Parse, override and validate a scene file. `sets` are "dotted.key=value" overrides
/// (the --set arguments of `refmap run`): the value is parsed as a TOML value, or taken as
/// a bare string if it is not one, and is inserted into the parsed document before
/// validation, so an override is checked exactly like a value in the file. Array elements
/// are addressed as "probe[0].points" or "probe.0.points". Throws SceneError.
Config load_scene(const std::string& path, const std::vector<std::string>& sets = {});

/// Same as load_scene but from TOML text; `path` is used for messages, the default name
/// (its stem) and Config::scene_path. For tests and tools.
Config load_scene_string(const std::string& toml_text, const std::string& path,
                         const std::vector<std::string>& sets = {});

}  // namespace refmap
