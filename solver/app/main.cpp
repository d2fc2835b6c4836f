// refmap command line:
//
//   refmap run SCENE.toml [--out DIR] [--threads N] [--fixed-threads] [--set key=value ...]
//              [--quiet] [--timing-warmup N]
//   refmap keys [--markdown]      (the scene-key reference, from solver/scene/scene_keys.cpp)
//   refmap resume DIR [--threads N] [--fixed-threads] [--quiet]
//   refmap keys [--markdown]
//   refmap --help | refmap run --help | refmap --version
//
// Exit codes: 0 success, 1 a bug (an unexpected exception), 2 bad command line, scene file
// or checkpoint (nothing is written), 3 the simulation failed (non-finite fields, blow-up,
// a solid lost, an output that cannot be written; partial output valid), 130 / 143 stopped
// by SIGINT / SIGTERM after writing a checkpoint.
#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#ifdef _OPENMP
#include <omp.h>
#include <unistd.h>
#endif

#include "solver/io/checkpoint_io.hpp"
#include "solver/model/config.hpp"
#include "solver/scene/memory_estimate.hpp"
#include "solver/app/run.hpp"
#include "solver/scene/option_names.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/scene_keys.hpp"
#include "solver/model/simulation.hpp"
#include "solver/app/stop_signal.hpp"

#ifndef REFMAP_VERSION
#define REFMAP_VERSION "0.1"
#endif

namespace fs = std::filesystem;

namespace {

constexpr int kExitError = 1, kExitUsage = 2, kExitFailed = 3;

int error(const std::string& msg, int code) {
  std::cerr << "refmap: error: " << msg << std::endl;
  return code;
}

/// Quotes an argument for a POSIX shell if it needs it.
std::string shell_quote(const std::string& s) {
  bool plain = !s.empty();
  for (char c : s)
    plain = plain && (std::isalnum((unsigned char)c) || std::string_view("_-+=.,/:@%").find(c) != std::string_view::npos);
  if (plain) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// DIR/scene.toml: the input file verbatim under a comment header that records the
/// --set overrides, so `refmap run DIR/scene.toml --set ...` reproduces the run.
void write_scene_copy(const fs::path& dir, const std::string& scene_path, const std::vector<std::string>& sets) {
  std::ifstream in(scene_path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::string header = "# Scene of this run, copied by refmap " REFMAP_VERSION " from " +
                       fs::absolute(scene_path).lexically_normal().string() + "\n";
  if (sets.empty()) {
    header += "# --set overrides: none\n";
  } else {
    header += "# --set overrides (NOT applied below; pass them again to reproduce):";
    for (const auto& s : sets) header += " --set " + shell_quote(s);
    header += "\n";
  }
  const fs::path out = dir / "scene.toml";
  const std::string tmp = out.string() + ".tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o) throw std::runtime_error("cannot write " + tmp);
    o << header << text.str();
    if (!text.str().empty() && text.str().back() != '\n') o << '\n';
    if (!o) throw std::runtime_error("cannot write " + tmp);
  }
  fs::rename(tmp, out);
}

void print_outputs(const fs::path& dir) {
  std::printf("output:      %s\n", dir.string().c_str());
  std::vector<fs::path> pvd;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".pvd") pvd.push_back(e.path());
  std::sort(pvd.begin(), pvd.end());
  for (const auto& p : pvd) std::printf("frames:      %s\n", p.string().c_str());
  const fs::path diag = dir / "diagnostics.csv";
  if (fs::exists(diag, ec)) std::printf("diagnostics: %s\n", diag.string().c_str());
  const fs::path solids = dir / "solids.csv";
  if (fs::exists(solids, ec)) std::printf("solids:      %s\n", solids.string().c_str());
  std::vector<fs::path> probes;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("probe_", 0) == 0 && e.path().extension() == ".csv") probes.push_back(e.path());
  }
  std::sort(probes.begin(), probes.end());
  for (const auto& p : probes) std::printf("probe:       %s\n", p.string().c_str());
}

/// DIR/timings.csv: the phase table of the run in machine-readable form ('#' key: value
/// lines, then phase,seconds,calls; see docs/output.md).
void write_timings_csv(const fs::path& dir, const refmap::Simulation& sim, const refmap::RunSummary& s,
                       int nthreads, long warmup) {
  std::ostringstream o;
  const refmap::Config& c = sim.config();
  long window_cells = 0;
  std::size_t bytes = 0;
  for (const auto& solid : sim.solids()) {
    window_cells += long(solid->ni()) * long(solid->nj());
    bytes += solid->storage_bytes();
  }
  o << "# refmap timings (wall seconds per phase over the timed steps)\n"
    << "# scene: " << c.name << "\n# nx: " << c.grid.nx << "\n# ny: " << c.grid.ny << "\n# threads: " << nthreads
    << "\n# steps: " << s.steps << "\n# warmup_steps: " << warmup << "\n# timed_steps: " << s.timed_steps
    << "\n# timed_wall_s: " << s.timed_wall_s << "\n# wall_s: " << s.wall_s << "\n# solids: " << sim.solids().size()
    << "\n# thread_switches: " << s.thread_switches << "\n# min_threads: " << s.min_threads
    << "\n# solid_window_cells: " << window_cells << "\n# solid_storage_bytes: " << bytes << "\n";
  sim.timers().write_csv(o, s.timed_wall_s);
  std::ofstream f(dir / "timings.csv", std::ios::trunc);
  f << o.str();
  if (!f) throw std::runtime_error("cannot write " + (dir / "timings.csv").string());
}

int set_threads(int threads, bool threads_given) {
#ifdef _OPENMP
  if (threads_given) omp_set_num_threads(threads);
  return omp_get_max_threads();
#else
  return 1;
#endif
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Run options whose checkpoints carry the scene (text, absolute path, --set overrides).
refmap::RunOptions checkpointed(const std::string& text, const std::string& path, const std::vector<std::string>& sets,
                                double ck_minutes) {
  refmap::RunOptions ro;
  ro.scene_text = text;
  ro.scene_path = path;
  ro.sets = sets;
  ro.checkpoint_minutes = ck_minutes;
  return ro;
}

/// Runs sim (fresh or resumed) into dir and reports: the part `run` and `resume` share.
int execute(refmap::Simulation& sim, const fs::path& dir, refmap::RunOptions ro, int nthreads, long warmup,
            bool quiet, bool fixed_threads) {
  const refmap::Config& cfg = sim.config();
  if (!quiet) {
    std::printf("memory: about %s\n",
                refmap::estimate_memory(cfg).summary().c_str());
    std::fflush(stdout);
  }
  ro.out_dir = dir.string();
  ro.progress = !quiet;
  ro.quiet = quiet;
  ro.timing_warmup_steps = warmup;
  ro.govern_threads = !fixed_threads;
  refmap::install_stop_handlers();
  const refmap::RunSummary s = refmap::run(sim, ro);

  if (s.failed) {
    std::fflush(stdout);
    std::cerr << "refmap: error: simulation failed after " << s.steps << " steps at t = " << s.t_end << ": "
              << s.failure << "\n";
    if (!s.failed_frame.empty()) std::cerr << "refmap: the failing state: " << s.failed_frame << "\n";
    std::cerr << "refmap: partial output in " << dir.string() << std::endl;
    return kExitFailed;
  }
  write_timings_csv(dir, sim, s, nthreads, warmup);
  if (s.signal) {
    std::fflush(stdout);
    std::cerr << "refmap: stopped by " << (s.signal == SIGINT ? "SIGINT" : s.signal == SIGTERM ? "SIGTERM" : "a signal")
              << " after step " << s.steps << " at t = " << s.t_end << "; outputs written up to there\n";
    if (!s.checkpoint.empty())
      std::cerr << "refmap: checkpoint " << s.checkpoint << "\nrefmap: continue with: refmap resume "
                << shell_quote(dir.string()) << std::endl;
    return 128 + s.signal;
  }
  if (!quiet) {
    std::printf("\nfinished: %ld steps, simulated time %.10g, wall %.3f s%s\n", s.steps, s.t_end, s.wall_s,
                s.steady ? " (steady state reached)" : "");
    if (s.thread_switches > 0)
      std::printf("threads: %d, down to %d while other processes used the cores (%d changes; --fixed-threads "
                  "keeps the team)\n",
                  nthreads, s.min_threads, s.thread_switches);
    print_outputs(dir);
    std::printf("\n");
    std::ostringstream table;
    if (warmup > 0)
      table << "(phase times of the last " << s.timed_steps << " steps, after " << warmup << " warm-up steps)\n";
    sim.timers().report(table, s.timed_wall_s);
    // one line per solid; beyond a handful of solids their sum (a 42-solid scene would
    // otherwise end with 42 lines nobody reads)
    auto line = [&](const std::string& who, const refmap::ExtrapolationCounters& c, long moves) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "%-21s %s extrapolation: %ld calls, %ld cells filled, %ld fallbacks%s, "
                    "%ld window moves\n",
                    who.c_str(), refmap::to_string(cfg.solid_opt.extrapolation), c.calls, c.cells_filled,
                    c.fallbacks, c.iterations ? (", " + std::to_string(c.iterations) + " PDE iterations").c_str() : "",
                    moves);
      table << buf;
    };
    constexpr std::size_t kSolidLines = 4;
    if (sim.solids().size() <= kSolidLines) {
      for (const auto& solid : sim.solids())
        line("solid " + solid->spec().name, solid->extrapolation_counters(), solid->rewindows());
    } else {
      refmap::ExtrapolationCounters all;
      long moves = 0;
      for (const auto& solid : sim.solids()) {
        const refmap::ExtrapolationCounters& c = solid->extrapolation_counters();
        all.calls += c.calls;
        all.cells_filled += c.cells_filled;
        all.fallbacks += c.fallbacks;
        all.iterations += c.iterations;
        moves += solid->rewindows();
      }
      line("all " + std::to_string(sim.solids().size()) + " solids", all, moves);
    }
    std::fputs(table.str().c_str(), stdout);
  }
  return 0;
}

/// The output directory, created; a directory that cannot be made is a usage error.
bool make_output_dir(const std::string& out, fs::path& dir, std::string& why) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) {
    why = "cannot create the output directory " + out + ": " + (ec ? ec.message() : "not a directory");
    return false;
  }
  dir = fs::absolute(out).lexically_normal();
  return true;
}

int cmd_run(const std::string& scene, std::string out, int threads, bool threads_given, bool fixed_threads,
            const std::vector<std::string>& sets, bool quiet, long warmup, double ck_minutes) {
  if (threads_given && threads < 1) return error("--threads must be >= 1, got " + std::to_string(threads), kExitUsage);
  if (warmup < 0) return error("--timing-warmup must be >= 0, got " + std::to_string(warmup), kExitUsage);

  refmap::Config cfg;
  try {
    cfg = refmap::load_scene(scene, sets);
  } catch (const refmap::SceneError& e) {
    return error(e.what(), kExitUsage);
  }
  const int nthreads = set_threads(threads, threads_given);

  if (out.empty()) out = (fs::path("out") / cfg.name).string();
  fs::path dir;
  std::string why;
  if (!make_output_dir(out, dir, why)) return error(why, kExitUsage);
  write_scene_copy(dir, scene, sets);

  if (!quiet) {
    std::printf("refmap %s: scene '%s' (%s), %d x %d cells, dx = %.6g, t = %.6g .. %.6g, %d thread%s\n", REFMAP_VERSION,
                cfg.name.c_str(), scene.c_str(), cfg.grid.nx, cfg.grid.ny, cfg.grid.dx, cfg.t_start, cfg.t_end,
                nthreads, nthreads == 1 ? "" : "s");
    std::fflush(stdout);
  }

  refmap::Simulation sim(cfg);
  const refmap::RunOptions ro =
      checkpointed(read_text(scene), fs::absolute(scene).lexically_normal().string(), sets, ck_minutes);
  return execute(sim, dir, ro, nthreads, warmup, quiet, fixed_threads);
}

int cmd_resume(const std::string& out, int threads, bool threads_given, bool fixed_threads, bool quiet,
               double ck_minutes) {
  if (threads_given && threads < 1) return error("--threads must be >= 1, got " + std::to_string(threads), kExitUsage);
  const fs::path dir = fs::absolute(out).lexically_normal();
  const std::string path = (dir / "checkpoint.bin").string();
  try {
    refmap::CheckpointReader r(path);
    const refmap::CheckpointScene sc = refmap::read_checkpoint_scene(r);
    refmap::Config cfg;
    try {
      cfg = refmap::load_scene_string(sc.text, sc.path, sc.sets);
    } catch (const refmap::SceneError& e) {
      return error(std::string("the checkpoint's scene: ") + e.what(), kExitUsage);
    }
    const int nthreads = set_threads(threads, threads_given);
    refmap::Simulation sim(cfg);
    sim.load_state(r);
    if (!quiet) {
      std::printf("refmap %s: resuming scene '%s' (%s) from %s at step %ld, t = %.10g, %d thread%s\n",
                  REFMAP_VERSION, cfg.name.c_str(), sc.path.c_str(), path.c_str(), sim.steps(), sim.time(), nthreads,
                  nthreads == 1 ? "" : "s");
      std::fflush(stdout);
    }
    refmap::RunOptions ro = checkpointed(sc.text, sc.path, sc.sets, ck_minutes);
    ro.resume = &r;
    return execute(sim, dir, ro, nthreads, 0, quiet, fixed_threads);
  } catch (const refmap::CheckpointError& e) {
    return error(std::string(e.what()) + " (nothing was changed)", kExitUsage);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"refmap " REFMAP_VERSION
               ": incompressible flow with soft solids on one Cartesian grid (reference map technique)",
               "refmap"};
  app.set_version_flag("--version", std::string("refmap ") + REFMAP_VERSION);
  app.footer("Run `refmap run --help` for the options of a run; scenes/README.md documents the scene file.");

  std::string scene, out;
  int threads = 0;
  std::vector<std::string> sets;
  bool quiet = false;
  long warmup = 0;
  CLI::App* run = app.add_subcommand("run", "run a simulation from a scene file");
  run->footer("Writes DIR/scene.toml (the scene, for reproducing the run), VTK frames with a .pvd series,\n"
              "diagnostics.csv, solids.csv, probe CSVs, timings.csv (wall time per phase) and checkpoint.bin. Exit codes:\n"
              "0 ok, 1 a bug, 2 bad command line or scene file (nothing written), 3 the simulation failed\n"
              "(partial output valid), 130/143 stopped by SIGINT/SIGTERM (continue with refmap resume DIR).\n"
              "Scene keys: scenes/README.md.");
  run->add_option("scene", scene, "scene file (TOML)")->required()->type_name("SCENE.toml");
  run->add_option("-o,--out", out, "output directory (default: out/<scene name>)")->type_name("DIR");
  CLI::Option* threads_opt =
      run->add_option("-j,--threads", threads, "number of OpenMP threads (default: OMP_NUM_THREADS or all cores)")
          ->type_name("N");
  bool fixed_threads = false;
  const char* fixed_help =
      "keep the team at --threads for the whole run (default: drop to the cores other processes leave free "
      "and return when they are free again; the results are the same bits either way)";
  run->add_flag("--fixed-threads", fixed_threads, fixed_help);
  run->add_option("-s,--set", sets,
                  "override a scene value, e.g. --set fluid.viscosity=0.001 --set solver.advection=superbee "
                  "(the value is TOML; a bare word is a string); repeatable")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  run->add_option("--timing-warmup", warmup,
                  "leave the first N steps out of the phase timings (table and DIR/timings.csv)")
      ->type_name("N");
  run->add_flag("-q,--quiet", quiet, "no progress display and no summary (errors are still printed)");
  double ck_minutes = -1.0;
  run->add_option("--checkpoint-minutes", ck_minutes,
                  "write DIR/checkpoint.bin every M wall minutes (default: output.checkpoint_minutes; 0: only with "
                  "frames and on SIGINT/SIGTERM)")
      ->type_name("M")
      ->check(CLI::NonNegativeNumber);

  std::string resume_dir;
  CLI::App* resume = app.add_subcommand("resume", "continue a run from its output directory's checkpoint");
  resume->footer("Reads DIR/checkpoint.bin (written with every frame, every output.checkpoint_minutes and on\n"
                 "SIGINT/SIGTERM) and runs on to the scene's end, continuing diagnostics.csv, the frames and\n"
                 "the .pvd series; with the same binary and thread count the result is the same bits as an\n"
                 "uninterrupted run. A damaged checkpoint is refused (exit 2) and nothing is changed.");
  resume->add_option("dir", resume_dir, "output directory of the run")->required()->type_name("DIR");
  CLI::Option* resume_threads_opt =
      resume->add_option("-j,--threads", threads, "number of OpenMP threads")->type_name("N");
  resume->add_flag("--fixed-threads", fixed_threads, fixed_help);
  resume->add_flag("-q,--quiet", quiet, "no progress display and no summary");
  resume->add_option("--checkpoint-minutes", ck_minutes, "as for run")->type_name("M")->check(CLI::NonNegativeNumber);

  bool markdown = false;
  CLI::App* keys = app.add_subcommand("keys", "print the reference of the scene-file keys");
  keys->add_flag("--markdown", markdown,
                 "print the markdown tables of scenes/README.md (the block between <!-- keys:begin --> and "
                 "<!-- keys:end -->)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : kExitUsage;
  }

  try {
    if (run->parsed()) return cmd_run(scene, out, threads, threads_opt->count() > 0, fixed_threads, sets, quiet, warmup, ck_minutes);
    if (resume->parsed()) return cmd_resume(resume_dir, threads, resume_threads_opt->count() > 0, fixed_threads, quiet,
                                                ck_minutes);
    if (keys->parsed()) {
      std::cout << (markdown ? refmap::scene_keys_markdown() : refmap::scene_keys_text());
      return 0;
    }
    std::cerr << app.help();
    return kExitUsage;
  } catch (const std::exception& e) {
    return error(e.what(), kExitError);
  } catch (...) {
    return error("unknown exception", kExitError);
  }
}
