#pragma once
// The scene names of the options whose keys the components parse themselves (their kinds:
// solver/model/component_kind.hpp), declared here so that the loader, the command line and
// the components see them through one light header (the core's names are in
// solver/scene/option_names.hpp, which includes this one). Each list is defined in the file
// of the kind that reads it:
//  * the solids' [solids] and [[solid]] options: solver/components/solids_keys.cpp;
//  * a rigid body's motion and forcing: solver/components/rigid_bodies.cpp;
//  * the implicit step's time.solid_picard_force: solver/components/implicit_velocity_step.cpp.
#include <span>

#include "kernels/reference_map.hpp"
#include "solver/io/enum_names.hpp"
#include "solver/model/config.hpp"

namespace refmap {

// the solids
std::span<const OptionName<ExtrapolationMethod>> option_names(ExtrapolationMethod);
std::span<const OptionName<ConstitutiveLaw>> option_names(ConstitutiveLaw);
std::span<const OptionName<StressForm>> option_names(StressForm);
std::span<const OptionName<StressBlend>> option_names(StressBlend);
std::span<const OptionName<XiFlux>> option_names(XiFlux);
std::span<const OptionName<XiVelocity>> option_names(XiVelocity);
std::span<const OptionName<SolidVelocity>> option_names(SolidVelocity);
// the rigid bodies
std::span<const OptionName<SolidMotion>> option_names(SolidMotion);
std::span<const OptionName<BodyForcing>> option_names(BodyForcing);
std::span<const OptionName<ForcingInterpolation>> option_names(ForcingInterpolation);
std::span<const OptionName<CutFaces>> option_names(CutFaces);
// the implicit velocity step
std::span<const OptionName<PicardForce>> option_names(PicardForce);

}  // namespace refmap
