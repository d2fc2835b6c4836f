// Tests of the reference-map extrapolation kernels: least squares (Jain & Mani Algorithm 2)
// and the Aslam (2004) linear PDE baseline.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/extrapolate_lsq.hpp"
#include "kernels/extrapolate_pde.hpp"
#include "solver/model/config.hpp"
#include "solver/model/extrapolation.hpp"
#include "solver/scene/option_names.hpp"
#include "core/field.hpp"
#include "tests/fixtures/zalesak_geometry.hpp"

namespace {

using namespace refmap;
constexpr double kPi = 3.14159265358979323846;

using Fn = std::function<double(double, double)>;

/// One window = the whole unit square, N x N cells, 2 ghost layers; known = phi < 0 at the
/// cell centre (ghosts included in the kernel domain).
struct Case {
  int N = 0, ng = 2;
  double dx = 0;
  Field xx, xy, phi;
  Mask known, known0;
  Case(int n, const Fn& phifn, const Fn& fx, const Fn& fy) : N(n), dx(1.0 / n) {
    xx.resize(N, N, ng); xy.resize(N, N, ng); phi.resize(N, N, ng);
    known.resize(N, N, ng); known0.resize(N, N, ng);
    for (int j = -ng; j < N + ng; ++j)
      for (int i = -ng; i < N + ng; ++i) {
        const double x = (i + 0.5) * dx, y = (j + 0.5) * dx;
        phi(i, j) = phifn(x, y);
        const bool k = phi(i, j) < 0.0;
        known(i, j) = known0(i, j) = k;
        xx(i, j) = k ? fx(x, y) : std::numeric_limits<double>::quiet_NaN();
        xy(i, j) = k ? fy(x, y) : std::numeric_limits<double>::quiet_NaN();
      }
  }
  double x(int i) const { return (i + 0.5) * dx; }
  ExtrapStats lsq(const LsqOptions& o) {
    return extrapolate_lsq(xx.view(), xy.view(), known.view(), N, N, ng, dx, o);
  }
  ExtrapStats pde(const PdeOptions& o) {
    return extrapolate_pde(xx.view(), xy.view(), known.view(), phi.cview(), N, N, ng, dx, o);
  }
  /// max |error| over the cells filled by the kernel (known now, not before) and, if
  /// `sel` is given, selected by it; optional count and RMS
  double max_err(const Fn& fx, const Fn& fy, long* nfilled = nullptr, double* rms = nullptr,
                 const std::function<bool(int, int)>& sel = nullptr) const {
    double e = 0, s2 = 0;
    long n = 0;
    for (int j = -ng; j < N + ng; ++j)
      for (int i = -ng; i < N + ng; ++i) {
        if (known0(i, j) || !known(i, j)) continue;
        if (sel && !sel(i, j)) continue;
        ++n;
        const double ex = std::fabs(xx(i, j) - fx(x(i), x(j)));
        const double ey = std::fabs(xy(i, j) - fy(x(i), x(j)));
        if (!(ex <= e)) e = ex;  // NaN-propagating max
        if (!(ey <= e)) e = ey;
        s2 += ex * ex + ey * ey;
      }
    if (nfilled) *nfilled = n;
    if (rms) *rms = n ? std::sqrt(s2 / (2.0 * n)) : 0.0;
    return e;
  }
};

Fn disc_phi(double cx = 0.5, double cy = 0.5, double r = 0.15) {
  return [=](double x, double y) { return std::hypot(x - cx, y - cy) - r; };
}
Fn zalesak_phi() {
  const auto z = geometry::SlottedDisk::unit();
  return [z](double x, double y) { return z.phi(x, y); };
}
// linear (affine) test field, O(1) values with a non-zero constant
const Fn lin_x = [](double x, double y) { return 0.3 + 1.7 * x - 0.4 * y; };
const Fn lin_y = [](double x, double y) { return -0.2 + 0.5 * x + 1.1 * y; };
// a smooth nonlinear field (the one bench/bench_extrapolate.cpp measures accuracy on)
const Fn nl_x = [](double x, double y) { return x + 0.1 * std::sin(2 * kPi * y); };
const Fn nl_y = [](double x, double y) { return y + 0.1 * x * x; };

/// cells within Chebyshev distance p of a known cell (the set LSQ fills in p passes)
std::vector<std::uint8_t> dilate(const Case& c, int p) {
  const int W = c.N + 2 * c.ng;
  std::vector<std::uint8_t> out(std::size_t(W) * W, 0);
  for (int j = -c.ng; j < c.N + c.ng; ++j)
    for (int i = -c.ng; i < c.N + c.ng; ++i) {
      if (!c.known0(i, j)) continue;
      for (int jj = std::max(-c.ng, j - p); jj <= std::min(c.N + c.ng - 1, j + p); ++jj)
        for (int ii = std::max(-c.ng, i - p); ii <= std::min(c.N + c.ng - 1, i + p); ++ii)
          out[std::size_t(jj + c.ng) * W + (ii + c.ng)] = 1;
    }
  return out;
}

void check_lsq_linear(Case& c, int passes, int radius2 = 32) {
  LsqOptions o;
  o.passes = passes;
  o.radius2 = radius2;
  const ExtrapStats s = c.lsq(o);
  long n = 0;
  const double err = c.max_err(lin_x, lin_y, &n);
  std::printf("  LSQ linear N=%d radius^2 %d: filled %ld, passes %d, fallbacks %ld, max err %.3e\n", c.N,
              radius2, s.cells_filled, s.passes, s.fallbacks, err);
  EXPECT_EQ(s.passes, passes);
  EXPECT_EQ(n, s.cells_filled);
  EXPECT_LT(err, 1e-12 * 2.0);  // field scale O(1) (|xi| <= 2 on the unit square)
  // filled set == Chebyshev dilation of the known set by `passes` cells: no holes
  const auto d = dilate(c, passes);
  const int W = c.N + 2 * c.ng;
  long mism = 0;
  for (int j = -c.ng; j < c.N + c.ng; ++j)
    for (int i = -c.ng; i < c.N + c.ng; ++i)
      mism += (c.known(i, j) != 0) != (d[std::size_t(j + c.ng) * W + (i + c.ng)] != 0);
  EXPECT_EQ(mism, 0);
}

}  // namespace

// --------------------------------------------------------------------------- LSQ

TEST(ExtrapolateLSQ, LinearExactDisc) {
  Case c(100, disc_phi(), lin_x, lin_y);
  check_lsq_linear(c, 5);
}

TEST(ExtrapolateLSQ, LinearExactZalesak) {
  Case c(100, zalesak_phi(), lin_x, lin_y);
  check_lsq_linear(c, 5);
}

TEST(ExtrapolateLSQ, LinearExactWithSmallerFitRadii) {
  // the solver's default 2 sqrt(2) (a 5 x 5 block, also the smallest radius a scene may set:
  // with radius^2 2, the 3 x 3 block, a band cell often sees only collinear known cells and
  // falls back to a line fit, which is not exact for a plane)
  for (int r2 : {8, 18}) {
    Case d(100, disc_phi(), lin_x, lin_y);
    check_lsq_linear(d, 6, r2);
    Case z(100, zalesak_phi(), lin_x, lin_y);
    check_lsq_linear(z, 6, r2);
  }
}

TEST(ExtrapolateLSQ, FitRadiusSelectsTheStencil) {
  // known: the half plane y < 0.25 of a 40^2 grid (rows j <= 9); one pass fills row 10.
  // Perturbing the known cell (20, 5), at offset (0, -5) from (20, 10), changes the fit there
  // only if 25 <= radius^2: with the paper's 32 it does, with 8 (the solver's default) it
  // must not, and the cells 3 or more columns away must not change with either.
  const Fn half = [](double, double y) { return y - 0.25; };
  for (int r2 : {8, 32}) {
    Case a(40, half, nl_x, nl_y), b(40, half, nl_x, nl_y);
    b.xx(20, 5) += 1.0;
    LsqOptions o;
    o.passes = 1;
    o.radius2 = r2;
    a.lsq(o);
    b.lsq(o);
    const double d0 = std::fabs(b.xx(20, 10) - a.xx(20, 10));
    const double d3 = std::fabs(b.xx(23, 10) - a.xx(23, 10));
    std::printf("  LSQ radius^2 %d: change at (20, 10) %.3e, at (23, 10) %.3e\n", r2, d0, d3);
    if (r2 == 8) EXPECT_EQ(d0, 0.0);
    else EXPECT_GT(d0, 1e-3);
    EXPECT_EQ(d3, 0.0);
    EXPECT_EQ(b.xy(20, 10), a.xy(20, 10));
  }
}

TEST(ExtrapolateLSQ, LinearExactZalesakHundredScale) {
  // the [0,100]^2 form: xi ~ x in [0, 100]; error relative to the field scale 100
  const auto z = geometry::SlottedDisk::hundred();
  const int N = 100, ng = 2;
  Field xx(N, N, ng), xy(N, N, ng);
  Mask k(N, N, ng), k0(N, N, ng);
  for (int j = -ng; j < N + ng; ++j)
    for (int i = -ng; i < N + ng; ++i) {
      const double x = i + 0.5, y = j + 0.5;
      k(i, j) = k0(i, j) = z.phi(x, y) < 0;
      xx(i, j) = k(i, j) ? 0.8 * x - 0.6 * y + 40.0 : 0.0;  // a rotation + shift
      xy(i, j) = k(i, j) ? 0.6 * x + 0.8 * y - 10.0 : 0.0;
    }
  LsqOptions o;
  o.passes = 6;
  const auto s = extrapolate_lsq(xx.view(), xy.view(), k.view(), N, N, ng, 1.0, o);
  double e = 0;
  for (int j = -ng; j < N + ng; ++j)
    for (int i = -ng; i < N + ng; ++i)
      if (k(i, j) && !k0(i, j)) {
        const double x = i + 0.5, y = j + 0.5;
        e = std::max({e, std::fabs(xx(i, j) - (0.8 * x - 0.6 * y + 40.0)),
                      std::fabs(xy(i, j) - (0.6 * x + 0.8 * y - 10.0))});
      }
  std::printf("  LSQ linear [0,100]^2 Zalesak: filled %ld, max err %.3e (scale 100)\n",
              s.cells_filled, e);
  EXPECT_GT(s.cells_filled, 0);
  EXPECT_LT(e, 1e-12 * 100.0);
}

TEST(ExtrapolateLSQ, LinearExactAtWindowEdges) {
  // tight window, no ghosts: the disc and its band cross the window edges, so many stencils
  // are clipped (the general path) and the band is cut by the edge
  const int ni = 37, nj = 33, ng = 0;
  const double dx = 0.01, x0 = 0.5 - 0.18, y0 = 0.5 - 0.14;  // window origin
  Field xx(ni, nj, ng), xy(ni, nj, ng);
  Mask k(ni, nj, ng), k0(ni, nj, ng);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const double x = x0 + (i + 0.5) * dx, y = y0 + (j + 0.5) * dx;
      k(i, j) = k0(i, j) = std::hypot(x - 0.5, y - 0.5) < 0.15;
      xx(i, j) = k(i, j) ? lin_x(x, y) : std::numeric_limits<double>::quiet_NaN();
      xy(i, j) = k(i, j) ? lin_y(x, y) : std::numeric_limits<double>::quiet_NaN();
    }
  LsqOptions o;
  o.passes = 12;
  const auto s = extrapolate_lsq(xx.view(), xy.view(), k.view(), ni, nj, ng, dx, o);
  double e = 0;
  long unfilled = 0;
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      unfilled += !k(i, j);
      if (k(i, j) && !k0(i, j)) {
        const double x = x0 + (i + 0.5) * dx, y = y0 + (j + 0.5) * dx;
        e = std::max({e, std::fabs(xx(i, j) - lin_x(x, y)), std::fabs(xy(i, j) - lin_y(x, y))});
      }
    }
  std::printf("  LSQ linear, clipped window: filled %ld, fallbacks %ld, unfilled %ld, err %.3e\n",
              s.cells_filled, s.fallbacks, unfilled, e);
  EXPECT_EQ(unfilled, 0);  // the passes reach every window cell...
  EXPECT_LT(s.passes, 12);  // ...and stop when there is nothing left
  EXPECT_EQ(s.fallbacks, 0);
  EXPECT_LT(e, 2e-12);
}

TEST(ExtrapolateLSQ, TargetBandNoHoles) {
  // flag2 = phi <= w_E = 6 dx: enough passes fill every target cell and nothing else
  for (int geom = 0; geom < 2; ++geom) {
    Case c(100, geom ? zalesak_phi() : disc_phi(), lin_x, lin_y);
    Mask tgt(c.N, c.N, c.ng);
    for (int j = -c.ng; j < c.N + c.ng; ++j)
      for (int i = -c.ng; i < c.N + c.ng; ++i) tgt(i, j) = c.phi(i, j) <= 6 * c.dx;
    LsqOptions o;
    o.passes = 10;
    o.target = tgt.cview();
    const auto s = c.lsq(o);
    long holes = 0, outside = 0;
    for (int j = -c.ng; j < c.N + c.ng; ++j)
      for (int i = -c.ng; i < c.N + c.ng; ++i) {
        holes += tgt(i, j) && !c.known(i, j);
        outside += !tgt(i, j) && c.known(i, j);
      }
    const double err = c.max_err(lin_x, lin_y);
    std::printf("  LSQ target band (%s): filled %ld in %d passes, holes %ld, err %.3e\n",
                geom ? "Zalesak" : "disc", s.cells_filled, s.passes, holes, err);
    EXPECT_EQ(holes, 0);
    EXPECT_EQ(outside, 0);
    EXPECT_LE(s.passes, 7);  // stopped early: 6 dx band reached in <= 7 passes
    EXPECT_LT(err, 2e-12);
  }
}

TEST(ExtrapolateLSQ, NonlinearConvergence) {
  const int Ns[] = {50, 100, 200, 400};
  double prev = 0;
  std::printf("  LSQ nonlinear field, disc r=0.15, 5 passes:\n");
  for (int N : Ns) {
    Case c(N, disc_phi(), nl_x, nl_y);
    LsqOptions o;
    o.passes = 5;
    const auto s = c.lsq(o);
    const double e = c.max_err(nl_x, nl_y);
    std::printf("    N=%4d  max err %.3e  order %s%.2f  fallbacks %ld\n", N, e,
                prev > 0 ? "" : "(n/a) ", prev > 0 ? std::log2(prev / e) : 0.0, s.fallbacks);
    EXPECT_EQ(s.fallbacks, 0);
    EXPECT_TRUE(std::isfinite(e));
    if (prev > 0) {
      EXPECT_GT(std::log2(prev / e), 1.0) << "N=" << N;
    }
    prev = e;
  }
}

TEST(ExtrapolateLSQ, DegenerateSingleRow) {
  // one row of known cells: the first pass is collinear -> 1-D line fits (fallbacks);
  // a field depending on x only is still reproduced exactly
  const int N = 40, ng = 2;
  Field xx(N, N, ng), xy(N, N, ng);
  Mask k(N, N, ng);
  xx.fill(std::numeric_limits<double>::quiet_NaN());
  xy.fill(std::numeric_limits<double>::quiet_NaN());
  for (int i = 10; i <= 25; ++i) {
    k(i, 20) = 1;
    xx(i, 20) = 2.0 * i + 1.0;
    xy(i, 20) = -0.5 * i;
  }
  LsqOptions o;
  o.passes = 4;
  const auto s = extrapolate_lsq(xx.view(), xy.view(), k.view(), N, N, ng, 1.0, o);
  double e = 0;
  bool finite = true;
  for (int j = -ng; j < N + ng; ++j)
    for (int i = -ng; i < N + ng; ++i)
      if (k(i, j)) {
        finite = finite && std::isfinite(xx(i, j)) && std::isfinite(xy(i, j));
        e = std::max({e, std::fabs(xx(i, j) - (2.0 * i + 1.0)), std::fabs(xy(i, j) + 0.5 * i)});
      }
  std::printf("  LSQ single row: filled %ld, fallbacks %ld, err %.3e\n", s.cells_filled,
              s.fallbacks, e);
  EXPECT_TRUE(finite);
  EXPECT_EQ(s.fallbacks, 2 * 18 + 2);  // exactly pass 1: rows j = 19, 21 (i = 9..26), (9|26, 20)
  EXPECT_EQ(s.cells_filled, (16 + 8) * 9 - 16);
  EXPECT_LT(e, 1e-12 * 50.0);
}

TEST(ExtrapolateLSQ, DegenerateFewCells) {
  const int N = 20, ng = 2;
  for (int nk = 1; nk <= 2; ++nk) {
    Field xx(N, N, ng), xy(N, N, ng);
    Mask k(N, N, ng);
    xx.fill(std::numeric_limits<double>::quiet_NaN());
    xy.fill(std::numeric_limits<double>::quiet_NaN());
    k(10, 10) = 1; xx(10, 10) = 3.0; xy(10, 10) = -1.0;
    if (nk == 2) { k(11, 11) = 1; xx(11, 11) = 4.0; xy(11, 11) = 0.0; }  // diagonal pair
    LsqOptions o;
    o.passes = 3;
    const auto s = extrapolate_lsq(xx.view(), xy.view(), k.view(), N, N, ng, 1.0, o);
    bool finite = true;
    for (int j = -ng; j < N + ng; ++j)
      for (int i = -ng; i < N + ng; ++i)
        if (k(i, j)) finite = finite && std::isfinite(xx(i, j)) && std::isfinite(xy(i, j));
    std::printf("  LSQ %d known cell(s): filled %ld, fallbacks %ld, xi(7,7) = (%g, %g)\n", nk,
                s.cells_filled, s.fallbacks, xx(7, 7), xy(7, 7));
    EXPECT_TRUE(finite);
    EXPECT_GT(s.fallbacks, 0);
    EXPECT_EQ(s.passes, 3);
    if (nk == 1) {  // pass 1 is the constant; pass 2+ fit planes to a constant field
      EXPECT_EQ(s.fallbacks, 8);
      EXPECT_DOUBLE_EQ(xx(7, 7), 3.0);
      EXPECT_DOUBLE_EQ(xy(13, 12), -1.0);
    } else {  // xi_x = 3 + (i - 10 + j - 10)/2 along the diagonal pair
      EXPECT_NEAR(xx(7, 7), 3.0 + (-3 - 3) * 0.5, 1e-12);
      EXPECT_NEAR(xx(13, 13), 3.0 + 3.0, 1e-12);
    }
  }
}

TEST(ExtrapolateLSQ, PassesStopWhenNothingToFill) {
  // known everywhere except one cell -> one pass, one cell
  const int N = 16, ng = 0;
  Field xx(N, N, ng, 1.0), xy(N, N, ng, 2.0);
  Mask k(N, N, ng, 1);
  k(5, 7) = 0;
  xx(5, 7) = std::numeric_limits<double>::quiet_NaN();
  LsqOptions o;
  o.passes = 6;
  const auto s = extrapolate_lsq(xx.view(), xy.view(), k.view(), N, N, ng, 1.0, o);
  EXPECT_EQ(s.cells_filled, 1);
  EXPECT_EQ(s.passes, 1);
  EXPECT_EQ(s.fallbacks, 0);
  EXPECT_NEAR(xx(5, 7), 1.0, 1e-14);
  EXPECT_NEAR(xy(5, 7), 2.0, 1e-14);
}

TEST(ExtrapolateLSQ, DeterministicThreads) {
  std::vector<double> ref_x, ref_y;
  const int saved = omp_get_max_threads();
  for (int nth : {1, 2}) {
    omp_set_num_threads(nth);
    Case c(400, zalesak_phi(), nl_x, nl_y);
    LsqOptions o;
    o.passes = 6;
    o.parallel_min = 1;  // force the parallel path
    c.lsq(o);
    std::vector<double> vx(c.xx.raw(), c.xx.raw() + c.xx.raw_size());
    std::vector<double> vy(c.xy.raw(), c.xy.raw() + c.xy.raw_size());
    if (nth == 1) { ref_x = vx; ref_y = vy; continue; }
    EXPECT_EQ(0, std::memcmp(vx.data(), ref_x.data(), vx.size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(vy.data(), ref_y.data(), vy.size() * sizeof(double)));
  }
  omp_set_num_threads(saved);
}

TEST(ExtrapolateLSQ, WorkspaceReuseMatchesFresh) {
  LsqWorkspace ws;
  for (int rep = 0; rep < 3; ++rep) {
    Case a(100, zalesak_phi(), nl_x, nl_y), b(100, zalesak_phi(), nl_x, nl_y);
    LsqOptions o;
    o.passes = 5;
    extrapolate_lsq(a.xx.view(), a.xy.view(), a.known.view(), a.N, a.N, a.ng, a.dx, o, &ws);
    b.lsq(o);
    EXPECT_EQ(0, std::memcmp(a.xx.raw(), b.xx.raw(), a.xx.raw_size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(a.known.raw(), b.known.raw(), a.known.raw_size()));
  }
}

// --------------------------------------------------------------------------- PDE

TEST(ExtrapolatePDE, LinearStraightInterface) {
  // tilted straight interface: constant normal, upwind differences of an affine field are
  // exact, so the steady state is exact up to the iteration tolerance -- except next to the
  // window edge, where a missing upwind neighbour drops that derivative term (error ~1e-2 at
  // the edge, decaying over ~14 cells); a solid's window never puts its band there.
  const double a = std::cos(0.3), b = std::sin(0.3);
  Case c(100, [=](double x, double y) { return a * (x - 0.45) + b * (y - 0.5); }, lin_x, lin_y);
  PdeOptions o;
  o.tol = 1e-12;
  const auto s = c.pde(o);
  long n = 0, ni = 0;
  const double err_all = c.max_err(lin_x, lin_y, &n);
  const double err = c.max_err(lin_x, lin_y, &ni, nullptr,
                               [](int i, int j) { return i >= 15 && j >= 15; });
  std::printf("  PDE linear, straight interface: filled %ld, iters q_n %d + xi %d, max err %.3e "
              "(%ld cells >= 15 from the lower/left window edge), %.3e (all)\n",
              s.cells_filled, s.iterations_qn, s.iterations_xi, err, ni, err_all);
  EXPECT_TRUE(s.converged);
  EXPECT_EQ(s.unreached, 0);
  EXPECT_GT(ni, 400);
  EXPECT_LT(err, 1e-11);  // tol 1e-12 relative (scale ~2): observed ~1e-15
}

TEST(ExtrapolatePDE, LinearDiscAndZalesak) {
  // curved interface / corners: the extended q_n carries the normal of the upwind cell, not
  // the local one, so an affine field is NOT reproduced (the error the LSQ method removes).
  // Zalesak: the largest errors sit in the fan of normals around the slot-mouth corners.
  for (int geom = 0; geom < 2; ++geom) {
    Case c(100, geom ? zalesak_phi() : disc_phi(), lin_x, lin_y);
    PdeOptions o;
    const auto s = c.pde(o);
    long n = 0;
    double rms = 0;
    const double err = c.max_err(lin_x, lin_y, &n, &rms);
    long band = 0;
    for (int j = -c.ng; j < c.N + c.ng; ++j)
      for (int i = -c.ng; i < c.N + c.ng; ++i) band += !c.known0(i, j) && c.phi(i, j) <= 5 * c.dx;
    std::printf("  PDE linear, %s: filled %ld / %ld, iters q_n %d + xi %d, fallbacks %ld, "
                "max err %.3e, rms %.3e (LSQ: round-off)\n", geom ? "Zalesak" : "disc",
                s.cells_filled, band, s.iterations_qn, s.iterations_xi, s.fallbacks, err, rms);
    EXPECT_TRUE(s.converged);
    EXPECT_EQ(s.unreached, 0);
    EXPECT_EQ(s.cells_filled, band);
    EXPECT_EQ(n, band);
    EXPECT_LT(err, geom ? 0.1 : 1e-3);   // observed 5.8e-2 / 3.5e-4
    EXPECT_GT(err, geom ? 1e-3 : 1e-5);  // and genuinely not exact
  }
}

TEST(ExtrapolatePDE, NonlinearBesideLsq) {
  // same cells for both: the PDE fill region phi <= 5 dx (LSQ with that target mask)
  std::printf("  nonlinear field, disc r=0.15, cells phi <= 5 dx: max / rms error, LSQ vs PDE\n");
  double pl = 0, pp = 0;
  for (int N : {50, 100, 200, 400}) {
    Case a(N, disc_phi(), nl_x, nl_y), b(N, disc_phi(), nl_x, nl_y);
    Mask tgt(N, N, a.ng);
    for (int j = -a.ng; j < N + a.ng; ++j)
      for (int i = -a.ng; i < N + a.ng; ++i) tgt(i, j) = a.phi(i, j) <= 5 * a.dx;
    LsqOptions lo;
    lo.passes = 8;
    lo.target = tgt.cview();
    const auto sl = a.lsq(lo);
    const auto s = b.pde(PdeOptions{});
    double rl = 0, rp = 0;
    long nl = 0, np = 0;
    const double el = a.max_err(nl_x, nl_y, &nl, &rl), ep = b.max_err(nl_x, nl_y, &np, &rp);
    std::printf("    N=%4d  LSQ %.3e / %.3e (order %.2f)   PDE %.3e / %.3e (order %.2f, "
                "iters %d+%d)  PDE/LSQ max %.2f\n", N, el, rl, pl > 0 ? std::log2(pl / el) : 0.0,
                ep, rp, pp > 0 ? std::log2(pp / ep) : 0.0, s.iterations_qn, s.iterations_xi,
                ep / el);
    EXPECT_EQ(nl, np);
    EXPECT_EQ(sl.cells_filled, s.cells_filled);
    EXPECT_EQ(sl.fallbacks, 0);
    EXPECT_TRUE(s.converged);
    EXPECT_EQ(s.unreached, 0);
    EXPECT_TRUE(std::isfinite(ep));
    if (pp > 0) {
      EXPECT_GT(std::log2(pl / el), 1.5) << "N=" << N;
      EXPECT_GT(std::log2(pp / ep), 1.5) << "N=" << N;
    }
    pl = el; pp = ep;
  }
}

TEST(ExtrapolatePDE, WarmStartSameAnswerFewerIterations) {
  Case a(100, zalesak_phi(), nl_x, nl_y), b(100, zalesak_phi(), nl_x, nl_y);
  const auto sa = a.pde(PdeOptions{});
  // b: initial guess = the exact field in the band
  for (int j = -b.ng; j < b.N + b.ng; ++j)
    for (int i = -b.ng; i < b.N + b.ng; ++i)
      if (!b.known(i, j)) { b.xx(i, j) = nl_x(b.x(i), b.x(j)); b.xy(i, j) = nl_y(b.x(i), b.x(j)); }
  PdeOptions o;
  o.warm_start = true;
  const auto sb = b.pde(o);
  std::printf("  PDE cold %d+%d iterations, warm %d+%d\n", sa.iterations_qn, sa.iterations_xi,
              sb.iterations_qn, sb.iterations_xi);
  EXPECT_LT(sb.iterations_xi, sa.iterations_xi);
  double d = 0;
  for (int j = -a.ng; j < a.N + a.ng; ++j)
    for (int i = -a.ng; i < a.N + a.ng; ++i)
      if (a.known(i, j) && !a.known0(i, j)) d = std::max(d, std::fabs(a.xx(i, j) - b.xx(i, j)));
  EXPECT_LT(d, 1e-7);
}

TEST(ExtrapolatePDE, DeterministicThreads) {
  std::vector<double> ref_x, ref_y;
  int ref_it = 0;
  const int saved = omp_get_max_threads();
  for (int nth : {1, 2}) {
    omp_set_num_threads(nth);
    Case c(400, zalesak_phi(), nl_x, nl_y);
    PdeOptions o;
    o.parallel_min = 1;
    const auto s = c.pde(o);
    std::vector<double> vx(c.xx.raw(), c.xx.raw() + c.xx.raw_size());
    std::vector<double> vy(c.xy.raw(), c.xy.raw() + c.xy.raw_size());
    if (nth == 1) { ref_x = vx; ref_y = vy; ref_it = s.iterations; continue; }
    EXPECT_EQ(s.iterations, ref_it);
    EXPECT_EQ(0, std::memcmp(vx.data(), ref_x.data(), vx.size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(vy.data(), ref_y.data(), vy.size() * sizeof(double)));
  }
  omp_set_num_threads(saved);
}

// The Extrapolator interface (make_extrapolator, the one mapping of solids.extrapolation):
// each method must give, call after call on its own workspace, exactly what its kernel gives
// with the options the solver maps from the scene (band 6 cells, fit radius 2 sqrt(2)).
TEST(ExtrapolatorInterface, FactoryMethodsMatchTheirKernels) {
  for (const ExtrapolationMethod m : {ExtrapolationMethod::Lsq, ExtrapolationMethod::Pde}) {
    const std::string method = to_string(m);
    SolidsOptions so;
    so.extrapolation = m;
    const auto ex = make_extrapolator(so);
    for (int rep = 0; rep < 2; ++rep) {  // the second call reuses the workspace
      const double r = rep == 0 ? 0.15 : 0.22;
      Case a(48, disc_phi(0.5, 0.5, r), nl_x, nl_y), b(48, disc_phi(0.5, 0.5, r), nl_x, nl_y);
      const ExtrapStats sa = ex->extrapolate(a.xx.view(), a.xy.view(), a.known.view(), a.phi.cview(),
                                             a.N, a.N, a.ng, a.dx);
      ExtrapStats sb;
      if (m == ExtrapolationMethod::Lsq) {
        LsqOptions o;
        o.passes = 6;
        o.radius2 = 8;
        sb = b.lsq(o);
      } else {
        PdeOptions o;
        o.band = 6 * b.dx;
        o.tol = so.pde_tol;
        o.max_iter = so.pde_max_iter;
        sb = b.pde(o);
      }
      EXPECT_GT(sa.cells_filled, 0) << method;
      EXPECT_EQ(sa.cells_filled, sb.cells_filled) << method;
      EXPECT_EQ(sa.iterations, sb.iterations) << method;
      for (int j = -a.ng; j < a.N + a.ng; ++j)
        for (int i = -a.ng; i < a.N + a.ng; ++i) {
          ASSERT_EQ(a.known(i, j), b.known(i, j)) << method << " " << i << " " << j;
          if (!a.known(i, j)) continue;
          ASSERT_EQ(a.xx(i, j), b.xx(i, j)) << method << " " << i << " " << j;
          ASSERT_EQ(a.xy(i, j), b.xy(i, j)) << method << " " << i << " " << j;
        }
    }
  }
  SolidsOptions bad;
  bad.extrapolation = ExtrapolationMethod(99);
  EXPECT_THROW(make_extrapolator(bad), std::invalid_argument);
}

// Extrapolator::extrapolate_layers, what the RK-4 stages of eq. (3.3) call (Solid::advect):
// least squares stops after `layers` passes, and the cells it fills -- exactly the cells
// within `layers` (Chebyshev distance) of the known ones -- carry the same bits as after a
// whole-band call (pass p reads only the cells known before it; tolerance 0). The rest stays
// unknown. The PDE method fills its whole band, as extrapolate() does.
TEST(ExtrapolatorInterface, LayersGiveTheWholeBandsInnerCells) {
  for (const ExtrapolationMethod m : {ExtrapolationMethod::Lsq, ExtrapolationMethod::Pde}) {
    const std::string method = to_string(m);
    SolidsOptions so;
    so.extrapolation = m;
    for (int layers = 1; layers <= 2; ++layers) {
      const auto full = make_extrapolator(so), part = make_extrapolator(so);
      Case a(48, disc_phi(0.5, 0.5, 0.18), nl_x, nl_y), b(48, disc_phi(0.5, 0.5, 0.18), nl_x, nl_y);
      const ExtrapStats sa = full->extrapolate(a.xx.view(), a.xy.view(), a.known.view(), a.phi.cview(), a.N, a.N,
                                               a.ng, a.dx);
      const ExtrapStats sb = part->extrapolate_layers(b.xx.view(), b.xy.view(), b.known.view(), b.phi.cview(), b.N,
                                                      b.N, b.ng, b.dx, layers);
      const auto near = dilate(b, layers);
      const int W = b.N + 2 * b.ng;
      long filled = 0;
      for (int j = -b.ng; j < b.N + b.ng; ++j)
        for (int i = -b.ng; i < b.N + b.ng; ++i) {
          if (m == ExtrapolationMethod::Lsq)
            ASSERT_EQ(b.known(i, j) != 0, near[std::size_t(j + b.ng) * W + (i + b.ng)] != 0)
                << method << " layers " << layers << " " << i << " " << j;
          else
            ASSERT_EQ(b.known(i, j), a.known(i, j)) << method << " " << i << " " << j;
          if (!b.known(i, j)) continue;
          filled += !b.known0(i, j);
          ASSERT_EQ(b.xx(i, j), a.xx(i, j)) << method << " layers " << layers << " " << i << " " << j;
          ASSERT_EQ(b.xy(i, j), a.xy(i, j)) << method << " layers " << layers << " " << i << " " << j;
        }
      EXPECT_EQ(filled, sb.cells_filled) << method;
      if (m == ExtrapolationMethod::Lsq) {
        EXPECT_EQ(sb.passes, layers);
        EXPECT_LT(sb.cells_filled, sa.cells_filled);  // the band is 6 layers
      } else {
        EXPECT_EQ(sb.cells_filled, sa.cells_filled);
      }
    }
  }
}
