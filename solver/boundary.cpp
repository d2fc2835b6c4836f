#include "solver/boundary.hpp"

#include <cmath>

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
    }
  }
  return s;
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
    case BcType::Periodic: break;
  }
  return {1.0, 0.0};
}

void fill_x_sides(Field& f, const SideBc& left, const SideBc& right, Mirror ml, Mirror mr) {
  const int nx = f.nx(), ny = f.ny(), ng = f.ng();
  for (int j = 0; j < ny; ++j) {
    for (int g = 1; g <= ng; ++g) {
      if (left.type == BcType::Periodic) {
        f(-g, j) = f(nx - g, j);
        f(nx - 1 + g, j) = f(g - 1, j);
      } else {
        f(-g, j) = ml.sign * f(g - 1, j) + ml.offset;
        f(nx - 1 + g, j) = mr.sign * f(nx - g, j) + mr.offset;
      }
    }
  }
}

void fill_y_sides(Field& f, const SideBc& bottom, const SideBc& top, Mirror mb, Mirror mt) {
  const int nx = f.nx(), ny = f.ny(), ng = f.ng();
  for (int g = 1; g <= ng; ++g) {
    for (int i = -ng; i < nx + ng; ++i) {
      if (bottom.type == BcType::Periodic) {
        f(i, -g) = f(i, ny - g);
        f(i, ny - 1 + g) = f(i, g - 1);
      } else {
        f(i, -g) = mb.sign * f(i, g - 1) + mb.offset;
        f(i, ny - 1 + g) = mt.sign * f(i, ny - g) + mt.offset;
      }
    }
  }
}

}  // namespace

void fill_vector_ghosts(Field& a, Field& b, const std::array<SideBc, 4>& bc, double t, double scale) {
  const SideBc &L = bc[Left], &R = bc[Right], &B = bc[Bottom], &T = bc[Top];
  // x component a: normal to the left/right walls, tangential to bottom/top
  fill_x_sides(a, L, R, mirror_for(L, true, t, scale), mirror_for(R, true, t, scale));
  fill_y_sides(a, B, T, mirror_for(B, false, t, scale), mirror_for(T, false, t, scale));
  // y component b: tangential to left/right, normal to bottom/top
  fill_x_sides(b, L, R, mirror_for(L, false, t, scale), mirror_for(R, false, t, scale));
  fill_y_sides(b, B, T, mirror_for(B, true, t, scale), mirror_for(T, true, t, scale));
}

void fill_scalar_ghosts(Field& s, const std::array<SideBc, 4>& bc) {
  const Mirror even{1.0, 0.0};
  fill_x_sides(s, bc[Left], bc[Right], even, even);
  fill_y_sides(s, bc[Bottom], bc[Top], even, even);
}

}  // namespace refmap
