#pragma once
// The solids' scene keys: the kind `solids` (solver/model/component_kind.hpp), defined in
// solids_keys.cpp, declares the keys of `[solids]` (the options every solid shares) and of
// `[[solid]]` (each solid's shape, material and initial velocity; a rigid body's keys in the
// same table are the rigid bodies' kind's, solver/components/rigid_bodies.hpp) and reads them
// into Config::solid_opt and Config::solids, which the core reads too (the loader's start
// checks, contact, the markers, the Simulation). The Solids component itself is made by the
// Simulation (solver/components/solids.hpp). Here: the scene names of the solids' options.
#include <span>

#include "kernels/reference_map.hpp"
#include "solver/io/enum_names.hpp"
#include "solver/model/config.hpp"

namespace refmap {

std::span<const OptionName<ExtrapolationMethod>> option_names(ExtrapolationMethod);
std::span<const OptionName<ConstitutiveLaw>> option_names(ConstitutiveLaw);
std::span<const OptionName<StressForm>> option_names(StressForm);
std::span<const OptionName<StressBlend>> option_names(StressBlend);
std::span<const OptionName<XiFlux>> option_names(XiFlux);
std::span<const OptionName<XiVelocity>> option_names(XiVelocity);
std::span<const OptionName<SolidVelocity>> option_names(SolidVelocity);

}  // namespace refmap
