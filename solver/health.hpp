#pragma once
// Health check of the state after a step: the run stops on the first failure instead of
// writing fields full of NaN.
#include <string>

namespace refmap {

class Simulation;

/// "" if the state after a step of size dt is healthy, else a message naming the step,
/// time and cell: non-finite u, v or p; a collapsed time step; or a face divergence that
/// changes a cell's volume by more than 1% per step (the projection failed).
std::string check_health(const Simulation& sim, double dt);

}  // namespace refmap
