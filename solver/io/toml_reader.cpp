// Reading a TOML file against a key catalogue (see solver/io/toml_reader.hpp).
#include "solver/io/toml_reader.hpp"

#include <cctype>
#include <cstdio>
#include <stdexcept>

#include "solver/io/expression.hpp"

namespace refmap {

namespace {

std::string format_position(const std::string& file, long line, long column) {
  std::string s = file;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  return s;
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}


}  // namespace

SceneError::SceneError(const std::string& file_, const std::string& key_, const std::string& what, long line_,
                       long column_)
    : std::runtime_error(one_line(format_position(file_, line_, column_) + ": " + (key_.empty() ? "" : key_ + ": ") +
                                  what)),
      file(file_),
      key(key_),
      line(line_),
      column(column_) {}

namespace toml_text {

std::string fmt_num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string dq(std::string_view s) {
  std::string r;
  r.reserve(s.size() + 2);
  r += '"';
  r += s;
  r += '"';
  return r;
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

/// "a string (\"abc\")", "an integer (3)": for type errors.
std::string describe(const toml::node& n) {
  std::string d = type_name(n);
  if (auto s = n.as_string()) return d + " (" + dq(s->get()) + ")";
  if (auto i = n.as_integer()) return d + " (" + std::to_string(i->get()) + ")";
  if (auto f = n.as_floating_point()) return d + " (" + fmt_num(f->get()) + ")";
  if (auto b = n.as_boolean()) return d + " (" + (b->get() ? "true" : "false") + ")";
  return d;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

/// " (did you mean 'x'?)" for the closest candidate, or "" if none is close.
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates, bool quote_as_string) {
  std::string best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (const auto& c : candidates) {
    std::string lw(word), lc(c);
    for (auto& ch : lw) ch = char(std::tolower((unsigned char)ch));
    for (auto& ch : lc) ch = char(std::tolower((unsigned char)ch));
    const std::size_t d = edit_distance(lw, lc);
    if (d < best_d) { best_d = d; best = c; }
  }
  const std::size_t limit = word.size() <= 3 ? 1 : (word.size() <= 6 ? 2 : 3);
  if (best.empty() || best_d > limit) return "";
  return quote_as_string ? " (did you mean " + dq(best) + "?)" : " (did you mean '" + best + "'?)";
}

std::string join(const std::vector<std::string>& v, const std::string& sep, bool quote) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += sep;
    s += quote ? dq(v[i]) : v[i];
  }
  return s;
}

}  // namespace toml_text

using namespace toml_text;

namespace {

std::string trim(std::string s) {
  const char* ws = " \t\r\n";
  s.erase(0, s.find_first_not_of(ws));
  const auto e = s.find_last_not_of(ws);
  s.erase(e == std::string::npos ? 0 : e + 1);
  return s;
}

struct PathComp {
  std::string name;      // table key, or empty for an index
  std::size_t index = 0;
  bool is_index = false;
};

bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

/// "probe[0].points" / "probe.0.points" -> components; also returns the normalised key.
std::vector<PathComp> parse_key_path(const TomlContext& ctx, const std::string& key, const std::string& arg, std::string& norm) {
  std::vector<PathComp> out;
  norm.clear();
  auto bad = [&](const std::string& why) -> void {
    throw SceneError(ctx.file, "--set " + arg, why);
  };
  std::size_t i = 0;
  while (i <= key.size()) {
    std::size_t dot = key.find('.', i);
    if (dot == std::string::npos) dot = key.size();
    std::string part = key.substr(i, dot - i);
    if (part.empty()) bad("malformed key " + dq(key) + " (empty component)");
    // name[3][4] or a pure number
    std::size_t br = part.find('[');
    std::string name = part.substr(0, br);
    if (all_digits(name)) {
      if (out.empty()) bad("malformed key " + dq(key) + " (starts with an index)");
      out.push_back({"", std::stoul(name), true});
      norm += "[" + name + "]";
    } else {
      if (name.empty()) bad("malformed key " + dq(key));
      if (name.front() == '"' || name.front() == '\'') {
        if (name.size() < 2 || name.back() != name.front()) bad("malformed key " + dq(key));
        name = name.substr(1, name.size() - 2);
      }
      out.push_back({name, 0, false});
      norm += (norm.empty() ? "" : ".") + name;
    }
    while (br != std::string::npos) {
      const std::size_t close = part.find(']', br);
      if (close == std::string::npos) bad("malformed key " + dq(key) + " (missing ']')");
      const std::string idx = part.substr(br + 1, close - br - 1);
      if (!all_digits(idx)) bad("malformed key " + dq(key) + " (array index must be a number)");
      out.push_back({"", std::stoul(idx), true});
      norm += "[" + idx + "]";
      br = close + 1 < part.size() ? (part[close + 1] == '[' ? close + 1 : std::string::npos) : std::string::npos;
      if (br == std::string::npos && close + 1 < part.size()) bad("malformed key " + dq(key));
    }
    i = dot + 1;
  }
  return out;
}

/// The value of one override: a TOML value if it parses as one, else the bare string.
toml::table parse_override_value(const std::string& value) {
  try {
    toml::table t = toml::parse("v = " + value);
    if (t.size() == 1 && t.contains("v")) return t;
  } catch (const toml::parse_error&) {
  }
  toml::table t;
  t.insert("v", value);
  return t;
}

}  // namespace

void apply_override(TomlContext& ctx, toml::table& root, const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos) throw SceneError(ctx.file, "--set " + arg, "expected key=value");
  const std::string key = trim(arg.substr(0, eq));
  const std::string value = trim(arg.substr(eq + 1));
  if (key.empty()) throw SceneError(ctx.file, "--set " + arg, "empty key");
  std::string norm;
  const std::vector<PathComp> path = parse_key_path(ctx, key, arg, norm);
  toml::table vt = parse_override_value(value);
  toml::node& val = *vt.get("v");

  toml::node* cur = &root;
  std::string so_far;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const PathComp& c = path[k];
    const bool last = k + 1 == path.size();
    const bool next_is_index = !last && path[k + 1].is_index;
    if (c.is_index) {
      toml::array* arr = cur->as_array();
      if (!arr) throw SceneError(ctx.file, norm, "cannot set: " + so_far + " is not an array (from --set)");
      if (c.index > arr->size())
        throw SceneError(ctx.file, norm,
                         "cannot set: index " + std::to_string(c.index) + " is out of range, " + so_far + " has " +
                             std::to_string(arr->size()) + " elements (from --set)");
      so_far += "[" + std::to_string(c.index) + "]";
      if (last) {
        if (c.index == arr->size()) arr->push_back(std::move(val));
        else arr->replace(arr->cbegin() + std::ptrdiff_t(c.index), std::move(val));
      } else {
        if (c.index == arr->size()) {
          if (next_is_index) arr->push_back(toml::array{});
          else arr->push_back(toml::table{});
        }
        cur = arr->get(c.index);
      }
    } else {
      toml::table* tbl = cur->as_table();
      if (!tbl) throw SceneError(ctx.file, norm, "cannot set: " + so_far + " is not a table (from --set)");
      so_far += (so_far.empty() ? "" : ".") + c.name;
      if (last) {
        tbl->insert_or_assign(c.name, std::move(val));
      } else {
        if (!tbl->contains(c.name)) {
          if (next_is_index) tbl->insert(c.name, toml::array{});
          else tbl->insert(c.name, toml::table{});
        }
        cur = tbl->get(c.name);
      }
    }
  }
  ctx.overridden.push_back(norm);
}

std::string expression_text(const TomlTable& t, const char* key) {
  const toml::node* n = t.node(key);
  std::string text;
  if (n && n->as_integer()) {
    text = std::to_string(n->as_integer()->get());
  } else if (n && n->as_floating_point()) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", n->as_floating_point()->get());
    text = buf;
  } else {
    text = t.string(key);
  }
  try {
    Expression e(text);
    (void)e;
  } catch (const std::invalid_argument& ex) {
    t.fail(key, "invalid expression " + dq(text) + ": " + ex.what());
  }
  return text;
}

}  // namespace refmap
