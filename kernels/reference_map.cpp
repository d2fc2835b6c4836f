#include "kernels/reference_map.hpp"

#include <cmath>

#include "kernels/advection.hpp"
#include "kernels/loop.hpp"

namespace refmap {

namespace {

/// The work of one cell of the right-hand side in cells of a simple row loop (the unit of
/// kMinParallelCells, kernels/loop.hpp): four limited face values and their velocities per
/// component. A solid's box of ~10 000 cells (one disc on 256^2) is then threaded.
constexpr int kRhsCellCost = 4;

/// van Leer-limited face value, q_f = qu + 0.5 psi(r) (qd - qu), psi(r) = (r + |r|) / (1 + |r|):
/// qu + e d / (e + d) with e = qu - quu, d = qd - qu when e d > 0, else qu (the harmonic mean
/// of the two slopes; r = 1 gives the central value)
inline double van_leer_face(double quu, double qu, double qd) {
  const double e = qu - quu, d = qd - qu;
  return e * d > 0.0 ? qu + e * d / (e + d) : qu;
}

/// minmod-limited face value, q_f = qu + 0.5 minmod(e, d) with e = qu - quu, d = qd - qu:
/// the smaller slope when both have one sign, else qu (r = 1 gives the central value)
inline double minmod_face(double quu, double qu, double qd) {
  const double e = qu - quu, d = qd - qu;
  if (!(e * d > 0.0)) return qu;
  return qu + 0.5 * (std::abs(e) < std::abs(d) ? e : d);
}

/// kCell: (uf, vf) are the cell velocities, read at the cell for both of its faces
/// (XiVelocity::Cell); else the face velocities.
template <XiFlux F, bool kCell>
void rhs_impl(CView xi_x, CView xi_y, CView phi, CView uf, CView vf, int ni, int nj, int i0,
              int j0, double dx, View kx, View ky) {
  const double s = -0.5 / dx;
  // the increment q_f - q_i towards the face between cell i and its neighbour i + o (o = +-1)
  // for the face velocity vel (> 0: towards +)
  auto incr = [](CView q, int i, int j, int di, int dj, double vel) {
    const double qc = q(i, j), qn = q(i + di, j + dj);
    if constexpr (F == XiFlux::Central) {
      return 0.5 * (qn - qc);
    } else {
      // the flow crosses the face from i to i + o when vel * o > 0
      const bool out = (di + dj) * vel >= 0.0;
      auto face = [](double a, double b, double c) {
        if constexpr (F == XiFlux::Superbee) return superbee_face(a, b, c);
        else if constexpr (F == XiFlux::Minmod) return minmod_face(a, b, c);
        else return van_leer_face(a, b, c);
      };
      const double f = out ? face(q(i - di, j - dj), qc, qn) : face(q(i + 2 * di, j + 2 * dj), qn, qc);
      return f - qc;
    }
  };
  parallel_rows(0, nj, ni * kRhsCellCost, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      if (!(phi(i, j) < 0.0)) {  // H = 0 outside Omega_S, eq. (3.4)
        kx(i, j) = 0.0;
        ky(i, j) = 0.0;
        continue;
      }
      const double ue = kCell ? uf(i0 + i, j0 + j) : uf(i0 + i + 1, j0 + j);
      const double uw = uf(i0 + i, j0 + j);
      const double vn = kCell ? vf(i0 + i, j0 + j) : vf(i0 + i, j0 + j + 1);
      const double vs = vf(i0 + i, j0 + j);
      // u.grad q = [ue (q_e - q_i) - uw (q_w - q_i) + vn (q_n - q_i) - vs (q_s - q_i)] / dx
      kx(i, j) = 2.0 * s * (ue * incr(xi_x, i, j, 1, 0, ue) - uw * incr(xi_x, i, j, -1, 0, uw) +
                            vn * incr(xi_x, i, j, 0, 1, vn) - vs * incr(xi_x, i, j, 0, -1, vs));
      ky(i, j) = 2.0 * s * (ue * incr(xi_y, i, j, 1, 0, ue) - uw * incr(xi_y, i, j, -1, 0, uw) +
                            vn * incr(xi_y, i, j, 0, 1, vn) - vs * incr(xi_y, i, j, 0, -1, vs));
    }
  });
}

}  // namespace

void reference_map_rhs(CView xi_x, CView xi_y, CView phi, CView uf, CView vf, int ni, int nj,
                       int i0, int j0, double dx, View kx, View ky, XiFlux flux) {
  switch (flux) {
    case XiFlux::Central: rhs_impl<XiFlux::Central, false>(xi_x, xi_y, phi, uf, vf, ni, nj, i0, j0, dx, kx, ky); break;
    case XiFlux::Superbee: rhs_impl<XiFlux::Superbee, false>(xi_x, xi_y, phi, uf, vf, ni, nj, i0, j0, dx, kx, ky); break;
    case XiFlux::VanLeer: rhs_impl<XiFlux::VanLeer, false>(xi_x, xi_y, phi, uf, vf, ni, nj, i0, j0, dx, kx, ky); break;
    case XiFlux::Minmod: rhs_impl<XiFlux::Minmod, false>(xi_x, xi_y, phi, uf, vf, ni, nj, i0, j0, dx, kx, ky); break;
  }
}

void reference_map_rhs_cell(CView xi_x, CView xi_y, CView phi, CView u, CView v, int ni, int nj,
                            int i0, int j0, double dx, View kx, View ky, XiFlux flux) {
  switch (flux) {
    case XiFlux::Central: rhs_impl<XiFlux::Central, true>(xi_x, xi_y, phi, u, v, ni, nj, i0, j0, dx, kx, ky); break;
    case XiFlux::Superbee: rhs_impl<XiFlux::Superbee, true>(xi_x, xi_y, phi, u, v, ni, nj, i0, j0, dx, kx, ky); break;
    case XiFlux::VanLeer: rhs_impl<XiFlux::VanLeer, true>(xi_x, xi_y, phi, u, v, ni, nj, i0, j0, dx, kx, ky); break;
    case XiFlux::Minmod: rhs_impl<XiFlux::Minmod, true>(xi_x, xi_y, phi, u, v, ni, nj, i0, j0, dx, kx, ky); break;
  }
}

void reference_map_rhs_cell(CView xi_x, CView xi_y, CView phi, CView u, CView v, int ni, int nj, int i0, int j0,
                            double dx, View kx, View ky) {
  const double s = -0.5 / dx;
  parallel_rows(0, nj, ni * kRhsCellCost, [&](int j) {
    for (int i = 0; i < ni; ++i) {
      if (!(phi(i, j) < 0.0)) {  // H = 0 outside Omega_S, eq. (3.4)
        kx(i, j) = 0.0;
        ky(i, j) = 0.0;
        continue;
      }
      const double uc = u(i0 + i, j0 + j), vc = v(i0 + i, j0 + j);
      kx(i, j) = s * (uc * (xi_x(i + 1, j) - xi_x(i - 1, j)) + vc * (xi_x(i, j + 1) - xi_x(i, j - 1)));
      ky(i, j) = s * (uc * (xi_y(i + 1, j) - xi_y(i - 1, j)) + vc * (xi_y(i, j + 1) - xi_y(i, j - 1)));
    }
  });
}

}  // namespace refmap
