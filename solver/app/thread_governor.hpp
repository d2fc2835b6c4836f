#pragma once
// How many threads the run uses, decided while it runs from what the machine's other
// processes use (results/threads.md, "Two threads that help every scene").
//
// On the 2-core machines refmap runs on, spinning waits at OpenMP barriers are what make a
// second thread pay off for one disc on an idle machine, where sleeping (passive) waits
// make it slower; but beside one busy process a spinning partner waits for a descheduled
// thread at every barrier and the run takes several times longer (measured:
// results/threads.md). No wait policy serves both, and the neighbour may start or stop
// during a long run. So refmap keeps libgomp's bounded spinning and changes the team size
// instead: every sampling interval it reads the CPU time spent on the CPUs it may run on
// (/proc/stat, the affinity mask) and its own (getrusage); the difference is what other
// processes used, in cores. With fewer cores left than threads, the run drops to the
// cores left (one thread beside one busy process runs as fast as alone); when they come
// back, it returns to the requested team. Team size never changes the results: every
// reduction of kernels/loop.hpp sums per-row partials in row order.
#include <chrono>

namespace refmap {

/// A spinning team loses most of its speed as soon as a neighbour takes a third of a core
/// (each barrier then waits for a descheduled partner): the team shrinks when the free
/// cores round down, with this slack, below it ...
inline constexpr double kShrinkSlack = 0.3;
/// ... and grows again only when they are within this slack of a whole core more (the gap
/// between the two keeps a neighbour near a fifth of a core from flipping the team).
inline constexpr double kGrowSlack = 0.15;

/// The team size for the next interval: at most `max_threads`, at least 1, following the
/// cores that other processes leave free of the machine's `ncpu` (they used `others_cores`
/// over the last interval).
int governed_threads(int current, int max_threads, int ncpu, double others_cores);

class ThreadGovernor {
 public:
  /// max_threads: the requested team (the ceiling); enabled = false leaves it fixed. The
  /// first sample comes after first_s (a run that starts beside a busy process loses at
  /// most that to spinning waits), the next ones every interval_s.
  ThreadGovernor(int max_threads, bool enabled, double interval_s = 0.25, double first_s = 0.05);
  /// Called between steps: samples when the interval has passed and sets the team size.
  void after_step();
  int threads() const { return threads_; }
  int switches() const { return switches_; }
  /// Smallest team used so far.
  int min_threads() const { return min_threads_; }

 private:
  bool sample(double& machine_busy_s, double& own_s) const;

  int max_threads_, threads_, ncpu_ = 1, switches_ = 0, min_threads_;
  bool enabled_;
  double interval_s_, next_s_;
  std::chrono::steady_clock::time_point t0_;
  double busy0_ = 0.0, own0_ = 0.0;
};

}  // namespace refmap
