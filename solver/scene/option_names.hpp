#pragma once
// The scene-file names of the physics options of solver/model/config.hpp. The loader
// (solver/scene/scene.cpp) parses a name into its enum once; everything after loading works on
// the enum, and output (timings.csv, log lines, solver names) prints to_string(e)
// (the templates are in solver/io/enum_names.hpp, which the lower layers use for their own
// enums).
#include <span>

#include "kernels/advection.hpp"
#include "solver/components/option_names.hpp"
#include "solver/io/enum_names.hpp"
#include "solver/model/config.hpp"

namespace refmap {

// The name lists (tag dispatch on a value of the enum); defined in option_names.cpp.
std::span<const OptionName<BcType>> option_names(BcType);
std::span<const OptionName<FlowMode>> option_names(FlowMode);
std::span<const OptionName<FluxScheme>> option_names(FluxScheme);
std::span<const OptionName<InitialKind>> option_names(InitialKind);
std::span<const OptionName<ViscousTime>> option_names(ViscousTime);
std::span<const OptionName<SolidStressTime>> option_names(SolidStressTime);
std::span<const OptionName<ElasticCoupling>> option_names(ElasticCoupling);
std::span<const OptionName<JumpFlux>> option_names(JumpFlux);
std::span<const OptionName<Splitting>> option_names(Splitting);

// Declared elsewhere, with the names: the pressure solver's options (solver/pressure/poisson.hpp),
// the shapes (solver/model/shape_params.hpp), the body-force estimator
// (solver/components/control_volume_forces.hpp), and the options whose keys the solids, the
// rigid bodies and the implicit step parse themselves (solver/components/option_names.hpp,
// included here, so the loader and the command line see those names through this header as
// before).

}  // namespace refmap
