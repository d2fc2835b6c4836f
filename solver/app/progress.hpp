#pragma once
// Progress display of a run on stderr. On a terminal: one live line, redrawn in place at
// most ~10 times per second (simulated time / end, step, dt, Poisson iterations and
// residual, wall time, ETA from the rate of simulated time). Otherwise (a pipe, a log
// file, CI): a plain log line every `log_interval_s` wall seconds.
#include <chrono>
#include <string>

namespace refmap {

class Progress {
 public:
  /// `enabled = false` prints nothing at all (quiet runs, tests): neither the progress
  /// display nor message() lines.
  Progress(double t0, double t1, double log_interval_s, bool enabled);
  ~Progress();  ///< ends a live line that finish() did not end

  void update(double t, long step, double dt, int poisson_iters, double poisson_residual);
  /// Prints `line` (plus a newline) on stderr on a line of its own; the live line is
  /// cleared first and redrawn after.
  void message(const std::string& line);
  /// Prints the final state (a last live-line redraw plus newline, or a last log line).
  void finish();

  bool live() const { return live_; }  ///< true when drawing a live line on a terminal

  /// "12.3s", "4m05s", "1h02m": for wall times.
  static std::string format_duration(double seconds);

 private:
  using clock = std::chrono::steady_clock;
  std::string status_line() const;
  void draw();
  void clear_line();

  double t0_, t1_, log_interval_s_;
  bool enabled_, live_ = false;
  clock::time_point start_, last_draw_;
  bool have_state_ = false, drawn_ = false, finished_ = false;
  std::size_t last_len_ = 0;
  // last state
  double t_ = 0, dt_ = 0, res_ = 0;
  long step_ = 0;
  int iters_ = 0;
};

}  // namespace refmap
