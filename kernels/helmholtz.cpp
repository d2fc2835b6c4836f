#include "kernels/helmholtz.hpp"

#include "kernels/loop.hpp"

namespace refmap {

void helmholtz_faces(CView m, View bx, View by, int nx, int ny, double ax, double ay,
                     const Sides& sides) {
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i <= nx; ++i) bx(i, j) = ax * 0.5 * (m(i - 1, j) + m(i, j));
    switch (sides[Left]) {  // Left and Right share a kind
      case FaceKind::Wall: bx(0, j) = 0.0; bx(nx, j) = 0.0; break;
      case FaceKind::Periodic: break;  // face nx = mean(m(nx-1), m(nx) = m(0)) = face 0
    }
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) by(i, j) = ay * 0.5 * (m(i, j - 1) + m(i, j));
    if (j == 0 || j == ny) {
      switch (sides[Bottom]) {
        case FaceKind::Wall:
          for (int i = 0; i < nx; ++i) by(i, j) = 0.0;
          break;
        case FaceKind::Periodic: break;
      }
    }
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
      case FaceKind::Periodic: break;
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
  for (int j = 0; j < ny; ++j) {
    switch (sides[Left]) {
      case FaceKind::Wall: x(-1, j) = 0.0; x(nx, j) = 0.0; break;
      case FaceKind::Periodic: x(-1, j) = x(nx - 1, j); x(nx, j) = x(0, j); break;
    }
  }
  for (int i = -1; i <= nx; ++i) {
    switch (sides[Bottom]) {
      case FaceKind::Wall: x(i, -1) = 0.0; x(i, ny) = 0.0; break;
      case FaceKind::Periodic: x(i, -1) = x(i, ny - 1); x(i, ny) = x(i, 0); break;
    }
  }
}

}  // namespace refmap
