#pragma once
// The extrapolation method of a scene: kernels/extrapolate.hpp defines the interface and
// the methods (least squares, Algorithm 2; Aslam's PDE); this maps the [solids] options
// to one of them. A new method: its kernel file, one case here, its name in
// solver/scene/option_names.cpp.
#include <memory>

#include "kernels/extrapolate.hpp"
#include "solver/model/config.hpp"

namespace refmap {

/// The method of SolidsOptions::extrapolation with its options.
std::unique_ptr<Extrapolator> make_extrapolator(const SolidsOptions& opt);

}  // namespace refmap
