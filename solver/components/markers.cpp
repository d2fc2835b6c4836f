#include "solver/components/markers.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "solver/io/checkpoint_io.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/model/simulation.hpp"
#include "solver/io/state_registry.hpp"
#include "solver/io/toml_reader.hpp"

namespace refmap {

std::vector<std::array<double, 2>> marker_reference_points(const SolidMarkers& m, const Shape& shape) {
  std::vector<std::array<double, 2>> pts = m.points;
  const int n = m.boundary;
  if (n <= 0) return pts;
  const BoundingBox bb = shape.bbox();
  const double cx = 0.5 * (bb.xmin + bb.xmax), cy = 0.5 * (bb.ymin + bb.ymax);
  if (!(shape.phi0(cx, cy) < 0.0))
    throw std::invalid_argument("boundary_markers: the centre of the shape's bounding box is not inside it");
  const double rmax = std::hypot(bb.xmax - bb.xmin, bb.ymax - bb.ymin);  // outside along every ray
  const double pi = std::acos(-1.0);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * pi * k / n, ca = std::cos(a), sa = std::sin(a);
    double lo = 0.0, hi = rmax;  // phi0 < 0 at lo, >= 0 at hi
    for (int it = 0; it < 200 && hi - lo > 1e-15 * rmax; ++it) {
      const double m = 0.5 * (lo + hi);
      (shape.phi0(cx + m * ca, cy + m * sa) < 0.0 ? lo : hi) = m;
    }
    const double r = 0.5 * (lo + hi);
    pts.push_back({cx + r * ca, cy + r * sa});
  }
  return pts;
}

bool solve_material_point(const Solid& s, const Grid& g, double X, double Y, double& x, double& y) {
  const Field &fx = s.xi_x(), &fy = s.xi_y();
  const int ng = fx.ng();
  const double dx = g.dx;
  for (int it = 0; it < 50; ++it) {
    // window cell coordinates: centre of window cell i at x0 + (i0 + i + 1/2) dx
    const double sx = (x - g.x0) / dx - 0.5 - s.i0(), sy = (y - g.y0) / dx - 0.5 - s.j0();
    const int i = std::clamp(int(std::floor(sx)), -ng, s.ni() + ng - 2);
    const int j = std::clamp(int(std::floor(sy)), -ng, s.nj() + ng - 2);
    const double a = sx - i, b = sy - j;
    auto interp = [&](const Field& f, double& val, double& dfdx, double& dfdy) {
      const double f00 = f(i, j), f10 = f(i + 1, j), f01 = f(i, j + 1), f11 = f(i + 1, j + 1);
      val = (1 - b) * ((1 - a) * f00 + a * f10) + b * ((1 - a) * f01 + a * f11);
      dfdx = ((1 - b) * (f10 - f00) + b * (f11 - f01)) / dx;
      dfdy = ((1 - a) * (f01 - f00) + a * (f11 - f10)) / dx;
    };
    double ex, exx, exy, ey, eyx, eyy;
    interp(fx, ex, exx, exy);
    interp(fy, ey, eyx, eyy);
    const double rx = ex - X, ry = ey - Y;
    const double det = exx * eyy - exy * eyx;
    if (!(std::abs(det) > 0.0)) return false;
    // Newton: grad xi . delta = -(xi - X)
    const double ddx = -(eyy * rx - exy * ry) / det, ddy = -(-eyx * rx + exx * ry) / det;
    x += ddx;
    y += ddy;
    if (std::hypot(ddx, ddy) < 1e-10 * dx) return true;
  }
  return false;
}

Markers::Markers(const std::vector<std::unique_ptr<Solid>>& solids, const Grid& g, const MarkerOptions& opt) : g_(g) {
  for (std::size_t s = 0; s < solids.size() && s < opt.per_solid.size(); ++s) {
    const auto ref = marker_reference_points(opt.per_solid[s], solids[s]->shape());
    for (std::size_t k = 0; k < ref.size(); ++k) {
      // xi = X at t = 0 (eq. 3.2's initial condition), so x = X
      pts_.push_back({int(s), int(k), ref[k][0], ref[k][1], ref[k][0], ref[k][1]});
    }
  }
  count_ = int(pts_.size());
}

void Markers::update(const std::vector<std::unique_ptr<Solid>>& solids) {
  for (Point& p : pts_) {
    double x = p.x, y = p.y;
    // a marker that does not converge (a solid torn apart) keeps its last iterate
    solve_material_point(*solids[p.solid], g_, p.X, p.Y, x, y);
    if (std::isfinite(x) && std::isfinite(y)) {
      p.x = x;
      p.y = y;
    }
  }
}

void Markers::save_state(CheckpointWriter& w) const {
  std::vector<double> xy;
  for (const Point& p : pts_) {
    xy.push_back(p.x);
    xy.push_back(p.y);
  }
  w.put_f64s("markers.xy", xy);
}

void Markers::load_state(CheckpointReader& r) {
  const std::vector<double> xy = r.get_f64s("markers.xy");
  if (xy.size() != 2 * pts_.size())
    throw CheckpointError("checkpoint " + r.path() + ": its scene has another number of markers");
  for (std::size_t k = 0; k < pts_.size(); ++k) {
    pts_[k].x = xy[2 * k];
    pts_[k].y = xy[2 * k + 1];
  }
}

void Markers::register_state(StateRegistry& reg) {
  reg.add_record(
      "markers", [this](CheckpointWriter& w) { save_state(w); }, [this](CheckpointReader& r) { load_state(r); });
}

void Markers::at(StepPoint p, Simulation& sim, double) {
  if (p == StepPoint::End) update(sim.solids());
}

namespace {

constexpr const char* kMarkersFile = "markers.csv";

}  // namespace

std::vector<ComponentFile> Markers::files() const {
  return {{kMarkersFile, {"frame", "t", "solid", "id", "x", "y"},
           [this](const Simulation& sim, int frame, std::vector<std::vector<double>>& rows) {
             for (const Point& p : pts_) rows.push_back({double(frame), sim.time(), double(p.solid), double(p.id), p.x, p.y});
           }}};
}

namespace {

using namespace toml_text;

/// The `markers` and `boundary_markers` of every [[solid]] (null: no solid has any). Each
/// point must lie in its solid's reference configuration, and the boundary points need the
/// centre of the shape's bounding box inside the shape (the rays start there).
std::shared_ptr<const ComponentOptions> parse_markers(const TomlTable& top, const Config& cfg) {
  if (cfg.solids.empty()) return nullptr;
  const toml::array* arr = top.node("solid")->as_array();  // the core checked it is one
  auto opt = std::make_shared<MarkerOptions>();
  bool any = false;
  for (std::size_t i = 0; i < cfg.solids.size(); ++i) {
    const TomlTable s = top.sub(*arr->get(i)->as_table(), "solid[" + std::to_string(i) + "]", "solid");
    SolidMarkers m;
    m.points = s.points("markers");
    m.boundary = int(s.integer("boundary_markers"));
    if (!m.points.empty() || m.boundary > 0) {
      const std::unique_ptr<Shape> shape = make_shape(cfg.solids[i].shape);  // the core built it once already
      const double dx = cfg.grid.dx;
      for (const auto& p : m.points)
        s.require(shape->phi0(p[0], p[1]) <= 1e-6 * dx, "markers",
                  "point [" + fmt_num(p[0]) + ", " + fmt_num(p[1]) + "] is not in the solid's reference configuration");
      if (m.boundary > 0) {
        const BoundingBox mb = shape->bbox();
        s.require(shape->phi0(0.5 * (mb.xmin + mb.xmax), 0.5 * (mb.ymin + mb.ymax)) < 0.0, "boundary_markers",
                  "the centre of the shape's bounding box lies outside the shape: give the points with `markers`");
      }
      any = true;
    }
    opt->per_solid.push_back(std::move(m));
  }
  if (!any) return nullptr;
  return opt;
}

std::unique_ptr<Component> make_markers(const ComponentOptions& o, Simulation& sim) {
  return std::make_unique<Markers>(sim.solids(), sim.grid(), static_cast<const MarkerOptions&>(o));
}

}  // namespace

ComponentKind markers_kind() {
  using namespace keys;
  ComponentKind k;
  k.name = "markers";
  k.keys = {
      shown_default(key("solid", "markers", KeyType::Points, {}, text_range("points of the reference configuration"),
                        "material points (X, Y) of the reference configuration, followed through xi and written to "
                        "`markers.csv` (docs/tracers.md)"),
                    "none"),
      integer("solid", "boundary_markers", SolidMarkers{}.boundary, ge(0),
              "also this many material points on the reference boundary, at equal angles about the centre of "
              "the shape's bounding box (which must lie inside the shape)"),
  };
  k.after = "solid.clamp";
  k.parse = parse_markers;
  k.files = {kMarkersFile};
  k.make = make_markers;
  return k;
}

}  // namespace refmap
