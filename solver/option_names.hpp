#pragma once
// The scene-file names of the physics options, in one place. The loader
// (solver/scene.cpp) parses a name into its enum once; everything after loading works on
// the enum, and output (timings.csv, log lines, solver names) prints to_string(e).
//
// Each enum has a list of {value, name}; the first name of a value is its canonical
// spelling (printed, documented, offered in error messages), later ones are accepted
// aliases (e.g. shape = "rectangle").
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kernels/advection.hpp"
#include "kernels/reference_map.hpp"
#include "solver/config.hpp"
#include "solver/poisson.hpp"
#include "solver/shape.hpp"

namespace refmap {

template <class E>
struct OptionName {
  E value;
  const char* name;
};

// The name lists (tag dispatch on a value of the enum); defined in option_names.cpp.
std::span<const OptionName<BcType>> option_names(BcType);
std::span<const OptionName<FlowMode>> option_names(FlowMode);
std::span<const OptionName<FluxScheme>> option_names(FluxScheme);
std::span<const OptionName<InitialKind>> option_names(InitialKind);
std::span<const OptionName<SolidVelocity>> option_names(SolidVelocity);
std::span<const OptionName<SolidMotion>> option_names(SolidMotion);
std::span<const OptionName<BodyForcing>> option_names(BodyForcing);
std::span<const OptionName<BodyForceEstimator>> option_names(BodyForceEstimator);
std::span<const OptionName<ExtrapolationMethod>> option_names(ExtrapolationMethod);
std::span<const OptionName<ConstitutiveLaw>> option_names(ConstitutiveLaw);
std::span<const OptionName<StressForm>> option_names(StressForm);
std::span<const OptionName<StressBlend>> option_names(StressBlend);
std::span<const OptionName<ViscousTime>> option_names(ViscousTime);
std::span<const OptionName<Splitting>> option_names(Splitting);
std::span<const OptionName<SolidStressTime>> option_names(SolidStressTime);
std::span<const OptionName<JumpFlux>> option_names(JumpFlux);
std::span<const OptionName<XiFlux>> option_names(XiFlux);
std::span<const OptionName<PoissonMethod>> option_names(PoissonMethod);
std::span<const OptionName<MgCycle>> option_names(MgCycle);
std::span<const OptionName<MgSmoother>> option_names(MgSmoother);
std::span<const OptionName<MgCoarseOperator>> option_names(MgCoarseOperator);
std::span<const OptionName<ShapeKind>> option_names(ShapeKind);

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

}  // namespace refmap
