#pragma once
// Header-only builders of the Poisson problems shared by tests/test_poisson.cpp and
// bench/bench_poisson.cpp, and an independent reference implementation of the operator
// of solver/poisson.hpp (plain Field indexing, no kernels) to check residuals.
//
// The standard reproducible problem of the solver study (standard_problem(N, R)):
//   unit square, N x N cells, homogeneous Neumann on all four sides,
//   rhs f = cos(pi x) cos(pi y) (projected to zero mean by the solver),
//   rho = 1 outside and R inside the disc of radius 0.2 centred at (0.5, 0.5), smoothed over
//   3 cells: rho = 1 + (R - 1) H(phi), phi = 0.2 - |x - c| (> 0 inside), w = 3 dx,
//   H(phi) = 0.5 (1 + phi/w + sin(pi phi/w)/pi) for |phi| < w (0 below, 1 above),
//   beta on faces = 1/rho_f with rho_f the arithmetic mean of the two adjacent cells,
//   beta = 0 on wall faces.
#include <cmath>
#include <functional>
#include <numbers>

#include "solver/field.hpp"
#include "solver/grid.hpp"
#include "solver/poisson.hpp"

namespace refmap::poisson_problem {

struct Problem {
  Grid grid;
  bool px = false, py = false;
  Field rho, beta_x, beta_y, rhs;

  PoissonOperator op() const {
    PoissonOperator o;
    o.grid = grid;
    o.periodic_x = px;
    o.periodic_y = py;
    o.beta_x = &beta_x;
    o.beta_y = &beta_y;
    return o;
  }
};

inline double smoothed_heaviside(double phi, double w) {
  if (phi <= -w) return 0.0;
  if (phi >= w) return 1.0;
  return 0.5 * (1.0 + phi / w + std::sin(std::numbers::pi * phi / w) / std::numbers::pi);
}

/// beta = 1/rho_f, rho_f = arithmetic mean of the two cells; wall faces 0, periodic faces
/// wrap (face 0 == face n).
inline void face_beta_from_rho(const Grid& g, bool px, bool py, const Field& rho, Field& bx,
                               Field& by) {
  const int nx = g.nx, ny = g.ny;
  bx.resize(nx + 1, ny);
  by.resize(nx, ny + 1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      if (i == 0 || i == nx) {
        bx(i, j) = px ? 2.0 / (rho(nx - 1, j) + rho(0, j)) : 0.0;
      } else {
        bx(i, j) = 2.0 / (rho(i - 1, j) + rho(i, j));
      }
    }
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (j == 0 || j == ny) {
        by(i, j) = py ? 2.0 / (rho(i, ny - 1) + rho(i, 0)) : 0.0;
      } else {
        by(i, j) = 2.0 / (rho(i, j - 1) + rho(i, j));
      }
    }
}

/// rho = 1 outside, ratio inside the disc (xc, yc, radius), smoothed over `cells` cells.
inline void disc_density(const Grid& g, double ratio, double xc, double yc, double radius,
                         double cells, Field& rho) {
  rho.resize(g.nx, g.ny);
  const double w = cells * g.dx;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double phi = radius - std::hypot(g.xc(i) - xc, g.yc(j) - yc);
      rho(i, j) = 1.0 + (ratio - 1.0) * smoothed_heaviside(phi, w);
    }
}

/// General builder: nx x ny cells of size dx from the origin, periodic flags, density
/// ratio `ratio` in a disc of radius 0.2 * min(Lx, Ly) at the domain centre (3-cell
/// smoothing; ratio 1 = constant coefficients), rhs(x, y) sampled at cell centres.
inline Problem disc_problem(int nx, int ny, double dx, bool px, bool py, double ratio,
                            const std::function<double(double, double)>& rhs) {
  Problem p;
  p.grid.nx = nx;
  p.grid.ny = ny;
  p.grid.dx = dx;
  p.px = px;
  p.py = py;
  const double lx = nx * dx, ly = ny * dx;
  disc_density(p.grid, ratio, 0.5 * lx, 0.5 * ly, 0.2 * std::min(lx, ly), 3.0, p.rho);
  face_beta_from_rho(p.grid, px, py, p.rho, p.beta_x, p.beta_y);
  p.rhs.resize(nx, ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) p.rhs(i, j) = rhs(p.grid.xc(i), p.grid.yc(j));
  return p;
}

/// The standard study problem (see the file comment).
inline Problem standard_problem(int n, double ratio) {
  const double pi = std::numbers::pi;
  return disc_problem(n, n, 1.0 / n, false, false, ratio,
                      [pi](double x, double y) { return std::cos(pi * x) * std::cos(pi * y); });
}

/// y = A x = (1/dx^2) sum_f beta_f (x_nb - x_P) straight from the problem's beta fields.
inline void apply_reference(const Problem& p, const Field& x, Field& y) {
  const int nx = p.grid.nx, ny = p.grid.ny;
  const double s = 1.0 / (p.grid.dx * p.grid.dx);
  y.resize(nx, ny);
  auto X = [&](int i, int j) {
    i = (i + nx) % nx;
    j = (j + ny) % ny;
    return x(i, j);
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double c = x(i, j);
      double a = 0.0;
      if (i > 0 || p.px) a += p.beta_x(i, j) * (X(i - 1, j) - c);
      if (i < nx - 1 || p.px) a += p.beta_x(i + 1, j) * (X(i + 1, j) - c);
      if (j > 0 || p.py) a += p.beta_y(i, j) * (X(i, j - 1) - c);
      if (j < ny - 1 || p.py) a += p.beta_y(i, j + 1) * (X(i, j + 1) - c);
      y(i, j) = s * a;
    }
}

inline double mean(const Field& a) {
  double s = 0.0;
  for (int j = 0; j < a.ny(); ++j)
    for (int i = 0; i < a.nx(); ++i) s += a(i, j);
  return s / (double(a.nx()) * a.ny());
}

/// ||(rhs - mean rhs) - A x||_2 / ||rhs - mean rhs||_2, independent of the solvers.
inline double reference_residual(const Problem& p, const Field& rhs, const Field& x) {
  Field ax;
  apply_reference(p, x, ax);
  const double m = mean(rhs);
  double rr = 0.0, bb = 0.0;
  for (int j = 0; j < p.grid.ny; ++j)
    for (int i = 0; i < p.grid.nx; ++i) {
      const double b = rhs(i, j) - m;
      rr += (b - ax(i, j)) * (b - ax(i, j));
      bb += b * b;
    }
  return bb > 0 ? std::sqrt(rr / bb) : std::sqrt(rr);
}
inline double reference_residual(const Problem& p, const Field& x) {
  return reference_residual(p, p.rhs, x);
}

}  // namespace refmap::poisson_problem
