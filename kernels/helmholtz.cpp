#include "kernels/helmholtz.hpp"

#include "kernels/loop.hpp"

namespace refmap {

namespace {
/// Whether a side has a boundary face of its own (everything but periodic): the face
/// coefficient there is 0 and the condition enters through the sink or not at all.
bool bounded(FaceKind k) {
  switch (k) {
    case FaceKind::Wall:
    case FaceKind::Inflow:   // velocity prescribed: like a wall for the change d
    case FaceKind::Outflow:  // zero normal derivative: a zero-flux face
      return true;
    case FaceKind::Periodic: return false;
  }
  return true;
}
}  // namespace

void helmholtz_faces(CView m, View bx, View by, int nx, int ny, double ax, double ay,
                     const Sides& sides) {
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i <= nx; ++i) bx(i, j) = ax * 0.5 * (m(i - 1, j) + m(i, j));
    // periodic: face nx = mean(m(nx-1), m(nx) = m(0)) = face 0, kept
    if (bounded(sides[Left])) bx(0, j) = 0.0;
    if (bounded(sides[Right])) bx(nx, j) = 0.0;
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) by(i, j) = ay * 0.5 * (m(i, j - 1) + m(i, j));
    if ((j == 0 && bounded(sides[Bottom])) || (j == ny && bounded(sides[Top])))
      for (int i = 0; i < nx; ++i) by(i, j) = 0.0;
  });
}

void helmholtz_sink(CView rho, CView m, View c, int nx, int ny, double dx, double dt, double ax,
                    double ay, const Sides& sides, const std::array<bool, 4>& fixed) {
  const double inv2 = 1.0 / (dx * dx), idt = 1.0 / dt;
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) c(i, j) = rho(i, j) * idt;
  });
  // the wall face's viscosity is the boundary cell's (the even mirror of
  // fill_scalar_ghosts, as the explicit operator sees it)
  for (int s = 0; s < 4; ++s) {
    switch (sides[Side(s)]) {
      case FaceKind::Periodic:
      case FaceKind::Outflow: break;  // zero normal derivative: no term
      case FaceKind::Inflow:          // both components prescribed (fixed[s] is true)
      case FaceKind::Wall: {
        if (!fixed[std::size_t(s)]) break;
        if (s == Left || s == Right) {
          const int i = s == Left ? 0 : nx - 1;
          for (int j = 0; j < ny; ++j) c(i, j) += 2.0 * ax * m(i, j) * inv2;
        } else {
          const int j = s == Bottom ? 0 : ny - 1;
          for (int i = 0; i < nx; ++i) c(i, j) += 2.0 * ay * m(i, j) * inv2;
        }
        break;
      }
    }
  }
}

void helmholtz_apply(CView x, CView bx, CView by, CView c, View out, int nx, int ny, double dx) {
  const double inv2 = 1.0 / (dx * dx);
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      const double xp = x(i, j);
      const double flux = bx(i + 1, j) * (x(i + 1, j) - xp) - bx(i, j) * (xp - x(i - 1, j)) +
                          by(i, j + 1) * (x(i, j + 1) - xp) - by(i, j) * (xp - x(i, j - 1));
      out(i, j) = flux * inv2 - c(i, j) * xp;
    }
  });
}

void helmholtz_ghosts(View x, int nx, int ny, const Sides& sides) {
  // a periodic side's partner is periodic too (checked when the scene is loaded)
  for (int j = 0; j < ny; ++j) {
    x(-1, j) = bounded(sides[Left]) ? 0.0 : x(nx - 1, j);
    x(nx, j) = bounded(sides[Right]) ? 0.0 : x(0, j);
  }
  for (int i = -1; i <= nx; ++i) {
    x(i, -1) = bounded(sides[Bottom]) ? 0.0 : x(i, ny - 1);
    x(i, ny) = bounded(sides[Top]) ? 0.0 : x(i, 0);
  }
}

}  // namespace refmap
