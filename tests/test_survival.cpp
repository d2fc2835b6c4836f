// Runs that survive (the exit-code contract of solver/app/main.cpp and the checkpoints of
// solver/model/checkpoint.cpp), tested on the refmap binary itself, as a user meets them:
//  - a run stopped by SIGINT and resumed gives the same diagnostics rows, events, frames
//    and .pvd series, bit for bit, as the uninterrupted run;
//  - SIGTERM: exit 143, every output of the state reached written, no temporary left;
//  - a damaged checkpoint is refused with exit 2 and changes nothing;
//  - failures during the run (a blow-up, a solid grown too wide for a periodic direction) end with
//    exit 3 and a message naming the step and time; a directory that cannot be made is
//    exit 2; a health check's stop writes frame_failed.vti of the refused state (not in
//    the .pvd series);
//  - a reused output directory holds no frames of the earlier run; no .pvd without frames.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/fixtures/scene_text.hpp"

#include <spawn.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace fs = std::filesystem;
using namespace refmap::testing;

namespace {

const std::string kBin = REFMAP_BINARY;
const std::string kScenes = std::string(REFMAP_SOURCE_DIR) + "/scenes/";

struct Result {
  int code = -1;
  std::string err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Starts refmap with `args` (stdout and stderr to files in `log`); returns the pid.
pid_t spawn(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> all{kBin};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, (log.string() + ".out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, (log.string() + ".err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, kBin.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

Result wait_for(pid_t pid, const fs::path& log) {
  int status = 0;
  waitpid(pid, &status, 0);
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = slurp(log.string() + ".err");
  return r;
}

Result run(const std::vector<std::string>& args, const fs::path& log) { return wait_for(spawn(args, log), log); }

/// Waits (up to a minute) until a running refmap's diagnostics.csv holds more than
/// `bytes` (its rows reach the file about once a wall second).
void wait_for_diagnostics(const fs::path& f, std::uintmax_t bytes) {
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60)) {
    std::error_code ec;
    if (fs::file_size(f, ec) > bytes && !ec) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

/// diagnostics.csv without its wall_time column (the one value that differs by nature).
std::string diagnostics_without_wall_time(const fs::path& f) {
  std::istringstream in(slurp(f));
  std::string line, out;
  int wall = -1;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '#') continue;
    std::vector<std::string> cols;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cols.push_back(c);
    if (wall < 0)
      for (std::size_t k = 0; k < cols.size(); ++k)
        if (cols[k] == "wall_time") wall = int(k);
    for (std::size_t k = 0; k < cols.size(); ++k)
      if (int(k) != wall) out += cols[k] + ",";
    out += "\n";
  }
  return out;
}

class Survival : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("refmap_survival_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  fs::path dir_;
};

}  // namespace

TEST_F(Survival, InterruptedAndResumedRunIsBitIdentical) {
  // two soft discs with contact at 128^2: solids, windows that move, the contact tracker
  const std::vector<std::string> common{"--threads", "1", "--quiet", "--set", "time.end=0.45"};
  auto args = [&](const std::string& out) {
    std::vector<std::string> a{"run", kScenes + "two_solids_tgv.toml", "--out", out};
    a.insert(a.end(), common.begin(), common.end());
    return a;
  };
  const fs::path A = dir_ / "whole", B = dir_ / "stopped";
  ASSERT_EQ(run(args(A.string()), dir_ / "a").code, 0);

  const pid_t pid = spawn(args(B.string()), dir_ / "b");
  ASSERT_GT(pid, 0);
  // stop it part-way: once some diagnostics rows (flushed about once a wall second) are on disk
  wait_for_diagnostics(B / "diagnostics.csv", 20000);
  kill(pid, SIGINT);
  const Result stopped = wait_for(pid, dir_ / "b");
  ASSERT_EQ(stopped.code, 130) << "the run ended before the signal, or did not stop cleanly: " << stopped.err;
  EXPECT_NE(stopped.err.find("refmap resume"), std::string::npos) << stopped.err;
  ASSERT_TRUE(fs::exists(B / "checkpoint.bin"));
  for (const auto& e : fs::directory_iterator(B))
    EXPECT_EQ(e.path().extension(), e.path().extension() == ".tmp" ? ".none" : e.path().extension())
        << "temporary left: " << e.path();
  // the partial output is valid: diagnostics end on a whole row
  const std::string partial = slurp(B / "diagnostics.csv");
  ASSERT_FALSE(partial.empty());
  EXPECT_EQ(partial.back(), '\n');
  const std::string partial_solids = slurp(B / "solids.csv");  // and solids.csv on a whole step
  ASSERT_FALSE(partial_solids.empty());
  EXPECT_EQ(partial_solids.back(), '\n');

  const Result resumed = run({"resume", B.string(), "--threads", "1", "--quiet"}, dir_ / "c");
  ASSERT_EQ(resumed.code, 0) << resumed.err;

  EXPECT_EQ(diagnostics_without_wall_time(A / "diagnostics.csv"), diagnostics_without_wall_time(B / "diagnostics.csv"));
  EXPECT_EQ(slurp(A / "solids.csv"), slurp(B / "solids.csv"));
  EXPECT_EQ(slurp(A / "events.csv"), slurp(B / "events.csv"));
  EXPECT_EQ(slurp(A / "two_solids_tgv.pvd"), slurp(B / "two_solids_tgv.pvd"));
  int frames = 0;
  for (const auto& e : fs::directory_iterator(A)) {
    if (e.path().extension() != ".vti") continue;
    ++frames;
    EXPECT_TRUE(slurp(e.path()) == slurp(B / e.path().filename())) << "frame differs: " << e.path().filename();
  }
  EXPECT_GT(frames, 3);
  int frames_b = 0;
  for (const auto& e : fs::directory_iterator(B)) frames_b += e.path().extension() == ".vti";
  EXPECT_EQ(frames, frames_b);
}

TEST_F(Survival, SigtermWritesEverythingOfTheStateReached) {
  const fs::path out = dir_ / "cavity";
  const pid_t pid = spawn({"run", kScenes + "lid_driven_cavity_re100.toml", "--out", out.string(), "--threads", "1",
                           "--quiet"},
                          dir_ / "t");
  wait_for_diagnostics(out / "diagnostics.csv", 5000);
  kill(pid, SIGTERM);
  const Result r = wait_for(pid, dir_ / "t");
  ASSERT_EQ(r.code, 143) << r.err;
  for (const char* f : {"checkpoint.bin", "timings.csv", "probe_u_vertical.csv", "probe_v_horizontal.csv"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_FALSE(e.path().string().ends_with(".tmp")) << "temporary left: " << e.path();
}

TEST_F(Survival, DamagedCheckpointIsRefusedAndNothingChanges) {
  const fs::path out = dir_ / "tg";
  ASSERT_EQ(run({"run", kScenes + "taylor_green.toml", "--out", out.string(), "--threads", "1", "--quiet", "--set",
                 "grid.nx=32", "--set", "grid.ny=32"},
                dir_ / "r")
                .code,
            0);
  ASSERT_TRUE(fs::exists(out / "checkpoint.bin"));  // written with the frames
  const std::string ck = slurp(out / "checkpoint.bin"), diag = slurp(out / "diagnostics.csv");
  for (const std::string& damaged : {ck.substr(0, ck.size() / 2), ck.substr(0, ck.size() - 1) + "x"}) {
    std::ofstream(out / "checkpoint.bin", std::ios::binary | std::ios::trunc) << damaged;
    const Result r = run({"resume", out.string(), "--quiet"}, dir_ / "d");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("checkpoint"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing was changed"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
    EXPECT_EQ(slurp(out / "diagnostics.csv"), diag);
    EXPECT_EQ(slurp(out / "checkpoint.bin"), damaged);
  }
  // a sound checkpoint whose diagnostics.csv was cut short: refused before any file is touched
  std::ofstream(out / "checkpoint.bin", std::ios::binary | std::ios::trunc) << ck;
  std::ofstream(out / "diagnostics.csv", std::ios::binary | std::ios::trunc) << diag.substr(0, 10);
  int frames = 0;
  for (const auto& e : fs::directory_iterator(out)) frames += e.path().extension() == ".vti";
  const Result cut = run({"resume", out.string(), "--quiet"}, dir_ / "c");
  EXPECT_EQ(cut.code, 2) << cut.err;
  EXPECT_NE(cut.err.find("shorter than when the checkpoint"), std::string::npos) << cut.err;
  int frames_after = 0;
  for (const auto& e : fs::directory_iterator(out)) frames_after += e.path().extension() == ".vti";
  EXPECT_EQ(frames_after, frames);
  EXPECT_EQ(slurp(out / "diagnostics.csv"), diag.substr(0, 10));

  const Result none = run({"resume", (dir_ / "no_such_run").string(), "--quiet"}, dir_ / "n");
  EXPECT_EQ(none.code, 2) << none.err;
}

TEST_F(Survival, BlowUpIsExit3NamingStepAndTime) {
  // a stiff disc (mu_s = 200, c = 20) at the fixed step 0.008 = 7.7 dx / c on 48^2: far past
  // the stiff solids' limit P = 0.5 (docs/stability.md), allowed at load by solids.solid_cfl
  // = 8 (a fixed step above solid_cfl dx / c is refused, solver/scene/scene.cpp)
  const fs::path out = dir_ / "blowup";
  const Result r = run({"run", kScenes + "disc_tgv.toml", "--out", out.string(), "--threads", "1", "--quiet", "--set",
                        "grid.nx=48", "--set", "grid.ny=48", "--set", "time.dt=0.008", "--set", "solids.solid_cfl=8",
                        "--set", "solid[0].mu_s=200", "--set", "time.end=4"},
                       dir_ / "b");
  EXPECT_EQ(r.code, 3) << r.err;
  // caught by the energy check (solver/app/run.cpp, BlowUpCheck) while the fields are finite
  EXPECT_NE(r.err.find("kinetic energy grew from"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("in one step (step 3, t = 0.024)"), std::string::npos) << r.err;
  const std::string diag = slurp(out / "diagnostics.csv");
  ASSERT_FALSE(diag.empty());
  EXPECT_EQ(diag.back(), '\n');
  // the failing state is written beside the frames (docs/stability.md) and named
  EXPECT_TRUE(fs::exists(out / "frame_failed.vti"));
  EXPECT_NE(r.err.find("the failing state: " + (out / "frame_failed.vti").string()), std::string::npos) << r.err;
  // the same step past the default solid_cfl is refused at load, exit 2, nothing run
  const Result refused = run({"run", kScenes + "disc_tgv.toml", "--out", (dir_ / "refused").string(), "--threads",
                              "1", "--quiet", "--set", "grid.nx=48", "--set", "grid.ny=48", "--set", "time.dt=0.008",
                              "--set", "solid[0].mu_s=200"},
                             dir_ / "r");
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find("time.dt: 0.008 is above the explicit solid time-step limit"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "refused" / "diagnostics.csv"));
}

TEST_F(Survival, VariationalForceFailureIsExit3WithTheFailingState) {
  // the variational solid force (docs/implicit.md) with the semi-implicit splitting at
  // k = 0.25 past its bound: mu_s / rho_s = 100, 64^2, P = 8 (dt_max = 8 dx / sqrt(2 mu_s)):
  // measured, the energy blows up and the run stops (step 158 with the frames of the scene, which
  // move the steps onto the output times; step 324 without them, results/implicit_variational.csv)
  const fs::path out = dir_ / "variational";
  const Result r = run({"run", kScenes + "disc_tgv.toml", "--out", out.string(), "--threads", "1", "--quiet", "--set",
                        "grid.nx=64", "--set", "grid.ny=64", "--set", "time.max_steps=400", "--set", "time.end=100",
                        "--set", "solid.0.mu_s=100", "--set", "time.viscous=\"implicit\"", "--set",
                        "time.solid_stress=\"semi_implicit\"", "--set", "time.solid_implicit_k=0.25", "--set",
                        "solids.stress_discretisation=\"variational\"", "--set", "time.dt_max=0.008838834764831844"},
                       dir_ / "v");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(fs::exists(out / "frame_failed.vti"));
  EXPECT_NE(r.err.find("the failing state: " + (out / "frame_failed.vti").string()), std::string::npos) << r.err;
}

namespace {
/// The FieldData TIME of a .vti frame (solver/io/vtk.cpp writes it with 17 digits).
double vti_time(const fs::path& p) {
  const std::string x = slurp(p);
  const auto k = x.find("Name=\"TIME\"");
  if (k == std::string::npos) return -1.0;
  const auto b = x.find('>', k);
  return std::stod(x.substr(b + 1));
}
}  // namespace

TEST_F(Survival, HealthStopWritesTheFailingStateOutsideTheSeries) {
  // a disc 1000 times lighter than the fluid (mu_s / rho_s kept at the scene's 0.5) fails at
  // 32^2 (bench/stability.py, sweep c): its map folds or its energy blows up (which one
  // the health checks see first depends on the step sequence), the run stops and
  // frame_failed.vti holds the state it refused, at that step's time
  const std::vector<std::string> common{"--threads", "1", "--quiet", "--set", "grid.nx=32", "--set", "grid.ny=32",
                                        "--set", "time.end=1", "--set", "solid.0.density=0.001", "--set",
                                        "solid.0.mu_s=0.0005"};
  auto args = [&](const fs::path& out, bool vtk) {
    std::vector<std::string> a{"run", kScenes + "disc_tgv.toml", "--out", out.string()};
    a.insert(a.end(), common.begin(), common.end());
    a.insert(a.end(), {"--set", std::string("output.vtk=") + (vtk ? "true" : "false")});
    return a;
  };
  const fs::path out = dir_ / "folded";
  const Result r = run(args(out, true), dir_ / "f");
  ASSERT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(r.err.find("reference map folded in solid 'disc'") != std::string::npos ||
              r.err.find("the solution is blowing up") != std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the failing state: " + (out / "frame_failed.vti").string()), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(out / "frame_failed.vti"));
  // its time is the failing step's: the last row of diagnostics.csv (written for the
  // failing state) and the "at t = ..." of the message (6 digits)
  const double t_frame = vti_time(out / "frame_failed.vti");
  const std::string diag = slurp(out / "diagnostics.csv");
  const auto last = diag.rfind('\n', diag.size() - 2);
  const std::string row = diag.substr(last + 1);
  const double t_row = std::stod(row.substr(row.find(',') + 1));
  EXPECT_NEAR(t_frame, t_row, 1e-9 * t_row) << row;
  const auto at = r.err.find(" at t = ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(t_frame, std::stod(r.err.substr(at + 8)), 1e-5 * t_frame);
  // not one of the series: the .pvd lists only the scheduled frames, all earlier
  const std::string pvd = slurp(out / "disc_tgv.pvd");
  EXPECT_EQ(pvd.find("frame_failed"), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("frame_00000.vti"), std::string::npos) << pvd;
  EXPECT_LT(vti_time(out / "frame_00001.vti"), t_frame);
  // written also when the scene asks for no frames (then the only frame, and no .pvd)
  const fs::path quiet = dir_ / "folded_novtk";
  ASSERT_EQ(run(args(quiet, false), dir_ / "g").code, 3);
  EXPECT_TRUE(fs::exists(quiet / "frame_failed.vti"));
  EXPECT_FALSE(fs::exists(quiet / "frame_00000.vti"));
  EXPECT_FALSE(fs::exists(quiet / "disc_tgv.pvd"));
}

TEST_F(Survival, SolidTooWideForAPeriodicDirectionIsExit3) {
  // solids may cross periodic sides (docs/reference_map.md), but a window never gets wider than the
  // period: a long ellipse turned by a prescribed rotation from across the periodic
  // direction x to along it needs 44 + 2 x 3 of the 48 cells (band 6 cells either side)
  const std::string scene = box_scene(48,
                                      "left = \"periodic\"\nright = \"periodic\"\nbottom = \"free_slip\"\n"
                                      "top = \"free_slip\"\n",
                                      "[initial]\nvelocity = \"expression\"\n"
                                      "u_expr = \"-1.5707963267948966*(y - 0.5)\"\n"
                                      "v_expr = \"1.5707963267948966*(x - 0.5)\"\n[solver]\nflow = \"prescribed\"\n"
                                      "[[solid]]\nname = \"spinner\"\nshape = \"ellipse\"\ncenter = [0.5, 0.5]\n"
                                      "semi_axes = [0.33, 0.04]\nangle = 1.5707963267948966\nvelocity = \"fluid\"\n",
                                      0.0);
  std::ofstream(dir_ / "wide.toml") << scene;
  const Result r = run({"run", (dir_ / "wide.toml").string(), "--out", (dir_ / "w").string(), "--quiet"}, dir_ / "w");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("'spinner' is too wide for the periodic direction x"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("in step "), std::string::npos) << r.err;
}

TEST_F(Survival, UncreatableOutputDirectoryIsExit2) {
  std::ofstream(dir_ / "a_file") << "x";
  const Result r = run({"run", kScenes + "taylor_green.toml", "--out", (dir_ / "a_file" / "out").string(), "--quiet"},
                       dir_ / "u");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("cannot create the output directory"), std::string::npos) << r.err;
}

TEST_F(Survival, ReusedDirectoryHoldsNoStaleFramesAndNoPvdWithoutFrames) {
  const fs::path out = dir_ / "reused";
  fs::create_directories(out);
  for (const char* f : {"frame_00099.vti", "old_scene.pvd", "probe_gone.csv", "checkpoint.bin", "notes.txt"})
    std::ofstream(out / f) << "earlier run";
  ASSERT_EQ(run({"run", kScenes + "taylor_green.toml", "--out", out.string(), "--quiet", "--set", "grid.nx=16",
                 "--set", "grid.ny=16", "--set", "output.vtk=false"},
                dir_ / "s")
                .code,
            0);
  EXPECT_FALSE(fs::exists(out / "frame_00099.vti"));
  EXPECT_FALSE(fs::exists(out / "old_scene.pvd"));
  EXPECT_FALSE(fs::exists(out / "probe_gone.csv"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));  // not refmap's: left alone
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_NE(e.path().extension(), ".pvd") << "a .pvd without frames: " << e.path();
  EXPECT_TRUE(fs::exists(out / "diagnostics.csv"));
}
