#pragma once
// A key of an input file described as data: its table, name, type, default, allowed range
// or choices and a one-line description (KeyDef), the tables (TableDef), and a catalogue
// of both (KeyCatalog). The TOML reader (solver/io/toml_reader.hpp) takes its allowed-key
// lists, defaults, range checks and choices from a catalogue; the scene's catalogue is
// solver/scene/scene_keys.cpp with the optional components' own entries
// (solver/model/component_kind.hpp). Generic: nothing here knows the scene's keys.
//
// The builders in namespace `keys` (num, integer, boolean, choice, only, ...) write one
// entry a line; a component declares its keys with them in its own file.
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "solver/io/enum_names.hpp"

namespace refmap {

enum class KeyType {
  Float,       ///< integer or float in the file, finite
  Integer,     ///< integer only
  Bool,
  String,
  Choice,      ///< one of `choices` (aliases of the enum's names, solver/io/enum_names.hpp, are accepted too)
  Vec2,        ///< [float, float]
  Points,      ///< [[float, float], ...]: a list of points
  InlineTable, ///< an inline table whose keys are those of a nested table ("solid.actuation")
  Expression,  ///< string (or a number) parsed by solver/io/expression.hpp
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

/// The tables and keys of one kind of input file, in reference order.
struct KeyCatalog {
  std::vector<TableDef> tables;
  std::vector<KeyDef> keys;

  /// The entry of `table`.`name`, or null.
  const KeyDef* find(const std::string& table, const std::string& name) const;
  /// The entry of `table`.`name`; throws std::logic_error if there is none (a loader bug).
  const KeyDef& key(const std::string& table, const std::string& name) const;
  /// The key names of a table, in reference order.
  std::vector<std::string> key_names(const std::string& table) const;
  /// The keys allowed at the top level: the top-level keys and the tables.
  std::vector<std::string> top_level_names() const;
};

/// Shortest "%g"-style text that reads back as v: 100, 0.5, 1e-8 (ranges and defaults in
/// the reference).
std::string key_number_text(double v);

/// One-line builders of entries.
namespace keys {

// ---- ranges
inline KeyRange gt(double lo, std::string note = "") { return {lo, std::nullopt, true, false, std::move(note), ""}; }
inline KeyRange ge(double lo, std::string note = "") { return {lo, std::nullopt, false, false, std::move(note), ""}; }
inline KeyRange in(double lo, bool lo_open, double hi, bool hi_open, std::string note = "") {
  return {lo, hi, lo_open, hi_open, std::move(note), ""};
}
/// A range enforced by a cross-key check in code; documented only.
inline KeyRange text_range(std::string text) { return {std::nullopt, std::nullopt, false, false, "", std::move(text)}; }

// ---- entries
inline KeyDef key(const char* table, const char* name, KeyType type, KeyValue def, KeyRange range, const char* desc) {
  KeyDef k;
  k.table = table;
  k.name = name;
  k.type = type;
  k.def = std::move(def);
  k.range = std::move(range);
  k.description = desc;
  return k;
}
inline KeyDef num(const char* table, const char* name, std::optional<double> def, KeyRange range, const char* desc) {
  return key(table, name, KeyType::Float, def ? KeyValue(*def) : KeyValue(), std::move(range), desc);
}
inline KeyDef integer(const char* table, const char* name, std::optional<long> def, KeyRange range, const char* desc) {
  return key(table, name, KeyType::Integer, def ? KeyValue(*def) : KeyValue(), std::move(range), desc);
}
inline KeyDef boolean(const char* table, const char* name, bool def, const char* desc) {
  return key(table, name, KeyType::Bool, def, {}, desc);
}
inline KeyDef vec2(const char* table, const char* name, std::optional<std::array<double, 2>> def, const char* desc) {
  return key(table, name, KeyType::Vec2, def ? KeyValue(*def) : KeyValue(), {}, desc);
}
inline KeyDef str(const char* table, const char* name, std::optional<std::string> def, const char* desc) {
  return key(table, name, KeyType::String, def ? KeyValue(*def) : KeyValue(), {}, desc);
}
/// A named option (solver/io/enum_names.hpp): the choices are the enum's canonical names.
template <class E>
KeyDef choice(const char* table, const char* name, std::optional<E> def, const char* desc) {
  KeyDef k = key(table, name, KeyType::Choice, def ? KeyValue(std::string(to_string(*def))) : KeyValue(), {}, desc);
  k.choices = canonical_names<E>();
  return k;
}
inline KeyDef only(KeyDef k, const char* selector, std::vector<std::string> values) {
  k.selector = selector;
  k.only = std::move(values);
  return k;
}
inline KeyDef shown_default(KeyDef k, const char* text) {
  k.default_text = text;
  return k;
}

}  // namespace keys

}  // namespace refmap
