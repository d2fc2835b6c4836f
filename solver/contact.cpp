#include "solver/contact.hpp"

#include <algorithm>
#include <cmath>

#include "solver/boundary.hpp"

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

struct Contribution {
  int gi, gj;  // the face: left (x) or bottom (y) face of cell (gi, gj)
  double w, f; // weight (for the momentum correction) and normal face force density
};

}  // namespace

Contact::Contact(const Config& cfg, double velocity_scale) : g_(cfg.grid) {
  const ContactOptions& o = cfg.contact;
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
  h_ = 2.0 * g_.dx;
  double rho_max = cfg.rho_f;
  for (const SolidSpec& s : cfg.solids) rho_max = std::max(rho_max, s.density);
  double U = o.velocity_scale > 0.0 ? o.velocity_scale : velocity_scale;
  if (!(U > 0.0)) U = g_.lx() / std::max(cfg.t_end - cfg.t_start, 1e-300);
  P_ = o.stiffness * rho_max * U * U;
  // the gap written when there is nothing to measure: no other solid's band meets this
  // one's, there is no other solid, or every side is periodic / contact.walls = false
  // (docs/output.md)
  sentinel_ = std::hypot(g_.lx(), g_.ly());
  const size_t n = cfg.solids.size();
  gap_solid_.assign(n, sentinel_);
  gap_wall_.assign(n, sentinel_);
  wall_state_.assign(n, {});
  pair_state_.assign(n * n, {});
}

double Contact::min_dt(double rho_min) const {
  if (!force_ || P_ <= 0.0) return 1e300;
  const double omega2 = 2.0 * 3.0 * P_ / (d_ * rho_min * h_);
  return 0.5 / std::sqrt(omega2);
}

double Contact::phi_at(const Solid& s, int gi, int gj) const {
  if (sides_.periodic_x()) gi = ((gi % g_.nx) + g_.nx) % g_.nx;
  if (sides_.periodic_y()) gj = ((gj % g_.ny) + g_.ny) % g_.ny;
  if (gi < 0 || gi >= g_.nx || gj < 0 || gj >= g_.ny) return s.band();
  return s.phi_global(gi, gj);
}

void Contact::add_force(const std::vector<std::unique_ptr<Solid>>& solids, Field& fxf, Field& fyf) {
  pair_totals_.clear();
  energy_ = 0.0;
  if (!force_ || P_ <= 0.0) return;
  const double P = P_, d = d_, h = h_, inv_dx = 1.0 / g_.dx;
  const int nx = g_.nx, ny = g_.ny;
  auto pressure = [&](double s) { return s < d ? P * std::pow(1.0 - s / d, 3) : 0.0; };
  auto ramp = [&](double phi) {  // chi = S(-phi / h), S(x) = x^2 (3 - 2x) on [0, 1]
    const double x = std::clamp(-phi / h, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
  };
  // Face contributions of solid a pushed by the obstacle at distance dist(gi, gj):
  // F_f = mean of p_c over the two cells of the face * (difference of chi_a across it) / dx
  // Only the cells of the box [bi0, bi1] x [bj0, bj1] (inclusive) are visited: the caller
  // passes the part of a's window where the obstacle's pressure can be non-zero (plus the
  // cells whose left/bottom face touches it), so the work follows the contact zone.
  auto layer = [&](const Solid& a, auto&& dist, std::vector<Contribution>& xs,
                   std::vector<Contribution>& ys, int bi0, int bi1, int bj0, int bj1) {
    xs.clear();
    ys.clear();
    const int gj_lo = std::max(a.j0() - 1, bj0), gj_hi = std::min(a.j0() + a.nj(), bj1);
    const int gi_lo = std::max(a.i0() - 1, bi0), gi_hi = std::min(a.i0() + a.ni(), bi1);
    for (int gj = gj_lo; gj <= gj_hi; ++gj)
      for (int gi = gi_lo; gi <= gi_hi; ++gi) {
        if (gi < 0 || gi >= nx || gj < 0 || gj >= ny) continue;
        const double c0 = ramp(phi_at(a, gi, gj));
        const double p0 = pressure(dist(gi, gj));
        energy_ += c0 * p0 * g_.dx * g_.dx;  // U = sum chi p_c dx^2 (see contact.hpp)
        // the face on the left (x) and at the bottom (y) of cell (gi, gj)
        for (int dir = 0; dir < 2; ++dir) {
          const int ni = dir == 0 ? gi - 1 : gi, nj = dir == 0 ? gj : gj - 1;
          const bool seam = dir == 0 ? ni < 0 : nj < 0;
          if (seam) {
            switch (sides_[dir == 0 ? Left : Bottom]) {
              case FaceKind::Wall:
              case FaceKind::Inflow:   // prescribed face velocity: no force on it
              case FaceKind::Outflow: continue;  // no force on an open face
              case FaceKind::Periodic: break;
            }
          }
          const double c1 = ramp(phi_at(a, ni, nj));
          if (c0 == c1) continue;
          const double pm = 0.5 * (p0 + pressure(dist(ni, nj)));
          if (pm <= 0.0) continue;
          const double f = pm * (c0 - c1) * inv_dx;
          (dir == 0 ? xs : ys).push_back({gi, gj, std::abs(f), f});
        }
      }
  };
  std::vector<Contribution> ax, ay, bx, by;
  auto apply = [&](const std::vector<Contribution>& xs, const std::vector<Contribution>& ys,
                   double cx, double cy, double* tot) {
    for (const auto& c : xs) {
      const double f = c.f + cx * c.w;
      fxf(c.gi, c.gj) += f;
      tot[0] += f;
    }
    for (const auto& c : ys) {
      const double f = c.f + cy * c.w;
      fyf(c.gi, c.gj) += f;
      tot[1] += f;
    }
  };
  auto sums = [](const std::vector<Contribution>& v, double& F, double& W) {
    F = W = 0.0;
    for (const auto& c : v) { F += c.f; W += c.w; }
  };
  const size_t n = solids.size();
  for (size_t ia = 0; ia < n; ++ia)
    for (size_t ib = ia + 1; ib < n; ++ib) {
      const Solid& a = *solids[ia];
      const Solid& b = *solids[ib];
      // Outside the other solid's window its phi is +band > d (range < band), so the
      // pressure vanishes there: only the overlap of the two windows matters, extended by
      // one cell up/right for the faces that touch it. Across a periodic direction the
      // windows may wrap, so there the whole window is visited.
      int bi0 = std::max(a.i0(), b.i0()) - 1, bi1 = std::min(a.i0() + a.ni(), b.i0() + b.ni());
      int bj0 = std::max(a.j0(), b.j0()) - 1, bj1 = std::min(a.j0() + a.nj(), b.j0() + b.nj());
      if (sides_.periodic_x()) { bi0 = -1; bi1 = nx; }
      if (sides_.periodic_y()) { bj0 = -1; bj1 = ny; }
      if (bi0 >= bi1 || bj0 >= bj1) continue;  // windows apart: no contact possible
      layer(a, [&](int gi, int gj) { return phi_at(b, gi, gj); }, ax, ay, bi0, bi1, bj0, bj1);
      layer(b, [&](int gi, int gj) { return phi_at(a, gi, gj); }, bx, by, bi0, bi1, bj0, bj1);
      if ((ax.empty() && ay.empty()) || (bx.empty() && by.empty())) continue;
      // equal and opposite: both totals replaced by +-(F_a - F_b)/2, per direction, the
      // difference spread over the same faces in proportion to their |force|
      double Fax, Wax, Fay, Way, Fbx, Wbx, Fby, Wby;
      sums(ax, Fax, Wax); sums(ay, Fay, Way); sums(bx, Fbx, Wbx); sums(by, Fby, Wby);
      double Fx = 0.5 * (Fax - Fbx), Fy = 0.5 * (Fay - Fby);
      if (!(Wax > 0.0 && Wbx > 0.0)) Fx = 0.0;  // no x-faces on one side: no x force
      if (!(Way > 0.0 && Wby > 0.0)) Fy = 0.0;
      auto corr = [](double target, double F, double W) { return W > 0.0 ? (target - F) / W : 0.0; };
      double ta[2] = {0, 0}, tb[2] = {0, 0};
      apply(ax, ay, corr(Fx, Fax, Wax), corr(Fy, Fay, Way), ta);
      apply(bx, by, corr(-Fx, Fbx, Wbx), corr(-Fy, Fby, Wby), tb);
      const double a2 = g_.dx * g_.dx;
      for (double q : {ta[0], ta[1], tb[0], tb[1]}) pair_totals_.push_back(q * a2);
    }
  for (const auto& sp : solids)
    for (int side = 0; side < 4; ++side) {
      if (!wall_[side]) continue;
      // the pressure needs a cell centre closer than d to the wall; the layer visits the
      // window plus one cell (and the left/bottom neighbours of those): skip the side
      // when even the nearest of them is at least d away
      const Solid& w = *sp;
      double nearest = 0.0;
      switch (side) {
        case Left: nearest = (w.i0() - 2 + 0.5) * g_.dx; break;
        case Right: nearest = (nx - (w.i0() + w.ni()) - 0.5) * g_.dx; break;
        case Bottom: nearest = (w.j0() - 2 + 0.5) * g_.dx; break;
        default: nearest = (ny - (w.j0() + w.nj()) - 0.5) * g_.dx; break;
      }
      if (nearest >= d) continue;
      layer(*sp,
            [&](int gi, int gj) {
              double dist, nx_, ny_;
              side_geometry(g_, side, gi, gj, dist, nx_, ny_);
              return dist;
            },
            ax, ay, -1, nx, -1, ny);
      double t[2] = {0, 0};
      apply(ax, ay, 0.0, 0.0, t);
    }
}

double Contact::pair_gap(const Solid& a, const Solid& b) const {
  const int i0 = std::max(a.i0(), b.i0()), i1 = std::min(a.i0() + a.ni(), b.i0() + b.ni());
  const int j0 = std::max(a.j0(), b.j0()), j1 = std::min(a.j0() + a.nj(), b.j0() + b.nj());
  double gap = sentinel_;
  bool any = false;
  for (int gj = j0; gj < j1; ++gj)
    for (int gi = i0; gi < i1; ++gi) {
      const double pa = a.phi()(gi - a.i0(), gj - a.j0()), pb = b.phi()(gi - b.i0(), gj - b.j0());
      if (!(pa < a.band() && pb < b.band())) continue;
      gap = any ? std::min(gap, pa + pb) : pa + pb;
      any = true;
    }
  return any ? gap : sentinel_;
}

double Contact::wall_gap(const Solid& s, int side) const {
  if (!wall_[side]) return sentinel_;
  double gap = sentinel_;
  bool any = false;
  for (int j = 0; j < s.nj(); ++j)
    for (int i = 0; i < s.ni(); ++i) {
      const double ph = s.phi()(i, j);
      if (!(ph < s.band())) continue;
      double dist, nx, ny;
      side_geometry(g_, side, s.i0() + i, s.j0() + j, dist, nx, ny);
      gap = any ? std::min(gap, dist + ph) : dist + ph;
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
  // hysteresis: a contact starts when the gap falls below d, ends when it exceeds d + dx/4
  const double d_on = d_, d_off = d_ + 0.25 * g_.dx;
  for (size_t i = 0; i < n; ++i) {
    gap_solid_[i] = sentinel_;
    gap_wall_[i] = sentinel_;
  }
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b) {
      const double gap = pair_gap(*solids[a], *solids[b]);
      gap_solid_[a] = std::min(gap_solid_[a], gap);
      gap_solid_[b] = std::min(gap_solid_[b], gap);
      PairState& ps = pair_state_[a * n + b];
      const bool now = ps.in_contact ? !(gap > d_off) : gap < d_on;
      if (now != ps.in_contact) {
        // relative normal velocity along the line of centroids, > 0 when separating
        double ex = diag[b].cx - diag[a].cx, ey = diag[b].cy - diag[a].cy;
        const double e = std::hypot(ex, ey);
        if (e > 0) { ex /= e; ey /= e; }
        const double vrel = (diag[b].u - diag[a].u) * ex + (diag[b].v - diag[a].v) * ey;
        const char* what = now ? "contact_start" : "contact_end";
        emit(t, int(a), what, vrel, solids[b]->spec().name);
        emit(t, int(b), what, vrel, solids[a]->spec().name);
        ps.in_contact = now;
      }
    }
  for (size_t i = 0; i < n; ++i)
    for (int side = 0; side < 4; ++side) {
      if (!wall_[side]) continue;
      const double gap = wall_gap(*solids[i], side);
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
