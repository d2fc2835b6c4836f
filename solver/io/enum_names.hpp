#pragma once
// Names of enum values, generic: an enum E gets a list of {value, name} by declaring
//     std::span<const OptionName<E>> option_names(E);
// next to it (found by argument-dependent lookup), and to_string / parse_option /
// canonical_names work on it. The first name of a value is its canonical spelling
// (printed, documented, offered in error messages), later ones are accepted aliases
// (e.g. shape = "rectangle"). Includes nothing of refmap, so every layer may use it: the
// pressure solvers name their options here without knowing the scene
// (solver/pressure/poisson.hpp), the scene loader parses names once into enums
// (solver/scene/option_names.hpp).
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace refmap {

template <class E>
struct OptionName {
  E value;
  const char* name;
};

/// Canonical name of an option value ("?" for a value outside the list).
template <class E>
const char* to_string(E e) {
  for (const auto& n : option_names(E{}))
    if (n.value == e) return n.name;
  return "?";
}

/// The value named `s` (canonical name or alias), or nullopt.
template <class E>
std::optional<E> parse_option(std::string_view s) {
  for (const auto& n : option_names(E{}))
    if (s == n.name) return n.value;
  return std::nullopt;
}

/// The canonical names, in list order (aliases left out).
template <class E>
std::vector<std::string> canonical_names() {
  std::vector<std::string> out;
  std::vector<E> seen;
  for (const auto& n : option_names(E{})) {
    bool dup = false;
    for (E v : seen) dup = dup || v == n.value;
    if (dup) continue;
    seen.push_back(n.value);
    out.emplace_back(n.name);
  }
  return out;
}

/// A span over a static name list (for the definitions of option_names).
template <class E, std::size_t N>
std::span<const OptionName<E>> name_list(const OptionName<E> (&a)[N]) {
  return {a, N};
}

}  // namespace refmap
