#include "solver/model/health.hpp"

#include <algorithm>

#include <cmath>
#include <cstdio>

#include "kernels/loop.hpp"
#include "solver/model/simulation.hpp"
#include "solver/model/solid.hpp"

namespace refmap {

std::string check_health(const Simulation& sim, double dt) {
  const Config& cfg = sim.config();
  const Grid& g = sim.grid();
  const Field &u = sim.u(), &v = sim.v(), &p = sim.p(), &uf = sim.uf(), &vf = sim.vf();
  const long nstep = sim.steps();
  const double t = sim.time();
  // two full passes per step: reduced over the team first, the serial scans below only
  // name the failing cell
  const double bad_cells = parallel_rows_sum(0, g.ny, g.nx, [&](int j) {
    double n = 0.0;
    for (int i = 0; i < g.nx; ++i)
      n += (std::isfinite(u(i, j)) && std::isfinite(v(i, j)) && std::isfinite(p(i, j))) ? 0.0 : 1.0;
    return n;
  });
  for (int j = 0; j < g.ny && bad_cells > 0.0; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (!std::isfinite(u(i, j)) || !std::isfinite(v(i, j)) || !std::isfinite(p(i, j))) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "non-finite %s at cell (%d, %d), x = %.6g, y = %.6g, step %ld, t = %.6g",
                      !std::isfinite(u(i, j)) ? "u" : !std::isfinite(v(i, j)) ? "v" : "p", i, j,
                      g.xc(i), g.yc(j), nstep, t);
        return buf;
      }
  if (!(dt > 1e-9 * (cfg.t_end - cfg.t_start))) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "time step collapsed to %.3g at step %ld, t = %.6g: the solution is blowing up "
                  "(kinetic energy %.3g)", dt, nstep, t, sim.kinetic_energy());
    return buf;
  }
  // the face velocities are exactly divergence-free up to the Poisson tolerance; a
  // relative volume change of 1% per step means the projection failed
  // the largest |div u_f| (a NaN counts as infinite)
  const double worst_all = parallel_rows_max(0, g.ny, g.nx, [&](int j) {
    double m = 0.0;
    for (int i = 0; i < g.nx; ++i) {
      const double d = std::abs(uf(i + 1, j) - uf(i, j) + vf(i, j + 1) - vf(i, j)) / g.dx;
      if (!(d <= m)) m = std::isnan(d) ? HUGE_VAL : d;
    }
    return m;
  });
  double worst = 0.0;
  int wi = 0, wj = 0;
  for (int j = 0; j < g.ny && !(worst_all * dt <= 1e-2); ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double d =
          std::abs(uf(i + 1, j) - uf(i, j) + vf(i, j + 1) - vf(i, j)) / g.dx;
      if (!(d <= worst)) { worst = d; wi = i; wj = j; }
    }
  if (!(worst * dt <= 1e-2)) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "face divergence exploded: |div u_f| dt = %.3g at cell (%d, %d), x = %.6g, "
                  "y = %.6g, step %ld, t = %.6g (Poisson: %d iterations, residual %.3g)",
                  worst * dt, wi, wj, g.xc(wi), g.yc(wj), nstep, t, sim.last_poisson_iterations(),
                  sim.last_poisson_residual());
    return buf;
  }
  return {};
}

std::string EnergyJumpCheck::check(const Simulation& sim) {
  const double ke = sim.kinetic_energy();
  std::string bad;
  if (steps_ >= kGrace && prev_ > 0.0 && ke > kFactor * std::max(prev_, peak_)) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "kinetic energy grew from %.3g to %.3g in one step (step %ld, t = %.6g): the solution is "
                  "blowing up",
                  prev_, ke, sim.steps(), sim.time());
    bad = buf;
  }
  ++steps_;
  peak_ = std::max(peak_, ke);
  prev_ = ke;
  return bad;
}

std::string check_reference_maps(const Simulation& sim) {
  const Grid& g = sim.grid();
  const double inv2 = 0.5 / g.dx;
  for (const auto& sp : sim.solids()) {
    const Solid& s = *sp;
    const Field &xx = s.xi_x(), &xy = s.xi_y(), &phi = s.phi();
    // the gradient the stress kernel uses (kernels/solid_stress.hpp, cell_stress): central
    // differences of xi (eq. 3.1); only cells inside the solid (phi < 0) count, the band's
    // extrapolated xi may fold without harm where (1 - H) is small
    auto det_at = [&](int i, int j) {
      const double gxx = (xx(i + 1, j) - xx(i - 1, j)) * inv2;
      const double gxy = (xx(i, j + 1) - xx(i, j - 1)) * inv2;
      const double gyx = (xy(i + 1, j) - xy(i - 1, j)) * inv2;
      const double gyy = (xy(i, j + 1) - xy(i, j - 1)) * inv2;
      return gxx * gyy - gxy * gyx;  // 1 / J of the deformation; NaN is left to the check above
    };
    // the common case, nothing folded, by a threaded count; the serial scan below (for the
    // worst cell) only when there is something to report
    const double n_folded = parallel_rows_sum(0, s.nj(), s.ni(), [&](int j) {
      double c = 0.0;
      for (int i = 0; i < s.ni(); ++i)
        if (phi(i, j) < 0.0 && det_at(i, j) <= 0.0) c += 1.0;
      return c;
    });
    if (n_folded == 0.0) continue;
    double worst = 0.0;
    int wi = -1, wj = -1;
    long folded = 0;
    for (int j = 0; j < s.nj(); ++j)
      for (int i = 0; i < s.ni(); ++i) {
        if (!(phi(i, j) < 0.0)) continue;
        const double det = det_at(i, j);
        if (det <= 0.0) {
          ++folded;
          if (wi < 0 || det < worst) { worst = det; wi = i; wj = j; }
        }
      }
    if (folded > 0) {
      const int gi = s.wrap().i(s.i0() + wi), gj = s.wrap().j(s.j0() + wj);  // the grid cell
      char buf[384];
      std::snprintf(buf, sizeof buf,
                    "reference map folded in solid '%s': det grad xi = %.3g <= 0 at cell (%d, %d), "
                    "x = %.6g, y = %.6g (phi = %.3g; %ld cell%s folded), step %ld, t = %.6g",
                    s.spec().name.c_str(), worst, gi, gj, g.xc(gi), g.yc(gj), phi(wi, wj), folded,
                    folded == 1 ? "" : "s", sim.steps(), sim.time());
      return buf;
    }
  }
  return {};
}

}  // namespace refmap
