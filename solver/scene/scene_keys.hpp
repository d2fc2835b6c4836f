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
// Checks that involve several keys (time.end > time.start, transition < band - 1,
// contact.range < band, probes inside the domain, the per-shape keys of a [[solid]]) stay
// as code next to the parse functions of scene.cpp; their entries here carry the range as
// text for the reference only.
#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace refmap {

enum class KeyType {
  Float,       ///< integer or float in the file, finite
  Integer,     ///< integer only
  Bool,
  String,
  Choice,      ///< one of `choices` (aliases of solver/scene/option_names.hpp are accepted too)
  Vec2,        ///< [float, float]
  Points,      ///< [[float, float], ...]: a list of points
  InlineTable, ///< an inline table whose keys are those of a nested table ("solid.actuation")
  Expression,  ///< string (or a number) parsed by solver/model/expression.hpp
  Boundary,    ///< a boundary condition: a string or an inline table (table "boundary.side")
};

/// A numeric range checked by the loader. The message is
///     must be <phrase>[ (<note>)], got <value>
/// with the phrase "> lo", ">= lo", "in (lo, hi]", ... (or `text` when given).
struct KeyRange {
  std::optional<double> lo, hi;
  bool lo_open = false, hi_open = false;
  std::string note;  ///< e.g. "0 = adaptive"
  /// Replaces the generated phrase in messages and in the reference (lsq_radius), or,
  /// without lo and hi, documents a range that a cross-key check enforces in code.
  std::string text;

  bool empty() const { return !lo && !hi && text.empty(); }
  bool contains(double v) const;
  std::string phrase() const;  ///< "> 0", "in (0, 2.5]", or `text`
};

/// A default value: none (the key is required), or a value of the key's type.
using KeyValue = std::variant<std::monostate, double, long, bool, std::string, std::array<double, 2>>;

struct KeyDef {
  std::string table;  ///< "" top level, "domain", "solver", "probe", "solid", "boundary.side", ...
  std::string name;
  KeyType type = KeyType::Float;
  KeyValue def;                      ///< monostate: required
  KeyRange range;
  std::vector<std::string> choices;  ///< KeyType::Choice: the canonical names
  std::string description;
  /// The key is only used when key `selector` of the same table is one of `only`
  /// (initial.u with velocity = "uniform", the shape keys of a [[solid]], ...).
  std::string selector;
  std::vector<std::string> only;
  std::string default_text;  ///< replaces the printed default (e.g. "file stem")

  bool required() const { return std::holds_alternative<std::monostate>(def) && default_text.empty(); }
  std::string dotted() const { return table.empty() ? name : table + "." + name; }
};

struct TableDef {
  std::string name;      ///< key in the file ("solver"; "solid" for [[solid]])
  std::string heading;   ///< "`[solver]`", "`[[solid]]`"
  bool required = false;
  bool repeatable = false;  ///< an array of tables
  bool nested = false;      ///< not a top-level key ("boundary.side")
  std::string intro;        ///< one line under the heading in the reference ("" for none)
};

const std::vector<TableDef>& scene_tables();
const std::vector<KeyDef>& scene_keys();

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
