#pragma once
// The scene-file schema as data: every table and every key with its type, default, allowed
// range or choices and a one-line description. The loader (solver/scene/scene.cpp) takes its
// allowed-key lists, defaults, range checks and choices from here, and the key reference
// of scenes/README.md is generated from it (`refmap keys --markdown`; the test
// SceneKeys.ReadmeIsGenerated fails when the two differ). Adding a key is one entry in
// scene_keys.cpp plus the line of the loader that stores it in Config.
//
// Defaults are read from a default-constructed Config (solver/model/config.hpp), so the member
// initialisers there are the only copy of a default value.
//
// The components (solver/model/component_kind.hpp) declare their own keys and tables in their
// own files (the solids' [solids] and [[solid]], the rigid bodies' keys in [[solid]] and the
// implicit step's in [time] too); scene_keys() and scene_tables() are the core's entries of
// scene_keys.cpp with the components' merged in (each component says after which key or
// table its entries go in the reference). The entry types and their builders are in
// solver/io/key_def.hpp.
//
// Checks that involve several keys (time.end > time.start, transition < band - 1,
// probes inside the domain, the per-shape keys of a [[solid]]) stay
// as code next to the parse functions (scene.cpp, or the component's own file); their entries here carry the range as
// text for the reference only.
#include <string>
#include <vector>

#include "solver/io/key_def.hpp"

namespace refmap {

const std::vector<TableDef>& scene_tables();
const std::vector<KeyDef>& scene_keys();
/// The two together, as the TOML reader (solver/io/toml_reader.hpp) takes them.
const KeyCatalog& scene_catalog();

/// The entry of `table`.`name`; throws std::logic_error if there is none (a loader bug).
const KeyDef& scene_key(const std::string& table, const std::string& name);
/// The key names of a table, in reference order.
std::vector<std::string> scene_key_names(const std::string& table);
/// The keys allowed at the top level: the top-level keys and the tables.
std::vector<std::string> scene_top_level_names();

/// "float > 0", "integer in [1, 100]", "\"central\" or \"superbee\"": the type column.
std::string key_type_text(const KeyDef& k);
/// "`0.5`", "required", "`\"central\"`": the default column.
std::string key_default_text(const KeyDef& k);

/// The key reference: one markdown section per table (the block between the markers
/// `<!-- keys:begin -->` and `<!-- keys:end -->` of scenes/README.md, markers excluded).
std::string scene_keys_markdown();
/// The same as plain text, one key a line (`refmap keys`).
std::string scene_keys_text();

}  // namespace refmap
