// Energy budget of the split stress step around a solid's surface (docs/implicit.md,
// docs/implicit.md "Why the splitting fails at the interface").
//
//   refmap_energy_budget <scene.toml> [--set key=value ...] [--steps N] [--out budget.csv]
//
// Runs the scene step by step (no output, no health checks: a run that blows up is what
// is measured) with a stage probe inside Simulation::step() (Simulation::set_stage_probe:
// u* after the momentum advection, u** after the stress step) and books, per step and per
// ring of cells by the level set phi^{n+1} / dx of solid 0, with ubar = (u^n + u^{n+1}) / 2
// the step's mean velocity (so the W terms sum to the change of the kinetic energy when rho
// does not change in time, as in disc_tgv with rho_s = rho_f):
//
//   W_s     dt sum ubar . f_s dx^2     work of the solid force f_s = div((1-H) sigma) (the
//                                      conservative cell form, eq. 3.6) at the cell it acts on
//   Pi      dt sum S : G(ubar) dx^2    the same exchange booked where the blended stress S
//                                      lives (G the central gradient, the adjoint of the
//                                      central divergence: sum Pi = -sum W_s up to wall terms)
//   W_v     dt sum ubar . f_v dx^2     the viscous force div mu (grad u* + grad u*^T)
//                                      (kernels/viscous.cpp) as the explicit step would apply it
//   W_i     sum ubar . (rho d - dt f_s - dt f_v) dx^2, d = u** - u*: the implicit term of
//                                      solver/model/implicit_step.hpp (implicit viscosity, eta of the
//                                      stabilised splitting, the rate operator); 0 if explicit
//   W_adv   sum rho ubar . (u* - u^n) dx^2   the momentum advection (eq. 5.1)
//   W_proj  sum rho ubar . (u^{n+1} - u**) dx^2   the projection (eqs. 5.4-5.7)
//   dE_xi   sum w^n (W^{n+1} - W^n) dx^2 over cells with phi^{n+1} < 0: the elastic energy
//                                      change where xi is advected (eq. 3.3)
//   dE_band the same over phi^{n+1} >= 0: where xi is extrapolated, not advected
//   dE_blend sum (w^{n+1} - w^n) W^{n+1} dx^2: the blend weight w = 1 - H(phi) moving
//   W_s_step as W_s with the stress step's own mean velocity (u* + u**) / 2
//
// W is the model's energy density of b (read back from the stored stress), so sum w W dx^2
// is the elastic energy of the diagnostics. The energy the stress coupling makes in a step
// is W_s + dE_xi + dE_band + dE_blend (kinetic energy given by the stress minus the elastic
// energy that paid for it): zero for an exact exchange, O(dt^2) and oscillating for the
// explicit (symplectic-Euler) lag when stable.
//
// Output (--out): one row per step and ring: step, t, dt, ring (phi/dx in [lo, hi)), cells,
// the terms, the ring's elastic energy, and the step's kinetic and elastic energy.
// bench/energy_budget.py runs the cases of docs/implicit.md and summarises them.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "kernels/solid_stress.hpp"
#include "kernels/viscous.hpp"
#include "solver/model/boundary.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"

namespace {

using namespace refmap;

// ring edges in phi / dx: the blend is |phi| < w_t (1.5 dx by default), the band 6 dx
const std::vector<double> kEdges = {-1e9, -3, -2, -1, 0, 1, 2, 3, 1e9};
const int kRings = int(kEdges.size()) - 1;

int ring_of(double phi_dx) {
  for (int r = 0; r < kRings; ++r)
    if (phi_dx < kEdges[std::size_t(r) + 1]) return r;
  return kRings - 1;
}

struct Terms {
  double ws_step = 0, ws = 0, pi = 0, wv = 0, wi = 0, wadv = 0, wproj = 0, dxi = 0, dband = 0,
         dblend = 0, ee = 0, cells = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: refmap_energy_budget scene.toml [--set k=v ...] [--steps N] [--out f.csv]\n";
    return 2;
  }
  std::string scene = argv[1], out = "budget.csv";
  std::vector<std::string> sets;
  long steps = 400;
  for (int a = 2; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--set" && a + 1 < argc) sets.push_back(argv[++a]);
    else if (s == "--steps" && a + 1 < argc) steps = std::atol(argv[++a]);
    else if (s == "--out" && a + 1 < argc) out = argv[++a];
    else { std::cerr << "unknown argument " << s << "\n"; return 2; }
  }
  Config cfg = load_scene(scene, sets);
  Simulation sim(cfg);
  const Grid& g = sim.grid();
  const int nx = g.nx, ny = g.ny;
  const double a = g.dx * g.dx;
  if (sim.solids().empty()) { std::cerr << "no solid\n"; return 2; }

  // per global cell: w = 1 - H(phi) and W of the last stress evaluation (solid 0)
  Field w_old(nx, ny, Grid::ng), W_old(nx, ny, Grid::ng), w_new(nx, ny, Grid::ng), W_new(nx, ny, Grid::ng);
  auto sample = [&](Field& w, Field& W) {
    w.fill(0.0);
    W.fill(0.0);
    const Solid& s = *sim.solids()[0];
    with_constitutive_model(s.spec(), [&](const auto& m) {
      for (int j = 0; j < s.nj(); ++j)
        for (int i = 0; i < s.ni(); ++i) {
          const double ph = s.phi()(i, j);
          const int gi = s.i0() + i, gj = s.j0() + j;
          if (ph < s.transition()) w(gi, gj) = 1.0 - smoothed_heaviside(ph, s.transition());
          W(gi, gj) = m.energy(m.strain({s.stress_xx()(i, j), s.stress_xy()(i, j), s.stress_yy()(i, j)}));
        }
    });
  };

  // u^n, u*, u**, u^{n+1} (ghosts from the walls), the forces and the blended stress
  Field un(nx, ny, Grid::ng), vn(nx, ny, Grid::ng), us(nx, ny, Grid::ng), vs(nx, ny, Grid::ng);
  Field uss(nx, ny, Grid::ng), vss(nx, ny, Grid::ng), un1(nx, ny, Grid::ng), vn1(nx, ny, Grid::ng);
  Field fsx(nx, ny, Grid::ng), fsy(nx, ny, Grid::ng), fvx(nx, ny, Grid::ng), fvy(nx, ny, Grid::ng);
  Field S[3] = {Field(nx, ny, Grid::ng), Field(nx, ny, Grid::ng), Field(nx, ny, Grid::ng)};
  std::vector<Terms> rings(static_cast<std::size_t>(kRings));

  sim.set_stage_probe([&](Simulation::Stage st, double dt) {
    if (st == Simulation::Stage::Advected) {
      us = sim.u();
      vs = sim.v();
      sim.apply_velocity_bc(us, vs, sim.time() + dt);  // the stress step's ghosts (t + dt)
      return;
    }
    // Stressed: u() = u**; the blended stress of this step; solid 0 at xi^{n+1}
    uss = sim.u();
    vss = sim.v();
    sim.apply_velocity_bc(uss, vss, sim.time() + dt);
    const Field* gs[3] = {&sim.solid_stress_xx(), &sim.solid_stress_xy(), &sim.solid_stress_yy()};
    for (int c = 0; c < 3; ++c) {
      S[c] = *gs[c];
      fill_scalar_ghosts(S[c], sim.config().bc);
    }
    fsx.fill(0.0);
    fsy.fill(0.0);
    add_stress_divergence(S[0].view(), S[1].view(), S[2].view(), fsx.view(), fsy.view(), nx, ny, g.dx);
    fvx.fill(0.0);
    fvy.fill(0.0);
    viscous_force(us.view(), vs.view(), sim.viscosity().view(), fvx.view(), fvy.view(), nx, ny, g.dx);
    sample(w_new, W_new);
  });

  // the terms of one step, per ring (after it: u^{n+1} known). The full step's mean
  // velocity ubar = (u^n + u^{n+1}) / 2 weighs every change of the step, so the terms
  // sum to the change of the kinetic energy (rho constant in time per cell, as in
  // disc_tgv with rho_s = rho_f; otherwise up to the density change)
  auto book = [&](double dt) {
    const Solid& s = *sim.solids()[0];
    const double inv2 = 0.5 / g.dx;
    for (auto& r : rings) r = Terms{};
    auto ubar = [&](const Field& a, const Field& b, int i, int j) { return 0.5 * (a(i, j) + b(i, j)); };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double phi = s.phi_global(i, j);
        Terms& r = rings[std::size_t(ring_of(phi / g.dx))];
        const double rho = sim.rho()(i, j);
        const double us_ = 0.5 * (us(i, j) + uss(i, j)), vs_ = 0.5 * (vs(i, j) + vss(i, j));
        const double ub = ubar(un, un1, i, j), vb = ubar(vn, vn1, i, j);
        const double du = uss(i, j) - us(i, j), dv = vss(i, j) - vs(i, j);
        r.ws_step += dt * (us_ * fsx(i, j) + vs_ * fsy(i, j)) * a;
        const double ws = dt * (ub * fsx(i, j) + vb * fsy(i, j)) * a;
        const double wv = dt * (ub * fvx(i, j) + vb * fvy(i, j)) * a;
        r.ws += ws;
        r.wv += wv;
        r.wi += rho * (ub * du + vb * dv) * a - ws - wv;
        r.wadv += rho * (ub * (us(i, j) - un(i, j)) + vb * (vs(i, j) - vn(i, j))) * a;
        r.wproj += rho * (ub * (un1(i, j) - uss(i, j)) + vb * (vn1(i, j) - vss(i, j))) * a;
        const double ux = (ubar(un, un1, i + 1, j) - ubar(un, un1, i - 1, j)) * inv2;
        const double uy = (ubar(un, un1, i, j + 1) - ubar(un, un1, i, j - 1)) * inv2;
        const double vx = (ubar(vn, vn1, i + 1, j) - ubar(vn, vn1, i - 1, j)) * inv2;
        const double vy = (ubar(vn, vn1, i, j + 1) - ubar(vn, vn1, i, j - 1)) * inv2;
        r.pi += dt * (S[0](i, j) * ux + S[1](i, j) * (uy + vx) + S[2](i, j) * vy) * a;
        const double dW = w_old(i, j) * (W_new(i, j) - W_old(i, j)) * a;
        (phi < 0.0 ? r.dxi : r.dband) += dW;
        r.dblend += (w_new(i, j) - w_old(i, j)) * W_new(i, j) * a;
        r.ee += w_new(i, j) * W_new(i, j) * a;
        r.cells += 1;
      }
    std::swap(w_old, w_new);
    std::swap(W_old, W_new);
  };

  std::ofstream f(out);
  f << "step,t,dt,ring_lo,ring_hi,cells,W_s_step,W_s,Pi,W_v,W_i,W_adv,W_proj,dE_xi,dE_band,dE_blend,"
       "ee_ring,ke,ee\n";
  f.precision(10);
  sample(w_old, W_old);  // the initial state (unstrained: W = 0)
  const double ke0 = sim.kinetic_energy();
  for (long n = 0; n < steps; ++n) {
    un = sim.u();
    vn = sim.v();
    sim.apply_velocity_bc(un, vn, sim.time());
    const double dt = sim.step();
    un1 = sim.u();
    vn1 = sim.v();
    sim.apply_velocity_bc(un1, vn1, sim.time());
    book(dt);
    const double ke = sim.kinetic_energy(), ee = sim.elastic_energy();
    for (int r = 0; r < kRings; ++r) {
      const Terms& t = rings[std::size_t(r)];
      f << sim.steps() << ',' << sim.time() << ',' << dt << ',' << kEdges[std::size_t(r)] << ','
        << kEdges[std::size_t(r) + 1] << ',' << t.cells << ',' << t.ws_step << ',' << t.ws << ','
        << t.pi << ',' << t.wv << ',' << t.wi << ',' << t.wadv << ',' << t.wproj << ',' << t.dxi
        << ',' << t.dband << ',' << t.dblend << ',' << t.ee << ',' << ke << ',' << ee << '\n';
    }
    if (!std::isfinite(ke) || ke > 1e6 * (ke0 + 1e-300)) {
      std::cerr << "stopped: kinetic energy " << ke << " at step " << sim.steps() << "\n";
      break;
    }
  }
  return 0;
}
