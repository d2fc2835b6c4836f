// Key descriptions and their catalogue (see solver/io/key_def.hpp).
#include "solver/io/key_def.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace refmap {

std::string key_number_text(double v) {
  char buf[64];
  if (v == std::floor(v) && std::fabs(v) < 1e15) {  // integers in full: 100, 1000000000
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  for (int prec = 1; prec <= 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::string s = buf;
  // 1e-08 -> 1e-8
  const auto e = s.find('e');
  if (e != std::string::npos) {
    std::size_t d = e + 1;
    if (d < s.size() && (s[d] == '-' || s[d] == '+')) ++d;
    while (d + 1 < s.size() && s[d] == '0') s.erase(d, 1);
    if (s[e + 1] == '+') s.erase(e + 1, 1);
  }
  return s;
}

bool KeyRange::contains(double v) const {
  if (lo && (lo_open ? !(v > *lo) : !(v >= *lo))) return false;
  if (hi && (hi_open ? !(v < *hi) : !(v <= *hi))) return false;
  return true;
}

std::string KeyRange::phrase() const {
  if (!text.empty()) return text;
  if (lo && hi)
    return std::string("in ") + (lo_open ? "(" : "[") + key_number_text(*lo) + ", " + key_number_text(*hi) + (hi_open ? ")" : "]");
  if (lo) return std::string(lo_open ? "> " : ">= ") + key_number_text(*lo);
  if (hi) return std::string(hi_open ? "< " : "<= ") + key_number_text(*hi);
  return "";
}

const KeyDef* KeyCatalog::find(const std::string& table, const std::string& name) const {
  for (const auto& k : keys)
    if (k.table == table && k.name == name) return &k;
  return nullptr;
}

const KeyDef& KeyCatalog::key(const std::string& table, const std::string& name) const {
  if (const KeyDef* k = find(table, name)) return *k;
  throw std::logic_error("key " + (table.empty() ? name : table + "." + name) + " is not in the key table");
}

std::vector<std::string> KeyCatalog::key_names(const std::string& table) const {
  std::vector<std::string> out;
  for (const auto& k : keys)
    if (k.table == table) out.push_back(k.name);
  return out;
}

std::vector<std::string> KeyCatalog::top_level_names() const {
  std::vector<std::string> out = key_names("");
  for (const auto& t : tables)
    if (!t.name.empty() && !t.nested) out.push_back(t.name);
  return out;
}

}  // namespace refmap
