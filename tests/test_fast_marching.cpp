// Fast marching reinitialisation (kernels/fast_marching): second-order convergence with
// Chopp's initialisation, sign preservation, idempotence on a distance function,
// window/ghost handling and workspace reuse.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>

#include "kernels/fast_marching.hpp"
#include "core/field.hpp"
#include "solver/model/shape.hpp"

using namespace refmap;

namespace {

struct Errors {
  double linf = 0.0, l2 = 0.0;
  int cells = 0;
  FmmStats stats;
};

using Fn = std::function<double(double, double)>;

constexpr double kGhost = 123.0;  // ghost cells hold this and must not change

void fill(Field& phi, int n, const Fn& f) {
  const double dx = 1.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) phi(i, j) = f((i + 0.5) * dx, (j + 0.5) * dx);
}

void expect_ghosts_untouched(const Field& phi) {
  const int n = phi.nx(), m = phi.ny(), g = phi.ng();
  int bad = 0;
  for (int j = -g; j < m + g; ++j)
    for (int i = -g; i < n + g; ++i)
      if ((i < 0 || j < 0 || i >= n || j >= m) && phi(i, j) != kGhost) ++bad;
  EXPECT_EQ(bad, 0) << "ghost cells were written";
}

/// Reinitialises f sampled at the cell centres of an n x n grid on the unit square and
/// compares with the exact signed distance over |exact| <= band.
Errors run_case(int n, const Fn& f, const Fn& exact, double band, const FmmOptions& opt = {}) {
  const double dx = 1.0 / n;
  Field phi(n, n, 2, kGhost);
  fill(phi, n, f);
  FmmWorkspace ws;
  Errors e;
  e.stats = reinitialise_fmm(phi.view(), n, n, dx, band, ws, opt);
  double s2 = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double d = exact((i + 0.5) * dx, (j + 0.5) * dx);
      if (std::abs(d) > band) continue;
      const double err = std::abs(phi(i, j) - d);
      e.linf = std::max(e.linf, err);
      s2 += err * err;
      ++e.cells;
    }
  e.l2 = std::sqrt(s2 / std::max(e.cells, 1));
  expect_ghosts_untouched(phi);
  return e;
}

constexpr double kCx = 0.5, kCy = 0.5, kR = 0.3;
double circle_dist(double x, double y) { return std::hypot(x - kCx, y - kCy) - kR; }
/// Zero set is the circle, but far from a distance function (|grad phi| varies from
/// about 0.3 to 1.7 along the band).
double circle_perturbed(double x, double y) {
  return circle_dist(x, y) * (1.0 + 0.5 * (x - kCx) * (x - kCx) + 2.0 * (y - 0.2) * (y - 0.2)) *
         (0.3 + x);
}

void report(const char* what, const int* ns, const Errors* e, int m) {
  for (int k = 0; k < m; ++k)
    std::printf("  [%s] N=%4d  Linf=%.3e  L2=%.3e  cells=%d init=%d marched=%d newton_fail=%d\n", what,
                ns[k], e[k].linf, e[k].l2, e[k].cells, e[k].stats.accepted_init, e[k].stats.marched,
                e[k].stats.newton_failures);
  for (int k = 0; k + 1 < m; ++k)
    std::printf("  [%s] ratio %d->%d: Linf %.2f  L2 %.2f\n", what, ns[k], ns[k + 1],
                e[k].linf / e[k + 1].linf, e[k].l2 / e[k + 1].l2);
}

}  // namespace

// The convergence check: band |phi| <= 6 dx, N = 64, 128, 256. (With a band of a fixed number
// of cells the march is a fixed number of steps, so the observed order is ~3.)
TEST(FastMarching, PerturbedCircleConvergesSecondOrder) {
  const int ns[] = {64, 128, 256};
  Errors e[3];
  for (int k = 0; k < 3; ++k) {
    e[k] = run_case(ns[k], circle_perturbed, circle_dist, 6.0 / ns[k]);
    EXPECT_EQ(e[k].stats.newton_failures, 0);
    EXPECT_GT(e[k].cells, 1000);
  }
  report("6dx band", ns, e, 3);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(e[k].linf / e[k + 1].linf, 3.5);
    EXPECT_GE(e[k].l2 / e[k + 1].l2, 3.5);
  }
  EXPECT_LT(e[2].linf, 2e-6);  // observed 1.67e-6 (0.04% of dx)
}

// A band of fixed physical width (0.15 = half the radius): the number of marching steps
// doubles with N, so this is the genuine order of the method: 2.
TEST(FastMarching, PerturbedCircleFixedBandSecondOrder) {
  const int ns[] = {128, 256, 512};
  Errors e[3];
  for (int k = 0; k < 3; ++k) e[k] = run_case(ns[k], circle_perturbed, circle_dist, 0.15);
  report("band 0.15", ns, e, 3);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(e[k].linf / e[k + 1].linf, 3.5);  // observed 3.63, 3.82
    EXPECT_GE(e[k].l2 / e[k + 1].l2, 3.5);      // observed 3.78, 3.89
  }
}

TEST(FastMarching, LinearInitialisationIsOnlyFirstOrder) {
  // the comparison that motivates Chopp's initialisation
  FmmOptions opt;
  opt.init = FmmInit::Linear;
  const int ns[] = {64, 128, 256};
  Errors e[3];
  for (int k = 0; k < 3; ++k) e[k] = run_case(ns[k], circle_perturbed, circle_dist, 6.0 / ns[k], opt);
  report("linear init", ns, e, 3);
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(e[k].linf / e[k + 1].linf, 2.5);
    EXPECT_GT(e[k].linf / e[k + 1].linf, 1.7);
  }
  const Errors chopp = run_case(256, circle_perturbed, circle_dist, 6.0 / 256);
  EXPECT_GT(e[2].linf, 100.0 * chopp.linf);
}

TEST(FastMarching, FirstOrderMarchIsFirstOrder) {
  FmmOptions opt;
  opt.second_order = false;
  const int ns[] = {128, 256};
  Errors e[2];
  for (int k = 0; k < 2; ++k) e[k] = run_case(ns[k], circle_perturbed, circle_dist, 0.15, opt);
  report("first-order march", ns, e, 2);
  EXPECT_LT(e[0].linf / e[1].linf, 2.5);
  const Errors second = run_case(256, circle_perturbed, circle_dist, 0.15);
  EXPECT_GT(e[1].linf, 10.0 * second.linf);
}

TEST(FastMarching, EllipseConverges) {
  // algebraic level set of a rotated ellipse (not a distance); exact distance from Shape
  const double a = 0.3, b = 0.2, ang = 0.4, c = std::cos(ang), s = std::sin(ang);
  Ellipse el(0.5, 0.5, a, b, ang);
  auto alg = [&](double x, double y) {
    const double u = c * (x - 0.5) + s * (y - 0.5), v = -s * (x - 0.5) + c * (y - 0.5);
    return u * u / (a * a) + v * v / (b * b) - 1.0;
  };
  auto exact = [&](double x, double y) { return el.phi0(x, y); };
  const int ns[] = {64, 128, 256};
  Errors e[3];
  for (int k = 0; k < 3; ++k) {
    e[k] = run_case(ns[k], alg, exact, 6.0 / ns[k]);
    EXPECT_EQ(e[k].stats.newton_failures, 0);
  }
  report("ellipse 6dx", ns, e, 3);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(e[k].linf / e[k + 1].linf, 3.5);  // observed ~9.9, ~9.2
    EXPECT_GE(e[k].l2 / e[k + 1].l2, 3.5);
  }
  EXPECT_LT(e[2].linf, 3e-5);
}

TEST(FastMarching, ExactDistanceNearlyUnchanged) {
  for (int n : {64, 128, 256}) {
    const double dx = 1.0 / n, band = 6.0 * dx;
    Field phi(n, n, 2, kGhost);
    fill(phi, n, circle_dist);
    const Field in = phi;
    FmmWorkspace ws;
    reinitialise_fmm(phi.view(), n, n, dx, band, ws);
    double change = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (std::abs(in(i, j)) <= band) change = std::max(change, std::abs(phi(i, j) - in(i, j)));
        else EXPECT_EQ(phi(i, j), in(i, j) < 0 ? -band : band);
      }
    // a second application moves it even less
    Field again = phi;
    reinitialise_fmm(again.view(), n, n, dx, band, ws);
    double change2 = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) change2 = std::max(change2, std::abs(again(i, j) - phi(i, j)));
    std::printf("  N=%d: max change of an exact distance %.3e (%.2e dx), second pass %.3e\n", n, change,
                change / dx, change2);
    EXPECT_LT(change, 0.01 * dx);
    EXPECT_LE(change2, change);
  }
}

TEST(FastMarching, SignPreservedEverywhere) {
  const int n = 160;
  const double dx = 1.0 / n, band = 6.0 * dx;
  ZalesakDisk z(0.5, 0.75, 0.15, 0.025, 0.85);
  // several components, saddles, thin features and kinks
  const Fn fields[] = {
      circle_perturbed,
      [&](double x, double y) { return z.phi0(x, y); },
      [](double x, double y) { return std::sin(9.0 * x) * std::cos(7.0 * y + 0.3) + 0.2 * std::sin(31.0 * x * y); },
      [](double x, double y) { return std::abs(x - 0.5) - 0.004; },  // sliver thinner than a cell
      [&](double x, double y) {  // specks: circles of radius 0.4 dx and 1.5 dx, a saddle
        return std::min({std::hypot(x - 0.3, y - 0.3) - 0.4 * dx, std::hypot(x - 0.7, y - 0.31) - 1.5 * dx,
                         (x - 0.5) * (y - 0.7) * 40.0 + 1e-3});
      },
  };
  int fallbacks = 0;
  for (const Fn& f : fields) {
    Field phi(n, n, 2, kGhost);
    fill(phi, n, f);
    const Field in = phi;
    FmmWorkspace ws;
    fallbacks += reinitialise_fmm(phi.view(), n, n, dx, band, ws).newton_failures;
    int flipped = 0, out_of_band = 0, nonfinite = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (!std::isfinite(phi(i, j))) ++nonfinite;
        if (std::signbit(phi(i, j)) != (in(i, j) < 0.0)) ++flipped;
        if (std::abs(phi(i, j)) > band) ++out_of_band;
      }
    EXPECT_EQ(nonfinite, 0);
    EXPECT_EQ(flipped, 0);
    EXPECT_EQ(out_of_band, 0);
    expect_ghosts_untouched(phi);
  }
  std::printf("  closest-point fallbacks to |phi|/|grad phi| over the rough fields: %d\n", fallbacks);
}

TEST(FastMarching, ZalesakDiskStaysCloseToExactDistance) {
  // phi0 of the slotted disk is an exact distance with kinks (slot corners, the slot's
  // centre line): FMM must keep it close, and exact away from the kinks' influence.
  ZalesakDisk z(0.5, 0.75, 0.15, 0.025, 0.85);
  for (int n : {100, 200}) {
    const double dx = 1.0 / n, band = 6.0 * dx;
    Field phi(n, n, 2, kGhost);
    fill(phi, n, [&](double x, double y) { return z.phi0(x, y); });
    const Field in = phi;
    FmmWorkspace ws;
    const FmmStats st = reinitialise_fmm(phi.view(), n, n, dx, band, ws);
    double m = 0.0, mean = 0.0;
    int c = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (std::abs(in(i, j)) <= band) {
          const double e = std::abs(phi(i, j) - in(i, j));
          m = std::max(m, e);
          mean += e;
          ++c;
        }
    mean /= c;
    std::printf("  Zalesak N=%d: max |change| %.3e (%.2f dx), mean %.3e (%.4f dx), newton_fail %d\n", n,
                m, m / dx, mean, mean / dx, st.newton_failures);
    EXPECT_LT(m, 0.5 * dx);
    EXPECT_LT(mean, 0.02 * dx);
  }
}

TEST(FastMarching, WindowOfLargerFieldMatchesFullGrid) {
  // a window (offset view into a larger field) that holds the solid and its band gives
  // bit-identical values to the whole-grid call, and nothing outside it is touched
  const int n = 128;
  const double dx = 1.0 / n, band = 6.0 * dx;
  auto f = [](double x, double y) {
    return (std::hypot(x - 0.4, y - 0.55) - 0.12) * (1.0 + 3.0 * (x - 0.3) * (x - 0.3));
  };
  Field full(n, n, 2, kGhost), part(n, n, 2, kGhost);
  fill(full, n, f);
  fill(part, n, f);
  const Field in = part;
  FmmWorkspace ws;
  reinitialise_fmm(full.view(), n, n, dx, band, ws);
  // disc bbox [0.28, 0.52] x [0.43, 0.67] + band + 3 cells -> cells 25..77 x 44..96
  const int i0 = 25, j0 = 44, ni = 53, nj = 55;
  View win{&part(i0, j0), part.stride()};
  reinitialise_fmm(win, ni, nj, dx, band, ws);
  int differ = 0, touched = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool inside = i >= i0 && i < i0 + ni && j >= j0 && j < j0 + nj;
      if (inside && part(i, j) != full(i, j)) ++differ;
      if (!inside && part(i, j) != in(i, j)) ++touched;
    }
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(touched, 0);
  expect_ghosts_untouched(part);
}

TEST(FastMarching, WorkspaceReuseGivesIdenticalResults) {
  auto run = [](int ni, int nj, FmmWorkspace& ws) {
    const double dx = 1.0 / ni;
    Field phi(ni, nj, 2, kGhost);
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i)
        phi(i, j) = circle_perturbed((i + 0.5) * dx, (j + 0.5) * dx);
    reinitialise_fmm(phi.view(), ni, nj, dx, 5.0 * dx, ws);
    return phi;
  };
  FmmWorkspace shared;
  const Field a1 = run(200, 180, shared);
  const Field b1 = run(64, 70, shared);  // smaller, different row length
  const Field a2 = run(200, 180, shared);
  FmmWorkspace fresh1, fresh2;
  const Field a0 = run(200, 180, fresh1);
  const Field b0 = run(64, 70, fresh2);
  int diff = 0;
  for (int j = 0; j < 180; ++j)
    for (int i = 0; i < 200; ++i) diff += (a1(i, j) != a0(i, j)) + (a2(i, j) != a0(i, j));
  for (int j = 0; j < 70; ++j)
    for (int i = 0; i < 64; ++i) diff += b1(i, j) != b0(i, j);
  EXPECT_EQ(diff, 0);
  // the workspace's distance arrays are back to +inf (the invariant the next call needs)
  for (double v : shared.upos) ASSERT_TRUE(std::isinf(v) && v > 0);
  for (double v : shared.uneg) ASSERT_TRUE(std::isinf(v) && v > 0);
}

TEST(FastMarching, NoInterfaceGivesBand) {
  const int n = 20;
  Field phi(n, n, 2, kGhost);
  fill(phi, n, [](double x, double y) { return 0.3 + x; });
  FmmWorkspace ws;
  const FmmStats st = reinitialise_fmm(phi.view(), n, n, 0.05, 0.2, ws);
  EXPECT_EQ(st.accepted_init, 0);
  EXPECT_EQ(st.marched, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) EXPECT_EQ(phi(i, j), 0.2);
  fill(phi, n, [](double x, double y) { return -1.0; });
  reinitialise_fmm(phi.view(), n, n, 0.05, 0.2, ws);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) EXPECT_EQ(phi(i, j), -0.2);
}

TEST(FastMarching, StraightFrontIsNearlyExact) {
  // a planar front: the bicubic is exact, hence the initialisation; the march is second
  // order. Cells whose foot point on the line lies outside the window are skipped: their
  // characteristic comes from a part of the front the window does not see.
  const int n = 64;
  const double dx = 1.0 / n, band = 8.0 * dx;
  const double nx = 0.6, ny = 0.8;  // unit normal
  Field phi(n, n, 2, kGhost);
  fill(phi, n, [&](double x, double y) { return 3.0 * (nx * (x - 0.5) + ny * (y - 0.47)); });
  FmmWorkspace ws;
  const FmmStats st = reinitialise_fmm(phi.view(), n, n, dx, band, ws);
  EXPECT_EQ(st.newton_failures, 0);
  double init_err = 0.0, err = 0.0;
  int cells = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
      const double d = nx * (x - 0.5) + ny * (y - 0.47);
      const double fx = x - d * nx, fy = y - d * ny;  // foot point
      if (std::abs(d) > band || fx < 2 * dx || fx > 1 - 2 * dx || fy < 2 * dx || fy > 1 - 2 * dx) continue;
      const double e = std::abs(phi(i, j) - d);
      if (std::abs(d) < 1.5 * dx) init_err = std::max(init_err, e);
      err = std::max(err, e);
      ++cells;
    }
  std::printf("  straight front: initialisation error %.2e, band error %.2e (dx = %.2e, %d cells)\n",
              init_err, err, dx, cells);
  EXPECT_GT(cells, 500);
  EXPECT_LT(init_err, 1e-12);
  EXPECT_LT(err, 0.02 * dx);
}

TEST(FastMarching, RejectsBadArguments) {
  Field phi(4, 4, 2, 1.0);
  FmmWorkspace ws;
  EXPECT_THROW(reinitialise_fmm(phi.view(), 1, 4, 0.1, 0.5, ws), std::invalid_argument);
  EXPECT_THROW(reinitialise_fmm(phi.view(), 4, 4, 0.0, 0.5, ws), std::invalid_argument);
  EXPECT_THROW(reinitialise_fmm(phi.view(), 4, 4, 0.1, -1.0, ws), std::invalid_argument);
}
