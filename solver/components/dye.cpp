#include "solver/components/dye.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "kernels/advection.hpp"
#include "kernels/loop.hpp"
#include "solver/model/boundary.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/simulation.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/io/toml_reader.hpp"

namespace refmap {

Dye::Dye(const Simulation& sim, const Expression& initial) : g_(sim.grid()), bc_(sim.config().bc) {
  const int nx = g_.nx, ny = g_.ny;
  for (Field* f : {&c_, &c1_, &r_, &scratch_}) f->resize(nx, ny, Grid::ng);
  const double t = sim.time();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) c_(i, j) = initial.eval(g_.xc(i), g_.yc(j), t);
}

void Dye::rate(Field& q, const Field& uf, const Field& vf, Field& r) {
  // an even mirror at every non-periodic side: no flux through a wall (u_f = 0 there),
  // zero gradient through an inflow or outflow side
  fill_scalar_ghosts(q, bc_);
  // the momentum's kernel advects two fields; the second copy goes to scratch_
  advect_rhs2(q.cview(), q.cview(), uf.cview(), vf.cview(), r.view(), scratch_.view(), g_.nx, g_.ny, g_.dx,
              FluxScheme::Superbee);
}

void Dye::advance(const Field& uf0, const Field& vf0, const Field& uf1, const Field& vf1, double dt) {
  const int nx = g_.nx, ny = g_.ny;
  ufm_ = uf0;
  vfm_ = vf0;
  for (auto [m, b] : {std::pair<Field*, const Field*>{&ufm_, &uf1}, {&vfm_, &vf1}}) {
    double* a = m->raw();
    const double* e = b->raw();
    for (std::size_t k = 0; k < m->raw_size(); ++k) a[k] = 0.5 * (a[k] + e[k]);
  }
  // Shu & Osher (1988), eq. 2.18:
  //   c1 = c + dt L(c; t),  c2 = 3/4 c + 1/4 (c1 + dt L(c1; t + dt)),
  //   c^{n+1} = 1/3 c + 2/3 (c2 + dt L(c2; t + dt/2))
  rate(c_, uf0, vf0, r_);
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) c1_(i, j) = c_(i, j) + dt * r_(i, j);
  });
  rate(c1_, uf1, vf1, r_);
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) c1_(i, j) = 0.75 * c_(i, j) + 0.25 * (c1_(i, j) + dt * r_(i, j));
  });
  rate(c1_, ufm_, vfm_, r_);
  parallel_rows(0, ny, nx, [&](int j) {
    for (int i = 0; i < nx; ++i) c_(i, j) = c_(i, j) / 3.0 + 2.0 / 3.0 * (c1_(i, j) + dt * r_(i, j));
  });
  fill_scalar_ghosts(c_, bc_);
}

void Dye::register_state(StateRegistry& reg) { reg.add_field("dye.c", c_); }

double Dye::max_dt(const Simulation& sim) const {
  const Field &uf = sim.uf(), &vf = sim.vf();
  double s = 0.0;
  for (int j = 0; j < g_.ny; ++j)
    for (int i = 0; i < g_.nx; ++i)
      s = std::max(s, std::max(std::abs(uf(i, j)), std::abs(uf(i + 1, j))) +
                          std::max(std::abs(vf(i, j)), std::abs(vf(i, j + 1))));
  return s > 0.0 ? 0.5 * g_.dx / s : std::numeric_limits<double>::infinity();
}

void Dye::at(StepPoint p, Simulation& sim, double dt) {
  if (p == StepPoint::Begin) {
    uf0_ = sim.uf();
    vf0_ = sim.vf();
  } else if (p == StepPoint::End) {
    advance(uf0_, vf0_, sim.uf(), sim.vf(), dt);
  }
}

void Dye::values(const Simulation&, std::vector<double>& out) const {
  double total = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int j = 0; j < g_.ny; ++j)
    for (int i = 0; i < g_.nx; ++i) {
      total += c_(i, j);
      lo = std::min(lo, c_(i, j));
      hi = std::max(hi, c_(i, j));
    }
  out.push_back(total * g_.dx * g_.dx);
  out.push_back(lo);
  out.push_back(hi);
}

namespace {

/// [dye]: its initial concentration (null: no [dye] table).
std::shared_ptr<const ComponentOptions> parse_dye(const TomlTable& top, const Config& cfg) {
  const toml::table* t = top.table("dye", false);
  if (!t) return nullptr;
  const TomlTable d = top.sub(*t, "dye", "dye");
  d.allow();
  auto opt = std::make_shared<DyeOptions>();
  opt->initial = Expression(expression_text(d, "initial"));  // expression_text checked it parses
  const Grid& g = cfg.grid;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double v = opt->initial.eval(g.xc(i), g.yc(j), cfg.t_start);
      if (!std::isfinite(v))
        d.fail("initial", "evaluates to " + toml_text::fmt_num(v) + " at x = " + toml_text::fmt_num(g.xc(i)) +
                              ", y = " + toml_text::fmt_num(g.yc(j)) + " (it must be finite over the grid)");
    }
  return opt;
}

std::unique_ptr<Component> make_dye(const ComponentOptions& o, Simulation& sim) {
  return std::make_unique<Dye>(sim, static_cast<const DyeOptions&>(o).initial);
}

}  // namespace

ComponentKind dye_kind() {
  ComponentKind k;
  k.name = "dye";
  k.tables = {{{"dye", "`[dye]`", false, false, false,
                "A passive dye carried by the flow, dc/dt + u . grad c = 0 (Superbee fluxes, SSP-RK3 in time; "
                "docs/components.md): the field `dye` of the VTK frames, its total and bounds in `diagnostics.csv`."},
               "tracers"}};
  k.keys = {keys::key("dye", "initial", KeyType::Expression, {}, {},
                      "initial concentration c(x, y) at the start time (see *Expressions*)")};
  k.parse = parse_dye;
  k.make = make_dye;
  return k;
}

}  // namespace refmap
