#include "solver/app/thread_governor.hpp"

#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace refmap {

int governed_threads(int current, int max_threads, int ncpu, double others_cores) {
  const double free_cores = double(ncpu) - std::max(0.0, others_cores);
  const auto fit = [&](double slack) { return std::clamp(int(std::floor(free_cores + slack)), 1, std::max(1, max_threads)); };
  if (const int n = fit(kShrinkSlack); n < current) return n;
  if (const int n = fit(kGrowSlack); n > current) return n;
  return current;
}

ThreadGovernor::ThreadGovernor(int max_threads, bool enabled, double interval_s, double first_s)
    : max_threads_(std::max(1, max_threads)),
      threads_(max_threads_),
      min_threads_(max_threads_),
      enabled_(enabled && max_threads_ > 1),
      interval_s_(interval_s),
      next_s_(first_s) {
  ncpu_ = std::max(1, omp_get_num_procs());
  t0_ = std::chrono::steady_clock::now();
  if (enabled_ && !sample(busy0_, own0_)) enabled_ = false;  // no /proc/stat: keep the team fixed
}

bool ThreadGovernor::sample(double& machine_busy_s, double& own_s) const {
  // /proc/stat's first line: jiffies of all CPUs in user, nice, system, idle, iowait, irq,
  // softirq, steal; busy = all but idle and iowait
  std::FILE* f = std::fopen("/proc/stat", "r");
  if (!f) return false;
  unsigned long long v[8] = {};
  const int n = std::fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4],
                            &v[5], &v[6], &v[7]);
  std::fclose(f);
  if (n < 5) return false;
  const double tick = double(sysconf(_SC_CLK_TCK));
  unsigned long long busy = 0;
  for (int k = 0; k < std::min(n, 7); ++k)  // steal time (k = 7) is other machines' work
    if (k != 3 && k != 4) busy += v[k];
  machine_busy_s = double(busy) / tick;
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  own_s = double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  return true;
}

void ThreadGovernor::after_step() {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(now - t0_).count();
  if (wall < next_s_) return;
  double busy = 0.0, own = 0.0;
  if (!sample(busy, own)) return;
  // jiffies are 10 ms: over 0.25 s the machine's busy time is known to ~0.04 core (over the
  // first 0.05 s to ~0.2), enough to tell a busy neighbour (~1 core) from an idle machine
  const double others = std::max(0.0, (busy - busy0_) - (own - own0_)) / wall;
  const int next = governed_threads(threads_, max_threads_, ncpu_, others);
  if (next != threads_) {
    threads_ = next;
    omp_set_num_threads(next);
    ++switches_;
    min_threads_ = std::min(min_threads_, next);
  }
  t0_ = now;
  next_s_ = interval_s_;
  busy0_ = busy;
  own0_ = own;
}

}  // namespace refmap
