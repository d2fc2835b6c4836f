#pragma once
// The run loop: steps a Simulation from t_start to t_end (or a steady state, or max_steps)
// on the output schedule of the scene, checks the state's health after every step and
// writes the output (VTK frames and their .pvd, diagnostics.csv, probes, events.csv).
#include <string>
#include <vector>

namespace refmap {

class Simulation;
class CheckpointReader;

struct RunOptions {
  std::string out_dir;          ///< where VTK, pvd, diagnostics.csv and probes go ("" = no output)
  bool progress = true;         ///< print progress (live line on a terminal, log lines otherwise)
  bool quiet = false;           ///< no progress, no summary (tests)
  long timing_warmup_steps = 0; ///< reset the phase timers after this many steps (0: time all)
  /// The scene as loaded (text, path, --set overrides): a checkpoint carries it so that
  /// `refmap resume` needs nothing else. Empty text: no checkpoints are written.
  std::string scene_text, scene_path;
  std::vector<std::string> sets;
  double checkpoint_minutes = -1.0;  ///< < 0: the scene's output.checkpoint_minutes
  /// Resuming: the checkpoint, read up to the run's own records (the Simulation has
  /// loaded its state from it); the output directory's files are continued, not replaced.
  CheckpointReader* resume = nullptr;
  /// Let the team size follow what other processes leave free (solver/app/thread_governor.hpp);
  /// the command line sets it, tests and benchmarks keep their fixed team.
  bool govern_threads = false;

  /// No output directory, no progress, no summary (tests, benchmarks).
  static RunOptions silent() {
    RunOptions o;
    o.progress = false;
    o.quiet = true;
    return o;
  }
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
  std::string failed_frame;     ///< frame_failed.vti of the state a health check refused ("" if none)
  int signal = 0;               ///< stopped by this signal (SIGINT, SIGTERM) after a clean checkpoint
  std::string checkpoint;       ///< the last checkpoint written ("" if none)
  int thread_switches = 0;      ///< team size changes by the thread governor
  int min_threads = 0;          ///< smallest team used (0: not governed)
};

/// The records of a checkpoint before the Simulation's state: the scene to rebuild it from.
struct CheckpointScene {
  std::string text, path;
  std::vector<std::string> sets;
};
/// Reads them (throws CheckpointError).
CheckpointScene read_checkpoint_scene(CheckpointReader& r);

/// Runs `sim` from its current time to t_end (or steady state, or max_steps), writing
/// output to opt.out_dir. A problem during the run (non-finite fields, a blow-up, a solid
/// that vanishes or reaches a periodic side, an output that cannot be written) ends it with
/// failed = true and a message naming the step and time; the output written so far stays
/// valid. SIGINT/SIGTERM (solver/app/stop_signal.hpp) end it after the current step with a
/// checkpoint.
RunSummary run(Simulation& sim, const RunOptions& opt);

}  // namespace refmap
