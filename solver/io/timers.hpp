#pragma once
// Wall-time accounting per phase of the time step, printed as a table at the end of a
// run. With -DREFMAP_LIKWID=ON each phase is also a likwid marker region.
#include <chrono>
#include <cstdio>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#ifdef REFMAP_HAVE_LIKWID
#include <likwid-marker.h>
#endif

namespace refmap {

class PhaseTimers {
 public:
  using clock = std::chrono::steady_clock;
  struct Entry { double seconds = 0.0; long calls = 0; };

  /// Books `seconds` and `calls` calls under `phase`. Not thread-safe: a phase run by
  /// several threads at once (the solids' phases) is timed once around its parallel
  /// region, and its parts are booked afterwards on one thread.
  void add(const std::string& phase, double seconds, long calls = 1) {
    auto it = entries_.find(phase);
    if (it == entries_.end()) { order_.push_back(phase); it = entries_.emplace(phase, Entry{}).first; }
    it->second.seconds += seconds;
    it->second.calls += calls;
  }
  const std::map<std::string, Entry>& entries() const { return entries_; }
  const std::vector<std::string>& order() const { return order_; }
  double total() const { double s = 0; for (auto& [k, e] : entries_) s += e.seconds; return s; }
  /// Forgets every phase (used to exclude warm-up steps from the accounting).
  void reset() { entries_.clear(); order_.clear(); }

  /// Machine-readable form of report(): "phase,seconds,calls" rows in table order, then
  /// "other" (wall - sum of phases, calls 0) and "total" (wall, calls 0).
  void write_csv(std::ostream& os, double wall) const {
    char buf[160];
    os << "phase,seconds,calls\n";
    for (const auto& name : order_) {
      const Entry& e = entries_.at(name);
      std::snprintf(buf, sizeof buf, "%s,%.9g,%ld\n", name.c_str(), e.seconds, e.calls);
      os << buf;
    }
    std::snprintf(buf, sizeof buf, "other,%.9g,0\ntotal,%.9g,0\n", wall - total(), wall);
    os << buf;
  }

  /// "phase  seconds  share  calls  ms/call" table; `wall` is the whole run's wall time.
  void report(std::ostream& os, double wall) const {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%-22s %10s %7s %9s %10s\n", "phase", "wall [s]", "share", "calls", "ms/call");
    os << buf;
    for (const auto& name : order_) {
      const Entry& e = entries_.at(name);
      std::snprintf(buf, sizeof buf, "%-22s %10.3f %6.1f%% %9ld %10.4f\n", name.c_str(), e.seconds,
                    wall > 0 ? 100.0 * e.seconds / wall : 0.0, e.calls,
                    e.calls ? 1e3 * e.seconds / e.calls : 0.0);
      os << buf;
    }
    std::snprintf(buf, sizeof buf, "%-22s %10.3f %6.1f%%\n", "other", wall - total(),
                  wall > 0 ? 100.0 * (wall - total()) / wall : 0.0);
    os << buf;
    std::snprintf(buf, sizeof buf, "%-22s %10.3f\n", "total", wall);
    os << buf;
  }

 private:
  std::map<std::string, Entry> entries_;
  std::vector<std::string> order_;
};

/// RAII: times the enclosing scope into `timers` under `phase` (and a likwid region).
class ScopedPhase {
 public:
  ScopedPhase(PhaseTimers& t, const char* phase) : t_(t), phase_(phase), start_(PhaseTimers::clock::now()) {
#ifdef REFMAP_HAVE_LIKWID
    LIKWID_MARKER_START(phase_);
#endif
  }
  ~ScopedPhase() {
#ifdef REFMAP_HAVE_LIKWID
    LIKWID_MARKER_STOP(phase_);
#endif
    t_.add(phase_, std::chrono::duration<double>(PhaseTimers::clock::now() - start_).count());
  }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  PhaseTimers& t_;
  const char* phase_;
  PhaseTimers::clock::time_point start_;
};

}  // namespace refmap
