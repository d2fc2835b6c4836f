#pragma once
// The scene-file names of the physics options of solver/model/config.hpp. The loader
// (solver/scene/scene.cpp) parses a name into its enum once; everything after loading works on
// the enum, and output (timings.csv, log lines, solver names) prints to_string(e)
// (the templates are in solver/io/enum_names.hpp, which the lower layers use for their own
// enums).
#include <span>

#include "kernels/advection.hpp"
#include "kernels/reference_map.hpp"
#include "solver/model/config.hpp"
#include "solver/io/enum_names.hpp"

namespace refmap {

// The name lists (tag dispatch on a value of the enum); defined in option_names.cpp.
std::span<const OptionName<BcType>> option_names(BcType);
std::span<const OptionName<FlowMode>> option_names(FlowMode);
std::span<const OptionName<FluxScheme>> option_names(FluxScheme);
std::span<const OptionName<InitialKind>> option_names(InitialKind);
std::span<const OptionName<SolidVelocity>> option_names(SolidVelocity);
std::span<const OptionName<SolidMotion>> option_names(SolidMotion);
std::span<const OptionName<BodyForcing>> option_names(BodyForcing);
std::span<const OptionName<ForcingInterpolation>> option_names(ForcingInterpolation);
std::span<const OptionName<ExtrapolationMethod>> option_names(ExtrapolationMethod);
std::span<const OptionName<ConstitutiveLaw>> option_names(ConstitutiveLaw);
std::span<const OptionName<StressForm>> option_names(StressForm);
std::span<const OptionName<StressBlend>> option_names(StressBlend);
std::span<const OptionName<ViscousTime>> option_names(ViscousTime);
std::span<const OptionName<SolidStressTime>> option_names(SolidStressTime);
std::span<const OptionName<ElasticCoupling>> option_names(ElasticCoupling);
std::span<const OptionName<PicardForce>> option_names(PicardForce);
std::span<const OptionName<JumpFlux>> option_names(JumpFlux);
std::span<const OptionName<XiFlux>> option_names(XiFlux);
std::span<const OptionName<XiVelocity>> option_names(XiVelocity);
std::span<const OptionName<Splitting>> option_names(Splitting);

// Declared next to their enums, with the names: the pressure solver's options
// (solver/pressure/poisson.hpp), the shapes (solver/model/shape_params.hpp), the body-force estimator
// (solver/components/control_volume_forces.hpp).

}  // namespace refmap
