// Scene files: TOML -> Config. See scenes/README.md for the key reference.
//
// Structure: every table of the schema is read through a Table helper that knows its
// dotted prefix, hands out typed values (with defaults, type and range checks) and
// rejects keys that are not in its allowed list. Adding a key = one name in allow() plus
// one getter call; adding a table = one name in the top-level allow() plus a parse_xxx.
#include "solver/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include <toml++/toml.h>

#include "solver/expression.hpp"

namespace refmap {

double SideBc::speed(double t) const {
  if (type != BcType::MovingWall) return 0.0;
  return oscillating ? velocity * std::sin(omega * t + phase) : velocity;
}

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

namespace {

// ---------------------------------------------------------------------------------------
// small utilities

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

std::string join(const std::vector<std::string>& v, const std::string& sep, bool quote = false) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += sep;
    s += quote ? dq(v[i]) : v[i];
  }
  return s;
}

// ---------------------------------------------------------------------------------------
// context: the file name (for messages) and which keys came from --set

struct Ctx {
  std::string file;
  std::vector<std::string> overridden;  // normalised dotted keys ("probe[0].points")

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

// ---------------------------------------------------------------------------------------
// a table of the schema

class Table {
 public:
  Table(const Ctx& ctx, const toml::table& t, std::string prefix) : ctx_(ctx), t_(t), prefix_(std::move(prefix)) {}

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

  /// Rejects every key that is not in `allowed`, reporting the first one in the file.
  void allow(std::initializer_list<const char*> allowed) const {
    std::vector<std::string> names(allowed.begin(), allowed.end());
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
    std::string sug = suggestion(worst_key, names, false);
    if (!sug.empty())
      what += sug;
    else
      what += names.empty() ? " (this table takes no keys)" : " (allowed: " + join(names, ", ") + ")";
    ctx_.fail(full(worst_key), worst, what, &worst_k->source());
  }

  // ---- typed getters. `def` = nullopt means required.

  double number(std::string_view key, std::optional<double> def = std::nullopt) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    double v;
    if (auto f = n->as_floating_point()) v = f->get();
    else if (auto i = n->as_integer()) v = double(i->get());
    else fail(key, "expected a number, got " + describe(*n));
    if (!std::isfinite(v)) fail(key, "must be a finite number, got " + fmt_num(v));
    return v;
  }

  long integer(std::string_view key, std::optional<long> def = std::nullopt) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    if (auto i = n->as_integer()) return long(i->get());
    if (auto f = n->as_floating_point()) {
      if (std::isfinite(f->get()) && f->get() == std::floor(f->get()))
        fail(key, "expected an integer, got a float (write " + fmt_num(f->get()) + " without the decimal point)");
    }
    fail(key, "expected an integer, got " + describe(*n));
  }

  bool boolean(std::string_view key, std::optional<bool> def = std::nullopt) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    if (auto b = n->as_boolean()) return b->get();
    fail(key, "expected true or false, got " + describe(*n));
  }

  std::string string(std::string_view key, std::optional<std::string> def = std::nullopt) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    if (auto s = n->as_string()) return s->get();
    fail(key, "expected a string, got " + describe(*n));
  }

  /// A string that must be one of `choices`.
  std::string choice(std::string_view key, const std::vector<std::string>& choices,
                     std::optional<std::string> def = std::nullopt) const {
    std::string s = string(key, def);
    for (const auto& c : choices)
      if (s == c) return s;
    fail(key, "unknown value " + dq(s) + suggestion(s, choices, true) + " (expected one of " +
                  join(choices, ", ", true) + ")");
  }

  std::array<double, 2> vec2(std::string_view key, std::optional<std::array<double, 2>> def = std::nullopt) const {
    const toml::node* n = node(key);
    if (!n) {
      if (!def) fail_missing(key);
      return *def;
    }
    const toml::array* a = n->as_array();
    if (!a) fail(key, "expected an array of two numbers [a, b], got " + describe(*n));
    if (a->size() != 2) fail(key, "expected an array of two numbers [a, b], got " + std::to_string(a->size()) + " elements");
    std::array<double, 2> out{};
    for (std::size_t i = 0; i < 2; ++i) {
      const toml::node& e = *a->get(i);
      if (auto f = e.as_floating_point()) out[i] = f->get();
      else if (auto in = e.as_integer()) out[i] = double(in->get());
      else fail(key, "expected an array of two numbers [a, b], element " + std::to_string(i) + " is " + describe(e));
      if (!std::isfinite(out[i])) fail(key, "elements must be finite numbers");
    }
    return out;
  }

  /// A sub-table; nullptr if absent and not required.
  const toml::table* table(std::string_view key, bool required) const {
    const toml::node* n = node(key);
    if (!n) {
      if (required) ctx_.fail(full(key), nullptr, "missing required table [" + full(key) + "]");
      return nullptr;
    }
    if (auto t = n->as_table()) return t;
    fail(key, "expected a table [" + full(key) + "], got " + describe(*n));
  }

  // ---- range checks on a value already read
  void require(bool ok, std::string_view key, const std::string& what) const {
    if (!ok) fail(key, what);
  }

 private:
  const Ctx& ctx_;
  const toml::table& t_;
  std::string prefix_;
};

// ---------------------------------------------------------------------------------------
// --set overrides

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
std::vector<PathComp> parse_key_path(const Ctx& ctx, const std::string& key, const std::string& arg, std::string& norm) {
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

void apply_override(Ctx& ctx, toml::table& root, const std::string& arg) {
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

// ---------------------------------------------------------------------------------------
// the schema

void parse_domain_grid(const Ctx& ctx, const Table& top, Config& cfg) {
  Table grid(ctx, *top.table("grid", true), "grid");
  grid.allow({"nx", "ny"});
  const long nx = grid.integer("nx");
  const long ny = grid.integer("ny");
  constexpr long kMax = 1L << 20;
  for (auto [key, n] : {std::pair<const char*, long>{"nx", nx}, {"ny", ny}}) {
    grid.require(n >= 8, key, "must be >= 8 (the multigrid solver needs at least 8 cells per direction), got " + std::to_string(n));
    grid.require(n <= kMax, key, "must be <= " + std::to_string(kMax) + ", got " + std::to_string(n));
  }
  grid.require(double(nx) * double(ny) <= 2.0e9, "ny", "grid too large: nx * ny must be <= 2e9");
  cfg.grid.nx = int(nx);
  cfg.grid.ny = int(ny);

  Table dom(ctx, *top.table("domain", true), "domain");
  dom.allow({"x0", "y0", "lx", "ly"});
  cfg.grid.x0 = dom.number("x0", 0.0);
  cfg.grid.y0 = dom.number("y0", 0.0);
  const double lx = dom.number("lx");
  dom.require(lx > 0, "lx", "must be > 0, got " + fmt_num(lx));
  const double ly_expected = lx * double(ny) / double(nx);
  if (dom.has("ly")) {
    const double ly = dom.number("ly");
    dom.require(ly > 0, "ly", "must be > 0, got " + fmt_num(ly));
    dom.require(std::fabs(ly - ly_expected) <= 1e-12 * ly_expected, "ly",
                "must equal domain.lx * grid.ny / grid.nx = " + fmt_num(ly_expected) +
                    " (cells must be square, dx = dy), got " + fmt_num(ly));
  }
  cfg.grid.dx = lx / double(nx);
}

void parse_fluid(const Ctx& ctx, const Table& top, Config& cfg) {
  Table f(ctx, *top.table("fluid", true), "fluid");
  f.allow({"density", "viscosity"});
  cfg.rho_f = f.number("density", 1.0);
  f.require(cfg.rho_f > 0, "density", "must be > 0, got " + fmt_num(cfg.rho_f));
  cfg.mu_f = f.number("viscosity");
  f.require(cfg.mu_f >= 0, "viscosity", "must be >= 0, got " + fmt_num(cfg.mu_f));
}

SideBc parse_side(const Ctx& ctx, const Table& b, const char* side) {
  static const std::vector<std::string> kinds = {"no_slip", "free_slip", "periodic", "moving_wall"};
  const toml::node* n = b.node(side);
  if (!n) b.fail_missing(side);
  SideBc bc;
  auto set_kind = [&](const std::string& s, auto&& failer) {
    if (s == "no_slip") bc.type = BcType::NoSlip;
    else if (s == "free_slip") bc.type = BcType::FreeSlip;
    else if (s == "periodic") bc.type = BcType::Periodic;
    else if (s == "moving_wall") bc.type = BcType::MovingWall;
    else
      failer("unknown boundary condition " + dq(s) + suggestion(s, kinds, true) +
             " (expected \"no_slip\", \"free_slip\", \"periodic\" or { type = \"moving_wall\", velocity = ... })");
  };
  if (auto s = n->as_string()) {
    set_kind(s->get(), [&](const std::string& w) { b.fail(side, w); });
    if (bc.type == BcType::MovingWall)
      b.fail(side, "a moving wall needs a velocity: write { type = \"moving_wall\", velocity = 1.0 }");
    return bc;
  }
  const toml::table* t = n->as_table();
  if (!t)
    b.fail(side, "expected a boundary condition (\"no_slip\", \"free_slip\", \"periodic\" or { type = \"moving_wall\", "
                 "velocity = ... }), got " + describe(*n));
  Table s(ctx, *t, b.full(side));
  s.allow({"type", "velocity", "omega", "phase"});
  set_kind(s.string("type"), [&](const std::string& w) { s.fail("type", w); });
  if (bc.type != BcType::MovingWall) {
    for (const char* k : {"velocity", "omega", "phase"})
      if (s.has(k)) s.fail(k, "only a moving_wall takes a velocity, omega or phase");
    return bc;
  }
  bc.velocity = s.number("velocity");
  if (s.has("omega")) {
    bc.oscillating = true;
    bc.omega = s.number("omega");
    s.require(bc.omega > 0, "omega", "must be > 0, got " + fmt_num(bc.omega));
    bc.phase = s.number("phase", 0.0);
  } else if (s.has("phase")) {
    s.fail("phase", "phase needs omega (speed = velocity * sin(omega t + phase))");
  }
  return bc;
}

void parse_boundary(const Ctx& ctx, const Table& top, Config& cfg) {
  Table b(ctx, *top.table("boundary", true), "boundary");
  b.allow({"left", "right", "bottom", "top"});
  const char* names[4] = {"left", "right", "bottom", "top"};
  for (int s = 0; s < 4; ++s) cfg.bc[s] = parse_side(ctx, b, names[s]);
  for (auto [a, c] : {std::pair<int, int>{Left, Right}, {Bottom, Top}}) {
    const bool pa = cfg.bc[a].type == BcType::Periodic, pc = cfg.bc[c].type == BcType::Periodic;
    if (pa != pc) {
      const int bad = pa ? c : a, good = pa ? a : c;
      b.fail(names[bad], std::string("must be \"periodic\" because boundary.") + names[good] +
                             " is: periodic must be set on both sides of a direction");
    }
  }
}

void parse_initial(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* t = top.table("initial", false);
  if (!t) return;
  Table in(ctx, *t, "initial");
  in.allow({"velocity", "u", "v", "amplitude", "wavenumber", "u_expr", "v_expr"});
  InitialVelocity& iv = cfg.init;
  iv.kind = in.choice("velocity", {"zero", "uniform", "taylor_green", "expression"}, std::string("zero"));
  struct Use { const char* key; const char* kind; };
  for (Use u : {Use{"u", "uniform"}, {"v", "uniform"}, {"amplitude", "taylor_green"}, {"wavenumber", "taylor_green"},
                {"u_expr", "expression"}, {"v_expr", "expression"}})
    if (in.has(u.key) && iv.kind != u.kind)
      in.fail(u.key, std::string("only used with initial.velocity = \"") + u.kind + "\" (velocity is \"" + iv.kind + "\")");
  if (iv.kind == "uniform") {
    iv.u = in.number("u", 0.0);
    iv.v = in.number("v", 0.0);
  } else if (iv.kind == "taylor_green") {
    iv.amplitude = in.number("amplitude", 1.0);
    iv.wavenumber = in.number("wavenumber", 0.0);
    in.require(iv.wavenumber >= 0, "wavenumber", "must be >= 0 (0 means 2 pi / domain.lx), got " + fmt_num(iv.wavenumber));
  } else if (iv.kind == "expression") {
    // a plain number is accepted as an expression too (u_expr = 0)
    auto expr_text = [&](const char* key) {
      const toml::node* n = in.node(key);
      if (n && n->as_integer()) return std::to_string(n->as_integer()->get());
      if (n && n->as_floating_point()) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", n->as_floating_point()->get());
        return std::string(buf);
      }
      return in.string(key);
    };
    iv.u_expr = expr_text("u_expr");
    iv.v_expr = expr_text("v_expr");
    for (const char* k : {"u_expr", "v_expr"}) {
      const std::string& text = std::string(k) == "u_expr" ? iv.u_expr : iv.v_expr;
      try {
        Expression e(text);
        (void)e;
      } catch (const std::invalid_argument& ex) {
        in.fail(k, "invalid expression " + dq(text) + ": " + ex.what());
      }
    }
  }
}

void parse_gravity(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* t = top.table("gravity", false);
  if (!t) return;
  Table g(ctx, *t, "gravity");
  g.allow({"g"});
  const auto v = g.vec2("g", std::array<double, 2>{0.0, 0.0});
  cfg.gx = v[0];
  cfg.gy = v[1];
}

void parse_time(const Ctx& ctx, const Table& top, Config& cfg) {
  Table t(ctx, *top.table("time", true), "time");
  t.allow({"start", "end", "cfl", "viscous_safety", "dt", "dt_max", "max_steps", "steady_tol"});
  cfg.t_start = t.number("start", 0.0);
  cfg.t_end = t.number("end");
  t.require(cfg.t_end > cfg.t_start, "end",
            "must be > time.start = " + fmt_num(cfg.t_start) + ", got " + fmt_num(cfg.t_end));
  cfg.cfl = t.number("cfl", 0.5);
  t.require(cfg.cfl > 0 && cfg.cfl <= 2.5, "cfl", "must be in (0, 2.5], got " + fmt_num(cfg.cfl));
  cfg.visc_safety = t.number("viscous_safety", 0.9);
  t.require(cfg.visc_safety > 0 && cfg.visc_safety <= 1, "viscous_safety",
            "must be in (0, 1], got " + fmt_num(cfg.visc_safety));
  cfg.dt_fixed = t.number("dt", 0.0);
  t.require(cfg.dt_fixed >= 0, "dt", "must be >= 0 (0 = adaptive), got " + fmt_num(cfg.dt_fixed));
  cfg.dt_max = t.number("dt_max", 1e30);
  t.require(cfg.dt_max > 0, "dt_max", "must be > 0, got " + fmt_num(cfg.dt_max));
  cfg.max_steps = t.integer("max_steps", 0);
  t.require(cfg.max_steps >= 0, "max_steps", "must be >= 0 (0 = unlimited), got " + std::to_string(cfg.max_steps));
  cfg.steady_tol = t.number("steady_tol", 0.0);
  t.require(cfg.steady_tol >= 0, "steady_tol", "must be >= 0 (0 = off), got " + fmt_num(cfg.steady_tol));
}

void parse_solver(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* tp = top.table("solver", false);
  if (!tp) return;
  Table s(ctx, *tp, "solver");
  s.allow({"flow", "advection", "poisson", "cycle", "smoother", "pre_smooth", "post_smooth", "tol", "max_iter",
           "coarse_cells"});
  PoissonOptions& p = cfg.poisson;
  cfg.flow = s.choice("flow", {"solve", "prescribed"}, cfg.flow);
  cfg.advection = s.choice("advection", {"central", "superbee"}, cfg.advection);
  p.method = s.choice("poisson", {"multigrid", "cg", "mgpcg"}, p.method);
  p.cycle = s.choice("cycle", {"V", "F"}, p.cycle);
  p.smoother = s.choice("smoother", {"rbgs", "jacobi"}, p.smoother);
  for (auto [key, dst] : {std::pair<const char*, int*>{"pre_smooth", &p.pre_smooth}, {"post_smooth", &p.post_smooth}}) {
    const long n = s.integer(key, *dst);
    s.require(n >= 1 && n <= 100, key, "must be in [1, 100], got " + std::to_string(n));
    *dst = int(n);
  }
  p.tol = s.number("tol", p.tol);
  s.require(p.tol > 0 && p.tol < 1, "tol", "must be in (0, 1), got " + fmt_num(p.tol));
  const long mi = s.integer("max_iter", p.max_iter);
  s.require(mi >= 1 && mi <= 1000000, "max_iter", "must be in [1, 1000000], got " + std::to_string(mi));
  p.max_iter = int(mi);
  const long cc = s.integer("coarse_cells", p.coarse_cells);
  s.require(cc >= 1 && cc <= 1000000, "coarse_cells", "must be in [1, 1000000], got " + std::to_string(cc));
  p.coarse_cells = int(cc);
}

void parse_output(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* tp = top.table("output", false);
  if (!tp) return;
  Table o(ctx, *tp, "output");
  o.allow({"interval", "vtk", "diagnostics_every", "log_interval"});
  cfg.output_interval = o.number("interval", 0.0);
  o.require(cfg.output_interval >= 0, "interval", "must be >= 0 (0 = first and last frame only), got " + fmt_num(cfg.output_interval));
  cfg.write_vtk = o.boolean("vtk", true);
  const long de = o.integer("diagnostics_every", 1);
  o.require(de >= 1 && de <= std::numeric_limits<int>::max(), "diagnostics_every", "must be >= 1, got " + std::to_string(de));
  cfg.diagnostics_every = int(de);
  cfg.log_interval_s = o.number("log_interval", 2.0);
  o.require(cfg.log_interval_s > 0, "log_interval", "must be > 0 seconds, got " + fmt_num(cfg.log_interval_s));
}

void parse_probes(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::node* n = top.node("probe");
  if (!n) return;
  const toml::array* arr = n->as_array();
  if (!arr) top.fail("probe", "expected an array of tables ([[probe]] sections), got " + describe(*n));
  static const std::vector<std::string> fields = {"u", "v", "p", "speed", "vorticity", "density"};
  const Grid& g = cfg.grid;
  const double tol = 1e-12 * std::max(g.lx(), g.ly());
  std::set<std::string> names;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string prefix = "probe[" + std::to_string(i) + "]";
    const toml::table* t = arr->get(i)->as_table();
    if (!t) ctx.fail(prefix, arr->get(i), "expected a table ([[probe]] section), got " + describe(*arr->get(i)));
    Table p(ctx, *t, prefix);
    p.allow({"name", "field", "start", "end", "points"});
    ProbeSpec spec;
    spec.name = p.string("name");
    bool ok = !spec.name.empty();
    for (char c : spec.name) ok = ok && (std::isalnum((unsigned char)c) || c == '_');
    p.require(ok, "name", "must be a non-empty name of letters, digits and '_' (it names the output file), got " + dq(spec.name));
    p.require(names.insert(spec.name).second, "name", "duplicate probe name " + dq(spec.name));
    spec.field = p.choice("field", fields);
    for (const char* key : {"start", "end"}) {
      const auto xy = p.vec2(key);
      const bool inside = xy[0] >= g.x0 - tol && xy[0] <= g.x0 + g.lx() + tol && xy[1] >= g.y0 - tol &&
                          xy[1] <= g.y0 + g.ly() + tol;
      p.require(inside, key,
                "point [" + fmt_num(xy[0]) + ", " + fmt_num(xy[1]) + "] is outside the domain [" + fmt_num(g.x0) + ", " +
                    fmt_num(g.x0 + g.lx()) + "] x [" + fmt_num(g.y0) + ", " + fmt_num(g.y0 + g.ly()) + "]");
      // snap onto the wall if within round-off of it
      const double x = std::clamp(xy[0], g.x0, g.x0 + g.lx()), y = std::clamp(xy[1], g.y0, g.y0 + g.ly());
      if (std::string(key) == "start") { spec.x0 = x; spec.y0 = y; }
      else { spec.x1 = x; spec.y1 = y; }
    }
    const long pts = p.integer("points");
    p.require(pts >= 2 && pts <= 10000000, "points", "must be in [2, 10000000], got " + std::to_string(pts));
    spec.points = int(pts);
    cfg.probes.push_back(spec);
  }
}

void parse_solids_options(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* tp = top.table("solids", false);
  if (!tp) return;
  Table s(ctx, *tp, "solids");
  s.allow({"extrapolation", "lsq_radius", "band", "transition", "conservative", "stress_discretisation", "xi_advection", "solid_cfl",
           "reinitialise", "pde_tol", "pde_max_iter"});
  SolidsOptions& o = cfg.solid_opt;
  o.extrapolation = s.choice("extrapolation", {"lsq", "pde"}, o.extrapolation);
  o.lsq_radius = s.number("lsq_radius", o.lsq_radius);
  s.require(o.lsq_radius * o.lsq_radius >= 8.0 - 1e-6 && o.lsq_radius * o.lsq_radius < 33.0, "lsq_radius",
            "must be in [2.83, 5.74] (cells: from the 5 x 5 block, 2 sqrt(2), to the paper's 4 sqrt(2) = 5.66), "
            "got " + fmt_num(o.lsq_radius));
  o.band = s.number("band", o.band);
  s.require(o.band > 1, "band", "must be > 1 (cells), got " + fmt_num(o.band));
  o.transition = s.number("transition", o.transition);
  s.require(o.transition > 0, "transition", "must be > 0 (cells), got " + fmt_num(o.transition));
  if (!(o.transition < o.band - 1)) {
    // blame the key the user wrote (the transition if both are given)
    if (s.has("transition"))
      s.fail("transition", "must be < solids.band - 1 = " + fmt_num(o.band - 1) + " (the smoothed interface must lie "
                           "inside the extrapolated band), got " + fmt_num(o.transition));
    s.fail("band", "must be > solids.transition + 1 = " + fmt_num(o.transition + 1) +
                       " (the smoothed interface must lie inside the extrapolated band), got " + fmt_num(o.band));
  }
  o.conservative = s.boolean("conservative", o.conservative);
  o.stress_discretisation = s.choice("stress_discretisation", {"face", "cell"}, o.stress_discretisation);
  o.xi_advection = s.choice("xi_advection", {"central", "superbee", "vanleer"}, o.xi_advection);
  o.solid_cfl = s.number("solid_cfl", o.solid_cfl);
  s.require(o.solid_cfl > 0 && o.solid_cfl <= 2, "solid_cfl", "must be in (0, 2], got " + fmt_num(o.solid_cfl));
  o.reinitialise = s.boolean("reinitialise", o.reinitialise);
  o.pde_tol = s.number("pde_tol", o.pde_tol);
  s.require(o.pde_tol > 0, "pde_tol", "must be > 0, got " + fmt_num(o.pde_tol));
  const long mi = s.integer("pde_max_iter", o.pde_max_iter);
  s.require(mi >= 1 && mi <= 1000000000L, "pde_max_iter", "must be in [1, 1000000000], got " + std::to_string(mi));
  o.pde_max_iter = int(mi);
}

void parse_contact(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::table* tp = top.table("contact", false);
  if (!tp) return;
  Table c(ctx, *tp, "contact");
  c.allow({"enabled", "walls", "range", "stiffness", "velocity_scale"});
  ContactOptions& o = cfg.contact;
  o.enabled = c.boolean("enabled", o.enabled);
  o.walls = c.boolean("walls", o.walls);
  o.range = c.number("range", o.range);
  c.require(o.range > 0 && o.range < cfg.solid_opt.band, "range",
            "must be in (0, solids.band = " + fmt_num(cfg.solid_opt.band) +
                ") cells (the level sets are only known within the band), got " + fmt_num(o.range));
  o.stiffness = c.number("stiffness", o.stiffness);
  c.require(o.stiffness >= 0, "stiffness", "must be >= 0, got " + fmt_num(o.stiffness));
  o.velocity_scale = c.number("velocity_scale", o.velocity_scale);
  c.require(o.velocity_scale >= 0, "velocity_scale",
            "must be >= 0 (0 = automatic), got " + fmt_num(o.velocity_scale));
}

/// Keys of a [[solid]] that belong to the shape, per shape kind.
struct ShapeKeys {
  const char* kind;
  std::vector<std::string> keys;
};

const std::vector<ShapeKeys>& shape_keys() {
  static const std::vector<ShapeKeys> k = {
      {"circle", {"center", "radius"}},
      {"ellipse", {"center", "semi_axes", "angle"}},
      {"rounded_rectangle", {"center", "half_size", "corner_radius", "angle"}},
      {"zalesak", {"center", "radius", "slot_half_width", "slot_top", "angle"}},
      {"tabulated", {"file"}},
  };
  return k;
}

void parse_solids(const Ctx& ctx, const Table& top, Config& cfg) {
  const toml::node* n = top.node("solid");
  if (!n) return;
  const toml::array* arr = n->as_array();
  if (!arr) top.fail("solid", "expected an array of tables ([[solid]] sections), got " + describe(*n));
  std::vector<std::string> kinds;
  std::vector<std::string> all_shape_keys;
  for (const auto& sk : shape_keys()) {
    kinds.push_back(sk.kind);
    for (const auto& k : sk.keys)
      if (std::find(all_shape_keys.begin(), all_shape_keys.end(), k) == all_shape_keys.end()) all_shape_keys.push_back(k);
  }
  const Grid& g = cfg.grid;
  const std::filesystem::path scene_dir = std::filesystem::path(ctx.file).parent_path();
  // a prescribed flow moves the solids kinematically: their material is not used
  const bool need_material = cfg.flow == "solve";
  std::set<std::string> names;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string prefix = "solid[" + std::to_string(i) + "]";
    const toml::table* t = arr->get(i)->as_table();
    if (!t) ctx.fail(prefix, arr->get(i), "expected a table ([[solid]] section), got " + describe(*arr->get(i)));
    Table s(ctx, *t, prefix);
    s.allow({"name", "shape", "center", "radius", "semi_axes", "half_size", "corner_radius", "slot_half_width",
             "slot_top", "angle", "file", "mu_s", "model", "c3", "density", "viscosity", "velocity", "u", "v", "omega"});
    SolidSpec sp;

    sp.name = s.string("name", "solid" + std::to_string(i));
    bool ok = !sp.name.empty();
    for (char c : sp.name) ok = ok && (std::isalnum((unsigned char)c) || c == '_');
    s.require(ok, "name", "must be a non-empty name of letters, digits and '_', got " + dq(sp.name));
    s.require(names.insert(sp.name).second, "name", "duplicate solid name " + dq(sp.name));

    // ---- shape
    ShapeParams& sh = sp.shape;
    sh.kind = s.choice("shape", kinds);
    const std::vector<std::string>* own = nullptr;
    for (const auto& sk : shape_keys())
      if (sh.kind == sk.kind) own = &sk.keys;
    for (const auto& k : all_shape_keys)
      if (s.has(k) && std::find(own->begin(), own->end(), k) == own->end())
        s.fail(k, "not a parameter of shape = " + dq(sh.kind) + " (it takes " + join(*own, ", ") + ")");

    auto positive = [&](const char* key, double v) {
      s.require(v > 0, key, "must be > 0, got " + fmt_num(v));
    };
    if (sh.kind != "tabulated") {
      const auto c = s.vec2("center");
      sh.cx = c[0];
      sh.cy = c[1];
      sh.angle = sh.kind == "circle" ? 0.0 : s.number("angle", 0.0);
    }
    if (sh.kind == "circle" || sh.kind == "zalesak") {
      sh.radius = s.number("radius");
      positive("radius", sh.radius);
    }
    if (sh.kind == "ellipse") {
      const auto ab = s.vec2("semi_axes");
      s.require(ab[0] > 0 && ab[1] > 0, "semi_axes",
                "both semi-axes must be > 0, got [" + fmt_num(ab[0]) + ", " + fmt_num(ab[1]) + "]");
      sh.a = ab[0];
      sh.b = ab[1];
    } else if (sh.kind == "rounded_rectangle") {
      const auto hs = s.vec2("half_size");
      s.require(hs[0] > 0 && hs[1] > 0, "half_size",
                "both half-sizes must be > 0, got [" + fmt_num(hs[0]) + ", " + fmt_num(hs[1]) + "]");
      sh.half_width = hs[0];
      sh.half_height = hs[1];
      sh.corner_radius = s.number("corner_radius", 0.0);
      const double rmax = std::min(hs[0], hs[1]);
      s.require(sh.corner_radius >= 0 && sh.corner_radius <= rmax, "corner_radius",
                "must be in [0, min(half_size) = " + fmt_num(rmax) + "], got " + fmt_num(sh.corner_radius));
    } else if (sh.kind == "zalesak") {
      sh.slot_half_width = s.number("slot_half_width");
      s.require(sh.slot_half_width > 0 && sh.slot_half_width < sh.radius, "slot_half_width",
                "must be in (0, radius = " + fmt_num(sh.radius) + "), got " + fmt_num(sh.slot_half_width));
      sh.slot_top = s.number("slot_top");
      const double h = std::sqrt(sh.radius * sh.radius - sh.slot_half_width * sh.slot_half_width);
      s.require(sh.slot_top > sh.cy - h && sh.slot_top < sh.cy + h, "slot_top",
                "must be strictly between the y where the slot walls meet the circle, (" + fmt_num(sh.cy - h) + ", " +
                    fmt_num(sh.cy + h) + "), got " + fmt_num(sh.slot_top));
    } else if (sh.kind == "tabulated") {
      const std::string f = s.string("file");
      s.require(!f.empty(), "file", "must be a non-empty path");
      std::filesystem::path fp(f);
      if (fp.is_relative() && !scene_dir.empty()) fp = scene_dir / fp;
      sh.file = fp.lexically_normal().string();
      std::error_code ec;
      if (!std::filesystem::exists(sh.file, ec))
        s.fail("file", "cannot read " + dq(sh.file) + ": no such file" +
                           (std::filesystem::path(f).is_relative() ? " (relative paths are relative to the scene file's directory)"
                                                                   : ""));
      if (std::filesystem::is_directory(sh.file, ec)) s.fail("file", "cannot read " + dq(sh.file) + ": is a directory");
    }

    // build it now, so that bad geometry fails at load time
    const char* shape_key = sh.kind == "tabulated" ? "file" : "shape";
    std::unique_ptr<Shape> shape;
    try {
      shape = make_shape(sh);
    } catch (const std::exception& e) {
      s.fail(shape_key, std::string("invalid geometry: ") + e.what());
    }
    const BoundingBox bb = shape->bbox();
    const double X0 = g.x0, X1 = g.x0 + g.lx(), Y0 = g.y0, Y1 = g.y0 + g.ly();
    if (!(bb.xmax > X0 && bb.xmin < X1 && bb.ymax > Y0 && bb.ymin < Y1))
      s.fail(sh.kind == "tabulated" ? "file" : "center",
             "the solid lies outside the domain: its bounding box [" + fmt_num(bb.xmin) + ", " + fmt_num(bb.xmax) +
                 "] x [" + fmt_num(bb.ymin) + ", " + fmt_num(bb.ymax) + "] does not intersect the domain [" +
                 fmt_num(X0) + ", " + fmt_num(X1) + "] x [" + fmt_num(Y0) + ", " + fmt_num(Y1) + "]");

    // ---- material
    const std::optional<double> no_default;
    sp.mu_s = s.number("mu_s", need_material ? no_default : std::optional<double>(0.0));
    s.require(sp.mu_s >= 0, "mu_s", "must be >= 0, got " + fmt_num(sp.mu_s));
    if (s.choice("model", {"neo_hookean", "strain_stiffening"}, std::string("neo_hookean")) == "strain_stiffening") {
      sp.model = ConstitutiveLaw::StrainStiffening;
      sp.c3 = s.number("c3");
      s.require(sp.c3 >= 0, "c3", "must be >= 0, got " + fmt_num(sp.c3));
      s.require(sp.mu_s > 0 || !need_material, "mu_s", "must be > 0 with model = \"strain_stiffening\" (it is c1)");
    } else if (s.has("c3")) {
      s.fail("c3", "only used with model = \"strain_stiffening\"");
    }
    sp.density = s.number("density", need_material ? no_default : std::optional<double>(1.0));
    s.require(sp.density > 0, "density", "must be > 0, got " + fmt_num(sp.density));
    sp.viscosity = s.number("viscosity", 0.0);
    s.require(sp.viscosity >= 0, "viscosity", "must be >= 0, got " + fmt_num(sp.viscosity));

    // ---- initial velocity
    sp.velocity = s.choice("velocity", {"rigid", "fluid"}, std::string("rigid"));
    if (sp.velocity == "fluid") {
      for (const char* k : {"u", "v", "omega"})
        if (s.has(k)) s.fail(k, "only used with velocity = \"rigid\" (velocity is \"fluid\": the solid keeps the fluid's velocity)");
    } else {
      sp.u = s.number("u", 0.0);
      sp.v = s.number("v", 0.0);
      sp.omega = s.number("omega", 0.0);
    }
    cfg.solids.push_back(std::move(sp));
  }
}

Config build_config(Ctx& ctx, toml::table& root, const std::vector<std::string>& sets) {
  for (const auto& s : sets) apply_override(ctx, root, s);

  Config cfg;
  cfg.scene_path = ctx.file;
  Table top(ctx, root, "");
  top.allow({"name", "domain", "grid", "fluid", "boundary", "initial", "gravity", "time", "solver", "output", "probe",
             "solids", "solid", "contact"});

  cfg.name = std::filesystem::path(ctx.file).stem().string();
  if (top.has("name")) {
    cfg.name = top.string("name");
    const bool ok = !cfg.name.empty() && cfg.name != "." && cfg.name != ".." &&
                    cfg.name.find_first_of("/\\") == std::string::npos;
    top.require(ok, "name", "must be a non-empty name without '/' (it names the output directory), got " + dq(cfg.name));
  }
  if (cfg.name.empty()) cfg.name = "scene";

  parse_domain_grid(ctx, top, cfg);
  parse_fluid(ctx, top, cfg);
  parse_boundary(ctx, top, cfg);
  parse_initial(ctx, top, cfg);
  parse_gravity(ctx, top, cfg);
  parse_time(ctx, top, cfg);
  parse_solver(ctx, top, cfg);
  parse_output(ctx, top, cfg);
  parse_probes(ctx, top, cfg);
  parse_solids_options(ctx, top, cfg);  // after parse_solver: the solids need cfg.flow
  parse_solids(ctx, top, cfg);
  parse_contact(ctx, top, cfg);  // after parse_solids_options: the range is checked against the band
  return cfg;
}

}  // namespace

Config load_scene_string(const std::string& text, const std::string& path, const std::vector<std::string>& sets) {
  Ctx ctx;
  ctx.file = path;
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw SceneError(path, "", "TOML syntax error: " + std::string(e.description()), long(b.line), long(b.column));
  }
  return build_config(ctx, root, sets);
}

Config load_scene(const std::string& path, const std::vector<std::string>& sets) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError(path, "", "cannot read scene file: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const bool exists = std::filesystem::exists(path, ec);
    throw SceneError(path, "", exists ? "cannot read scene file: permission denied or unreadable"
                                      : "cannot read scene file: no such file");
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw SceneError(path, "", "cannot read scene file: read error");
  return load_scene_string(ss.str(), path, sets);
}

}  // namespace refmap
