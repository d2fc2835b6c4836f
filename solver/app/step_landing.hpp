#pragma once
// The step that lands on a target time (the next VTK frame or t_end) without leaving a sliver.
//
// Time accumulated in steps of a fixed dt drifts from the exact multiples by rounding (about
// n ulp(t) after n steps: about 1e-11 after 126 800 steps of 5e-5 at t = 6.34). A full step can then
// stop short of the target by more than the run's tolerance eps_t, and the next step, cut to
// land on it, is that sliver, which the health check reads as a collapsed step (it stopped the
// Turek & Hron FSI3 run at t = 6.34). So a step that would stop short of the target by more than
// eps_t but by less than 1e-4 dt is stretched to reach it (at most 0.01 % longer). Gaps up to
// eps_t keep the old step, so runs that never drift so far are unchanged to the bit.

#include <algorithm>

namespace refmap {

inline double landing_step(double dt, double gap, double eps_t) {
  if (gap < dt || (gap - dt > eps_t && gap - dt < 1e-4 * dt)) return std::max(gap, 1e-300);
  return dt;
}

}  // namespace refmap
