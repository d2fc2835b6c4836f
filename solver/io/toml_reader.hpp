#pragma once
// Reading a TOML input file against a catalogue of its keys (solver/io/key_def.hpp), generic:
// typed getters with the catalogue's defaults, ranges and choices, named options
// (solver/io/enum_names.hpp), unknown-key detection with a "did you mean" suggestion, "--set
// key=value" overrides, and errors that name the dotted key and its position
// (SceneError, solver/io/input_error.hpp):
//
//     <file>:<line>:<column>: <dotted.key>: <what is wrong>
//
// The scene's schema (which tables, which keys, the checks across keys) is
// solver/scene/scene.cpp and solver/scene/scene_keys.cpp; an optional component reads its own keys
// with this (solver/model/component_kind.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "solver/io/enum_names.hpp"
#include "solver/io/input_error.hpp"
#include "solver/io/key_def.hpp"

namespace refmap {

/// Text for messages.
namespace toml_text {
/// "%.10g"
std::string fmt_num(double v);
/// "\"s\""
std::string dq(std::string_view s);
/// "a string (\"abc\")", "an integer (3)": for type errors.
std::string describe(const toml::node& n);
/// " (did you mean 'x'?)" for the closest candidate, or "" if none is close.
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates, bool quote_as_string);
std::string join(const std::vector<std::string>& v, const std::string& sep, bool quote = false);
}  // namespace toml_text

/// The file being read: its name (for messages), which keys came from --set, and the
/// catalogue of its keys.
struct TomlContext {
  std::string file;
  std::vector<std::string> overridden;  ///< normalised dotted keys ("probe[0].points")
  const KeyCatalog* catalog = nullptr;

  bool from_set(const std::string& key) const {
    for (const auto& o : overridden) {
      if (key == o) return true;
      if (key.size() > o.size() && key.compare(0, o.size(), o) == 0 && (key[o.size()] == '.' || key[o.size()] == '['))
        return true;
    }
    return false;
  }

  /// Throws the SceneError for `key`. The position is that of `where` if given (a key's
  /// own source), else of the node `at`, when it comes from the file; a value that came
  /// from --set (or a table created by one) is marked "(from --set)" instead.
  [[noreturn]] void fail(const std::string& key, const toml::node* at, const std::string& what,
                         const toml::source_region* where = nullptr) const {
    const toml::source_region* src = where ? where : (at ? &at->source() : nullptr);
    const bool in_file = src && src->path && *src->path == file && src->begin.line > 0;
    bool set = !key.empty() && from_set(key);
    if (!set && at && !in_file && !key.empty())  // a node created by an override of a key below it
      for (const auto& o : overridden)
        if (o.size() > key.size() && o.compare(0, key.size(), key) == 0 && (o[key.size()] == '.' || o[key.size()] == '['))
          set = true;
    const long line = in_file && !set ? long(src->begin.line) : 0;
    const long col = in_file && !set ? long(src->begin.column) : 0;
    throw SceneError(file, key, what + (set ? " (from --set)" : ""), line, col);
  }
};

/// One table of the file, read against its entries in the catalogue: typed values with the
/// entries' defaults, types, ranges and choices, and a rejection of keys it does not list.
class TomlTable {
 public:
  /// `schema`: the table's name in the catalogue ("solid" for "solid[2]"); `prefix`: its
  /// dotted path in the file, for messages ("solid[2]").
  TomlTable(const TomlContext& ctx, const toml::table& t, std::string prefix, std::string schema)
      : ctx_(ctx), t_(t), prefix_(std::move(prefix)), schema_(std::move(schema)) {}
  /// Another table of the same file (a sub-table, an element of an array of tables).
  TomlTable sub(const toml::table& t, std::string prefix, std::string schema) const {
    return TomlTable(ctx_, t, std::move(prefix), std::move(schema));
  }
  const TomlContext& context() const { return ctx_; }

  std::string full(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }
  const toml::node* node(std::string_view key) const { return t_.get(key); }
  bool has(std::string_view key) const { return t_.contains(key); }
  const toml::table& raw() const { return t_; }
  const std::string& prefix() const { return prefix_; }

  [[noreturn]] void fail(std::string_view key, const std::string& what) const {
    ctx_.fail(full(key), node(key), what);
  }
  [[noreturn]] void fail_missing(std::string_view key) const {
    ctx_.fail(full(key), &t_, "missing required key");
  }

  /// Rejects every key that is not in the table's entry list of the catalogue, reporting
  /// the first one in the file.
  void allow() const {
    const std::vector<std::string> names =
        schema_.empty() ? ctx_.catalog->top_level_names() : ctx_.catalog->key_names(schema_);
    const toml::node* worst = nullptr;
    const toml::key* worst_k = nullptr;
    std::string worst_key;
    auto pos = [](const toml::key* k) {
      const auto& s = k->source();
      return std::pair<long, long>(s.begin.line > 0 ? long(s.begin.line) : std::numeric_limits<long>::max(),
                                   long(s.begin.column));
    };
    for (const auto& [k, v] : t_) {
      const std::string key(k.str());
      bool ok = false;
      for (const auto& a : names) ok = ok || a == key;
      if (ok) continue;
      if (!worst || pos(&k) < pos(worst_k)) { worst = &v; worst_k = &k; worst_key = key; }
    }
    if (!worst) return;
    std::string what = "unknown key";
    std::string sug = toml_text::suggestion(worst_key, names, false);
    if (!sug.empty())
      what += sug;
    else
      what += names.empty() ? " (this table takes no keys)" : " (allowed: " + toml_text::join(names, ", ") + ")";
    ctx_.fail(full(worst_key), worst, what, &worst_k->source());
  }

  // ---- typed getters: the default (none: required) and the range are those of the key's
  // entry in the catalogue.

  const KeyDef& entry(std::string_view key) const { return ctx_.catalog->key(schema_, std::string(key)); }

  double number(std::string_view key) const {
    const double v = read_number(key, default_of<double>(key));
    checked(key, v, toml_text::fmt_num(v));
    return v;
  }
  /// A number whose requiredness depends on other keys ([[solid]] mu_s with flow = "solve").
  double number(std::string_view key, bool required) const {
    const double v = read_number(key, required ? std::nullopt : default_of<double>(key));
    checked(key, v, toml_text::fmt_num(v));
    return v;
  }
  long integer(std::string_view key) const {
    const long v = read_integer(key, default_of<long>(key));
    checked(key, double(v), std::to_string(v));
    return v;
  }
  bool boolean(std::string_view key) const { return read_boolean(key, default_of<bool>(key)); }
  std::string string(std::string_view key) const { return read_string(key, default_of<std::string>(key)); }
  std::array<double, 2> vec2(std::string_view key) const {
    return read_vec2(key, default_of<std::array<double, 2>>(key));
  }
  /// A string that must be one of the entry's choices.
  std::string choice(std::string_view key) const {
    const KeyDef& k = entry(key);
    std::string s = string(key);
    for (const auto& c : k.choices)
      if (s == c) return s;
    fail(key, "unknown value " + toml_text::dq(s) + toml_text::suggestion(s, k.choices, true) + " (expected one of " +
                  toml_text::join(k.choices, ", ", true) + ")");
  }
  /// A named option (solver/io/enum_names.hpp): canonical names or aliases are accepted;
  /// the message of an unknown name lists the canonical ones.
  template <class E>
  E option(std::string_view key) const {
    const std::vector<std::string> names = canonical_names<E>();
    const std::string s = string(key);
    if (auto e = parse_option<E>(s)) return *e;
    fail(key, "unknown value " + toml_text::dq(s) + toml_text::suggestion(s, names, true) + " (expected one of " + toml_text::join(names, ", ", true) +
                  ")");
  }

  /// The first key present although it belongs to another value of its selector
  /// (initial.u with velocity = "zero"), in table order; nullopt if there is none.
  std::optional<std::string> misplaced(const std::string& selector, const std::string& value) const {
    for (const auto& k : ctx_.catalog->keys) {
      if (k.table != schema_ || k.selector != selector || !has(k.name)) continue;
      if (std::find(k.only.begin(), k.only.end(), value) == k.only.end()) return k.name;
    }
    return std::nullopt;
  }
  /// The keys that a selector value takes, in table order.
  std::vector<std::string> keys_of(const std::string& selector, const std::string& value) const {
    std::vector<std::string> out;
    for (const auto& k : ctx_.catalog->keys)
      if (k.table == schema_ && k.selector == selector && std::find(k.only.begin(), k.only.end(), value) != k.only.end())
        out.push_back(k.name);
    return out;
  }

 private:
  template <class T>
  std::optional<T> default_of(std::string_view key) const {
    const KeyDef& k = entry(key);
    if (const T* v = std::get_if<T>(&k.def)) return *v;
    return std::nullopt;
  }
  /// The entry's range check: "must be > 0 (note), got -1".
  void checked(std::string_view key, double v, const std::string& shown) const {
    const KeyRange& r = entry(key).range;
    if ((r.lo || r.hi) && !r.contains(v))
      fail(key, "must be " + r.phrase() + (r.note.empty() ? "" : " (" + r.note + ")") + ", got " + shown);
  }

  // ---- raw getters: `def` = nullopt means required.

  double read_number(std::string_view key, std::optional<double> def) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    double v;
    if (auto f = n->as_floating_point()) v = f->get();
    else if (auto i = n->as_integer()) v = double(i->get());
    else fail(key, "expected a number, got " + toml_text::describe(*n));
    if (!std::isfinite(v)) fail(key, "must be a finite number, got " + toml_text::fmt_num(v));
    return v;
  }

  long read_integer(std::string_view key, std::optional<long> def) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    if (auto i = n->as_integer()) return long(i->get());
    if (auto f = n->as_floating_point()) {
      if (std::isfinite(f->get()) && f->get() == std::floor(f->get()))
        fail(key, "expected an integer, got a float (write " + toml_text::fmt_num(f->get()) + " without the decimal point)");
    }
    fail(key, "expected an integer, got " + toml_text::describe(*n));
  }

  bool read_boolean(std::string_view key, std::optional<bool> def) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    if (auto b = n->as_boolean()) return b->get();
    fail(key, "expected true or false, got " + toml_text::describe(*n));
  }

  std::string read_string(std::string_view key, std::optional<std::string> def) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    if (auto s = n->as_string()) return s->get();
    fail(key, "expected a string, got " + toml_text::describe(*n));
  }

  /// A list of points [[x, y], ...] (KeyType::Points; absent: empty).
 public:
  std::vector<std::array<double, 2>> points(std::string_view key) const {
    std::vector<std::array<double, 2>> out;
    const toml::node* n = node(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    const std::string want = "expected a list of points [[x, y], ...], ";
    if (!a) fail(key, want + "got " + toml_text::describe(*n));
    for (std::size_t k = 0; k < a->size(); ++k) {
      const toml::array* p = a->get(k)->as_array();
      if (!p || p->size() != 2) fail(key, want + "element " + std::to_string(k) + " is " + toml_text::describe(*a->get(k)));
      std::array<double, 2> xy{};
      for (std::size_t i = 0; i < 2; ++i) {
        const toml::node& e = *p->get(i);
        if (auto f = e.as_floating_point()) xy[i] = f->get();
        else if (auto in = e.as_integer()) xy[i] = double(in->get());
        else fail(key, want + "element " + std::to_string(k) + " has " + toml_text::describe(e));
        if (!std::isfinite(xy[i])) fail(key, "coordinates must be finite numbers");
      }
      out.push_back(xy);
    }
    return out;
  }

 private:
  std::array<double, 2> read_vec2(std::string_view key, std::optional<std::array<double, 2>> def) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    const toml::array* a = n->as_array();
    if (!a) fail(key, "expected an array of two numbers [a, b], got " + toml_text::describe(*n));
    if (a->size() != 2) fail(key, "expected an array of two numbers [a, b], got " + std::to_string(a->size()) + " elements");
    std::array<double, 2> out{};
    for (std::size_t i = 0; i < 2; ++i) {
      const toml::node& e = *a->get(i);
      if (auto f = e.as_floating_point()) out[i] = f->get();
      else if (auto in = e.as_integer()) out[i] = double(in->get());
      else fail(key, "expected an array of two numbers [a, b], element " + std::to_string(i) + " is " + toml_text::describe(e));
      if (!std::isfinite(out[i])) fail(key, "elements must be finite numbers");
    }
    return out;
  }

 public:
  /// A sub-table; nullptr if absent and not required.
  const toml::table* table(std::string_view key, bool required) const {
    const toml::node* n = node(key);
    if (!n) {
      if (required) ctx_.fail(full(key), nullptr, "missing required table [" + full(key) + "]");
      return nullptr;
    }
    if (auto t = n->as_table()) return t;
    fail(key, "expected a table [" + full(key) + "], got " + toml_text::describe(*n));
  }

  // ---- range checks on a value already read
  void require(bool ok, std::string_view key, const std::string& what) const {
    if (!ok) fail(key, what);
  }

 private:
  const TomlContext& ctx_;
  const toml::table& t_;
  std::string prefix_;
  std::string schema_;
};

/// Applies one "--set dotted.key=value" to the parsed document (before it is read): the
/// value is parsed as a TOML value, or taken as a bare string if it is not one; array
/// elements are addressed as "probe[0].points" or "probe.0.points". Records the key in
/// ctx.overridden (messages then say "(from --set)").
void apply_override(TomlContext& ctx, toml::table& root, const std::string& arg);

/// The text of an expression key (solver/io/expression.hpp); a plain number is accepted as an
/// expression too (u_expr = 0). The expression is parsed here so a bad one fails at load
/// time.
std::string expression_text(const TomlTable& t, const char* key);

}  // namespace refmap
