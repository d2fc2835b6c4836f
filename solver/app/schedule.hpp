#pragma once
// When an output of a run is written (solver/app/run.cpp keeps the outputs in one list, each
// with its schedule): every n steps, at multiples of a simulated-time interval (the run
// lands a step on each), or every so many wall seconds.
#include <chrono>
#include <limits>

#include "solver/app/step_landing.hpp"

namespace refmap {

class Schedule {
 public:
  using Clock = std::chrono::steady_clock;

  /// After every n-th step (steps % n == 0).
  static Schedule every_steps(long n) {
    Schedule s;
    s.steps_ = n;
    return s;
  }
  /// At `next`, next + interval, ... before t_end (not at t_end itself: the run's end
  /// writes its own); eps_t is the run's time tolerance.
  static Schedule every_time(double next, double interval, double t_end, double eps_t) {
    Schedule s;
    s.next_ = next;
    s.interval_ = interval;
    s.t_end_ = t_end;
    s.eps_t_ = eps_t;
    return s;
  }
  /// Whenever `seconds` of wall time have passed since the last write (or the start).
  static Schedule every_wall_seconds(double seconds) {
    Schedule s;
    s.wall_s_ = seconds;
    s.last_ = Clock::now();
    return s;
  }
  /// Never (an output the scene turned off).
  static Schedule never() { return {}; }

  /// Is the output due after the step that brought the run to step `steps`, time t?
  bool due(long steps, double t) const {
    if (steps_ > 0) return steps % steps_ == 0;
    if (interval_ > 0.0) return t >= next_ - eps_t_ && t < t_end_ - eps_t_;
    if (wall_s_ > 0.0) return Clock::now() - last_ >= std::chrono::duration<double>(wall_s_);
    return false;
  }
  /// The output is being written now: move on to the next time.
  void advance() {
    if (interval_ > 0.0) next_ += interval_;
    if (wall_s_ > 0.0) last_ = Clock::now();
  }
  /// dt shortened (or stretched by a sliver, solver/app/step_landing.hpp) to land on the next
  /// time of a time schedule that has one before t_end.
  double land(double dt, double t) const {
    if (interval_ > 0.0 && next_ < t_end_) return landing_step(dt, next_ - t, eps_t_);
    return dt;
  }
  /// The next time of a time schedule (checkpointed: a resumed run keeps its frame times).
  double next_time() const { return next_; }
  void set_next_time(double t) { next_ = t; }

 private:
  long steps_ = 0;
  double next_ = std::numeric_limits<double>::infinity(), interval_ = 0.0, t_end_ = 0.0, eps_t_ = 0.0;
  double wall_s_ = 0.0;
  Clock::time_point last_{};
};

}  // namespace refmap
