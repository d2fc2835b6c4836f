#pragma once
// Anderson acceleration of the passes of time.solid_picard_iterations
// (time.solid_picard_anderson; solver/model/solid_picard.cpp, docs/implicit.md).
//
// A pass is a map x -> g(x): x, the velocities that move xi (and, in the defect form, the
// velocity change the pass corrects), g, the same fields at the end of the pass. The plain
// iteration takes x_{k+1} = g_k. Anderson's type-II update with depth m (Walker & Ni 2011,
// SIAM J. Numer. Anal. 49, 1715-1735, eq. 2.2 in the "difference" form) keeps the last m + 1
// outputs g_j and residuals r_j = g_j - x_j, solves the small least-squares problem
//     min_gamma || r_k - sum_j gamma_j (r_{j+1} - r_j) ||_2
// and takes x_{k+1} = g_k - sum_j gamma_j (g_{j+1} - g_j): an affine combination of the
// outputs, so divergence-free face velocities stay divergence-free and boundary values
// stay as every pass set them. With one output recorded it is the plain step.
#include <deque>
#include <vector>

#include "core/field.hpp"

namespace refmap {

class AndersonMixer {
 public:
  explicit AndersonMixer(int depth) : depth_(depth) {}

  /// Forgets the history (a new time step).
  void reset();
  /// Records the pass's outputs g and residuals r (copies) and writes the next pass's inputs
  /// into x (x[i] gets the combination of the outputs g[i]; the residuals, which may be
  /// fewer fields than the outputs, only set the coefficients).
  void next(const std::vector<const Field*>& g, const std::vector<const Field*>& r,
            const std::vector<Field*>& x);
  /// The coefficients gamma of the last next() (empty for a plain step).
  const std::vector<double>& gamma() const { return gamma_; }

 private:
  int depth_;
  std::deque<std::vector<Field>> g_, r_;
  std::vector<double> gamma_;
};

}  // namespace refmap
