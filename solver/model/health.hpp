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

/// A kinetic energy that grows by orders of magnitude in one step is a blow-up even while
/// every field is still finite (an explicit step far past its stability limit can take
/// the energy from 0.1 to 5e4 in one step). Growth by more than kFactor over the larger of
/// the previous step's energy and the largest so far stops the run; the first kGrace steps
/// of a run are exempt (a flow started from rest multiplies its energy by large factors at
/// first). Call check() once after every step.
class EnergyJumpCheck {
 public:
  static constexpr double kFactor = 1e3;
  static constexpr long kGrace = 2;
  /// "" or the message naming the two energies, the step and time.
  std::string check(const Simulation& sim);

 private:
  long steps_ = 0;
  double prev_ = 0.0, peak_ = 0.0;
};

/// "" unless some solid's reference map is folded: det grad xi <= 0 (central differences,
/// as the stress kernel takes them, eq. 3.1) in a cell with phi < 0. The deformation
/// gradient F = (grad xi)^{-1} then has det F <= 0 - the material has passed through
/// itself - and the stress of eq. (2.9) is meaningless; the message names the solid, the
/// global cell (i, j), x, y, the step and time. The run loop calls it after check_health and
/// the kinetic-energy check, so a step that blows up is reported as the blow-up it is and a
/// fold as the first sign of failure only while the energy is still bounded.
std::string check_reference_maps(const Simulation& sim);

}  // namespace refmap
