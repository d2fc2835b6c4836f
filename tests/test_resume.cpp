// Checkpoints are built from the state registry (solver/io/state_registry.hpp): a run stopped
// after N steps, written to a checkpoint and continued by a new Simulation must give the
// same bits as the run that never stopped - for every shipped scene and for the implicit
// variants whose warm-start state was once left out (found when a resumed turek_hron_fsi2
// differed from the first step after the resume). And a component that only a test knows
// about has its state checkpointed without any change to the checkpoint code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "solver/app/run.hpp"
#include "solver/io/checkpoint_io.hpp"
#include "solver/model/diagnostics.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"
#include "solver/io/state_registry.hpp"
#include "test_helpers.hpp"

namespace refmap {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path temp_file(const std::string& name) {
  return fs::temp_directory_path() / ("refmap_resume_" + std::to_string(::getpid()) + "_" + name + ".ck");
}

/// The diagnostics.csv rows (wall time 0) of n steps, each followed by its solids.csv rows.
std::vector<std::vector<double>> steps(Simulation& sim, int n) {
  std::vector<std::vector<double>> rows;
  for (int k = 0; k < n; ++k) {
    const double dt = sim.step();
    rows.push_back(diagnostic_values(sim, dt, 0.0));
    for (const auto& solid_row : solid_values(sim))  // solids.csv's rows of the step
      rows.back().insert(rows.back().end(), solid_row.begin(), solid_row.end());
  }
  return rows;
}

/// Bitwise equality of two rows (NaN == NaN, +0 != -0: the same bits).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::string state_bytes(const Simulation& sim, const std::string& name) {
  CheckpointWriter w;
  sim.save_state(w);
  const fs::path p = temp_file(name);
  w.save(p.string());
  std::string s = slurp(p);
  fs::remove(p);
  return s;
}

/// Runs 2n steps in one go and n + n with a checkpoint between them (a new Simulation
/// built from the same scene loads it); expects the same rows and the same final state.
void expect_resume_bit_identical(const Config& cfg, int n, const std::string& name) {
  Simulation whole(cfg);
  steps(whole, n);
  const auto rows_whole = steps(whole, n);

  const fs::path ck = temp_file(name + "_mid");
  {
    Simulation first(cfg);
    steps(first, n);
    CheckpointWriter w;
    first.save_state(w);
    w.save(ck.string());
  }
  Simulation resumed(cfg);
  CheckpointReader r(ck.string());
  resumed.load_state(r);
  EXPECT_TRUE(r.at_end()) << name << ": records left over";
  fs::remove(ck);
  const auto rows_resumed = steps(resumed, n);

  ASSERT_EQ(rows_whole.size(), rows_resumed.size());
  for (std::size_t k = 0; k < rows_whole.size(); ++k)
    EXPECT_TRUE(same_bits(rows_whole[k], rows_resumed[k])) << name << ": diagnostics row " << k + 1
                                                           << " after the resume differs";
  EXPECT_TRUE(state_bytes(whole, name + "_a") == state_bytes(resumed, name + "_b"))
      << name << ": the state after the resumed steps differs";
}

struct Case {
  std::string scene;
  std::vector<std::string> sets;
  std::string label;
};

std::vector<Case> cases() {
  std::vector<Case> c;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(std::string(REFMAP_SOURCE_DIR) + "/scenes"))
    if (e.path().extension() == ".toml") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  for (const auto& n : names) c.push_back({n, {}, n.substr(0, n.size() - 5)});
  // the implicit velocity step's warm start (solver/model/implicit_step.hpp) in each form
  c.push_back({"couette_elastic.toml", {"time.viscous=implicit"}, "couette_elastic_implicit_viscous"});
  c.push_back({"disc_tgv.toml", {"time.solid_stress=semi_implicit", "grid.nx=64", "grid.ny=64"}, "disc_tgv_semi_implicit"});
  c.push_back({"disc_tgv.toml", {"time.solid_stress=upper_convected", "grid.nx=64", "grid.ny=64"}, "disc_tgv_upper_convected"});
  // Algorithm 1's coupling (the shipped scenes with soft solids use the default, Verlet)
  c.push_back({"disc_tgv.toml", {"time.elastic_coupling=\"symplectic_euler\"", "grid.nx=64", "grid.ny=64"}, "disc_tgv_symplectic_euler"});
  // the components that are off in the shipped scenes
  c.push_back({"flag_clamped.toml", {"output.body_force=control_volume"}, "flag_clamped_control_volume"});
  return c;
}

void PrintTo(const Case& c, std::ostream* os) { *os << c.label; }

class Resume : public ::testing::TestWithParam<Case> {};

TEST_P(Resume, ContinuesBitForBit) {
  const Case& c = GetParam();
  const Config cfg = load_scene(testing::scene_path(c.scene), c.sets);
  // 4 steps on each side: the implicit step's initial guess extrapolates the last two
  // changes, so from the third step after a resume everything of its state is read
  expect_resume_bit_identical(cfg, 4, c.label);
}

INSTANTIATE_TEST_SUITE_P(EveryScene, Resume, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.label; });

/// A component no scene knows: a running sum of the kinetic energy over the steps, and a
/// time-step limit from it. Its state reaches the checkpoint only through register_state.
class EnergyIntegral : public Component {
 public:
  const char* name() const override { return "energy integral"; }
  void register_state(StateRegistry& reg) override {
    reg.add_value("test.energy_integral", integral_);
    reg.add_count("test.calls", calls_);
  }
  double max_dt(const Simulation&) const override { return 1.0 / (1.0 + calls_); }
  void at(StepPoint p, Simulation& sim, double dt) override {
    if (p != StepPoint::End) return;
    integral_ += dt * sim.kinetic_energy();
    ++calls_;
  }
  std::vector<std::string> columns() const override { return {"energy_integral"}; }
  void values(const Simulation&, std::vector<double>& out) const override { out.push_back(integral_); }
  /// energy_integral.csv: one row per VTK frame (the run loop writes it, solver/app/run.cpp).
  std::vector<ComponentFile> files() const override {
    return {{"energy_integral.csv", {"frame", "t", "integral"},
             [this](const Simulation& sim, int frame, std::vector<std::vector<double>>& rows) {
               rows.push_back({double(frame), sim.time(), integral_});
             }}};
  }
  double integral() const { return integral_; }

 private:
  double integral_ = 0.0;
  int calls_ = 0;
};

Config small_taylor_green() {
  return load_scene(testing::scene_path("taylor_green.toml"), {"grid.nx=16", "grid.ny=16"});
}

TEST(Components, StateOfAComponentAddedOnlyHereIsCheckpointed) {
  const Config cfg = small_taylor_green();
  auto make = [&] {
    auto sim = std::make_unique<Simulation>(cfg);
    sim->add_component(std::make_unique<EnergyIntegral>());
    return sim;
  };
  auto whole = make();
  steps(*whole, 6);
  auto first = make();
  steps(*first, 3);
  const fs::path ck = temp_file("component");
  {
    CheckpointWriter w;
    first->save_state(w);
    w.save(ck.string());
  }
  auto resumed = make();
  CheckpointReader r(ck.string());
  resumed->load_state(r);
  fs::remove(ck);
  EXPECT_EQ(resumed->component<EnergyIntegral>()->integral(), first->component<EnergyIntegral>()->integral());
  EXPECT_GT(resumed->component<EnergyIntegral>()->integral(), 0.0);
  steps(*resumed, 3);
  EXPECT_EQ(resumed->component<EnergyIntegral>()->integral(), whole->component<EnergyIntegral>()->integral());
  // a Simulation without the component refuses the checkpoint (a record it does not know)
  Simulation plain(cfg);
  CheckpointWriter w;
  first->save_state(w);
  w.save(ck.string());
  CheckpointReader r2(ck.string());
  plain.load_state(r2);
  EXPECT_FALSE(r2.at_end());
  fs::remove(ck);
}

TEST(Components, HooksLimitTheStepAndAddColumns) {
  const Config cfg = small_taylor_green();
  Simulation sim(cfg);
  const double free_dt = sim.stable_dt();
  sim.add_component(std::make_unique<EnergyIntegral>());
  // the component's limit 1 / (1 + calls) is far below the flow's at 16^2 only if the
  // flow's is above 1: compare with the minimum of both instead
  EXPECT_EQ(sim.stable_dt(), std::min(free_dt, 1.0));
  const auto cols = diagnostic_columns(sim);
  ASSERT_FALSE(cols.empty());
  EXPECT_EQ(cols.back(), "energy_integral");
  const double dt = sim.step();
  const auto vals = diagnostic_values(sim, dt, 0.0);
  ASSERT_EQ(vals.size(), cols.size());
  // the sum after one step: dt times the kinetic energy at its end
  EXPECT_DOUBLE_EQ(vals.back(), dt * sim.kinetic_energy());
}

TEST(Components, OwnFileIsWrittenAtFramesAndContinuedAfterACheckpoint) {
  // 20 steps of 0.005 with a frame (and a checkpoint) every 4 steps; the stopped run ends
  // after step 10, its last checkpoint is that of step 8, and its final frame (step 10)
  // is written after it: the resumed run must cut that row off and write the same file
  Config cfg = small_taylor_green();
  cfg.dt_fixed = 0.005;
  cfg.t_end = 0.1;
  cfg.output_interval = 0.02;
  cfg.write_vtk = true;
  cfg.checkpoint_frames = true;
  const fs::path dir = fs::temp_directory_path() / ("refmap_component_file_" + std::to_string(::getpid()));
  const fs::path whole_dir = dir / "whole", stopped_dir = dir / "stopped";
  fs::remove_all(dir);
  fs::create_directories(whole_dir);
  // a reused directory loses the files of every kind (ComponentKind::files), even of one
  // this scene does not use
  std::ofstream(whole_dir / "tracers.csv") << "stale\n";
  RunOptions opt = RunOptions::silent();
  opt.scene_text = "checkpointed";  // checkpoints are written only with a scene text
  auto make = [&](const Config& c) {
    auto sim = std::make_unique<Simulation>(c);
    sim->add_component(std::make_unique<EnergyIntegral>());
    return sim;
  };
  auto whole = make(cfg);
  opt.out_dir = whole_dir.string();
  ASSERT_FALSE(run(*whole, opt).failed);
  EXPECT_FALSE(fs::exists(whole_dir / "tracers.csv"));
  const std::string file_whole = slurp(whole_dir / "energy_integral.csv");
  // one row per frame, the frame's index first and the integral of the end last
  std::istringstream in(file_whole);
  std::string line, last;
  int rows = 0, frames = 0;
  std::getline(in, line);
  EXPECT_EQ(line, "frame,t,integral");
  while (std::getline(in, line)) {
    EXPECT_EQ(std::stoi(line.substr(0, line.find(','))), rows) << line;
    ++rows;
    last = line;
  }
  for (const auto& e : fs::directory_iterator(whole_dir)) frames += e.path().extension() == ".vti";
  EXPECT_EQ(rows, frames);
  EXPECT_GE(rows, 6);  // frames at steps 0, 4, 8, 12, 16, 20
  // %.10g in the file: 10 significant digits
  const double integral = std::stod(last.substr(last.rfind(',') + 1));
  EXPECT_NEAR(integral, whole->component<EnergyIntegral>()->integral(),
              1e-9 * whole->component<EnergyIntegral>()->integral());

  Config stop = cfg;
  stop.max_steps = 10;
  auto first = make(stop);
  opt.out_dir = stopped_dir.string();
  ASSERT_FALSE(run(*first, opt).failed);
  ASSERT_NE(slurp(stopped_dir / "energy_integral.csv"), file_whole);
  CheckpointReader r((stopped_dir / "checkpoint.bin").string());
  read_checkpoint_scene(r);
  auto resumed = make(cfg);
  resumed->load_state(r);
  EXPECT_EQ(resumed->steps(), 8);
  opt.resume = &r;
  ASSERT_FALSE(run(*resumed, opt).failed);
  EXPECT_EQ(slurp(stopped_dir / "energy_integral.csv"), file_whole);
  fs::remove_all(dir);
}

/// A component whose columns go right after built-in ones (Component::columns_after,
/// solid_columns_after).
class Anchored : public Component {
 public:
  const char* name() const override { return "anchored"; }
  std::vector<std::string> columns() const override { return {"twice_time"}; }
  void values(const Simulation& sim, std::vector<double>& out) const override { out.push_back(2.0 * sim.time()); }
  const char* columns_after() const override { return "time"; }
  std::vector<std::string> solid_columns() const override { return {"index_plus_one"}; }
  void solid_values(const Simulation&, int k, std::vector<double>& out) const override { out.push_back(k + 1.0); }
  const char* solid_columns_after() const override { return "area"; }
};

TEST(Components, ColumnsGoRightAfterTheBuiltInColumnTheyName) {
  const Config cfg = load_scene(testing::scene_path("disc_tgv.toml"), {"grid.nx=64", "grid.ny=64"});
  Simulation sim(cfg);
  sim.add_component(std::make_unique<Anchored>());
  const double dt = sim.step();
  const auto cols = diagnostic_columns(sim);
  const auto vals = diagnostic_values(sim, dt, 0.0);
  ASSERT_EQ(cols.size(), vals.size());
  auto at = [&](const std::vector<std::string>& c, const std::string& name) {
    return std::size_t(std::find(c.begin(), c.end(), name) - c.begin());
  };
  const std::size_t k = at(cols, "twice_time");
  ASSERT_LT(k, cols.size());
  EXPECT_EQ(cols[k - 1], "time");
  EXPECT_EQ(vals[k], 2.0 * sim.time());  // exact: a doubling
  // the contact component's column keeps its place after total_energy
  const std::size_t e = at(cols, "contact_energy");
  ASSERT_LT(e, cols.size());
  EXPECT_EQ(cols[e - 1], "total_energy");
  const auto scols = solid_columns(sim);
  const auto rows = solid_values(sim);
  ASSERT_EQ(rows.size(), sim.solids().size());
  ASSERT_EQ(rows[0].size(), scols.size());
  // "area" is the solids' component's column (first after step, time, solid): a component
  // that names it comes after the solids' columns, which stay together, and before contact's,
  // which name the solids' last column, sigma_max
  EXPECT_EQ(scols[3], "area");
  const std::size_t s = at(scols, "index_plus_one");
  ASSERT_LT(s, scols.size());
  EXPECT_EQ(scols[s - 1], "sigma_max");
  for (std::size_t r = 0; r < rows.size(); ++r) EXPECT_EQ(rows[r][s], double(r) + 1.0);
  const std::size_t gap = at(scols, "gap_solid");
  ASSERT_LT(gap, scols.size());
  EXPECT_EQ(scols[gap - 1], "index_plus_one");
  EXPECT_EQ(scols[gap + 1], "gap_wall");
}

TEST(StateRegistry, RefusesATagRegisteredTwice) {
  StateRegistry reg;
  double a = 0, b = 0;
  reg.add_value("x", a);
  EXPECT_THROW(reg.add_value("x", b), std::logic_error);
  EXPECT_EQ(reg.tags(), std::vector<std::string>{"x"});
}

}  // namespace
}  // namespace refmap
