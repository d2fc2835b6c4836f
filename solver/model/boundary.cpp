#include "solver/model/boundary.hpp"

#include <cmath>
#include <stdexcept>

namespace refmap {

double SideBc::speed(double t) const {
  if (type != BcType::MovingWall) return 0.0;
  return oscillating ? velocity * std::sin(omega * t + phase) : velocity;
}

Sides face_sides(const std::array<SideBc, 4>& bc) {
  Sides s;
  for (int k = 0; k < 4; ++k) {
    switch (bc[k].type) {
      case BcType::NoSlip:
      case BcType::MovingWall:
      case BcType::FreeSlip: s.kind[k] = FaceKind::Wall; break;
      case BcType::Periodic: s.kind[k] = FaceKind::Periodic; break;
      case BcType::Inflow: s.kind[k] = FaceKind::Inflow; break;
      case BcType::Outflow: s.kind[k] = FaceKind::Outflow; break;
    }
  }
  return s;
}

double max_inflow_speed(const std::array<SideBc, 4>& bc, const Grid& g, double t) {
  double m = 0.0;
  for (int k = 0; k < 4; ++k) {
    if (bc[k].type != BcType::Inflow) continue;
    const bool xside = k == Left || k == Right;
    const Expression& e = xside ? bc[k].inflow_u : bc[k].inflow_v;
    const int n = xside ? g.ny : g.nx;
    const double xf = k == Left ? g.x0 : g.x0 + g.lx(), yf = k == Bottom ? g.y0 : g.y0 + g.ly();
    for (int i = 0; i < n; ++i)
      m = std::max(m, std::abs(xside ? e.eval(xf, g.yc(i), t) : e.eval(g.xc(i), yf, t)));
  }
  return m;
}

bool outflow_sink(const Field& beta_x, const Field& beta_y, Sides sides, const Grid& g, Field& sink) {
  if (!sides.any(FaceKind::Outflow)) {
    sink = Field();
    return false;
  }
  const int nx = g.nx, ny = g.ny;
  if (sink.nx() != nx || sink.ny() != ny) sink.resize(nx, ny, 1);
  sink.fill(0.0);
  const double s = 2.0 / (g.dx * g.dx);
  // corner cells of two outflow sides get both terms
  if (sides[Left] == FaceKind::Outflow)
    for (int j = 0; j < ny; ++j) sink(0, j) += s * beta_x(0, j);
  if (sides[Right] == FaceKind::Outflow)
    for (int j = 0; j < ny; ++j) sink(nx - 1, j) += s * beta_x(nx, j);
  if (sides[Bottom] == FaceKind::Outflow)
    for (int i = 0; i < nx; ++i) sink(i, 0) += s * beta_y(i, 0);
  if (sides[Top] == FaceKind::Outflow)
    for (int i = 0; i < nx; ++i) sink(i, ny - 1) += s * beta_y(i, ny);
  return true;
}

namespace {

// sign of the mirror for the component normal / tangential to a wall
struct Mirror {
  double sign;    // ghost = sign * mirror + offset
  double offset;  // 2 U for a moving wall's tangential component
};

Mirror mirror_for(const SideBc& s, bool normal_component, double t, double scale) {
  switch (s.type) {
    case BcType::NoSlip: return {-1.0, 0.0};
    case BcType::MovingWall:
      return normal_component ? Mirror{-1.0, 0.0} : Mirror{-1.0, 2.0 * scale * s.speed(t)};
    case BcType::FreeSlip: return normal_component ? Mirror{-1.0, 0.0} : Mirror{1.0, 0.0};
    case BcType::Inflow: return {-1.0, 0.0};  // plus the profile's 2 U_in (Profile below)
    case BcType::Outflow: return {1.0, 0.0};
    case BcType::Periodic: break;
  }
  return {1.0, 0.0};
}

}  // namespace

bool velocity_prescribed(const SideBc& bc, bool normal_component) {
  // (an inflow profile is held at its value of the step's start for a change over the step)
  return bc.type != BcType::Periodic && mirror_for(bc, normal_component, 0.0, 1.0).sign < 0.0;
}

namespace {

/// An inflow side's offset 2 scale U_in along the side (nullptr expression: none).
struct Profile {
  const Expression* e = nullptr;
  const Grid* g = nullptr;
  double t = 0.0, scale = 1.0;
  double xface = 0.0, yface = 0.0;
  bool along_y = true;  ///< a left/right side: the position along it is y
  double offset(int k) const {
    return along_y ? 2.0 * scale * e->eval(xface, g->yc(k), t) : 2.0 * scale * e->eval(g->xc(k), yface, t);
  }
};

Profile profile_for(const SideBc& s, int side, bool x_component, const Grid* g, double t, double scale) {
  Profile p;
  if (s.type != BcType::Inflow) return p;
  if (!g) throw std::logic_error("fill_vector_ghosts: an inflow side needs the grid");
  p.e = x_component ? &s.inflow_u : &s.inflow_v;
  p.g = g;
  p.t = t;
  p.scale = scale;
  p.xface = side == Left ? g->x0 : g->x0 + g->lx();
  p.yface = side == Bottom ? g->y0 : g->y0 + g->ly();
  p.along_y = side == Left || side == Right;
  return p;
}

void fill_x_sides(Field& f, const SideBc& left, const SideBc& right, Mirror ml, Mirror mr,
                  const Profile& pl = {}, const Profile& pr = {}) {
  const int nx = f.nx(), ny = f.ny(), ng = f.ng();
  const bool periodic = left.type == BcType::Periodic;
  for (int j = 0; j < ny; ++j) {
    if (periodic) {
      for (int g = 1; g <= ng; ++g) {
        f(-g, j) = f(nx - g, j);
        f(nx - 1 + g, j) = f(g - 1, j);
      }
      continue;
    }
    const double ol = pl.e ? pl.offset(j) : ml.offset, orr = pr.e ? pr.offset(j) : mr.offset;
    for (int g = 1; g <= ng; ++g) {
      f(-g, j) = ml.sign * f(g - 1, j) + ol;
      f(nx - 1 + g, j) = mr.sign * f(nx - g, j) + orr;
    }
  }
}

void fill_y_sides(Field& f, const SideBc& bottom, const SideBc& top, Mirror mb, Mirror mt,
                  const Profile& pb = {}, const Profile& pt = {}) {
  const int nx = f.nx(), ny = f.ny(), ng = f.ng();
  // the side kind and the profile test are hoisted out of the row loops, which then
  // vectorise (a per-cell test cost ~2 % of a cavity step)
  const bool periodic = bottom.type == BcType::Periodic;
  for (int g = 1; g <= ng; ++g) {
    if (periodic) {
      for (int i = -ng; i < nx + ng; ++i) {
        f(i, -g) = f(i, ny - g);
        f(i, ny - 1 + g) = f(i, g - 1);
      }
      continue;
    }
    if (pb.e)
      for (int i = -ng; i < nx + ng; ++i) f(i, -g) = mb.sign * f(i, g - 1) + pb.offset(i);
    else
      for (int i = -ng; i < nx + ng; ++i) f(i, -g) = mb.sign * f(i, g - 1) + mb.offset;
    if (pt.e)
      for (int i = -ng; i < nx + ng; ++i) f(i, ny - 1 + g) = mt.sign * f(i, ny - g) + pt.offset(i);
    else
      for (int i = -ng; i < nx + ng; ++i) f(i, ny - 1 + g) = mt.sign * f(i, ny - g) + mt.offset;
  }
}

void fill_vector(Field& a, Field& b, const std::array<SideBc, 4>& bc, const Grid* grid, double t, double scale) {
  const SideBc &L = bc[Left], &R = bc[Right], &B = bc[Bottom], &T = bc[Top];
  auto prof = [&](int side, bool xcomp) { return profile_for(bc[side], side, xcomp, grid, t, scale); };
  // x component a: normal to the left/right walls, tangential to bottom/top
  fill_x_sides(a, L, R, mirror_for(L, true, t, scale), mirror_for(R, true, t, scale), prof(Left, true),
               prof(Right, true));
  fill_y_sides(a, B, T, mirror_for(B, false, t, scale), mirror_for(T, false, t, scale), prof(Bottom, true),
               prof(Top, true));
  // y component b: tangential to left/right, normal to bottom/top
  fill_x_sides(b, L, R, mirror_for(L, false, t, scale), mirror_for(R, false, t, scale), prof(Left, false),
               prof(Right, false));
  fill_y_sides(b, B, T, mirror_for(B, true, t, scale), mirror_for(T, true, t, scale), prof(Bottom, false),
               prof(Top, false));
}

}  // namespace

void fill_vector_ghosts(Field& a, Field& b, const std::array<SideBc, 4>& bc, const Grid& g, double t,
                        double scale) {
  fill_vector(a, b, bc, &g, t, scale);
}

void fill_vector_ghosts(Field& a, Field& b, const std::array<SideBc, 4>& bc, double t, double scale) {
  fill_vector(a, b, bc, nullptr, t, scale);
}

void fill_scalar_ghosts(Field& s, const std::array<SideBc, 4>& bc) {
  const Mirror even{1.0, 0.0};
  fill_x_sides(s, bc[Left], bc[Right], even, even);
  fill_y_sides(s, bc[Bottom], bc[Top], even, even);
}

}  // namespace refmap
