#include "solver/components/solids.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "kernels/loop.hpp"
#include "kernels/solid_stress.hpp"
#include "solver/io/checkpoint_io.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/io/timers.hpp"
#include "solver/model/boundary.hpp"
#include "solver/model/simulation.hpp"

namespace refmap {

namespace {

// Work of a solid's phase for parallel_items, in cells of a simple row loop (the unit of
// kMinParallelCells): window cells times the cost of a window cell relative to an axpy
// cell. Measured on two_solids_tgv, 1 thread: advection + extrapolation + level set
// ~200 ns per window cell and step, the window stress ~15 ns, the diagnostics a few ns;
// an axpy cell ~0.5-1 ns.
constexpr long kStepCellCost = 64, kStressCellCost = 16, kDiagnosticsCellCost = 4;

long window_work(const Solid& s, long cell_cost) { return long(s.ni()) * s.nj() * cell_cost; }

}  // namespace

Solids::Solids(const Config& cfg, const Sides& sides) : grid_(cfg.grid), rho_f_(cfg.rho_f) {
  bool elastic = false;
  for (const SolidSpec& sp : cfg.solids) {
    solids_.push_back(std::make_unique<Solid>(sp, cfg.solid_opt, cfg.grid, sides, cfg.rho_f));
    elastic = elastic || sp.mu_s > 0.0;
  }
  if (elastic)
    for (Field* f : {&sxx_, &sxy_, &syy_}) f->resize(cfg.grid.nx, cfg.grid.ny, Grid::ng);
}

void Solids::register_state(StateRegistry& reg) {
  // a count record first, so that a checkpoint of a scene with other solids fails on it
  reg.add_record(
      "sim.solids", [this](CheckpointWriter& w) { w.put_i64("sim.solids", std::int64_t(solids_.size())); },
      [this](CheckpointReader& r) {
        if (r.get_i64("sim.solids") != std::int64_t(solids_.size()))
          throw CheckpointError("checkpoint " + r.path() + ": its scene has another number of solids");
      });
  for (std::size_t k = 0; k < solids_.size(); ++k) {
    const std::string tag = "solid" + std::to_string(k);
    Solid& s = *solids_[k];
    reg.add_record(
        tag, [&s, tag](CheckpointWriter& w) { s.save_state(w, tag); },
        [&s, tag](CheckpointReader& r) { s.load_state(r, tag); });
  }
  // the contact tracker's records are the contact component's
  // (solver/components/contact_component.hpp), the rigid bodies' ("bodies") theirs
  // (solver/components/rigid_bodies.hpp)
}

bool Solids::viscous() const {
  for (const auto& s : solids_)
    if (s->spec().viscosity > 0.0) return true;
  return false;
}

bool Solids::density_contrast() const {
  for (const auto& s : solids_)
    if (s->spec().density != rho_f_) return true;
  return false;
}

double Solids::gravity_acceleration(double gmag) const {
  double accel = gmag;
  for (const auto& s : solids_)
    if (!s->spec().rigid())  // a rigid body's motion is imposed
      accel = std::max(accel, gmag * std::abs(s->spec().density - rho_f_) / s->spec().density);
  return accel;
}

double Solids::explicit_dt() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& s : solids_) dt = std::min(dt, s->min_dt());
  return dt;
}

void Solids::values(const Simulation& sim, std::vector<double>& out) const {
  out.push_back(elastic_energy_);
  out.push_back(sim.kinetic_energy() + elastic_energy_);
}

void Solids::solid_values(const Simulation& sim, int k, std::vector<double>& out) const {
  const SolidDiagnostics& d = sim.solid_diagnostics()[std::size_t(k)];
  for (double x : {d.area, d.cx, d.cy, d.u, d.v, d.sigma_max}) out.push_back(x);
}

void Solids::frame_fields(FrameFields& out) const {
  const Grid& g = grid_;
  Field& phi = out.owned.emplace_back(g.nx, g.ny, Grid::ng, 1e30);
  Field& xix = out.owned.emplace_back(g.nx, g.ny, Grid::ng, 0.0);
  Field& xiy = out.owned.emplace_back(g.nx, g.ny, Grid::ng, 0.0);
  Field& normal = out.owned.emplace_back(g.nx, g.ny, Grid::ng, 0.0);
  for (const auto& s : solids_) {
    for (int j = 0; j < s->nj(); ++j)
      for (int i = 0; i < s->ni(); ++i) {
        const int gi = s->wrap().i(s->i0() + i), gj = s->wrap().j(s->j0() + j);
        const double ph = s->phi()(i, j);
        if (ph < phi(gi, gj)) {
          phi(gi, gj) = ph;
          if (ph < s->band()) {
            xix(gi, gj) = s->xi_x()(i, j);
            xiy(gi, gj) = s->xi_y()(i, j);
          }
        }
      }
  }
  double cap = 0.0;
  for (const auto& s : solids_) cap = std::max(cap, s->band());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      phi(i, j) = std::min(phi(i, j), cap);
      if (elastic()) normal(i, j) = 0.5 * (sxx_(i, j) + syy_(i, j));
    }
  out.scalars.emplace_back("phi", &phi);
  out.scalars.emplace_back("normal_stress", &normal);
  out.vectors.push_back({"xi", &xix, &xiy});
  if (elastic())
    for (const auto& [name, f] : {std::pair<const char*, const Field*>{"stress_xx", &sxx_}, {"stress_xy", &sxy_},
                                  {"stress_yy", &syy_}})
      out.scalars.emplace_back(name, f);
}

void Solids::impose_initial_velocity(Field& u, Field& v) const {
  for (const auto& s : solids_) s->impose_initial_velocity(u, v);
}

void Solids::move(const Carrier& by, double dt, const std::vector<std::unique_ptr<Component>>& components,
                  PhaseTimers& timers) {
  // Algorithm 1, steps 1-2 for every solid: each solid's work touches only its own window
  // and workspaces, so the solids run concurrently, one solid per thread
  // (kernels/loop.hpp, parallel_items); a single or dominant solid threads its row loops.
  using clock = std::chrono::steady_clock;
  const int n = int(solids_.size());
  // per solid: [xi advection without its stage re-extrapolations, extrapolation, level set]
  std::vector<std::array<double, 3>> secs(std::size_t(n), std::array<double, 3>{});
  const auto w0 = clock::now();
  // (the rigid bodies moved to their poses of t + dt at StepPoint::Begin)
  parallel_items(n, [&](int k) { return window_work(*solids_[std::size_t(k)], kStepCellCost); }, [&](int k) {
    Solid& s = *solids_[std::size_t(k)];
    // the RK-4 stages re-extrapolate the band (Solid::advect): that time is booked under
    // "extrapolation", the rest under "xi advection"
    const double ext0 = s.extrapolation_counters().seconds;
    const auto t0 = clock::now();
    // a rigid body's reference map is set from its pose, not advected (solver/components/rigid_bodies.hpp)
    bool rigid = false;
    for (const auto& c : components) rigid = rigid || c->moves_solid(k);
    if (!rigid) s.advect(by.uf, by.vf, by.u, by.v, dt);
    const double t_adv = std::chrono::duration<double>(clock::now() - t0).count();
    if (!rigid) s.extrapolate();
    for (const auto& c : components) c->place_solid(k, solids_);  // the rigid bodies' maps
    const double t_ext = s.extrapolation_counters().seconds - ext0;
    const double t_stage_ext = std::min(t_ext, t_adv);
    const auto t1 = clock::now();
    s.rebuild_level_set();
    secs[std::size_t(k)] = {t_adv - t_stage_ext, t_ext,
                            std::chrono::duration<double>(clock::now() - t1).count()};
  });
  // PhaseTimers is not thread-safe: book here, the wall time of the region split in the
  // proportions of the solids' (thread) times, one call per solid as before
  const double wall = std::chrono::duration<double>(clock::now() - w0).count();
  std::array<double, 3> sum{};
  for (const auto& a : secs)
    for (int c = 0; c < 3; ++c) sum[std::size_t(c)] += a[std::size_t(c)];
  const double all = sum[0] + sum[1] + sum[2];
  const double scale = all > 0.0 ? wall / all : 0.0;
  timers.add("xi advection", sum[0] * scale, n);
  timers.add("extrapolation", sum[1] * scale, n);
  timers.add("level set", sum[2] * scale, n);
}

void Solids::blend(Field& rho, Field& mu, double rho_f, double mu_f) const {
  // eq. (3.6): q = q_f + sum_i (1 - H_i) (q_s,i - q_f), in solid order
  for (const auto& s : solids_) {
    s->add_blend(rho, s->spec().density, rho_f);
    s->add_blend(mu, s->spec().viscosity, mu_f);
  }
}

void Solids::stress_force(Field& fx, Field& fy, const Config& cfg) {
  const Grid& g = cfg.grid;
  elastic_energy_ = 0.0;
  if (!elastic()) return;
  // the stress on each window, solids concurrently; then the blend into the global tensor
  // (or force), serially in solid order: windows overlap, and the sums must have the same
  // bits for any number of threads
  parallel_items(int(solids_.size()),
                 [&](int k) { return window_work(*solids_[std::size_t(k)], kStressCellCost); },
                 [&](int k) { solids_[std::size_t(k)]->compute_stress(); });
  for (Field* f : {&sxx_, &sxy_, &syy_}) parallel_fill(f->raw(), f->raw_size(), 0.0);
  for (const auto& s : solids_) elastic_energy_ += s->blend_stress_into(sxx_, sxy_, syy_, fx, fy);
  if (cfg.solid_opt.conservative && cfg.solid_opt.stress_form == StressForm::Cell) {
    for (Field* f : {&sxx_, &sxy_, &syy_}) fill_scalar_ghosts(*f, cfg.bc);
    add_stress_divergence(sxx_.view(), sxy_.view(), syy_.view(), fx.view(), fy.view(), g.nx, g.ny, g.dx);
  }
}

const std::vector<SolidDiagnostics>& Solids::diagnostics(const Field& u, const Field& v, long step) const {
  if (diag_step_ != step || diag_.size() != solids_.size()) {
    diag_.resize(solids_.size());
    // each solid's sums over its own window into its own entry: solids concurrently
    parallel_items(int(solids_.size()),
                   [&](int k) { return window_work(*solids_[std::size_t(k)], kDiagnosticsCellCost); },
                   [&](int k) { diag_[std::size_t(k)] = solids_[std::size_t(k)]->diagnostics(u, v); });
    diag_step_ = step;
  }
  return diag_;
}

}  // namespace refmap
