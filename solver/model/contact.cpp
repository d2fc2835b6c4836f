#include "solver/model/contact.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/loop.hpp"
#include "solver/model/boundary.hpp"

namespace refmap {

namespace {

/// Inward unit normal of a side and the distance of cell centre (i, j) to it.
void side_geometry(const Grid& g, int side, int i, int j, double& dist, double& nx, double& ny) {
  switch (side) {
    case Left: dist = g.xc(i) - g.x0; nx = 1; ny = 0; break;
    case Right: dist = g.x0 + g.lx() - g.xc(i); nx = -1; ny = 0; break;
    case Bottom: dist = g.yc(j) - g.y0; nx = 0; ny = 1; break;
    default: dist = g.y0 + g.ly() - g.yc(j); nx = 0; ny = -1; break;
  }
}

// Work of a contact task or gap sweep for parallel_items per visited cell, in cells of a
// simple row loop (kernels/loop.hpp): a few phi lookups, a ramp and sometimes a pressure.
constexpr long kContactCellCost = 16;

}  // namespace

const ContactOptions& contact_options(const Config& cfg) {
  static const ContactOptions defaults;
  const ContactOptions* o = cfg.component_options<ContactOptions>("contact");
  return o ? *o : defaults;
}

Contact::Contact(const Config& cfg, const ContactOptions& o, double velocity_scale) : g_(cfg.grid) {
  sides_ = face_sides(cfg.bc);
  for (int s = 0; s < 4; ++s) {
    switch (sides_.kind[s]) {
      case FaceKind::Wall: wall_[s] = o.walls; break;
      // an open side repels nothing: a solid may be carried in or out through it
      case FaceKind::Inflow:
      case FaceKind::Outflow:
      case FaceKind::Periodic: wall_[s] = false; break;
    }
  }
  force_ = o.enabled && cfg.flow == FlowMode::Solve;
  d_ = o.range * g_.dx;
  cfl_ = o.cfl;
  h_ = 2.0 * g_.dx;
  double rho_max = cfg.rho_f;
  for (const SolidSpec& s : cfg.solids) rho_max = std::max(rho_max, s.density);
  // P = stiffness rho_max U^2 (contact.hpp). U given, or automatic: the scene's own velocity
  // scales (from Simulation) raised to the largest solid speed seen (see_speed). It used to
  // fall back to l_x / (t_end - t_start) when the scene had none, so dt depended on time.end
  auto_U_ = !(o.velocity_scale > 0.0);
  P_unit_ = o.stiffness * rho_max;
  U_ = auto_U_ ? std::max(velocity_scale, 0.0) : o.velocity_scale;
  P_ = P_unit_ * U_ * U_;
  // the gap written when there is nothing to measure: no other solid's band meets this
  // one's, there is no other solid, or every side is periodic / contact.walls = false
  // (docs/output.md)
  sentinel_ = std::hypot(g_.lx(), g_.ly());
  const size_t n = cfg.solids.size();
  gap_solid_.assign(n, sentinel_);
  gap_wall_.assign(n, sentinel_);
  wall_state_.assign(n, {});
  touching_.clear();
}

namespace {
/// A soft solid clamped to a rigid body and that body (solver/model/rigid_body.hpp): no contact.
bool clamped_pair(const Solid& a, int ia, const Solid& b, int ib) {
  return a.spec().clamp_index == ib || b.spec().clamp_index == ia;
}
}  // namespace

void Contact::see_speed(double speed) {
  if (!auto_U_ || !(speed > U_)) return;
  U_ = speed;
  P_ = P_unit_ * U_ * U_;
}

double Contact::min_dt(double rho_min) const {
  if (!force_ || P_ <= 0.0) return 1e300;
  const double omega2 = 2.0 * 3.0 * P_ / (d_ * rho_min * h_);
  return cfl_ / std::sqrt(omega2);
}

bool Contact::clear_of_contact(double speed, double dt) const {
  if (!observed_) return false;
  const double closing = speed * dt;
  for (size_t i = 0; i < gap_wall_.size(); ++i)
    if (!(gap_wall_[i] - d_ > closing + g_.dx && gap_solid_[i] - d_ > 2.0 * closing + g_.dx)) return false;
  return true;
}

double Contact::phi_at(const Solid& s, int gi, int gj) const {
  if (sides_.periodic_x()) gi = ((gi % g_.nx) + g_.nx) % g_.nx;
  if (sides_.periodic_y()) gj = ((gj % g_.ny) + g_.ny) % g_.ny;
  if (gi < 0 || gi >= g_.nx || gj < 0 || gj >= g_.ny) return s.band();
  return s.phi_global(gi, gj);
}

void Contact::find_pairs(const std::vector<std::unique_ptr<Solid>>& solids, int margin,
                         std::vector<std::pair<int, int>>& out) {
  const int n = int(solids.size());
  if (!broad_phase_) {  // every pair, as the loop before the broad phase (tests)
    out.clear();
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b) out.emplace_back(a, b);
    return;
  }
  window_boxes_.resize(std::size_t(n));
  for (int k = 0; k < n; ++k) {
    const Solid& s = *solids[std::size_t(k)];
    CellBox& b = window_boxes_[std::size_t(k)];
    b.lo[0] = s.i0() - margin; b.hi[0] = s.i0() + s.ni() + margin;
    b.lo[1] = s.j0() - margin; b.hi[1] = s.j0() + s.nj() + margin;
  }
  CellDomain dom;
  dom.n[0] = g_.nx; dom.n[1] = g_.ny;
  dom.periodic[0] = sides_.periodic_x(); dom.periodic[1] = sides_.periodic_y();
  finder_.find(window_boxes_, dom, out);
}

template <class Dist>
void Contact::fill_layer(const Solid& a, Dist&& dist, const std::array<int, 4>& box, Layer& out) const {
  out.x.clear();
  out.y.clear();
  out.energy.clear();
  const double P = P_, d = d_, h = h_, inv_dx = 1.0 / g_.dx;
  const int nx = g_.nx, ny = g_.ny;
  auto pressure = [&](double s) { return s < d ? P * std::pow(1.0 - s / d, 3) : 0.0; };
  auto ramp = [&](double phi) {  // chi = S(-phi / h), S(x) = x^2 (3 - 2x) on [0, 1]
    const double x = std::clamp(-phi / h, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
  };
  // F_f = mean of p_c over the two cells of the face * (difference of chi_a across it) / dx.
  // Only the cells of the box are visited: the part of a's window where the obstacle's
  // pressure can be non-zero (plus the cells whose left/bottom face touches it), so the
  // work follows the contact zone.
  int gj_lo = std::max(a.j0() - 1, box[2]), gj_hi = std::min(a.j0() + a.nj(), box[3]);
  int gi_lo = std::max(a.i0() - 1, box[0]), gi_hi = std::min(a.i0() + a.ni(), box[1]);
  // a window across a periodic side (unwrapped indices, solver/model/periodic_window.hpp): the
  // box (the whole period there) is visited, phi_at finds the window's cells
  if (sides_.periodic_x() && (a.i0() < 0 || a.i0() + a.ni() > nx)) { gi_lo = box[0]; gi_hi = box[1]; }
  if (sides_.periodic_y() && (a.j0() < 0 || a.j0() + a.nj() > ny)) { gj_lo = box[2]; gj_hi = box[3]; }
  for (int gj = gj_lo; gj <= gj_hi; ++gj)
    for (int gi = gi_lo; gi <= gi_hi; ++gi) {
      if (gi < 0 || gi >= nx || gj < 0 || gj >= ny) continue;
      const double c0 = ramp(phi_at(a, gi, gj));
      // p_c at this cell, evaluated only where it is used (chi_a > 0 or a face with a
      // chi_a jump): the same values as evaluating it everywhere
      double p0 = -1.0;
      auto p_here = [&]() { return p0 >= 0.0 ? p0 : (p0 = pressure(dist(gi, gj))); };
      if (c0 > 0.0) {
        const double e = c0 * p_here() * g_.dx * g_.dx;  // U = sum chi p_c dx^2 (contact.hpp)
        if (e != 0.0) out.energy.push_back(e);
      }
      // the face on the left (x) and at the bottom (y) of cell (gi, gj)
      for (int dir = 0; dir < 2; ++dir) {
        const int ni = dir == 0 ? gi - 1 : gi, nj = dir == 0 ? gj : gj - 1;
        const bool seam = dir == 0 ? ni < 0 : nj < 0;
        if (seam) {
          switch (sides_[dir == 0 ? Left : Bottom]) {
            case FaceKind::Wall: continue;  // no normal flux through a wall face
            case FaceKind::Inflow:          // prescribed face velocity: no force on it
            case FaceKind::Outflow: continue;  // no force on an open face
            case FaceKind::Periodic: break;
          }
        }
        const double c1 = ramp(phi_at(a, ni, nj));
        if (c0 == c1) continue;
        const double pm = 0.5 * (p_here() + pressure(dist(ni, nj)));
        if (pm <= 0.0) continue;
        const double f = pm * (c0 - c1) * inv_dx;
        (dir == 0 ? out.x : out.y).push_back({gi, gj, std::abs(f), f});
      }
    }
}

bool Contact::add_force(const std::vector<std::unique_ptr<Solid>>& solids, Field& fxf, Field& fyf) {
  pair_totals_.clear();
  energy_ = 0.0;
  if (!force_ || P_ <= 0.0) return false;
  const int nx = g_.nx, ny = g_.ny;
  const int n = int(solids.size());
  // per solid the boxes of {phi < 0} and {phi < d} (not used across periodic directions,
  // where windows wrap)
  boxes_.resize(std::size_t(n));
  const bool wrap = sides_.periodic_x() || sides_.periodic_y() || !narrow_boxes_;
  if (!wrap)
    parallel_items(
        n, [&](int k) { return long(solids[std::size_t(k)]->ni()) * solids[std::size_t(k)]->nj(); },
        [&](int k) {
          const Solid& s = *solids[std::size_t(k)];
          Boxes& b = boxes_[std::size_t(k)];
          b = Boxes{{s.i0() + s.ni(), -1, s.j0() + s.nj(), -1}, {s.i0() + s.ni(), -1, s.j0() + s.nj(), -1}};
          for (int j = 0; j < s.nj(); ++j)
            for (int i = 0; i < s.ni(); ++i) {
              const double ph = s.phi()(i, j);
              if (!(ph < d_)) continue;
              const int gi = s.i0() + i, gj = s.j0() + j;
              auto grow = [&](int* box) {
                box[0] = std::min(box[0], gi); box[1] = std::max(box[1], gi);
                box[2] = std::min(box[2], gj); box[3] = std::max(box[3], gj);
              };
              grow(b.near);
              if (ph < 0.0) grow(b.in);
            }
        });
  // Cells that can contribute to a's layer against an obstacle whose pressure region is
  // the box `near`: the cell or its left/bottom neighbour in a's {phi < 0} box and the
  // cell or that neighbour in `near` (fill_layer adds nothing elsewhere, so narrowing the
  // box to them changes no bit).
  auto narrow = [&](std::array<int, 4> box, const int* in, const int* near) {
    if (wrap) return box;
    box[0] = std::max({box[0], in[0], near[0]});
    box[1] = std::min({box[1], in[1] + 1, near[1] + 1});
    box[2] = std::max({box[2], in[2], near[2]});
    box[3] = std::min({box[3], in[3] + 1, near[3] + 1});
    return box;
  };
  auto empty = [](const std::array<int, 4>& b) { return b[0] > b[1] || b[2] > b[3]; };
  // the tasks, in the order their results are applied (pairs, then solids and walls).
  // Pairs whose windows, inflated by a cell, do not meet have no cell where a's ramp
  // changes and b's pressure is non-zero on the same face (outside its window phi_b =
  // band > d), so their layers would be empty: leaving them out changes no bit.
  tasks_.clear();
  find_pairs(solids, 1, pairs_);
  for (const auto& [ia, ib] : pairs_) {
    const Solid& a = *solids[std::size_t(ia)];
    const Solid& b = *solids[std::size_t(ib)];
    if (clamped_pair(a, ia, b, ib)) continue;  // held together on purpose
    // Outside the other solid's window its phi is +band > d (range < band), so the
    // pressure vanishes there: only the overlap of the two windows matters, extended by
    // one cell up/right for the faces that touch it. Across a periodic direction the
    // windows may wrap, so there the whole window is visited.
    std::array<int, 4> box{std::max(a.i0(), b.i0()) - 1, std::min(a.i0() + a.ni(), b.i0() + b.ni()),
                           std::max(a.j0(), b.j0()) - 1, std::min(a.j0() + a.nj(), b.j0() + b.nj())};
    if (sides_.periodic_x()) { box[0] = -1; box[1] = nx; }
    if (sides_.periodic_y()) { box[2] = -1; box[3] = ny; }
    if (box[0] >= box[1] || box[2] >= box[3]) continue;  // windows apart: no contact possible
    Task t{ia, ib, -1, {narrow(box, boxes_[std::size_t(ia)].in, boxes_[std::size_t(ib)].near),
                        narrow(box, boxes_[std::size_t(ib)].in, boxes_[std::size_t(ia)].near)}};
    if (empty(t.box[0]) && empty(t.box[1])) continue;  // no layer cell within range
    tasks_.push_back(t);
  }
  for (int ia = 0; ia < n; ++ia)
    for (int side = 0; side < 4; ++side) {
      if (!wall_[side]) continue;
      // the pressure needs a cell centre closer than d to the wall; the layer visits the
      // window plus one cell (and the left/bottom neighbours of those): skip the side
      // when even the nearest of them is at least d away
      const Solid& w = *solids[std::size_t(ia)];
      double nearest = 0.0;
      switch (side) {
        case Left: nearest = (w.i0() - 2 + 0.5) * g_.dx; break;
        case Right: nearest = (nx - (w.i0() + w.ni()) - 0.5) * g_.dx; break;
        case Bottom: nearest = (w.j0() - 2 + 0.5) * g_.dx; break;
        default: nearest = (ny - (w.j0() + w.nj()) - 0.5) * g_.dx; break;
      }
      if (nearest >= d_) continue;
      // the wall's pressure region: the cells whose centre is closer than d to it
      // (k + 0.5) dx < d for k < m; one more cell against rounding of the cell centres
      const int m = int(std::ceil(d_ / g_.dx - 0.5)) + 1;
      int near[4] = {0, nx - 1, 0, ny - 1};
      switch (side) {
        case Left: near[1] = m - 1; break;
        case Right: near[0] = nx - m; break;
        case Bottom: near[3] = m - 1; break;
        default: near[2] = ny - m; break;
      }
      Task t{ia, -1, side, {narrow({-1, nx, -1, ny}, boxes_[std::size_t(ia)].in, near), {}}};
      if (empty(t.box[0])) continue;
      tasks_.push_back(t);
    }
  if (layers_.size() < tasks_.size()) layers_.resize(tasks_.size());

  // the tasks' contributions, concurrently (each reads the solids and writes its own layers)
  auto cells = [&](const Solid& s, const std::array<int, 4>& b) {
    const long wi = std::min(s.i0() + s.ni(), b[1]) - std::max(s.i0() - 1, b[0]) + 1;
    const long wj = std::min(s.j0() + s.nj(), b[3]) - std::max(s.j0() - 1, b[2]) + 1;
    return std::max(0L, wi) * std::max(0L, wj);
  };
  parallel_items(
      int(tasks_.size()),
      [&](int k) {
        const Task& t = tasks_[std::size_t(k)];
        const long c = cells(*solids[std::size_t(t.a)], t.box[0]) +
                       (t.b >= 0 ? cells(*solids[std::size_t(t.b)], t.box[1]) : 0);
        return c * kContactCellCost;
      },
      [&](int k) {
        const Task& t = tasks_[std::size_t(k)];
        auto& L = layers_[std::size_t(k)];
        const Solid& a = *solids[std::size_t(t.a)];
        if (t.b >= 0) {
          const Solid& b = *solids[std::size_t(t.b)];
          fill_layer(a, [&](int gi, int gj) { return phi_at(b, gi, gj); }, t.box[0], L[0]);
          fill_layer(b, [&](int gi, int gj) { return phi_at(a, gi, gj); }, t.box[1], L[1]);
        } else {
          fill_layer(
              a,
              [&](int gi, int gj) {
                double dist, nx_, ny_;
                side_geometry(g_, t.side, gi, gj, dist, nx_, ny_);
                return dist;
              },
              t.box[0], L[0]);
        }
      });

  // applied serially in task order: the face sums and the energy have the bits of a
  // serial run on any number of threads
  bool wrote = false;
  auto apply = [&](const Layer& l, double cx, double cy, double* tot) {
    wrote = wrote || !l.x.empty() || !l.y.empty();
    for (const auto& c : l.x) {
      const double f = c.f + cx * c.w;
      fxf(c.gi, c.gj) += f;
      tot[0] += f;
    }
    for (const auto& c : l.y) {
      const double f = c.f + cy * c.w;
      fyf(c.gi, c.gj) += f;
      tot[1] += f;
    }
  };
  auto sums = [](const std::vector<Contribution>& v, double& F, double& W) {
    F = W = 0.0;
    for (const auto& c : v) { F += c.f; W += c.w; }
  };
  for (std::size_t k = 0; k < tasks_.size(); ++k) {
    const Task& t = tasks_[k];
    const Layer& A = layers_[k][0];
    for (double e : A.energy) energy_ += e;
    if (t.b < 0) {  // a wall: no reaction to balance
      double tw[2] = {0, 0};
      apply(A, 0.0, 0.0, tw);
      continue;
    }
    const Layer& B = layers_[k][1];
    for (double e : B.energy) energy_ += e;
    if ((A.x.empty() && A.y.empty()) || (B.x.empty() && B.y.empty())) continue;
    // equal and opposite: both totals replaced by +-(F_a - F_b)/2, per direction, the
    // difference spread over the same faces in proportion to their |force|
    double Fax, Wax, Fay, Way, Fbx, Wbx, Fby, Wby;
    sums(A.x, Fax, Wax); sums(A.y, Fay, Way); sums(B.x, Fbx, Wbx); sums(B.y, Fby, Wby);
    double Fx = 0.5 * (Fax - Fbx), Fy = 0.5 * (Fay - Fby);
    if (!(Wax > 0.0 && Wbx > 0.0)) Fx = 0.0;  // no x-faces on one side: no x force
    if (!(Way > 0.0 && Wby > 0.0)) Fy = 0.0;
    auto corr = [](double target, double F, double W) { return W > 0.0 ? (target - F) / W : 0.0; };
    double ta[2] = {0, 0}, tb[2] = {0, 0};
    apply(A, corr(Fx, Fax, Wax), corr(Fy, Fay, Way), ta);
    apply(B, corr(-Fx, Fbx, Wbx), corr(-Fy, Fby, Wby), tb);
    const double a2 = g_.dx * g_.dx;
    for (double q : {ta[0], ta[1], tb[0], tb[1]}) pair_totals_.push_back(q * a2);
  }
  return wrote;
}

double Contact::pair_gap(const Solid& a, const Solid& b) const {
  // the overlap of a's window with each image of b's by whole periods in a periodic
  // direction (windows are unwrapped and at most one period wide: solver/model/periodic_window.hpp);
  // only k = 0 unless one of them crosses a periodic side
  auto images = [](int a0, int an, int b0, int bn, int n, bool periodic) {
    auto floor_div = [](int p, int q) { return p / q - ((p % q != 0) && ((p < 0) != (q < 0))); };
    if (!periodic) return std::array<int, 2>{0, 0};
    return std::array<int, 2>{floor_div(a0 - b0 - bn, n) + 1, floor_div(a0 + an - b0 - 1, n)};
  };
  const auto kx = images(a.i0(), a.ni(), b.i0(), b.ni(), g_.nx, sides_.periodic_x());
  const auto ky = images(a.j0(), a.nj(), b.j0(), b.nj(), g_.ny, sides_.periodic_y());
  double gap = sentinel_;
  bool any = false;
  for (int sy = ky[0]; sy <= ky[1]; ++sy)
    for (int sx = kx[0]; sx <= kx[1]; ++sx) {
      const int bi0 = b.i0() + sx * g_.nx, bj0 = b.j0() + sy * g_.ny;
      const int i0 = std::max(a.i0(), bi0), i1 = std::min(a.i0() + a.ni(), bi0 + b.ni());
      const int j0 = std::max(a.j0(), bj0), j1 = std::min(a.j0() + a.nj(), bj0 + b.nj());
      for (int gj = j0; gj < j1; ++gj)
        for (int gi = i0; gi < i1; ++gi) {
          const double pa = a.phi()(gi - a.i0(), gj - a.j0()), pb = b.phi()(gi - bi0, gj - bj0);
          if (!(pa < a.band() && pb < b.band())) continue;
          gap = any ? std::min(gap, pa + pb) : pa + pb;
          any = true;
        }
    }
  return any ? gap : sentinel_;
}

std::array<double, 4> Contact::wall_gaps(const Solid& s) const {
  // one pass over the solid's window for all four sides (each cell's phi read once)
  std::array<double, 4> gap{sentinel_, sentinel_, sentinel_, sentinel_};
  bool any = false;
  for (int j = 0; j < s.nj(); ++j)
    for (int i = 0; i < s.ni(); ++i) {
      const double ph = s.phi()(i, j);
      if (!(ph < s.band())) continue;
      for (int side = 0; side < 4; ++side) {
        if (!wall_[side]) continue;
        double dist, nx, ny;
        side_geometry(g_, side, s.i0() + i, s.j0() + j, dist, nx, ny);
        gap[size_t(side)] = any ? std::min(gap[size_t(side)], dist + ph) : dist + ph;
      }
      any = true;
    }
  return gap;
}

namespace {
const char* wall_name(int side) {
  static const char* names[4] = {"wall_left", "wall_right", "wall_bottom", "wall_top"};
  return names[side];
}
}  // namespace

void Contact::emit(double t, int solid, const char* what, double value, const std::string& with) {
  events_.push_back({t, solid, what, value, with});
}

// A negative restitution means the solid never moved away from the wall before the next
// contact started (no rebound); restitution_unfinished (a run ending mid-bounce) is only a
// lower bound of that bounce's coefficient (docs/output.md).
void Contact::close_rebound(double t, int solid, int side, WallState& w, const char* event) {
  // restitution = -v_after / v_before: v_before the most negative normal velocity
  // (towards the wall) of the approach, v_after the largest normal velocity from the start
  // of the contact until the rebound ends; only for a real approach (v_before < 0)
  if (w.v_before < 0.0) emit(t, solid, event, -w.vmax / w.v_before, wall_name(side));
  w.pending = false;
}

void Contact::observe(double t, const std::vector<std::unique_ptr<Solid>>& solids,
                      const std::vector<SolidDiagnostics>& diag) {
  const size_t n = solids.size();
  // the strength follows the fastest solid so far (automatic U only): a solid faster than
  // every scale of the scene foresaw is still stopped (docs/stability.md: P >~ 10 rho V^2)
  for (size_t i = 0; i < n && i < diag.size(); ++i) see_speed(std::hypot(diag[i].u, diag[i].v));
  // hysteresis: a contact starts when the gap falls below d, ends when it exceeds d + dx/4
  const double d_on = d_, d_off = d_ + 0.25 * g_.dx;
  observed_ = true;
  for (size_t i = 0; i < n; ++i) {
    gap_solid_[i] = sentinel_;
    gap_wall_[i] = sentinel_;
  }
  // the gaps, concurrently (one item per pair of solids whose windows overlap -- no other
  // pair has a gap below the sentinel -- and one per solid for its walls; read-only), then
  // the contact states and events serially in pair order
  find_pairs(solids, 0, pairs_);
  const size_t np = pairs_.size();
  pair_gap_.assign(np, sentinel_);
  side_gap_.assign(n, {sentinel_, sentinel_, sentinel_, sentinel_});
  auto overlap = [](const Solid& a, const Solid& b) {
    const long wi = std::min(a.i0() + a.ni(), b.i0() + b.ni()) - std::max(a.i0(), b.i0());
    const long wj = std::min(a.j0() + a.nj(), b.j0() + b.nj()) - std::max(a.j0(), b.j0());
    return std::max(0L, wi) * std::max(0L, wj);
  };
  const bool any_wall = wall_[0] || wall_[1] || wall_[2] || wall_[3];
  parallel_items(
      int(np + n),
      [&](int k) {
        if (size_t(k) < np)
          return overlap(*solids[size_t(pairs_[size_t(k)].first)], *solids[size_t(pairs_[size_t(k)].second)]) *
                 kContactCellCost;
        const Solid& s = *solids[size_t(k) - np];
        return any_wall ? long(s.ni()) * s.nj() * kContactCellCost : 1L;
      },
      [&](int k) {
        if (size_t(k) < np) {
          const auto [a, b] = pairs_[size_t(k)];
          pair_gap_[size_t(k)] = pair_gap(*solids[size_t(a)], *solids[size_t(b)]);
        } else {
          side_gap_[size_t(k) - np] = wall_gaps(*solids[size_t(k) - np]);
        }
      });
  // every pair with a gap or in contact, in the order of the all-pairs loop: the two
  // sorted lists merged (a pair in contact whose windows have parted has the sentinel gap)
  next_touching_.clear();
  size_t p = 0, q = 0;
  while (p < np || q < touching_.size()) {
    const bool from_p = p < np && (q >= touching_.size() || !(touching_[q] < pairs_[p]));
    const bool from_q = q < touching_.size() && (p >= np || !(pairs_[p] < touching_[q]));
    const auto [ia, ib] = from_p ? pairs_[p] : touching_[q];
    const double gap = from_p ? pair_gap_[p] : sentinel_;
    const bool was = from_q;
    p += from_p;
    q += from_q;
    const size_t a = size_t(ia), b = size_t(ib);
    if (clamped_pair(*solids[a], ia, *solids[b], ib)) continue;  // no gap, no events
    gap_solid_[a] = std::min(gap_solid_[a], gap);
    gap_solid_[b] = std::min(gap_solid_[b], gap);
    const bool now = was ? !(gap > d_off) : gap < d_on;
    if (now != was) {
      // relative normal velocity along the line of centroids, > 0 when separating
      double ex = diag[b].cx - diag[a].cx, ey = diag[b].cy - diag[a].cy;
      // the nearest images across periodic sides (the centroids are unwrapped)
      if (sides_.periodic_x()) ex -= g_.lx() * std::round(ex / g_.lx());
      if (sides_.periodic_y()) ey -= g_.ly() * std::round(ey / g_.ly());
      const double e = std::hypot(ex, ey);
      if (e > 0) { ex /= e; ey /= e; }
      const double vrel = (diag[b].u - diag[a].u) * ex + (diag[b].v - diag[a].v) * ey;
      const char* what = now ? "contact_start" : "contact_end";
      emit(t, int(a), what, vrel, solids[b]->spec().name);
      emit(t, int(b), what, vrel, solids[a]->spec().name);
    }
    if (now) next_touching_.emplace_back(ia, ib);
  }
  touching_.swap(next_touching_);
  for (size_t i = 0; i < n; ++i)
    for (int side = 0; side < 4; ++side) {
      if (!wall_[side]) continue;
      const double gap = side_gap_[i][size_t(side)];
      gap_wall_[i] = std::min(gap_wall_[i], gap);
      double dist, nx, ny;
      side_geometry(g_, side, 0, 0, dist, nx, ny);
      const double vn = diag[i].u * nx + diag[i].v * ny;  // > 0: away from the wall
      WallState& w = wall_state_[i][side];
      if (!w.started) { w.started = true; w.vmin = vn; }
      if (!w.in_contact) {
        w.vmin = std::min(w.vmin, vn);  // the approach: min since the last contact_end
        if (w.pending) {
          w.vmax = std::max(w.vmax, vn);
          if (vn < 0.0) close_rebound(t, int(i), side, w);  // moving back towards the wall
        }
        if (gap < d_on) {
          if (w.pending) close_rebound(t, int(i), side, w);
          w.in_contact = true;
          w.v_before = std::min(w.vmin, vn);
          w.vmax = vn;
          emit(t, int(i), "contact_start", vn, wall_name(side));
        }
      } else {
        w.vmax = std::max(w.vmax, vn);
        if (gap > d_off) {
          w.in_contact = false;
          w.pending = true;
          w.vmin = vn;
          emit(t, int(i), "contact_end", vn, wall_name(side));
        }
      }
    }
}

void Contact::finish(double t) {
  for (size_t i = 0; i < wall_state_.size(); ++i)
    for (int side = 0; side < 4; ++side) {
      auto& w = wall_state_[i][side];
      if (w.pending || w.in_contact) {
        // the run ended during a contact or before the rebound was over: the value is
        // only a lower bound of the bounce's restitution, so it gets its own event name
        close_rebound(t, int(i), side, w, "restitution_unfinished");
        if (w.in_contact) w.v_before = 0.0;  // reported once
      }
    }
}

}  // namespace refmap
