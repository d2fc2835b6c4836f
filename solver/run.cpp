#include "solver/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "solver/csv.hpp"
#include "solver/diagnostics.hpp"
#include "solver/health.hpp"
#include "solver/probes.hpp"
#include "solver/progress.hpp"
#include "solver/simulation.hpp"
#include "solver/vtk.hpp"

namespace refmap {

namespace {

namespace fs = std::filesystem;

double wall_seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Cell fields of the solids for the VTK frames: the solid nearest each cell (smallest
/// phi) gives phi and xi (0 outside every band); phi is capped at the widest band.
void solid_output_fields(const Simulation& sim, Field& phi, Field& xix, Field& xiy,
                         Field& normal) {
  const Grid& g = sim.grid();
  const Field &sxx = sim.solid_stress_xx(), &syy = sim.solid_stress_yy();
  phi.resize(g.nx, g.ny, Grid::ng, 1e30);
  xix.resize(g.nx, g.ny, Grid::ng, 0.0);
  xiy.resize(g.nx, g.ny, Grid::ng, 0.0);
  normal.resize(g.nx, g.ny, Grid::ng, 0.0);
  for (const auto& s : sim.solids()) {
    for (int j = 0; j < s->nj(); ++j)
      for (int i = 0; i < s->ni(); ++i) {
        const int gi = s->i0() + i, gj = s->j0() + j;
        const double ph = s->phi()(i, j);
        if (ph < phi(gi, gj)) {
          phi(gi, gj) = ph;
          if (ph < s->band()) {
            xix(gi, gj) = s->xi_x()(i, j);
            xiy(gi, gj) = s->xi_y()(i, j);
          }
        }
      }
  }
  double cap = 0.0;
  for (const auto& s : sim.solids()) cap = std::max(cap, s->band());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      phi(i, j) = std::min(phi(i, j), cap);
      if (sxx.nx() > 0) normal(i, j) = 0.5 * (sxx(i, j) + syy(i, j));
    }
}

/// The files of a run in opt.out_dir; every writer does nothing without an output
/// directory (and the frames nothing with write_vtk = false).
class RunOutput {
 public:
  RunOutput(Simulation& sim, const std::string& out_dir) : sim_(sim), dir_(out_dir) {
    if (dir_.empty()) return;
    const Config& cfg = sim_.config();
    const Grid& g = sim_.grid();
    fs::create_directories(dir_);
    remove_earlier_output();
    std::ostringstream head;
    head << "refmap diagnostics, scene " << cfg.name << ", grid " << g.nx << " x " << g.ny
         << ", dx " << g.dx;
    csv_ = std::make_unique<CsvWriter>((fs::path(dir_) / "diagnostics.csv").string(),
                                       diagnostic_columns(sim_), head.str());
    if (cfg.write_vtk)  // no .pvd without frames
      pvd_ = std::make_unique<PvdSeries>((fs::path(dir_) / (cfg.name + ".pvd")).string());
  }

  /// A directory used before holds the files of the earlier run; frames of that run
  /// beside this one's would be read as one series. Only the names refmap writes are
  /// removed (frames and their temporaries, .pvd series, the CSV outputs, checkpoints);
  /// scene.toml is written by the caller before the run, anything else is left alone.
  void remove_earlier_output() {
    std::error_code ec;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
      const std::string f = e.path().filename().string();
      const bool ours = (f.rfind("frame_", 0) == 0 && (e.path().extension() == ".vti" || f.ends_with(".vti.tmp"))) ||
                        e.path().extension() == ".pvd" || f.ends_with(".pvd.tmp") ||
                        (f.rfind("probe_", 0) == 0 && e.path().extension() == ".csv") || f == "diagnostics.csv" ||
                        f == "events.csv" || f == "timings.csv" || f.rfind("checkpoint.bin", 0) == 0;
      if (ours && e.is_regular_file(ec)) stale.push_back(e.path());
    }
    for (const auto& p : stale) fs::remove(p, ec);
  }

  bool enabled() const { return !dir_.empty(); }
  bool frames() const { return enabled() && sim_.config().write_vtk; }

  /// A VTK frame of the current state, added to the .pvd series.
  void frame() {
    if (!frames()) return;
    ScopedPhase ph(sim_.timers(), "output");
    Field vort = sim_.named_field("vorticity");
    char name[64];
    std::snprintf(name, sizeof name, "frame_%05d.vti", frame_++);
    std::vector<VtkScalar> scalars{{"p", &sim_.p()}, {"vorticity", &vort}, {"density", &sim_.rho()}};
    std::vector<VtkVector> vectors{{"velocity", &sim_.u(), &sim_.v()}};
    Field phi, xix, xiy, normal;
    if (!sim_.solids().empty()) {
      solid_output_fields(sim_, phi, xix, xiy, normal);
      scalars.push_back({"phi", &phi});
      scalars.push_back({"normal_stress", &normal});
      vectors.push_back({"xi", &xix, &xiy});
      if (sim_.solid_stress_xx().nx() > 0) {
        scalars.push_back({"stress_xx", &sim_.solid_stress_xx()});
        scalars.push_back({"stress_xy", &sim_.solid_stress_xy()});
        scalars.push_back({"stress_yy", &sim_.solid_stress_yy()});
      }
    }
    write_vti((fs::path(dir_) / name).string(), sim_.grid(), scalars, vectors, sim_.time());
    pvd_->add(sim_.time(), name);
  }

  /// A diagnostics.csv row of the current state.
  void row(double last_dt, double wall_s) {
    if (!csv_) return;
    ScopedPhase ph(sim_.timers(), "diagnostics");
    csv_->row(diagnostic_values(sim_, last_dt, wall_s));
  }

  /// probe_NAME.csv of every probe of the scene.
  void probes() {
    if (!enabled()) return;
    ScopedPhase ph(sim_.timers(), "output");
    for (const ProbeSpec& pr : sim_.config().probes) {
      Field f = sim_.named_field(pr.field);
      write_probe_csv((fs::path(dir_) / ("probe_" + pr.name + ".csv")).string(), pr, sim_.grid(), f);
    }
  }

  void flush() {
    if (csv_) csv_->flush();
  }

  /// events.csv: the contact event log, one "time,solid,event,value,with" row per event.
  void events(const std::vector<ContactEvent>& log) {
    if (!enabled()) return;
    const std::string path = (fs::path(dir_) / "events.csv").string();
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "time,solid,event,value,with\n");
    for (const ContactEvent& e : log)
      std::fprintf(f, "%.10g,%d,%s,%.10g,%s\n", e.time, e.solid, e.event.c_str(), e.value, e.with.c_str());
    std::fclose(f);
  }

 private:
  Simulation& sim_;
  std::string dir_;
  std::unique_ptr<CsvWriter> csv_;
  std::unique_ptr<PvdSeries> pvd_;
  int frame_ = 0;
};

/// steady_tol: max over cells of |u^{n+1} - u^n| / dt (both components) against the
/// tolerance; keeps the velocity before each step.
class SteadyCheck {
 public:
  explicit SteadyCheck(double tol) : tol_(tol) {}
  bool enabled() const { return tol_ > 0.0; }
  void before_step(const Simulation& sim) {
    if (!enabled()) return;
    u_old_ = sim.u();
    v_old_ = sim.v();
  }
  /// The rate of change over the step of size dt just taken.
  double rate(const Simulation& sim, double dt) const {
    const Grid& g = sim.grid();
    const Field &u = sim.u(), &v = sim.v();
    double change = 0.0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        change = std::max({change, std::abs(u(i, j) - u_old_(i, j)),
                           std::abs(v(i, j) - v_old_(i, j))});
    return change / dt;
  }
  bool reached(double rate) const { return rate < tol_; }

 private:
  double tol_;
  Field u_old_, v_old_;
};

}  // namespace

RunSummary run(Simulation& sim, const RunOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const Config& cfg = sim.config();
  RunSummary sum;
  RunOutput out(sim, opt.out_dir);
  Progress progress(cfg.t_start, cfg.t_end, cfg.log_interval_s, opt.progress && !opt.quiet);
  double last_dt = 0.0;
  out.frame();
  out.row(last_dt, wall_seconds_since(wall0));

  // output schedule: steps land exactly on the frame times and the end time
  const double eps_t = 1e-12 * std::max(1.0, std::abs(cfg.t_end));
  const double frame_interval = cfg.output_interval > 0.0 ? cfg.output_interval : cfg.t_end;
  double next_frame = cfg.output_interval > 0.0 ? cfg.t_start + cfg.output_interval : cfg.t_end;
  const int diag_every = std::max(1, cfg.diagnostics_every);
  SteadyCheck steady(cfg.steady_tol);
  // phase timers cover the steps after the warm-up (and the final output)
  auto timed0 = wall0;
  long timed_step0 = sim.steps();
  while (sim.time() < cfg.t_end - eps_t) {
    if (opt.timing_warmup_steps > 0 && sim.steps() == opt.timing_warmup_steps) {
      sim.timers().reset();
      timed0 = std::chrono::steady_clock::now();
      timed_step0 = sim.steps();
    }
    if (cfg.max_steps > 0 && sim.steps() >= cfg.max_steps) break;
    double dt = cfg.dt_fixed > 0.0 ? cfg.dt_fixed : sim.stable_dt();
    dt = std::min(dt, cfg.t_end - sim.time());
    if (out.frames() && next_frame < cfg.t_end && next_frame - sim.time() < dt)
      dt = std::max(next_frame - sim.time(), 1e-300);
    steady.before_step(sim);
    sim.step(dt);
    last_dt = dt;

    std::string bad = check_health(sim, dt);
    if (!bad.empty()) {
      out.row(last_dt, wall_seconds_since(wall0));
      sum.failed = true;
      sum.failure = bad;
      break;
    }
    if (sim.steps() % diag_every == 0) out.row(last_dt, wall_seconds_since(wall0));
    if (out.frames() && sim.time() >= next_frame - eps_t && sim.time() < cfg.t_end - eps_t) {
      out.frame();
      next_frame += frame_interval;
    }
    progress.update(sim.time(), sim.steps(), dt, sim.last_poisson_iterations(),
                    sim.last_poisson_residual());
    if (steady.enabled()) {
      const double rate = steady.rate(sim, dt);
      if (steady.reached(rate)) {
        sum.steady = true;
        progress.message("steady state reached at t = " + std::to_string(sim.time()) +
                         " (max |du/dt| = " + std::to_string(rate) + ")");
        break;
      }
    }
  }
  progress.finish();
  if (!sum.failed) {
    if (sim.steps() % diag_every != 0) out.row(last_dt, wall_seconds_since(wall0));
    out.frame();
    out.probes();
  }
  out.flush();
  if (sim.contact()) {
    sim.finish_events();
    out.events(sim.contact()->events());
  }
  sum.steps = sim.steps();
  sum.t_end = sim.time();
  sum.wall_s = wall_seconds_since(wall0);
  sum.timed_steps = sim.steps() - timed_step0;
  sum.timed_wall_s = wall_seconds_since(timed0);
  return sum;
}

}  // namespace refmap
