#include "solver/components/tracers.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "kernels/rk4.hpp"
#include "solver/model/boundary.hpp"
#include "solver/io/checkpoint_io.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/probes.hpp"
#include "solver/model/simulation.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/io/toml_reader.hpp"

namespace refmap {

std::vector<std::array<double, 2>> tracer_seeds(const std::vector<TracerSeed>& seeds) {
  std::vector<std::array<double, 2>> pts;
  auto lerp = [](double a, double b, int k, int n) { return n == 1 ? 0.5 * (a + b) : k == n - 1 ? b : a + (b - a) * k / double(n - 1); };
  for (const TracerSeed& s : seeds) {
    if (!s.box) {
      for (int k = 0; k < s.n; ++k) pts.push_back({lerp(s.x0, s.x1, k, s.n), lerp(s.y0, s.y1, k, s.n)});
    } else {
      for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i) pts.push_back({lerp(s.x0, s.x1, i, s.nx), lerp(s.y0, s.y1, j, s.ny)});
    }
  }
  return pts;
}

Tracers::Tracers(const Grid& g, const std::vector<std::array<double, 2>>& points, bool periodic_x, bool periodic_y)
    : g_(g), px_(periodic_x), py_(periodic_y), n_(int(points.size())) {
  // one row of n points, no ghosts: the RK-4 kernel loops over an n x 1 "interior"
  for (Field* f : {&x_, &y_, &sx_, &sy_, &accx_, &accy_, &kx_, &ky_}) f->resize(n_, 1, 0);
  for (int k = 0; k < n_; ++k) {
    x_(k, 0) = points[k][0];
    y_(k, 0) = points[k][1];
  }
}

double Tracers::wrap_x(double x) const {
  const double a = g_.x0, L = g_.lx();
  if (px_) return x - L * std::floor((x - a) / L);
  return std::fmin(std::fmax(x, a), a + L);
}

double Tracers::wrap_y(double y) const {
  const double a = g_.y0, L = g_.ly();
  if (py_) return y - L * std::floor((y - a) / L);
  return std::fmin(std::fmax(y, a), a + L);
}

void Tracers::begin_step(const Field& u, const Field& v) {
  u0_ = u;
  v0_ = v;
}

void Tracers::advance(const Field& u1, const Field& v1, double dt) {
  Rk4Fields f{x_.cview(), y_.cview(), sx_.view(), sy_.view(), accx_.view(), accy_.view(),
              kx_.view(), ky_.view(), x_.view(), y_.view(), n_, 1};
  rk4_step(f, dt, [&](int stage, View kx, View ky) {
    // weight of the end-of-step velocity at this stage's time t + c dt, c = 0, 1/2, 1/2, 1
    const double w = stage == 1 ? 0.0 : stage == 4 ? 1.0 : 0.5;
    const Field& px = stage == 1 ? x_ : sx_;
    const Field& py = stage == 1 ? y_ : sy_;
    for (int k = 0; k < n_; ++k) {
      const double x = wrap_x(px(k, 0)), y = wrap_y(py(k, 0));
      const double ua = sample_bilinear(g_, u0_, x, y), va = sample_bilinear(g_, v0_, x, y);
      const double ub = w == 0.0 ? ua : sample_bilinear(g_, u1, x, y);
      const double vb = w == 0.0 ? va : sample_bilinear(g_, v1, x, y);
      kx(k, 0) = ua + w * (ub - ua);
      ky(k, 0) = va + w * (vb - va);
    }
  });
  for (int k = 0; k < n_; ++k) {
    x_(k, 0) = wrap_x(x_(k, 0));
    y_(k, 0) = wrap_y(y_(k, 0));
  }
}

void Tracers::save_state(CheckpointWriter& w) const {
  w.put_field("tracers.x", x_);
  w.put_field("tracers.y", y_);
}

void Tracers::load_state(CheckpointReader& r) {
  r.get_field("tracers.x", x_);
  r.get_field("tracers.y", y_);
  if (x_.nx() != n_ || y_.nx() != n_)
    throw CheckpointError("checkpoint " + r.path() + ": its scene has another number of tracers");
}

void Tracers::register_state(StateRegistry& reg) {
  reg.add_record(
      "tracers", [this](CheckpointWriter& w) { save_state(w); }, [this](CheckpointReader& r) { load_state(r); });
}

void Tracers::at(StepPoint p, Simulation& sim, double dt) {
  // the cell velocity with its ghosts filled at the time of each end of the step
  if (p == StepPoint::Begin) {
    u0_ = sim.u();
    v0_ = sim.v();
    sim.apply_velocity_bc(u0_, v0_, sim.time());
  } else if (p == StepPoint::End) {
    u1_ = sim.u();
    v1_ = sim.v();
    sim.apply_velocity_bc(u1_, v1_, sim.time());
    advance(u1_, v1_, dt);
  }
}

namespace {

constexpr const char* kTracersFile = "tracers.csv";

}  // namespace

std::vector<ComponentFile> Tracers::files() const {
  return {{kTracersFile, {"frame", "t", "id", "x", "y"},
           [this](const Simulation& sim, int frame, std::vector<std::vector<double>>& rows) {
             for (int k = 0; k < n_; ++k) rows.push_back({double(frame), sim.time(), double(k), x(k), y(k)});
           }}};
}

namespace {

using namespace toml_text;

/// The [[tracers]] tables of the scene into their seeds (null: none).
std::shared_ptr<const ComponentOptions> parse_tracers(const TomlTable& top, const Config& cfg) {
  const TomlContext& ctx = top.context();
  const toml::node* n = top.node("tracers");
  if (!n) return nullptr;
  auto opt = std::make_shared<TracerOptions>();
  const toml::array* arr = n->as_array();
  if (!arr) top.fail("tracers", "expected an array of tables ([[tracers]] sections), got " + describe(*n));
  const Grid& g = cfg.grid;
  const double tol = 1e-12 * std::max(g.lx(), g.ly());
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string prefix = "tracers[" + std::to_string(i) + "]";
    const toml::table* t = arr->get(i)->as_table();
    if (!t) ctx.fail(prefix, arr->get(i), "expected a table ([[tracers]] section), got " + describe(*arr->get(i)));
    const TomlTable p = top.sub(*t, prefix, "tracers");
    p.allow();
    TracerSeed sd;
    sd.box = p.has("box");
    const char* key = sd.box ? "box" : "line";
    if (sd.box && p.has("line")) p.fail("line", "give either `line` (with `n`) or `box` (with `nx`, `ny`), not both");
    if (!sd.box && !p.has("line")) ctx.fail(prefix, t, "needs `line` (with `n`) or `box` (with `nx`, `ny`)");
    if (const char* other = sd.box ? "n" : (p.has("nx") ? "nx" : p.has("ny") ? "ny" : nullptr); other && p.has(other))
      p.fail(other, std::string("not used with `") + key + "`");
    const auto pts = p.points(key);
    p.require(pts.size() == 2, key, "expected two points [[x0, y0], [x1, y1]], got " + std::to_string(pts.size()));
    for (const auto& xy : pts)
      p.require(xy[0] >= g.x0 - tol && xy[0] <= g.x0 + g.lx() + tol && xy[1] >= g.y0 - tol && xy[1] <= g.y0 + g.ly() + tol,
                key, "point [" + fmt_num(xy[0]) + ", " + fmt_num(xy[1]) + "] is outside the domain [" + fmt_num(g.x0) +
                         ", " + fmt_num(g.x0 + g.lx()) + "] x [" + fmt_num(g.y0) + ", " + fmt_num(g.y0 + g.ly()) + "]");
    sd.x0 = std::clamp(pts[0][0], g.x0, g.x0 + g.lx());
    sd.y0 = std::clamp(pts[0][1], g.y0, g.y0 + g.ly());
    sd.x1 = std::clamp(pts[1][0], g.x0, g.x0 + g.lx());
    sd.y1 = std::clamp(pts[1][1], g.y0, g.y0 + g.ly());
    if (sd.box) {
      sd.nx = int(p.integer("nx"));
      sd.ny = int(p.integer("ny"));
    } else {
      sd.n = int(p.integer("n"));
    }
    opt->seeds.push_back(sd);
  }
  if (opt->seeds.empty()) return nullptr;
  return opt;
}


std::unique_ptr<Component> make_tracers(const ComponentOptions& o, Simulation& sim) {
  const Sides& sides = sim.sides();  // the Simulation's, built once
  return std::make_unique<Tracers>(sim.grid(), tracer_seeds(static_cast<const TracerOptions&>(o).seeds),
                                   sides.periodic_x(), sides.periodic_y());
}

}  // namespace

ComponentKind tracers_kind() {
  using namespace keys;
  using KT = KeyType;
  ComponentKind k;
  k.name = "tracers";
  k.tables = {{{"tracers", "`[[tracers]]`", false, true, false,
                "Passive fluid tracers, written to `tracers.csv` at every VTK frame (docs/tracers.md). Each table "
                "seeds a `line` (with `n`) or a `box` (with `nx`, `ny`)."},
               "probe"}};
  k.keys = {
      shown_default(key("tracers", "line", KT::Points, {}, text_range("two points inside the domain"),
                        "seed `n` tracers on the segment [[x0, y0], [x1, y1]], ends included (give `line` or `box`)"),
                    "—"),
      shown_default(integer("tracers", "n", {}, in(1, false, 10000000, false), "number of tracers on `line`"), "—"),
      shown_default(key("tracers", "box", KT::Points, {}, text_range("two corners inside the domain"),
                        "seed `nx` x `ny` tracers on the lattice of the box with corners [[x0, y0], [x1, y1]], corners "
                        "included"),
                    "—"),
      shown_default(integer("tracers", "nx", {}, in(1, false, 100000, false), "tracers along x in `box`"), "—"),
      shown_default(integer("tracers", "ny", {}, in(1, false, 100000, false), "tracers along y in `box`"), "—"),
  };
  k.files = {kTracersFile};
  k.parse = parse_tracers;
  k.make = make_tracers;
  return k;
}

}  // namespace refmap
