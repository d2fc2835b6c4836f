#include "kernels/control_volume.hpp"

#include <algorithm>

namespace refmap {

std::array<double, 3> box_surface_force(const SurfaceFields& f, const ControlBox& b, const BoxFrame& fr) {
  const double dx = fr.dx, inv = 1.0 / dx;
  const bool solid = f.sxx.p != nullptr;
  double fx = 0.0, fy = 0.0, tz = 0.0;
  // one face of the surface: traction t (per unit length) at (xc, yc), length dx
  auto add = [&](double tx, double ty, double xc, double yc) {
    fx += tx * dx;
    fy += ty * dx;
    tz += ((xc - fr.xr) * ty - (yc - fr.yr) * tx) * dx;
  };
  // x-faces i = i0 (n = -x) and i = i1 (n = +x), rows j0 .. j1-1; face i lies between
  // cells i-1 and i
  for (const int side : {0, 1}) {
    const int i = side == 0 ? b.i0 : b.i1;
    const double nx = side == 0 ? -1.0 : 1.0;
    const bool boundary = i == 0 || i == fr.nx;
    const int in = side == 0 ? i : i - 1;  // the box's own cell next to the face
    for (int j = b.j0; j < b.j1; ++j) {
      const double p = 0.5 * (f.p(i - 1, j) + f.p(i, j));
      const double mu = 0.5 * (f.mu(i - 1, j) + f.mu(i, j));
      const double dudx = (f.u(i, j) - f.u(i - 1, j)) * inv;
      const double dvdx = (f.v(i, j) - f.v(i - 1, j)) * inv;
      const double dudy = 0.25 * (f.u(i - 1, j + 1) - f.u(i - 1, j - 1) + f.u(i, j + 1) - f.u(i, j - 1)) * inv;
      double sxx = -p + 2.0 * mu * dudx, syx = mu * (dudy + dvdx);
      if (solid) {
        sxx += boundary ? f.sxx(in, j) : 0.5 * (f.sxx(i - 1, j) + f.sxx(i, j));
        syx += boundary ? f.sxy(in, j) : 0.5 * (f.sxy(i - 1, j) + f.sxy(i, j));
      }
      // momentum flux rho u (u . n) with the face velocity the advection used
      const double un = f.uf(i, j) * nx;
      const double mx = 0.5 * (f.rho(i - 1, j) * f.u(i - 1, j) + f.rho(i, j) * f.u(i, j));
      const double my = 0.5 * (f.rho(i - 1, j) * f.v(i - 1, j) + f.rho(i, j) * f.v(i, j));
      add(sxx * nx - mx * un, syx * nx - my * un, fr.x0 + i * dx, fr.y0 + (j + 0.5) * dx);
    }
  }
  // y-faces j = j0 (n = -y) and j = j1 (n = +y), columns i0 .. i1-1
  for (const int side : {0, 1}) {
    const int j = side == 0 ? b.j0 : b.j1;
    const double ny = side == 0 ? -1.0 : 1.0;
    const bool boundary = j == 0 || j == fr.ny;
    const int in = side == 0 ? j : j - 1;
    for (int i = b.i0; i < b.i1; ++i) {
      const double p = 0.5 * (f.p(i, j - 1) + f.p(i, j));
      const double mu = 0.5 * (f.mu(i, j - 1) + f.mu(i, j));
      const double dvdy = (f.v(i, j) - f.v(i, j - 1)) * inv;
      const double dudy = (f.u(i, j) - f.u(i, j - 1)) * inv;
      const double dvdx = 0.25 * (f.v(i + 1, j - 1) - f.v(i - 1, j - 1) + f.v(i + 1, j) - f.v(i - 1, j)) * inv;
      double syy = -p + 2.0 * mu * dvdy, sxy = mu * (dudy + dvdx);
      if (solid) {
        syy += boundary ? f.syy(i, in) : 0.5 * (f.syy(i, j - 1) + f.syy(i, j));
        sxy += boundary ? f.sxy(i, in) : 0.5 * (f.sxy(i, j - 1) + f.sxy(i, j));
      }
      const double un = f.vf(i, j) * ny;
      const double mx = 0.5 * (f.rho(i, j - 1) * f.u(i, j - 1) + f.rho(i, j) * f.u(i, j));
      const double my = 0.5 * (f.rho(i, j - 1) * f.v(i, j - 1) + f.rho(i, j) * f.v(i, j));
      add(sxy * ny - mx * un, syy * ny - my * un, fr.x0 + (i + 0.5) * dx, fr.y0 + j * dx);
    }
  }
  return {fx, fy, tz};
}

std::array<double, 6> box_momentum(CView u, CView v, CView w, double rho_w, const ControlBox& b, const BoxFrame& fr) {
  std::array<double, 6> s{};
  const double da = fr.dx * fr.dx;
  for (int j = b.j0; j < b.j1; ++j) {
    const double ry = fr.y0 + (j + 0.5) * fr.dx - fr.yr;
    for (int i = b.i0; i < b.i1; ++i) {
      const double rx = fr.x0 + (i + 0.5) * fr.dx - fr.xr;
      const double wf = std::clamp(w(i, j), 0.0, 1.0), ws = 1.0 - wf;
      const double mu = wf * rho_w * u(i, j) * da, mv = wf * rho_w * v(i, j) * da;
      s[0] += mu;
      s[1] += mv;
      s[2] += rx * mv - ry * mu;
      s[3] += ws * da;
      s[4] += ws * rx * da;
      s[5] += ws * ry * da;
    }
  }
  return s;
}

}  // namespace refmap
