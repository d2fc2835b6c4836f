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

/// Face coefficients from fx(i, j) / fy(i, j) (the x face left of / the y face below cell
/// (i, j)), zero on a bounded side's own faces.
template <class FX, class FY>
void faces_from(FX fx, FY fy, View bx, View by, int nx, int ny, const Sides& sides) {
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i <= nx; ++i) bx(i, j) = fx(i, j);
    // periodic: face nx = mean(m(nx-1), m(nx) = m(0)) = face 0, kept
    if (bounded(sides[Left])) bx(0, j) = 0.0;
    if (bounded(sides[Right])) bx(nx, j) = 0.0;
  });
  parallel_rows(0, ny + 1, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) by(i, j) = fy(i, j);
    if ((j == 0 && bounded(sides[Bottom])) || (j == ny && bounded(sides[Top])))
      for (int i = 0; i < nx; ++i) by(i, j) = 0.0;
  });
}

/// c = rho / dt, plus 2 k / dx^2 in the cells next to a side that fixes the component,
/// with k = kx(i, j) on left/right and ky(i, j) on bottom/top: the wall face's coefficient
/// is the boundary cell's (the even mirror of fill_scalar_ghosts, as the explicit operator
/// sees it).
template <class KX, class KY>
void sink_from(CView rho, KX kx, KY ky, View c, int nx, int ny, double dx, double dt,
               const Sides& sides, const std::array<bool, 4>& fixed) {
  const double inv2 = 1.0 / (dx * dx), idt = 1.0 / dt;
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) c(i, j) = rho(i, j) * idt;
  });
  for (int s = 0; s < 4; ++s) {
    switch (sides[Side(s)]) {
      case FaceKind::Periodic:
      case FaceKind::Outflow: break;  // zero normal derivative: no term
      case FaceKind::Inflow:          // both components prescribed (fixed[s] is true)
      case FaceKind::Wall: {
        if (!fixed[std::size_t(s)]) break;
        if (s == Left || s == Right) {
          const int i = s == Left ? 0 : nx - 1;
          for (int j = 0; j < ny; ++j) c(i, j) += 2.0 * kx(i, j) * inv2;
        } else {
          const int j = s == Bottom ? 0 : ny - 1;
          for (int i = 0; i < nx; ++i) c(i, j) += 2.0 * ky(i, j) * inv2;
        }
        break;
      }
    }
  }
}
}  // namespace

void helmholtz_faces(CView m, View bx, View by, int nx, int ny, double ax, double ay,
                     const Sides& sides) {
  faces_from([&](int i, int j) { return ax * 0.5 * (m(i - 1, j) + m(i, j)); },
             [&](int i, int j) { return ay * 0.5 * (m(i, j - 1) + m(i, j)); }, bx, by, nx, ny, sides);
}

void helmholtz_sink(CView rho, CView m, View c, int nx, int ny, double dx, double dt, double ax,
                    double ay, const Sides& sides, const std::array<bool, 4>& fixed) {
  sink_from(rho, [&](int i, int j) { return ax * m(i, j); }, [&](int i, int j) { return ay * m(i, j); }, c, nx,
            ny, dx, dt, sides, fixed);
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

void helmholtz_faces_cells(CView kx, CView ky, View bx, View by, int nx, int ny, const Sides& sides) {
  faces_from([&](int i, int j) { return 0.5 * (kx(i - 1, j) + kx(i, j)); },
             [&](int i, int j) { return 0.5 * (ky(i, j - 1) + ky(i, j)); }, bx, by, nx, ny, sides);
}

void helmholtz_sink_cells(CView rho, CView kx, CView ky, View c, int nx, int ny, double dx,
                          double dt, const Sides& sides, const std::array<bool, 4>& fixed) {
  sink_from(rho, [&](int i, int j) { return kx(i, j); }, [&](int i, int j) { return ky(i, j); }, c, nx, ny, dx,
            dt, sides, fixed);
}

void rate_stress_force(CView du, CView dv, CView qxx, CView qxy, CView qyy, View fx, View fy,
                       int nx, int ny, double dx, bool full) {
  const double inv2 = 1.0 / (dx * dx);
  const double c = full ? 1.0 : 0.0;  // weight of the compact part
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      // face values of q (mean of the two cells): east, west, north, south
      const double xxe = 0.5 * (qxx(i, j) + qxx(i + 1, j)), xxw = 0.5 * (qxx(i - 1, j) + qxx(i, j));
      const double xye = 0.5 * (qxy(i, j) + qxy(i + 1, j)), xyw = 0.5 * (qxy(i - 1, j) + qxy(i, j));
      const double yye = 0.5 * (qyy(i, j) + qyy(i + 1, j)), yyw = 0.5 * (qyy(i - 1, j) + qyy(i, j));
      const double xxn = 0.5 * (qxx(i, j) + qxx(i, j + 1)), xxs = 0.5 * (qxx(i, j - 1) + qxx(i, j));
      const double xyn = 0.5 * (qxy(i, j) + qxy(i, j + 1)), xys = 0.5 * (qxy(i, j - 1) + qxy(i, j));
      const double yyn = 0.5 * (qyy(i, j) + qyy(i, j + 1)), yys = 0.5 * (qyy(i, j - 1) + qyy(i, j));
      // derivatives times dx on the faces: normal compact, tangential the mean of the two
      // cells' central differences (kernels/viscous.cpp)
      const double ux_e = du(i + 1, j) - du(i, j), ux_w = du(i, j) - du(i - 1, j);
      const double vx_e = dv(i + 1, j) - dv(i, j), vx_w = dv(i, j) - dv(i - 1, j);
      const double uy_e = 0.25 * (du(i + 1, j + 1) - du(i + 1, j - 1) + du(i, j + 1) - du(i, j - 1));
      const double uy_w = 0.25 * (du(i, j + 1) - du(i, j - 1) + du(i - 1, j + 1) - du(i - 1, j - 1));
      const double vy_e = 0.25 * (dv(i + 1, j + 1) - dv(i + 1, j - 1) + dv(i, j + 1) - dv(i, j - 1));
      const double vy_w = 0.25 * (dv(i, j + 1) - dv(i, j - 1) + dv(i - 1, j + 1) - dv(i - 1, j - 1));
      const double uy_n = du(i, j + 1) - du(i, j), uy_s = du(i, j) - du(i, j - 1);
      const double vy_n = dv(i, j + 1) - dv(i, j), vy_s = dv(i, j) - dv(i, j - 1);
      const double ux_n = 0.25 * (du(i + 1, j + 1) - du(i - 1, j + 1) + du(i + 1, j) - du(i - 1, j));
      const double ux_s = 0.25 * (du(i + 1, j) - du(i - 1, j) + du(i + 1, j - 1) - du(i - 1, j - 1));
      const double vx_n = 0.25 * (dv(i + 1, j + 1) - dv(i - 1, j + 1) + dv(i + 1, j) - dv(i - 1, j));
      const double vx_s = 0.25 * (dv(i + 1, j) - dv(i - 1, j) + dv(i + 1, j - 1) - dv(i - 1, j - 1));
      // u equation: tau_xx on x faces, tau_xy on y faces
      const double txx_e = 2.0 * (c * xxe * ux_e + xye * uy_e);
      const double txx_w = 2.0 * (c * xxw * ux_w + xyw * uy_w);
      const double txy_n = xyn * ux_n + c * yyn * uy_n + xxn * vx_n + xyn * vy_n;
      const double txy_s = xys * ux_s + c * yys * uy_s + xxs * vx_s + xys * vy_s;
      fx(i, j) = (txx_e - txx_w + txy_n - txy_s) * inv2;
      // v equation: tau_xy on x faces, tau_yy on y faces
      const double tyx_e = xye * ux_e + yye * uy_e + c * xxe * vx_e + xye * vy_e;
      const double tyx_w = xyw * ux_w + yyw * uy_w + c * xxw * vx_w + xyw * vy_w;
      const double tyy_n = 2.0 * (xyn * vx_n + c * yyn * vy_n);
      const double tyy_s = 2.0 * (xys * vx_s + c * yys * vy_s);
      fy(i, j) = (tyx_e - tyx_w + tyy_n - tyy_s) * inv2;
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
