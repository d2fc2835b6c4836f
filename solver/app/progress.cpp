#include "solver/app/progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace refmap {

Progress::Progress(double t0, double t1, double log_interval_s, bool enabled)
    : t0_(t0), t1_(t1), log_interval_s_(log_interval_s > 0 ? log_interval_s : 2.0), enabled_(enabled) {
  start_ = last_draw_ = clock::now();
  if (enabled_) {
    const char* term = std::getenv("TERM");
    live_ = isatty(fileno(stderr)) && !(term && std::strcmp(term, "dumb") == 0);
  }
}

Progress::~Progress() {
  if (live_ && drawn_ && !finished_) {
    std::fputc('\n', stderr);
    std::fflush(stderr);
  }
}

std::string Progress::format_duration(double s) {
  char buf[48];
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s / 60), int(std::fmod(s, 60.0)));
  else if (s < 100 * 3600.0) std::snprintf(buf, sizeof buf, "%dh%02dm", int(s / 3600), int(std::fmod(s, 3600.0) / 60));
  else std::snprintf(buf, sizeof buf, "%.0fh", s / 3600);
  return buf;
}

std::string Progress::status_line() const {
  const double wall = std::chrono::duration<double>(clock::now() - start_).count();
  const double span = t1_ - t0_;
  const double done = span > 0 ? (t_ - t0_) / span : 1.0;
  std::string eta = "?";
  if (t_ > t0_ && wall > 0) {
    const double rate = (t_ - t0_) / wall;  // simulated time per wall second
    eta = format_duration(std::max(0.0, (t1_ - t_) / rate));
  }
  char buf[256];
  // most important first: a narrow terminal truncates the end
  std::snprintf(buf, sizeof buf, "t %.6g/%.6g (%5.1f%%)  eta %s  wall %s  step %ld  dt %.3e  poisson %d it (res %.1e)",
                t_, t1_, 100.0 * std::clamp(done, 0.0, 1.0), eta.c_str(), format_duration(wall).c_str(), step_, dt_,
                iters_, res_);
  return buf;
}

void Progress::clear_line() {
  if (!live_ || !drawn_) return;
  std::fputc('\r', stderr);
  for (std::size_t i = 0; i < last_len_; ++i) std::fputc(' ', stderr);
  std::fputc('\r', stderr);
  drawn_ = false;
}

void Progress::draw() {
  if (!have_state_) return;
  std::string line = status_line();
  if (live_) {
    // a line longer than the terminal would wrap and '\r' could not redraw it
    struct winsize ws {};
    if (ioctl(fileno(stderr), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 10 && line.size() >= ws.ws_col)
      line.resize(std::size_t(ws.ws_col) - 1);
    std::fputc('\r', stderr);
    std::fputs(line.c_str(), stderr);
    for (std::size_t i = line.size(); i < last_len_; ++i) std::fputc(' ', stderr);  // erase leftovers
    last_len_ = line.size();
    drawn_ = true;
  } else {
    std::fprintf(stderr, "[refmap] %s\n", line.c_str());
  }
  std::fflush(stderr);
  last_draw_ = clock::now();
}

void Progress::update(double t, long step, double dt, int poisson_iters, double poisson_residual) {
  if (!enabled_) return;
  t_ = t; step_ = step; dt_ = dt; iters_ = poisson_iters; res_ = poisson_residual;
  have_state_ = true;
  const double since = std::chrono::duration<double>(clock::now() - last_draw_).count();
  if (since >= (live_ ? 0.1 : log_interval_s_)) draw();
}

void Progress::message(const std::string& line) {
  if (!enabled_) return;
  const bool redraw = live_ && drawn_;
  clear_line();
  std::fputs(line.c_str(), stderr);
  std::fputc('\n', stderr);
  if (redraw && !finished_) draw();
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  draw();
  if (live_ && drawn_) std::fputc('\n', stderr);
  std::fflush(stderr);
  finished_ = true;
}

}  // namespace refmap
