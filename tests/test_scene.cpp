#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"

namespace fs = std::filesystem;
using refmap::BcType;
using refmap::Config;
using refmap::load_scene;
using refmap::SceneError;
using refmap::ExtrapolationMethod;
using refmap::FlowMode;
using refmap::FluxScheme;
using refmap::InitialKind;
using refmap::MgCycle;
using refmap::MgSmoother;
using refmap::PoissonMethod;
using refmap::ShapeKind;
using refmap::SolidVelocity;

namespace {

const char* kBase = R"(
[domain]
lx = 1.0

[grid]
nx = 16
ny = 16

[fluid]
viscosity = 0.01

[boundary]
left = "no_slip"
right = "no_slip"
bottom = "no_slip"
top = { type = "moving_wall", velocity = 1.0 }

[time]
end = 1.0
)";

/// A scene file in a fresh temp folder; removed with the fixture.
class SceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("refmap_test_scene_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& text, const std::string& name = "scene.toml") {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  /// The SceneError message for `text` (fails the test if it loads).
  std::string error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
    const std::string path = write(text);
    try {
      load_scene(path, sets);
    } catch (const SceneError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.find('\n'), std::string::npos) << "message must be one line: " << msg;
      EXPECT_EQ(msg.rfind(path, 0), 0u) << "message must start with the file: " << msg;
      EXPECT_EQ(e.file, path);
      return msg;
    }
    ADD_FAILURE() << "scene loaded but should have failed:\n" << text;
    return "";
  }

  fs::path dir_;
};

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << "test bug: '" << from << "' not in base scene";
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

#define EXPECT_HAS(msg, sub) EXPECT_NE((msg).find(sub), std::string::npos) << "message: " << (msg) << "\nwanted: " << (sub)

}  // namespace

// ---------------------------------------------------------------------------------------
// valid scenes

TEST_F(SceneFiles, SceneMinimalDefaults) {
  const std::string path = write(kBase, "my_cavity.toml");
  const Config c = load_scene(path);
  EXPECT_EQ(c.name, "my_cavity");  // file stem
  EXPECT_EQ(c.scene_path, path);
  EXPECT_EQ(c.grid.nx, 16);
  EXPECT_EQ(c.grid.ny, 16);
  EXPECT_DOUBLE_EQ(c.grid.dx, 1.0 / 16);
  EXPECT_EQ(c.grid.x0, 0.0);
  EXPECT_EQ(c.grid.y0, 0.0);
  EXPECT_EQ(c.rho_f, 1.0);
  EXPECT_EQ(c.mu_f, 0.01);
  EXPECT_EQ(c.bc[refmap::Left].type, BcType::NoSlip);
  EXPECT_EQ(c.bc[refmap::Top].type, BcType::MovingWall);
  EXPECT_EQ(c.bc[refmap::Top].velocity, 1.0);
  EXPECT_FALSE(c.bc[refmap::Top].oscillating);
  EXPECT_EQ(c.bc[refmap::Top].speed(123.0), 1.0);
  EXPECT_EQ(c.bc[refmap::Left].speed(1.0), 0.0);
  EXPECT_EQ(c.init.kind, InitialKind::Zero);
  EXPECT_EQ(c.gx, 0.0);
  EXPECT_EQ(c.gy, 0.0);
  EXPECT_EQ(c.t_start, 0.0);
  EXPECT_EQ(c.t_end, 1.0);
  EXPECT_EQ(c.cfl, 0.5);
  EXPECT_EQ(c.visc_safety, 0.9);
  EXPECT_EQ(c.dt_fixed, 0.0);
  EXPECT_EQ(c.max_steps, 0);
  EXPECT_EQ(c.steady_tol, 0.0);
  EXPECT_EQ(c.advection, FluxScheme::Central);
  EXPECT_EQ(c.poisson.method, PoissonMethod::Multigrid);
  EXPECT_EQ(c.poisson.cycle, MgCycle::V);
  EXPECT_EQ(c.poisson.smoother, MgSmoother::Rbgs);
  EXPECT_EQ(c.output_interval, 0.0);
  EXPECT_TRUE(c.write_vtk);
  EXPECT_EQ(c.diagnostics_every, 1);
  EXPECT_EQ(c.log_interval_s, 2.0);
  EXPECT_TRUE(c.probes.empty());
}

TEST_F(SceneFiles, SceneFullFillsConfig) {
  const std::string text = R"(
name = "couette"
[domain]
x0 = -0.5
y0 = 1.0
lx = 2.0
ly = 0.5
[grid]
nx = 64
ny = 16
[fluid]
density = 2
viscosity = 0.25
[boundary]
left = "periodic"
right = "periodic"
bottom = "free_slip"
top = { type = "moving_wall", velocity = 0.5, omega = 3.0, phase = 0.25 }
[initial]
velocity = "taylor_green"
amplitude = 0.1
[gravity]
g = [0, -9.81]
[time]
start = 0.5
end = 2
cfl = 0.8
viscous_safety = 0.5
dt = 5e-4
dt_max = 0.01
max_steps = 1000
steady_tol = 1e-8
[solver]
advection = "superbee"
poisson = "mgpcg"
cycle = "F"
smoother = "jacobi"
pre_smooth = 3
post_smooth = 1
tol = 1e-9
max_iter = 50
coarse_cells = 16
[output]
interval = 0.1
vtk = false
diagnostics_every = 10
log_interval = 5
[[probe]]
name = "u_centre"
field = "u"
start = [0.5, 1.0]
end = [0.5, 1.5]
points = 33
[[probe]]
name = "p_line"
field = "p"
start = [-0.5, 1.25]
end = [1.5, 1.25]
points = 2
)";
  const Config c = load_scene(write(text));
  EXPECT_EQ(c.name, "couette");
  EXPECT_EQ(c.grid.x0, -0.5);
  EXPECT_EQ(c.grid.y0, 1.0);
  EXPECT_DOUBLE_EQ(c.grid.dx, 2.0 / 64);
  EXPECT_DOUBLE_EQ(c.grid.ly(), 0.5);
  EXPECT_EQ(c.rho_f, 2.0);
  EXPECT_EQ(c.mu_f, 0.25);
  EXPECT_EQ(c.bc[refmap::Left].type, BcType::Periodic);
  EXPECT_EQ(c.bc[refmap::Right].type, BcType::Periodic);
  EXPECT_EQ(c.bc[refmap::Bottom].type, BcType::FreeSlip);
  const auto& top = c.bc[refmap::Top];
  EXPECT_EQ(top.type, BcType::MovingWall);
  EXPECT_TRUE(top.oscillating);
  EXPECT_EQ(top.velocity, 0.5);
  EXPECT_EQ(top.omega, 3.0);
  EXPECT_EQ(top.phase, 0.25);
  EXPECT_DOUBLE_EQ(top.speed(0.7), 0.5 * std::sin(3.0 * 0.7 + 0.25));
  EXPECT_EQ(c.init.kind, InitialKind::TaylorGreen);
  EXPECT_EQ(c.init.amplitude, 0.1);
  EXPECT_EQ(c.init.wavenumber, 0.0);
  EXPECT_EQ(c.gx, 0.0);
  EXPECT_EQ(c.gy, -9.81);
  EXPECT_EQ(c.t_start, 0.5);
  EXPECT_EQ(c.t_end, 2.0);
  EXPECT_EQ(c.cfl, 0.8);
  EXPECT_EQ(c.visc_safety, 0.5);
  EXPECT_EQ(c.dt_fixed, 5e-4);  // below the explicit viscous limit 0.5 x 2 x (1/32)^2 / (6 x 0.25) = 6.5e-4
  EXPECT_EQ(c.dt_max, 0.01);
  EXPECT_EQ(c.max_steps, 1000);
  EXPECT_EQ(c.steady_tol, 1e-8);
  EXPECT_EQ(c.advection, FluxScheme::Superbee);
  EXPECT_EQ(c.poisson.method, PoissonMethod::Mgpcg);
  EXPECT_EQ(c.poisson.cycle, MgCycle::F);
  EXPECT_EQ(c.poisson.smoother, MgSmoother::Jacobi);
  EXPECT_EQ(c.poisson.pre_smooth, 3);
  EXPECT_EQ(c.poisson.post_smooth, 1);
  EXPECT_EQ(c.poisson.tol, 1e-9);
  EXPECT_EQ(c.poisson.max_iter, 50);
  EXPECT_EQ(c.poisson.coarse_cells, 16);
  EXPECT_EQ(c.output_interval, 0.1);
  EXPECT_FALSE(c.write_vtk);
  EXPECT_EQ(c.diagnostics_every, 10);
  EXPECT_EQ(c.log_interval_s, 5.0);
  ASSERT_EQ(c.probes.size(), 2u);
  EXPECT_EQ(c.probes[0].name, "u_centre");
  EXPECT_EQ(c.probes[0].field, "u");
  EXPECT_EQ(c.probes[0].x0, 0.5);
  EXPECT_EQ(c.probes[0].y0, 1.0);
  EXPECT_EQ(c.probes[0].x1, 0.5);
  EXPECT_EQ(c.probes[0].y1, 1.5);
  EXPECT_EQ(c.probes[0].points, 33);
  EXPECT_EQ(c.probes[1].name, "p_line");
  EXPECT_EQ(c.probes[1].x1, 1.5);
}

TEST_F(SceneFiles, SceneInitialKinds) {
  Config c = load_scene(write(std::string(kBase) + "[initial]\nvelocity = \"uniform\"\nu = 2\nv = -0.5\n"));
  EXPECT_EQ(c.init.kind, InitialKind::Uniform);
  EXPECT_EQ(c.init.u, 2.0);
  EXPECT_EQ(c.init.v, -0.5);
  c = load_scene(write(std::string(kBase) +
                       "[initial]\nvelocity = \"expression\"\nu_expr = \"sin(2*pi*x)*cos(2*pi*y)\"\nv_expr = \"0\"\n"));
  EXPECT_EQ(c.init.kind, InitialKind::Expression);
  EXPECT_EQ(c.init.u_expr, "sin(2*pi*x)*cos(2*pi*y)");
  EXPECT_EQ(c.init.v_expr, "0");
  // numbers are accepted as expressions (also from --set, where a bare 0 is an integer)
  c = load_scene(write(std::string(kBase) + "[initial]\nvelocity = \"expression\"\nu_expr = 0.5\nv_expr = \"y\"\n"),
                 {"initial.v_expr=-2"});
  EXPECT_EQ(c.init.u_expr, "0.5");
  EXPECT_EQ(c.init.v_expr, "-2");
}

TEST_F(SceneFiles, SceneIntegersAcceptedAsFloats) {
  const Config c = load_scene(write(replace(replace(kBase, "lx = 1.0", "lx = 2"), "viscosity = 0.01", "viscosity = 0")));
  EXPECT_EQ(c.grid.dx, 2.0 / 16);
  EXPECT_EQ(c.mu_f, 0.0);
}

// ---------------------------------------------------------------------------------------
// errors: every message is one line, starts with the file and names the key

TEST_F(SceneFiles, SceneErrorUnknownKeyTypo) {
  const std::string m = error_of(replace(kBase, "viscosity = 0.01", "viscosty = 0.01"));
  EXPECT_HAS(m, "fluid.viscosty: unknown key");
  EXPECT_HAS(m, "did you mean 'viscosity'");
  EXPECT_HAS(m, "scene.toml:10:1: fluid.viscosty");  // line:column of the typo
}

TEST_F(SceneFiles, SceneErrorUnknownTopLevelTable) {
  const std::string m = error_of(std::string(kBase) + "[[body]]\nshape = \"disk\"\n");
  EXPECT_HAS(m, "body: unknown key");
}

TEST_F(SceneFiles, SceneErrorMissingKeyAndTable) {
  EXPECT_HAS(error_of(replace(kBase, "lx = 1.0", "")), "domain.lx: missing required key");
  EXPECT_HAS(error_of(replace(kBase, "end = 1.0", "")), "time.end: missing required key");
  EXPECT_HAS(error_of(replace(kBase, "[time]\nend = 1.0", "")), "time: missing required table");
  EXPECT_HAS(error_of(replace(kBase, "top = { type = \"moving_wall\", velocity = 1.0 }", "")),
             "boundary.top: missing required key");
}

TEST_F(SceneFiles, SceneErrorWrongType) {
  std::string m = error_of(replace(kBase, "viscosity = 0.01", "viscosity = \"abc\""));
  EXPECT_HAS(m, "fluid.viscosity: expected a number, got a string (\"abc\")");
  m = error_of(replace(kBase, "nx = 16", "nx = 16.0"));
  EXPECT_HAS(m, "grid.nx: expected an integer");
  m = error_of(replace(kBase, "nx = 16", "nx = \"16\""));
  EXPECT_HAS(m, "grid.nx: expected an integer, got a string");
  m = error_of(std::string(kBase) + "[output]\nvtk = 1\n");
  EXPECT_HAS(m, "output.vtk: expected true or false");
  m = error_of(std::string(kBase) + "[gravity]\ng = [1]\n");
  EXPECT_HAS(m, "gravity.g: expected an array of two numbers");
  m = error_of("fluid = 3\n" + replace(kBase, "[fluid]\nviscosity = 0.01", ""));
  EXPECT_HAS(m, "fluid: expected a table");
}

TEST_F(SceneFiles, SceneErrorOutOfRange) {
  std::string m = error_of(replace(kBase, "viscosity = 0.01", "viscosity = -0.01"));
  EXPECT_HAS(m, "fluid.viscosity: must be >= 0");
  EXPECT_HAS(m, "scene.toml:10:13: fluid.viscosity");  // position of the value
  EXPECT_HAS(error_of(replace(kBase, "[fluid]", "[fluid]\ndensity = 0")), "fluid.density: must be > 0");
  EXPECT_HAS(error_of(replace(kBase, "nx = 16", "nx = 4")), "grid.nx: must be >= 8");
  EXPECT_HAS(error_of(replace(kBase, "ny = 16", "ny = 7")), "grid.ny: must be >= 8");
  EXPECT_HAS(error_of(replace(kBase, "end = 1.0", "start = 2.0\nend = 1.0")), "time.end: must be > time.start");
  EXPECT_HAS(error_of(replace(kBase, "end = 1.0", "end = 0")), "time.end: must be > time.start");
  EXPECT_HAS(error_of(replace(kBase, "end = 1.0", "end = 1.0\ncfl = 3")), "time.cfl: must be in (0, 2.5]");
  EXPECT_HAS(error_of(replace(kBase, "end = 1.0", "end = 1.0\nviscous_safety = 0")), "time.viscous_safety");
  EXPECT_HAS(error_of(replace(kBase, "end = 1.0", "end = nan")), "time.end: must be a finite number");
  EXPECT_HAS(error_of(replace(kBase, "lx = 1.0", "lx = 1.0\nly = 2.0")), "domain.ly: must equal domain.lx * grid.ny / grid.nx");
  EXPECT_HAS(error_of(replace(kBase, "lx = 1.0", "lx = -1.0")), "domain.lx: must be > 0");
  EXPECT_HAS(error_of(std::string(kBase) + "[solver]\ntol = 2\n"), "solver.tol: must be in (0, 1)");
  EXPECT_HAS(error_of(std::string(kBase) + "[solver]\npre_smooth = 0\n"), "solver.pre_smooth");
  EXPECT_HAS(error_of(std::string(kBase) + "[output]\ndiagnostics_every = 0\n"), "output.diagnostics_every");
}

TEST_F(SceneFiles, SceneErrorBadChoice) {
  std::string m = error_of(std::string(kBase) + "[solver]\nadvection = \"superbe\"\n");
  EXPECT_HAS(m, "solver.advection: unknown value \"superbe\"");
  EXPECT_HAS(m, "did you mean \"superbee\"");
  EXPECT_HAS(error_of(std::string(kBase) + "[solver]\npoisson = \"sor\"\n"), "solver.poisson: unknown value \"sor\"");
  EXPECT_HAS(error_of(std::string(kBase) + "[solver]\ncycle = \"W\"\n"), "solver.cycle");
  EXPECT_HAS(error_of(std::string(kBase) + "[initial]\nvelocity = \"random\"\n"), "initial.velocity");
}

TEST_F(SceneFiles, SceneErrorBoundary) {
  std::string m = error_of(replace(kBase, "left = \"no_slip\"", "left = \"noslip\""));
  EXPECT_HAS(m, "boundary.left: unknown boundary condition \"noslip\"");
  EXPECT_HAS(m, "did you mean \"no_slip\"");
  m = error_of(replace(kBase, "top = { type = \"moving_wall\", velocity = 1.0 }", "top = \"moving_wall\""));
  EXPECT_HAS(m, "boundary.top: a moving wall needs a velocity");
  m = error_of(replace(kBase, "top = { type = \"moving_wall\", velocity = 1.0 }", "top = { type = \"moving_wall\" }"));
  EXPECT_HAS(m, "boundary.top.velocity: missing required key");
  m = error_of(replace(kBase, "left = \"no_slip\"", "left = \"periodic\""));
  EXPECT_HAS(m, "boundary.right: must be \"periodic\" because boundary.left is");
  m = error_of(replace(kBase, "velocity = 1.0 }", "velocity = 1.0, speed = 2 }"));
  EXPECT_HAS(m, "boundary.top.speed: unknown key");
  m = error_of(replace(kBase, "left = \"no_slip\"", "left = { type = \"no_slip\", velocity = 1 }"));
  EXPECT_HAS(m, "boundary.left.velocity: only a moving_wall");
  m = error_of(replace(kBase, "left = \"no_slip\"", "left = 3"));
  EXPECT_HAS(m, "boundary.left: expected a boundary condition");
}

TEST_F(SceneFiles, SceneErrorInitial) {
  std::string m = error_of(std::string(kBase) +
                           "[initial]\nvelocity = \"expression\"\nu_expr = \"sin(z)\"\nv_expr = \"0\"\n");
  EXPECT_HAS(m, "initial.u_expr: invalid expression \"sin(z)\"");
  EXPECT_HAS(m, "unknown identifier 'z'");
  m = error_of(std::string(kBase) + "[initial]\nvelocity = \"expression\"\nu_expr = \"1\"\nv_expr = \"(1\"\n");
  EXPECT_HAS(m, "initial.v_expr: invalid expression");
  m = error_of(std::string(kBase) + "[initial]\nvelocity = \"zero\"\nu = 1\n");
  EXPECT_HAS(m, "initial.u: only used with initial.velocity = \"uniform\"");
}

TEST_F(SceneFiles, SceneErrorProbes) {
  const std::string good = "[[probe]]\nname = \"a\"\nfield = \"u\"\nstart = [0.5, 0]\nend = [0.5, 1]\npoints = 5\n";
  EXPECT_NO_THROW(load_scene(write(std::string(kBase) + good)));
  auto probe = [&](const std::string& from, const std::string& to) { return std::string(kBase) + replace(good, from, to); };
  EXPECT_HAS(error_of(probe("name = \"a\"", "name = \"a b\"")), "probe[0].name: must be a non-empty name");
  EXPECT_HAS(error_of(probe("field = \"u\"", "field = \"w\"")), "probe[0].field: unknown value \"w\"");
  EXPECT_HAS(error_of(probe("start = [0.5, 0]", "start = [1.5, 0]")), "probe[0].start: point [1.5, 0] is outside the domain");
  EXPECT_HAS(error_of(probe("points = 5", "points = 1")), "probe[0].points: must be in [2,");
  EXPECT_HAS(error_of(probe("points = 5\n", "")), "probe[0].points: missing required key");
  EXPECT_HAS(error_of(probe("points = 5", "points = 5\ncolour = 1")), "probe[0].colour: unknown key");
  EXPECT_HAS(error_of(std::string(kBase) + good + good), "probe[1].name: duplicate probe name \"a\"");
  EXPECT_HAS(error_of(std::string(kBase) + "[probe]\nname = \"a\"\n"), "probe: expected an array of tables");
}

TEST_F(SceneFiles, SceneErrorSyntax) {
  const std::string m = error_of(replace(kBase, "viscosity = 0.01", "viscosity = = 0.01"));
  EXPECT_HAS(m, "TOML syntax error");
  EXPECT_HAS(m, "scene.toml:10:");
}

TEST_F(SceneFiles, SceneErrorUnreadableFile) {
  const std::string path = (dir_ / "does_not_exist.toml").string();
  try {
    load_scene(path);
    FAIL() << "no error for a missing file";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot read scene file: no such file");
  }
  try {
    load_scene(dir_.string());
    FAIL() << "no error for a directory";
  } catch (const SceneError& e) {
    EXPECT_HAS(std::string(e.what()), "is a directory");
  }
}

TEST_F(SceneFiles, SceneErrorBadName) {
  EXPECT_HAS(error_of(std::string("name = \"a/b\"\n") + kBase), "name: must be a non-empty name without '/'");
}

// ---------------------------------------------------------------------------------------
// --set overrides

TEST_F(SceneFiles, SceneSetOverrides) {
  const std::string path = write(std::string(kBase) +
                                 "[[probe]]\nname = \"a\"\nfield = \"u\"\nstart = [0.5, 0]\nend = [0.5, 0.5]\npoints = 5\n");
  const Config c = load_scene(path, {
                                        "fluid.viscosity=0.001",
                                        "grid.nx=32",                       // ly derived: 0.5
                                        "solver.advection=superbee",        // bare word -> string
                                        "solver.cycle=\"F\"",               // quoted TOML string
                                        "time.end=2",                       // integer where a float is expected
                                        " output.vtk = false ",             // spaces around key and value
                                        "gravity.g=[0, -9.81]",             // creates the [gravity] table
                                        "boundary.top={ type = \"moving_wall\", velocity = 2 }",
                                        "probe[0].points=50",
                                        "probe.0.field=v",
                                        "name=overridden",
                                    });
  EXPECT_EQ(c.mu_f, 0.001);
  EXPECT_EQ(c.grid.nx, 32);
  EXPECT_DOUBLE_EQ(c.grid.dx, 1.0 / 32);
  EXPECT_DOUBLE_EQ(c.grid.ly(), 0.5);
  EXPECT_EQ(c.advection, FluxScheme::Superbee);
  EXPECT_EQ(c.poisson.cycle, MgCycle::F);
  EXPECT_EQ(c.t_end, 2.0);
  EXPECT_FALSE(c.write_vtk);
  EXPECT_EQ(c.gy, -9.81);
  EXPECT_EQ(c.bc[refmap::Top].velocity, 2.0);
  ASSERT_EQ(c.probes.size(), 1u);
  EXPECT_EQ(c.probes[0].points, 50);
  EXPECT_EQ(c.probes[0].field, "v");
  EXPECT_EQ(c.name, "overridden");
  // the last of two overrides of the same key wins
  EXPECT_EQ(load_scene(path, {"grid.nx=8", "grid.nx=32"}).grid.nx, 32);
}

TEST_F(SceneFiles, SceneSetErrors) {
  std::string m = error_of(kBase, {"fluid.viscosty=1"});
  EXPECT_HAS(m, "fluid.viscosty: unknown key");
  EXPECT_HAS(m, "(from --set)");
  EXPECT_EQ(m.find(":1:"), std::string::npos) << "no file position for a --set value: " << m;
  m = error_of(kBase, {"body.radius=1"});
  EXPECT_HAS(m, "body: unknown key");
  EXPECT_HAS(m, "(from --set)");
  m = error_of(kBase, {"solid.radius=1"});  // [[solid]] is an array of tables
  EXPECT_HAS(m, "solid: expected an array of tables ([[solid]] sections), got a table (from --set)");
  m = error_of(kBase, {"grid.nx=abc"});
  EXPECT_HAS(m, "grid.nx: expected an integer, got a string (\"abc\") (from --set)");
  m = error_of(kBase, {"fluid.viscosity=-1"});
  EXPECT_HAS(m, "fluid.viscosity: must be >= 0, got -1 (from --set)");
  m = error_of(kBase, {"fluid.viscosity"});
  EXPECT_HAS(m, "--set fluid.viscosity: expected key=value");
  m = error_of(kBase, {"grid.nx.foo=1"});
  EXPECT_HAS(m, "grid.nx.foo: cannot set: grid.nx is not a table");
  m = error_of(kBase, {"probe[3].points=1"});
  EXPECT_HAS(m, "probe[3].points: cannot set: index 3 is out of range");
}

// The complete example of scenes/README.md is a valid scene.
TEST_F(SceneFiles, SceneReadmeExampleLoads) {
  std::ifstream in(std::string(REFMAP_SOURCE_DIR) + "/scenes/README.md");
  ASSERT_TRUE(in) << "scenes/README.md not found";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string md = ss.str();
  const auto sec = md.find("## Complete example");
  ASSERT_NE(sec, std::string::npos);
  const auto b = md.find("```toml\n", sec);
  ASSERT_NE(b, std::string::npos);
  const auto e = md.find("```", b + 8);
  ASSERT_NE(e, std::string::npos);
  const Config c = load_scene(write(md.substr(b + 8, e - b - 8)));
  EXPECT_EQ(c.name, "cavity_example");
  EXPECT_EQ(c.grid.nx, 128);
  EXPECT_EQ(c.mu_f, 0.01);
  EXPECT_EQ(c.bc[refmap::Top].type, BcType::MovingWall);
  EXPECT_EQ(c.probes.size(), 2u);
}

// ---------------------------------------------------------------------------------------
// solids: [solids], [[solid]], solver.flow

namespace {

const char* kTwoSolids = R"(
[solver]
flow = "solve"

[solids]
extrapolation = "pde"
band = 8
transition = 2.5
conservative = false
solid_cfl = 0.25
reinitialise = false
pde_tol = 1e-8
pde_max_iter = 500

[[solid]]
name = "disc"
shape = "circle"
center = [0.25, 0.5]
radius = 0.1
mu_s = 0.5
density = 2.0
viscosity = 0.01
u = 1.0
v = -0.5
omega = 3

[[solid]]
shape = "rounded_rectangle"
center = [0.7, 0.4]
half_size = [0.1, 0.05]
corner_radius = 0.02
angle = 0.3
mu_s = 0
density = 1
velocity = "fluid"
)";

const char* kOneCircle = R"(
[[solid]]
shape = "circle"
center = [0.5, 0.5]
radius = 0.2
mu_s = 1.0
density = 1.0
)";

}  // namespace

TEST_F(SceneFiles, SceneSolidsFillConfig) {
  const Config c = load_scene(write(std::string(kBase) + kTwoSolids));
  EXPECT_EQ(c.flow, FlowMode::Solve);
  EXPECT_EQ(c.solid_opt.extrapolation, ExtrapolationMethod::Pde);
  EXPECT_EQ(c.solid_opt.band, 8.0);
  EXPECT_EQ(c.solid_opt.transition, 2.5);
  EXPECT_FALSE(c.solid_opt.conservative);
  EXPECT_EQ(c.solid_opt.solid_cfl, 0.25);
  EXPECT_FALSE(c.solid_opt.reinitialise);
  EXPECT_EQ(c.solid_opt.pde_tol, 1e-8);
  EXPECT_EQ(c.solid_opt.pde_max_iter, 500);
  ASSERT_EQ(c.solids.size(), 2u);

  const refmap::SolidSpec& a = c.solids[0];
  EXPECT_EQ(a.name, "disc");
  EXPECT_EQ(a.shape.kind, ShapeKind::Circle);
  EXPECT_EQ(a.shape.cx, 0.25);
  EXPECT_EQ(a.shape.cy, 0.5);
  EXPECT_EQ(a.shape.radius, 0.1);
  EXPECT_EQ(a.shape.angle, 0.0);
  EXPECT_EQ(a.mu_s, 0.5);
  EXPECT_EQ(a.density, 2.0);
  EXPECT_EQ(a.viscosity, 0.01);
  EXPECT_EQ(a.velocity, SolidVelocity::Rigid);
  EXPECT_EQ(a.u, 1.0);
  EXPECT_EQ(a.v, -0.5);
  EXPECT_EQ(a.omega, 3.0);

  const refmap::SolidSpec& b = c.solids[1];
  EXPECT_EQ(b.name, "solid1");  // default name: solid<index>
  EXPECT_EQ(b.shape.kind, ShapeKind::RoundedRectangle);
  EXPECT_EQ(b.shape.cx, 0.7);
  EXPECT_EQ(b.shape.cy, 0.4);
  EXPECT_EQ(b.shape.half_width, 0.1);
  EXPECT_EQ(b.shape.half_height, 0.05);
  EXPECT_EQ(b.shape.corner_radius, 0.02);
  EXPECT_EQ(b.shape.angle, 0.3);
  EXPECT_EQ(b.mu_s, 0.0);
  EXPECT_EQ(b.density, 1.0);
  EXPECT_EQ(b.viscosity, 0.0);
  EXPECT_EQ(b.velocity, SolidVelocity::Fluid);
  EXPECT_EQ(b.u, 0.0);
  EXPECT_EQ(b.omega, 0.0);
}

TEST_F(SceneFiles, SceneSolidsDefaultsAndShapes) {
  Config c = load_scene(write(kBase));
  EXPECT_EQ(c.flow, FlowMode::Solve);
  EXPECT_TRUE(c.solids.empty());
  EXPECT_EQ(c.solid_opt.extrapolation, ExtrapolationMethod::Lsq);
  EXPECT_DOUBLE_EQ(c.solid_opt.lsq_radius * c.solid_opt.lsq_radius, 8.0);  // 2 sqrt(2): the 5 x 5 block
  EXPECT_EQ(c.solid_opt.band, 6.0);
  EXPECT_EQ(c.solid_opt.transition, 3.0);
  EXPECT_TRUE(c.solid_opt.conservative);
  EXPECT_EQ(c.solid_opt.solid_cfl, 0.5);
  EXPECT_TRUE(c.solid_opt.reinitialise);
  EXPECT_EQ(c.solid_opt.pde_tol, 1e-8);
  EXPECT_EQ(c.solid_opt.pde_max_iter, 1000);

  c = load_scene(write(std::string(kBase) + kOneCircle));
  ASSERT_EQ(c.solids.size(), 1u);
  EXPECT_EQ(c.solids[0].name, "solid0");
  EXPECT_EQ(c.solids[0].velocity, SolidVelocity::Rigid);

  c = load_scene(write(std::string(kBase) + "[[solid]]\nshape = \"ellipse\"\ncenter = [0.5, 0.5]\nsemi_axes = [0.2, 0.1]\n"
                                            "angle = 0.5\nmu_s = 1\ndensity = 1\n"));
  EXPECT_EQ(c.solids[0].shape.kind, ShapeKind::Ellipse);
  EXPECT_EQ(c.solids[0].shape.a, 0.2);
  EXPECT_EQ(c.solids[0].shape.b, 0.1);
  EXPECT_EQ(c.solids[0].shape.angle, 0.5);

  c = load_scene(write(std::string(kBase) + "[[solid]]\nshape = \"zalesak\"\ncenter = [0.5, 0.75]\nradius = 0.15\n"
                                            "slot_half_width = 0.025\nslot_top = 0.85\nmu_s = 1\ndensity = 1\n"));
  EXPECT_EQ(c.solids[0].shape.kind, ShapeKind::Zalesak);
  EXPECT_EQ(c.solids[0].shape.radius, 0.15);
  EXPECT_EQ(c.solids[0].shape.slot_half_width, 0.025);
  EXPECT_EQ(c.solids[0].shape.slot_top, 0.85);

  // tabulated: a relative path is relative to the scene file's directory; the loader
  // stores the resolved path
  fs::create_directories(dir_ / "data");
  std::ofstream(dir_ / "data" / "blob.txt") << "# a 3 x 3 table\n3 3 0.25 0.25 0.25\n1 1 1\n1 -1 1\n1 1 1\n";
  c = load_scene(write(std::string(kBase) + "[[solid]]\nshape = \"tabulated\"\nfile = \"data/blob.txt\"\nmu_s = 1\ndensity = 1\n"));
  EXPECT_EQ(c.solids[0].shape.kind, ShapeKind::Tabulated);
  EXPECT_EQ(fs::path(c.solids[0].shape.file), (dir_ / "data" / "blob.txt").lexically_normal());

  // prescribed flow: the solid's material is not needed
  c = load_scene(write(std::string(kBase) + "[solver]\nflow = \"prescribed\"\n" +
                       "[[solid]]\nshape = \"circle\"\ncenter = [0.5, 0.5]\nradius = 0.2\nvelocity = \"fluid\"\n"));
  EXPECT_EQ(c.flow, FlowMode::Prescribed);
  EXPECT_EQ(c.solids[0].mu_s, 0.0);
  EXPECT_EQ(c.solids[0].density, 1.0);
}

TEST_F(SceneFiles, SceneSolidErrorsNameTheKey) {
  const std::string base = std::string(kBase) + kOneCircle;
  // missing mu_s
  std::string m = error_of(replace(base, "mu_s = 1.0\n", ""));
  EXPECT_HAS(m, "solid[0].mu_s: missing required key");
  EXPECT_HAS(error_of(replace(base, "density = 1.0\n", "")), "solid[0].density: missing required key");
  // unknown shape
  m = error_of(replace(base, "shape = \"circle\"", "shape = \"circel\""));
  EXPECT_HAS(m, "solid[0].shape: unknown value \"circel\"");
  EXPECT_HAS(m, "did you mean \"circle\"");
  // negative density
  m = error_of(replace(base, "density = 1.0", "density = -2"));
  EXPECT_HAS(m, "solid[0].density: must be > 0, got -2");
  EXPECT_HAS(m, "scene.toml:26:11:");  // position of the value
  // radius on an ellipse
  m = error_of(replace(base, "shape = \"circle\"", "shape = \"ellipse\"\nsemi_axes = [0.2, 0.1]"));
  EXPECT_HAS(m, "solid[0].radius: not a parameter of shape = \"ellipse\" (it takes center, semi_axes, angle)");
  // bad tabulated file path
  m = error_of(std::string(kBase) + "[[solid]]\nshape = \"tabulated\"\nfile = \"nope/missing.txt\"\nmu_s = 1\ndensity = 1\n");
  EXPECT_HAS(m, "solid[0].file: cannot read \"" + (dir_ / "nope" / "missing.txt").string() + "\": no such file");
  // [solids] extrapolation = "foo"
  m = error_of(base + "[solids]\nextrapolation = \"foo\"\n");
  EXPECT_HAS(m, "solids.extrapolation: unknown value \"foo\" (expected one of \"lsq\", \"pde\")");
}

TEST_F(SceneFiles, SceneSolidErrorsMore) {
  const std::string base = std::string(kBase) + kOneCircle;
  auto with = [&](const std::string& extra) { return replace(base, "density = 1.0\n", "density = 1.0\n" + extra); };
  // shape parameters
  EXPECT_HAS(error_of(replace(base, "radius = 0.2", "radius = 0")), "solid[0].radius: must be > 0");
  EXPECT_HAS(error_of(replace(base, "radius = 0.2\n", "")), "solid[0].radius: missing required key");
  EXPECT_HAS(error_of(replace(base, "center = [0.5, 0.5]\n", "")), "solid[0].center: missing required key");
  EXPECT_HAS(error_of(with("angle = 1\n")), "solid[0].angle: not a parameter of shape = \"circle\"");
  EXPECT_HAS(error_of(with("file = \"x\"\n")), "solid[0].file: not a parameter of shape = \"circle\"");
  EXPECT_HAS(error_of(replace(base, "shape = \"circle\"\ncenter = [0.5, 0.5]\nradius = 0.2",
                              "shape = \"ellipse\"\ncenter = [0.5, 0.5]\nsemi_axes = [0.2, -0.1]")),
             "solid[0].semi_axes: both semi-axes must be > 0");
  EXPECT_HAS(error_of(replace(base, "shape = \"circle\"\ncenter = [0.5, 0.5]\nradius = 0.2",
                              "shape = \"rounded_rectangle\"\ncenter = [0.5, 0.5]\nhalf_size = [0.2, 0.1]\ncorner_radius = 0.15")),
             "solid[0].corner_radius: must be in [0, min(half_size) = 0.1]");
  EXPECT_HAS(error_of(replace(base, "shape = \"circle\"", "shape = \"zalesak\"\nslot_half_width = 0.3\nslot_top = 0.6")),
             "solid[0].slot_half_width: must be in (0, radius = 0.2)");
  EXPECT_HAS(error_of(replace(base, "shape = \"circle\"", "shape = \"zalesak\"\nslot_half_width = 0.05\nslot_top = 0.9")),
             "solid[0].slot_top: must be strictly between");
  EXPECT_HAS(error_of(with("colour = \"red\"\n")), "solid[0].colour: unknown key");
  // outside the domain
  EXPECT_HAS(error_of(replace(base, "center = [0.5, 0.5]", "center = [2, 0.5]")),
             "solid[0].center: the solid lies outside the domain: its bounding box [1.8, 2.2] x [0.3, 0.7]");
  // material and velocity
  EXPECT_HAS(error_of(replace(base, "mu_s = 1.0", "mu_s = -1")), "solid[0].mu_s: must be >= 0");
  EXPECT_HAS(error_of(with("viscosity = -1\n")), "solid[0].viscosity: must be >= 0");
  EXPECT_HAS(error_of(with("velocity = \"still\"\n")), "solid[0].velocity: unknown value \"still\"");
  EXPECT_HAS(error_of(with("velocity = \"fluid\"\nomega = 1\n")), "solid[0].omega: only used with velocity = \"rigid\"");
  // names
  EXPECT_HAS(error_of(with("name = \"a-b\"\n")), "solid[0].name: must be a non-empty name");
  EXPECT_HAS(error_of(base + "[[solid]]\nname = \"solid0\"\nshape = \"circle\"\ncenter = [0.5, 0.5]\nradius = 0.1\nmu_s = 1\n"
                             "density = 1\n"),
             "solid[1].name: duplicate solid name \"solid0\"");
  // tabulated file that make_shape rejects
  std::ofstream(dir_ / "bad.txt") << "3 3 0 0 0.5\n1 1 1\n1 1 1\n1 1 1\n";  // no solid in it
  std::string m = error_of(std::string(kBase) + "[[solid]]\nshape = \"tabulated\"\nfile = \"bad.txt\"\nmu_s = 1\ndensity = 1\n");
  EXPECT_HAS(m, "solid[0].file: invalid geometry: tabulated shape");
  EXPECT_HAS(m, "no value <= 0");
  std::ofstream(dir_ / "short.txt") << "3 3 0 0 0.5\n1 -1 1\n1 1\n";
  EXPECT_HAS(error_of(std::string(kBase) + "[[solid]]\nshape = \"tabulated\"\nfile = \"short.txt\"\nmu_s = 1\ndensity = 1\n"),
             "solid[0].file: invalid geometry: tabulated shape");
  // [solids] ranges and [solver] flow
  EXPECT_HAS(error_of(base + "[solids]\nband = 1\n"), "solids.band: must be > 1");
  EXPECT_HAS(error_of(base + "[solids]\nband = 3.5\n"), "solids.band: must be > solids.transition + 1 = 4");
  EXPECT_HAS(error_of(base + "[solids]\nband = 5\ntransition = 4\n"), "solids.transition: must be < solids.band - 1 = 4");
  EXPECT_HAS(error_of(base + "[solids]\nstress_blend = \"specific\"\nstress_discretisation = \"face\"\n"),
             "solids.stress_blend: \"specific\" needs stress_discretisation = \"cell\" and conservative = true");
  EXPECT_HAS(error_of(base, {"time.solid_implicit_cfl=8"}),
             "time.solid_implicit_cfl: needs solid_stress = \"semi_implicit\" or \"upper_convected\"");
  EXPECT_HAS(error_of(base, {"time.solid_implicit_reach=2"}),
             "time.solid_implicit_reach: needs solid_stress = \"semi_implicit\" or \"upper_convected\"");
  EXPECT_HAS(error_of(base + "[solids]\nband = 5\ntransition = 3\n", {"time.solid_implicit_reach=2.5", "time.solid_stress=\"semi_implicit\""}),
             "time.solid_implicit_reach: must be <= solids.band - solids.transition = 2 cells");
  EXPECT_HAS(error_of(base + "[solids]\ntransition = 0\n"), "solids.transition: must be > 0");
  EXPECT_HAS(error_of(base + "[solids]\nsolid_cfl = 8.5\n"), "solids.solid_cfl: must be in (0, 8]");
  EXPECT_HAS(error_of(base + "[solids]\nlsq_radius = 2\n"), "solids.lsq_radius: must be in [2.83, 5.74]");
  EXPECT_HAS(error_of(base + "[solids]\nlsq_radius = 6\n"), "solids.lsq_radius: must be in [2.83, 5.74]");
  EXPECT_EQ(load_scene(write(base + "[solids]\nlsq_radius = 5.66\n")).solid_opt.lsq_radius, 5.66);
  EXPECT_HAS(error_of(base + "[solids]\npde_tol = 0\n"), "solids.pde_tol: must be > 0");
  EXPECT_HAS(error_of(base + "[solids]\npde_max_iter = 0\n"), "solids.pde_max_iter: must be in [1,");
  EXPECT_HAS(error_of(base + "[solids]\nconservative = 1\n"), "solids.conservative: expected true or false");
  EXPECT_HAS(error_of(base + "[solids]\nwidth = 1\n"), "solids.width: unknown key");
  EXPECT_HAS(error_of(base + "[solver]\nflow = \"frozen\"\n"), "solver.flow: unknown value \"frozen\"");
  EXPECT_HAS(error_of("solid = 3\n" + std::string(kBase)), "solid: expected an array of tables");
}

TEST_F(SceneFiles, SceneSolidSetOverrides) {
  const std::string path = write(std::string(kBase) + kOneCircle);
  Config c = load_scene(path, {"solids.extrapolation=\"pde\""});
  EXPECT_EQ(c.solid_opt.extrapolation, ExtrapolationMethod::Pde);
  c = load_scene(path, {"solids.extrapolation=pde", "solid[0].mu_s=2", "solid.0.name=blob", "solver.flow=prescribed"});
  EXPECT_EQ(c.solid_opt.extrapolation, ExtrapolationMethod::Pde);
  EXPECT_EQ(c.solids[0].mu_s, 2.0);
  EXPECT_EQ(c.solids[0].name, "blob");
  EXPECT_EQ(c.flow, FlowMode::Prescribed);
  std::string m = error_of(std::string(kBase) + kOneCircle, {"solids.extrapolation=foo"});
  EXPECT_HAS(m, "solids.extrapolation: unknown value \"foo\"");
  EXPECT_HAS(m, "(from --set)");
  m = error_of(std::string(kBase) + kOneCircle, {"solid[0].shape=ellipse"});
  EXPECT_HAS(m, "solid[0].radius: not a parameter of shape = \"ellipse\"");
}

// The shipped Zalesak scene loads (prescribed flow, no material for the solid).
TEST_F(SceneFiles, SceneZalesakLoads) {
  const Config c = load_scene(std::string(REFMAP_SOURCE_DIR) + "/scenes/zalesak.toml");
  EXPECT_EQ(c.flow, FlowMode::Prescribed);
  EXPECT_EQ(c.solid_opt.band, 5.0);
  ASSERT_EQ(c.solids.size(), 1u);
  EXPECT_EQ(c.solids[0].name, "slotted_disk");
  EXPECT_EQ(c.solids[0].shape.kind, ShapeKind::Zalesak);
  EXPECT_EQ(c.solids[0].velocity, SolidVelocity::Fluid);
  EXPECT_EQ(load_scene(std::string(REFMAP_SOURCE_DIR) + "/scenes/zalesak.toml", {"solids.extrapolation=\"pde\""})
                .solid_opt.extrapolation,
            ExtrapolationMethod::Pde);
}

// The solids example of scenes/README.md is a valid scene.
TEST_F(SceneFiles, SceneReadmeSolidsExampleLoads) {
  std::ifstream in(std::string(REFMAP_SOURCE_DIR) + "/scenes/README.md");
  ASSERT_TRUE(in) << "scenes/README.md not found";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string md = ss.str();
  const auto sec = md.find("## Example with solids");
  ASSERT_NE(sec, std::string::npos);
  const auto b = md.find("```toml\n", sec);
  ASSERT_NE(b, std::string::npos);
  const auto e = md.find("```", b + 8);
  ASSERT_NE(e, std::string::npos);
  const Config c = load_scene(write(md.substr(b + 8, e - b - 8)));
  EXPECT_EQ(c.name, "solids_example");
  ASSERT_EQ(c.solids.size(), 2u);
  EXPECT_EQ(c.solids[0].name, "disc");
  EXPECT_EQ(c.solids[1].shape.kind, ShapeKind::RoundedRectangle);
  EXPECT_EQ(c.solids[1].omega, 1.0);
}

// ---------------------------------------------------------------------------------------
// A fixed time.dt above an explicit limit of its scene is refused at load (docs/stability.md;
// solver/scene/scene.cpp, check_fixed_step; the limits' formulas: solver/model/time_step_limits.hpp).
// Each limit on both sides: 0.1 % below it loads, 0.1 % above it is refused naming the
// limit and the key that lifts it.

namespace {
std::string dt_set(double dt) {
  char b[64];
  std::snprintf(b, sizeof b, "time.dt=%.17g", dt);
  return b;
}
}  // namespace

TEST_F(SceneFiles, FixedStepAboveTheExplicitViscousLimitIsRefused) {
  // kBase: dx = 1/16, rho = 1, mu = 0.01: limit 0.9 dx^2 / (6 mu) = 0.05859375
  const double limit = 0.9 / 256.0 / 0.06;
  EXPECT_NO_THROW(load_scene(write(kBase), {dt_set(0.999 * limit)}));
  const std::string m = error_of(kBase, {dt_set(1.001 * limit)});
  EXPECT_HAS(m, "time.dt: 0.05865234375 is above the explicit viscous limit 0.05859375 of this scene");
  EXPECT_HAS(m, "mu / rho = 0.01 of the fluid");
  EXPECT_HAS(m, "set time.viscous = \"implicit\"");
  // lifted by the implicit viscous step, moved by viscous_safety
  EXPECT_NO_THROW(load_scene(write(kBase), {dt_set(1.001 * limit), "time.viscous=\"implicit\""}));
  EXPECT_NO_THROW(load_scene(write(kBase), {dt_set(1.001 * limit), "time.viscous_safety=0.95"}));
  // a solid's Kelvin-Voigt viscosity over its density above the fluid's sets it: 0.1 / 2 = 0.05
  // against 0.01, limit 0.9 dx^2 / (6 x 0.05) = 0.01171875; named
  // (mu_s = 0: no solid time-step limit)
  const std::string solid =
      std::string(kBase) + replace(replace(kOneCircle, "density = 1.0", "density = 2.0\nviscosity = 0.1"), "mu_s = 1.0", "mu_s = 0.0");
  const double solid_limit = 0.9 / 256.0 / 0.3;
  EXPECT_NO_THROW(load_scene(write(solid), {dt_set(0.999 * solid_limit)}));
  EXPECT_HAS(error_of(solid, {dt_set(1.001 * solid_limit)}),
             "is above the explicit viscous limit 0.01171875 of this scene (time.viscous_safety rho dx^2 / (6 mu) = 0.9 x "
             "0.0625^2 / 6 / 0.05, mu / rho = 0.05 of solid 'solid0'");
  // no flow solve, no viscous term: a prescribed flow takes any step
  EXPECT_NO_THROW(load_scene(write(std::string(kBase) + "[solver]\nflow = \"prescribed\"\n"), {dt_set(10 * limit)}));
}

TEST_F(SceneFiles, FixedStepAboveTheExplicitSolidLimitIsRefused) {
  // a disc with mu_s = 1 (G = 2 mu_s = 2 at rest), rho_s = 2 on dx = 1/16: the explicit stress's
  // limit solid_cfl dx sqrt(rho_s / G) at the default solid_cfl 0.5 is 0.03125 (the viscous
  // limit, 0.0586, is above)
  const std::string base = std::string(kBase) + replace(kOneCircle, "density = 1.0", "density = 2.0");
  const double limit = 0.5 / 16.0;
  EXPECT_NO_THROW(load_scene(write(base), {dt_set(0.999 * limit)}));
  const std::string m = error_of(base, {dt_set(1.001 * limit)});
  EXPECT_HAS(m, "time.dt: 0.03128125 is above the explicit solid time-step limit 0.03125 of solid 'solid0' "
                "(solids.solid_cfl dx sqrt(rho_s / G) = 0.5 x 0.0625 x sqrt(2 / 2)");
  EXPECT_HAS(m, "set time.solid_stress = \"semi_implicit\" or \"upper_convected\"");
  EXPECT_HAS(m, "raise solids.solid_cfl");
  // lifted by an implicit solid stress, moved by solids.solid_cfl
  EXPECT_NO_THROW(load_scene(write(base), {dt_set(1.001 * limit), "time.solid_stress=\"semi_implicit\""}));
  EXPECT_NO_THROW(load_scene(write(base), {dt_set(1.001 * limit), "time.solid_stress=\"upper_convected\""}));
  EXPECT_NO_THROW(load_scene(write(base), {dt_set(1.001 * limit), "solids.solid_cfl=0.6"}));
  // a rigid body has no stress and no limit (1.5x: still below the viscous limit 0.0586)
  EXPECT_NO_THROW(load_scene(write(replace(base, "mu_s = 1.0", "motion = \"fixed\"")), {dt_set(1.5 * limit)}));
}

TEST_F(SceneFiles, RefinedCylinderWithItsStepScaledByDxIsRefused) {
  // a new user's case: scenes/cylinder_re20.toml at 20 cells per diameter (dx = 0.005) with
  // its fixed step scaled with dx, 0.9278 dx = 0.004639, blew up at t = 0.46 (face
  // divergence, exit 3); the explicit viscous limit there is 0.9 dx^2 / (6 nu) = 0.00375
  const std::string cyl = std::string(REFMAP_SOURCE_DIR) + "/scenes/cylinder_re20.toml";
  const std::vector<std::string> fine{"grid.nx=440", "grid.ny=82", "time.dt=0.004639"};
  try {
    load_scene(cyl, fine);
    ADD_FAILURE() << "the refined cylinder with an explicit viscous step above its limit loaded";
  } catch (const SceneError& e) {
    EXPECT_HAS(std::string(e.what()), "time.dt: 0.004639 is above the explicit viscous limit 0.00375 of this scene");
  }
  std::vector<std::string> implicit = fine;
  implicit.push_back("time.viscous=\"implicit\"");  // as bench/run_cylinder.sh refines it
  EXPECT_NO_THROW(load_scene(cyl, implicit));
  EXPECT_NO_THROW(load_scene(cyl));  // the shipped grid: 0.009278 against the limit 0.015
}
