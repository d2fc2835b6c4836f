// Results do not depend on the number of OpenMP threads: every floating-point reduction
// of the solver sums one partial per row in row order (kernels/loop.hpp), and the
// parallel kernels only split the rows among threads, so 1 and 2 threads must give the
// same bits -- not merely the same digits. A round-off difference would grow through the
// iteration and the contact/extrapolation thresholds, so the comparison is exact.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <string>
#include <vector>

#include "solver/option_names.hpp"
#include "tests/fixtures/poisson_problem.hpp"
#include "solver/poisson.hpp"
#include "solver/scene.hpp"
#include "solver/simulation.hpp"
#include "solver/solid.hpp"
#include "test_helpers.hpp"

namespace refmap {
namespace {

using testing::scene_path;

/// Restores the team size when the test ends (also on failure).
struct ThreadsGuard {
  int saved = omp_get_max_threads();
  ~ThreadsGuard() { omp_set_num_threads(saved); }
};

std::vector<double> copy(const Field& f) { return {f.raw(), f.raw() + f.raw_size()}; }

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

struct SimState {
  std::vector<std::vector<double>> fields;  // u, v, p, then xi_x, xi_y of every solid
  double t = 0.0;
};

SimState run_two_solids(int threads, int steps) {
  omp_set_num_threads(threads);
  Config cfg = load_scene(scene_path("two_solids_tgv.toml"));
  Simulation sim(cfg);
  for (int n = 0; n < steps; ++n) sim.step();
  SimState s;
  s.t = sim.time();
  s.fields = {copy(sim.u()), copy(sim.v()), copy(sim.p())};
  for (const auto& sol : sim.solids()) {
    s.fields.push_back(copy(sol->xi_x()));
    s.fields.push_back(copy(sol->xi_y()));
  }
  return s;
}

// Two soft discs in a Taylor-Green vortex, 128^2 (grids this size were parallel and
// reduced in thread-dependent order before): u, v, p and both reference maps after 40
// steps must be bitwise identical on 1 and 2 threads.
TEST(Threads, SolidScene128SameBitsOnOneAndTwoThreads) {
  if (omp_get_num_procs() < 2) GTEST_SKIP() << "needs 2 processors";
  ThreadsGuard guard;
  const SimState a = run_two_solids(1, 40);
  const SimState b = run_two_solids(2, 40);
  ASSERT_EQ(a.fields.size(), 7u);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  EXPECT_EQ(a.t, b.t);
  const char* names[] = {"u", "v", "p", "xi_x[0]", "xi_y[0]", "xi_x[1]", "xi_y[1]"};
  for (std::size_t k = 0; k < a.fields.size(); ++k)
    EXPECT_TRUE(same_bits(a.fields[k], b.fields[k])) << names[k] << " differs";
}

// A Poisson solve at 256^2 (density ratio 1000): every recorded residual of the
// iteration and the final iterate bitwise identical on 1 and 2 threads, for each solver.
TEST(Threads, PoissonSolve256SameIteratesOnOneAndTwoThreads) {
  if (omp_get_num_procs() < 2) GTEST_SKIP() << "needs 2 processors";
  ThreadsGuard guard;
  const poisson_problem::Problem p = poisson_problem::standard_problem(256, 1000.0);
  for (const PoissonMethod method : {PoissonMethod::Multigrid, PoissonMethod::Mgpcg, PoissonMethod::Cg}) {
    const std::string m = to_string(method);
    std::vector<std::vector<double>> x, hist;
    for (int t : {1, 2}) {
      omp_set_num_threads(t);
      PoissonOptions o;
      o.method = method;
      o.record_history = true;
      o.max_iter = 60;  // enough for CG to show a drift, bounded cost
      auto s = make_poisson_solver(o);
      s->setup(p.op());
      Field xt(p.grid.nx, p.grid.ny);
      const SolveStats st = s->solve(p.rhs, xt);
      x.push_back(copy(xt));
      hist.push_back(st.history);
    }
    EXPECT_FALSE(hist[0].empty()) << m;
    EXPECT_TRUE(same_bits(hist[0], hist[1])) << m << ": residual histories differ";
    EXPECT_TRUE(same_bits(x[0], x[1])) << m << ": iterates differ";
  }
}

}  // namespace
}  // namespace refmap
