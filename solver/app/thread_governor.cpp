#include "solver/app/thread_governor.hpp"

#include <omp.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace refmap {

int governed_threads(int current, int max_threads, int ncpu, double others_cores) {
  const double free_cores = double(ncpu) - std::max(0.0, others_cores);
  const auto fit = [&](double slack) {
    return std::clamp(int(std::floor(free_cores + slack)), 1, std::max(1, max_threads));
  };
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
  // /proc/stat's per-CPU lines "cpuN user nice system idle iowait irq softirq steal ...", in
  // jiffies; busy = all but idle, iowait and steal (steal is other machines' work). Only the
  // CPUs this process may run on count (a run pinned by taskset or a batch system is not
  // slowed by work on the machine's other CPUs).
  cpu_set_t mask;
  CPU_ZERO(&mask);
  const bool have_mask = sched_getaffinity(0, sizeof mask, &mask) == 0;
  std::FILE* f = std::fopen("/proc/stat", "r");
  if (!f) return false;
  char line[512];
  unsigned long long busy = 0;
  int cpus = 0;
  while (std::fgets(line, sizeof line, f)) {
    // per-CPU lines only: "cpu" then the CPU's number (the summary line has a space there,
    // which %d would skip)
    if (std::strncmp(line, "cpu", 3) != 0 || !std::isdigit(static_cast<unsigned char>(line[3]))) continue;
    int cpu = -1;
    unsigned long long v[7] = {};
    if (std::sscanf(line, "cpu%d %llu %llu %llu %llu %llu %llu %llu", &cpu, &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                    &v[6]) < 5 ||
        cpu < 0)
      continue;
    if (have_mask && (cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &mask))) continue;
    busy += v[0] + v[1] + v[2] + v[5] + v[6];
    ++cpus;
  }
  std::fclose(f);
  if (cpus == 0) return false;
  machine_busy_s = double(busy) / double(sysconf(_SC_CLK_TCK));
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
