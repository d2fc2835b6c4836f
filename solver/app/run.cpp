#include "solver/app/run.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "solver/io/checkpoint_io.hpp"
#include "solver/io/csv.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/diagnostics.hpp"
#include "solver/model/health.hpp"
#include "solver/model/probes.hpp"
#include "solver/app/progress.hpp"
#include "solver/model/simulation.hpp"
#include "solver/app/schedule.hpp"
#include "solver/app/step_landing.hpp"
#include "solver/app/stop_signal.hpp"
#include "solver/app/thread_governor.hpp"
#include "solver/io/vtk.hpp"

namespace refmap {

namespace {

namespace fs = std::filesystem;

double wall_seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The files of a run in opt.out_dir; every writer does nothing without an output
/// directory (and the frames nothing with write_vtk = false).
class RunOutput {
 public:
  RunOutput(Simulation& sim, const std::string& out_dir) : sim_(sim), dir_(out_dir), files_(component_files(sim)) {
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
    if (!sim_.solids().empty()) {
      std::ostringstream sh;
      sh << "refmap per-solid diagnostics, scene " << cfg.name << ", one row per solid and diagnostics.csv row;"
         << " solid = index in the scene:";
      for (std::size_t k = 0; k < sim_.solids().size(); ++k) sh << ' ' << k << '=' << sim_.solids()[k]->spec().name;
      solids_csv_ = std::make_unique<CsvWriter>((fs::path(dir_) / "solids.csv").string(), solid_columns(sim_), sh.str());
    }
    if (cfg.write_vtk)  // no .pvd without frames
      pvd_ = std::make_unique<PvdSeries>((fs::path(dir_) / (cfg.name + ".pvd")).string());
    for (ComponentCsv& f : files_)
      f.csv = std::make_unique<CsvWriter>((fs::path(dir_) / f.file.name).string(), f.file.columns);
  }

  /// The outputs as they were when the checkpoint was written: diagnostics.csv cut back to
  /// its rows then, frames written after it removed, the .pvd series rewritten.
  RunOutput(Simulation& sim, const std::string& out_dir, CheckpointReader& r)
      : sim_(sim), dir_(out_dir), files_(component_files(sim)) {
    frame_ = int(r.get_i64("run.frames"));
    const std::int64_t n = r.get_i64("run.pvd_entries");
    std::vector<std::pair<double, std::string>> entries;
    for (std::int64_t k = 0; k < n; ++k) {
      const double t = r.get_f64("run.pvd_time");
      entries.emplace_back(t, r.get_string("run.pvd_file"));
    }
    const auto bytes = std::size_t(r.get_i64("run.csv_bytes"));
    const long rows = long(r.get_i64("run.csv_rows"));
    const auto solids_bytes = std::size_t(r.get_i64("run.solids_bytes"));
    const long solids_rows = long(r.get_i64("run.solids_rows"));
    // the components' files (only the scenes whose components have files hold the records)
    for (ComponentCsv& f : files_) {
      f.bytes = r.get_i64(record(f, "bytes"));
      f.rows = r.get_i64(record(f, "rows"));
    }
    if (!r.at_end()) throw CheckpointError("checkpoint " + r.path() + ": records left over at the end");
    if (dir_.empty()) return;
    // everything is checked before any file is touched: a checkpoint that cannot be
    // continued changes nothing
    std::error_code ec;
    const fs::path diag = fs::path(dir_) / "diagnostics.csv";
    const fs::path solids = fs::path(dir_) / "solids.csv";
    for (const auto& [f, size] : {std::pair{diag, bytes}, std::pair{solids, solids_bytes}})
      if (size > 0 && (fs::file_size(f, ec) < size || ec))
        throw CheckpointError(f.string() + " is shorter than when the checkpoint " + r.path() +
                              " was written: the run cannot be continued");
    for (const ComponentCsv& c : files_) {
      const fs::path f = fs::path(dir_) / c.file.name;
      if (c.bytes > 0 && (fs::file_size(f, ec) < std::uintmax_t(c.bytes) || ec))
        throw CheckpointError(f.string() + " is shorter than when the checkpoint " + r.path() +
                              " was written: the run cannot be continued");
    }
    fs::create_directories(dir_);
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
      const std::string f = e.path().filename().string();
      int idx = -1;
      if (std::sscanf(f.c_str(), "frame_%d.vti", &idx) == 1 && idx >= frame_) fs::remove(e.path(), ec);
      if (f == kFailedFrame) fs::remove(e.path(), ec);
      if (f.ends_with(".vti.tmp")) fs::remove(e.path(), ec);
    }
    const Config& cfg = sim_.config();
    if (bytes > 0)
      csv_ = std::make_unique<CsvWriter>(CsvWriter::resume((fs::path(dir_) / "diagnostics.csv").string(),
                                                           diagnostic_columns(sim_), bytes, rows));
    if (solids_bytes > 0)
      solids_csv_ = std::make_unique<CsvWriter>(CsvWriter::resume(solids.string(), solid_columns(sim_), solids_bytes, solids_rows));
    if (cfg.write_vtk) {
      pvd_ = std::make_unique<PvdSeries>((fs::path(dir_) / (cfg.name + ".pvd")).string());
      pvd_->restore(entries);
    }
    for (ComponentCsv& f : files_)
      if (f.bytes > 0)
        f.csv = std::make_unique<CsvWriter>(CsvWriter::resume((fs::path(dir_) / f.file.name).string(), f.file.columns,
                                                              std::size_t(f.bytes), long(f.rows)));
  }

  /// The run's own records of a checkpoint (after flushing diagnostics.csv).
  void save_state(CheckpointWriter& w) {
    flush();
    w.put_i64("run.frames", frame_);
    const auto entries = pvd_ ? pvd_->entries() : std::vector<std::pair<double, std::string>>{};
    w.put_i64("run.pvd_entries", std::int64_t(entries.size()));
    for (const auto& [t, f] : entries) {
      w.put_f64("run.pvd_time", t);
      w.put_string("run.pvd_file", f);
    }
    w.put_i64("run.csv_bytes", csv_ ? std::int64_t(csv_->bytes()) : 0);
    w.put_i64("run.csv_rows", csv_ ? csv_->rows() : 0);
    w.put_i64("run.solids_bytes", solids_csv_ ? std::int64_t(solids_csv_->bytes()) : 0);
    w.put_i64("run.solids_rows", solids_csv_ ? solids_csv_->rows() : 0);
    for (const ComponentCsv& f : files_) {
      w.put_i64(record(f, "bytes"), f.csv ? std::int64_t(f.csv->bytes()) : 0);
      w.put_i64(record(f, "rows"), f.csv ? f.csv->rows() : 0);
    }
  }
  const std::string& dir() const { return dir_; }

  /// A directory used before holds the files of the earlier run; frames of that run
  /// beside this one's would be read as one series. Only the names refmap writes are
  /// removed (frames and their temporaries, .pvd series, the CSV outputs, checkpoints);
  /// scene.toml is written by the caller before the run, anything else is left alone.
  void remove_earlier_output() {
    std::error_code ec;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
      const std::string f = e.path().filename().string();
      bool ours = (f.rfind("frame_", 0) == 0 && (e.path().extension() == ".vti" || f.ends_with(".vti.tmp"))) ||
                  e.path().extension() == ".pvd" || f.ends_with(".pvd.tmp") ||
                  (f.rfind("probe_", 0) == 0 && e.path().extension() == ".csv") || f == "diagnostics.csv" ||
                  f == "solids.csv" || f == "events.csv" || f == "timings.csv" || f.rfind("checkpoint.bin", 0) == 0;
      for (const ComponentKind& k : component_kinds())  // the components' own files (Component::files)
        ours = ours || std::find(k.files.begin(), k.files.end(), f) != k.files.end();
      if (ours && e.is_regular_file(ec)) stale.push_back(e.path());
    }
    for (const auto& p : stale) fs::remove(p, ec);
  }

  bool enabled() const { return !dir_.empty(); }
  bool frames() const { return enabled() && sim_.config().write_vtk; }

  /// A VTK frame of the current state, added to the .pvd series.
  void frame() {
    if (!frames()) return;
    char name[64];
    std::snprintf(name, sizeof name, "frame_%05d.vti", frame_++);
    write_frame(name);
    pvd_->add(sim_.time(), name);
    component_rows(frame_ - 1);
  }

  /// The rows of the components' files of frame `f` (the current state).
  void component_rows(int f) {
    std::vector<std::vector<double>> rows;
    for (ComponentCsv& c : files_) {
      if (!c.csv) continue;
      rows.clear();
      c.file.rows(sim_, f, rows);
      for (const auto& row : rows) c.csv->row(row);
    }
  }

  /// frame_failed.vti: the state a health check refused, so that the failure can be looked
  /// at (docs/stability.md). Written whenever there is an output directory, also with output.vtk =
  /// false (one file, at the end); its TIME is the failing step's. Not in the .pvd: the
  /// series holds only scheduled frames of healthy states, and a reader of the series must
  /// not take this one for one of them. Returns the path ("" without an output directory).
  std::string failed_frame() {
    if (!enabled()) return {};
    write_frame(kFailedFrame);
    return (fs::path(dir_) / kFailedFrame).string();
  }
  static constexpr const char* kFailedFrame = "frame_failed.vti";

 private:
  void write_frame(const char* name) {
    ScopedPhase ph(sim_.timers(), "output");
    Field vort = sim_.named_field("vorticity");
    std::vector<VtkScalar> scalars{{"p", &sim_.p()}, {"vorticity", &vort}, {"density", &sim_.rho()}};
    std::vector<VtkVector> vectors{{"velocity", &sim_.u(), &sim_.v()}};
    // the components' fields (solver/model/component.hpp), the solids' first
    FrameFields extra;
    for (const auto& c : sim_.components()) c->frame_fields(extra);
    for (const auto& [field_name, f] : extra.scalars) scalars.push_back({field_name, f});
    for (const auto& v : extra.vectors) vectors.push_back({v.name, v.x, v.y});
    write_vti((fs::path(dir_) / name).string(), sim_.grid(), scalars, vectors, sim_.time());
  }

 public:

  /// A diagnostics.csv row of the current state, and its solids.csv rows.
  void row(double last_dt, double wall_s) {
    if (!csv_) return;
    ScopedPhase ph(sim_.timers(), "diagnostics");
    csv_->row(diagnostic_values(sim_, last_dt, wall_s));
    if (solids_csv_) solids_csv_->rows(solid_values(sim_));
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
    if (solids_csv_) solids_csv_->flush();
    for (ComponentCsv& f : files_)
      if (f.csv) f.csv->flush();
  }

 private:
  /// A component's file (solver/model/component.hpp) and its writer (null without an
  /// output directory); bytes and rows as a checkpoint recorded them (resume).
  struct ComponentCsv {
    ComponentFile file;
    std::unique_ptr<CsvWriter> csv;
    std::int64_t bytes = 0, rows = 0;
  };
  /// The components' files, in the order of the components and of their lists: written
  /// only with VTK frames (their rows are written at the frames).
  static std::vector<ComponentCsv> component_files(const Simulation& sim) {
    std::vector<ComponentCsv> files;
    if (!sim.config().write_vtk) return files;
    for (const auto& c : sim.components())
      for (ComponentFile& f : c->files()) files.push_back({std::move(f), nullptr});
    return files;
  }
  /// The checkpoint record of a file's length: run.<stem>_bytes, run.<stem>_rows.
  static std::string record(const ComponentCsv& f, const char* what) {
    return "run." + fs::path(f.file.name).stem().string() + "_" + what;
  }

  Simulation& sim_;
  std::string dir_;
  std::unique_ptr<CsvWriter> csv_;
  std::unique_ptr<CsvWriter> solids_csv_;  ///< only with solids
  std::unique_ptr<PvdSeries> pvd_;
  std::vector<ComponentCsv> files_;  ///< the components' own files (only with VTK frames)
  int frame_ = 0;
};

/// steady_tol: max over cells of |u^{n+1} - u^n| / dt (both components) against the
/// tolerance; keeps the velocity before each step. The steady state of this split scheme
/// depends on dt at first order (docs/method.md), so steady results depend on cfl.
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

CheckpointScene read_checkpoint_scene(CheckpointReader& r) {
  CheckpointScene c;
  c.text = r.get_string("scene.text");
  c.path = r.get_string("scene.path");
  const std::int64_t n = r.get_i64("scene.sets");
  for (std::int64_t k = 0; k < n; ++k) c.sets.push_back(r.get_string("scene.set"));
  return c;
}

namespace {

/// An output written during the run: when, and what. The list in run() is every output
/// of a step, in the order they are written after it.
struct ScheduledOutput {
  const char* name;
  bool enabled;
  Schedule when;
  std::function<void()> write;
};

/// A check of the state after a step: "" or what is wrong (solver/model/health.hpp).
using HealthCheck = std::function<std::string(const Simulation&, double dt)>;

}  // namespace

RunSummary run(Simulation& sim, const RunOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const Config& cfg = sim.config();
  RunSummary sum;
  const double eps_t = 1e-12 * std::max(1.0, std::abs(cfg.t_end));
  double last_dt = 0.0;
  std::unique_ptr<RunOutput> outp;
  double next_frame = cfg.output_interval > 0.0 ? cfg.t_start + cfg.output_interval : cfg.t_end;
  if (opt.resume) {
    CheckpointReader& r = *opt.resume;
    next_frame = r.get_f64("run.next_frame");
    last_dt = r.get_f64("run.last_dt");
    outp = std::make_unique<RunOutput>(sim, opt.out_dir, r);
  } else {
    outp = std::make_unique<RunOutput>(sim, opt.out_dir);
  }
  RunOutput& out = *outp;
  Progress progress(cfg.t_start, cfg.t_end, cfg.log_interval_s, opt.progress && !opt.quiet);
  if (!opt.resume) {
    out.frame();
    out.row(last_dt, wall_seconds_since(wall0));
  }

  // the outputs of a step, in the order they are written: the diagnostics row, a frame
  // (steps land on the frame times; with a checkpoint when output.checkpoint_frames), a
  // checkpoint every checkpoint_minutes of wall time. A checkpoint (solver/model/checkpoint.cpp)
  // is also written on SIGINT/SIGTERM; it goes to a temporary and is renamed, so the file
  // on disk is always a whole checkpoint.
  const bool checkpoints = out.enabled() && !opt.scene_text.empty();
  const double ck_minutes = opt.checkpoint_minutes >= 0.0 ? opt.checkpoint_minutes : cfg.checkpoint_minutes;
  const double frame_interval = cfg.output_interval > 0.0 ? cfg.output_interval : cfg.t_end;
  enum { kRow, kFrame, kTimedCheckpoint };
  std::vector<ScheduledOutput> outputs(3);
  auto write_checkpoint = [&]() {
    if (!checkpoints) return;
    ScopedPhase ph(sim.timers(), "checkpoint");
    CheckpointWriter w;
    w.put_string("scene.text", opt.scene_text);
    w.put_string("scene.path", opt.scene_path);
    w.put_i64("scene.sets", std::int64_t(opt.sets.size()));
    for (const auto& s : opt.sets) w.put_string("scene.set", s);
    sim.save_state(w);
    w.put_f64("run.next_frame", outputs[kFrame].when.next_time());
    w.put_f64("run.last_dt", last_dt);
    out.save_state(w);
    sum.checkpoint = (fs::path(out.dir()) / "checkpoint.bin").string();
    w.save(sum.checkpoint);
    outputs[kTimedCheckpoint].when.advance();  // the wall clock counts from any checkpoint
  };
  outputs[kRow] = {"diagnostics", true, Schedule::every_steps(std::max(1, cfg.diagnostics_every)),
                   [&] { out.row(last_dt, wall_seconds_since(wall0)); }};
  outputs[kFrame] = {"frame", out.frames(), Schedule::every_time(next_frame, frame_interval, cfg.t_end, eps_t), [&] {
                       out.frame();
                       if (cfg.checkpoint_frames) write_checkpoint();
                     }};
  outputs[kTimedCheckpoint] = {"checkpoint", checkpoints && ck_minutes > 0.0,
                               Schedule::every_wall_seconds(60.0 * ck_minutes), write_checkpoint};

  // the checks of every step's state, in this order: a blow-up is reported as one before
  // the folded reference map it causes (solver/model/health.hpp)
  EnergyJumpCheck blowup;
  const std::vector<HealthCheck> health{check_health,
                                        [&](const Simulation& s, double) { return blowup.check(s); },
                                        [](const Simulation& s, double) { return check_reference_maps(s); }};

  SteadyCheck steady(cfg.steady_tol);
  // phase timers cover the steps after the warm-up (and the final output)
  auto timed0 = wall0;
  long timed_step0 = sim.steps();
  auto fail = [&](const std::string& what) {
    sum.failed = true;
    sum.failure = what;
  };
  const int team0 = omp_get_max_threads();
  ThreadGovernor governor(team0, opt.govern_threads);
  while (sim.time() < cfg.t_end - eps_t) {
    if (opt.timing_warmup_steps > 0 && sim.steps() == opt.timing_warmup_steps) {
      sim.timers().reset();
      timed0 = std::chrono::steady_clock::now();
      timed_step0 = sim.steps();
    }
    if (cfg.max_steps > 0 && sim.steps() >= cfg.max_steps) break;
    double dt = cfg.dt_fixed > 0.0 ? cfg.dt_fixed : sim.stable_dt();
    dt = landing_step(dt, cfg.t_end - sim.time(), eps_t);
    for (const ScheduledOutput& o : outputs)
      if (o.enabled) dt = o.when.land(dt, sim.time());
    steady.before_step(sim);
    const long step0 = sim.steps();
    const double t0 = sim.time();
    try {
      sim.step(dt);
    } catch (const std::runtime_error& e) {
      // a solid that vanished or reached a periodic side, a window that cannot be fitted:
      // the state is part-way through the step, so nothing more of it is written
      char where[128];
      std::snprintf(where, sizeof where, " (in step %ld, from t = %.6g with dt = %.3g)", step0 + 1, t0, dt);
      fail(e.what() + std::string(where));
      break;
    }
    last_dt = dt;
    governor.after_step();

    try {
      std::string bad;
      for (const HealthCheck& h : health)
        if (bad = h(sim, dt); !bad.empty()) break;
      if (!bad.empty()) {
        out.row(last_dt, wall_seconds_since(wall0));
        fail(bad);
        try {  // a frame that cannot be written must not hide the health check's message
          sum.failed_frame = out.failed_frame();
        } catch (const std::runtime_error&) {
        }
        break;
      }
      for (ScheduledOutput& o : outputs)
        if (o.enabled && o.when.due(sim.steps(), sim.time())) {
          o.when.advance();
          o.write();
        }
      if (const int sig = stop_requested()) {
        write_checkpoint();
        sum.signal = sig;
        break;
      }
    } catch (const std::runtime_error& e) {  // an output that cannot be written (full disk)
      char where[128];
      std::snprintf(where, sizeof where, " (after step %ld, t = %.6g)", sim.steps(), sim.time());
      fail(e.what() + std::string(where));
      break;
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
  try {  // the end of the run: the last row and frame (unless written), probes, the components' end
    if (!sum.failed) {
      if (!outputs[kRow].when.due(sim.steps(), sim.time())) out.row(last_dt, wall_seconds_since(wall0));
      if (!sum.signal) out.frame();
      out.probes();
    }
    out.flush();
    // the components' end (the contact's events.csv: solver/components/contact_component.hpp)
    for (const auto& c : sim.components()) c->finish(sim, out.enabled() ? out.dir() : std::string());
  } catch (const std::runtime_error& e) {
    if (!sum.failed) fail(e.what() + std::string(" (writing the final output)"));
  }
  sum.steps = sim.steps();
  sum.t_end = sim.time();
  sum.wall_s = wall_seconds_since(wall0);
  sum.timed_steps = sim.steps() - timed_step0;
  sum.timed_wall_s = wall_seconds_since(timed0);
  sum.thread_switches = governor.switches();
  sum.min_threads = opt.govern_threads ? governor.min_threads() : 0;
  if (governor.switches() > 0) omp_set_num_threads(team0);  // the caller's team again
  return sum;
}

}  // namespace refmap
