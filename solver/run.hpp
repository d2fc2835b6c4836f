#pragma once
// The run loop: steps a Simulation from t_start to t_end (or a steady state, or max_steps)
// on the output schedule of the scene, checks the state's health after every step and
// writes the output (VTK frames and their .pvd, diagnostics.csv, probes, events.csv).
#include <string>

namespace refmap {

class Simulation;

struct RunOptions {
  std::string out_dir;          ///< where VTK, pvd, diagnostics.csv and probes go ("" = no output)
  bool progress = true;         ///< print progress (live line on a terminal, log lines otherwise)
  bool quiet = false;           ///< no progress, no summary (tests)
  long timing_warmup_steps = 0; ///< reset the phase timers after this many steps (0: time all)
};

struct RunSummary {
  long steps = 0;
  double t_end = 0.0;
  double wall_s = 0.0;
  long timed_steps = 0;         ///< steps covered by the phase timers (after the warm-up)
  double timed_wall_s = 0.0;    ///< wall seconds covered by the phase timers
  bool steady = false;          ///< stopped by steady_tol
  bool failed = false;          ///< stopped because fields went non-finite / divergence exploded
  std::string failure;          ///< the message in that case
};

/// Runs `sim` from its current time to t_end (or steady state), writing output to
/// opt.out_dir.
RunSummary run(Simulation& sim, const RunOptions& opt);

}  // namespace refmap
