#pragma once
// What the projection (kernels/projection.*) and the pressure solvers (solver/pressure/poisson_*,
// kernels/multigrid.*) need to know about each side of the domain: its FaceKind.
//
//   Wall      normal face velocity 0, beta_f = 0 on the boundary face, so the pressure
//             correction has a homogeneous Neumann condition there;
//   Periodic  the side wraps to the opposite one: face 0 and face n of that direction are
//             one face (computed from the wrapped ghost cells). Always set on both sides
//             of a direction.
//   Inflow    prescribed normal face velocity (the mean of the cell and its ghost, which
//             the ghost fill sets to the prescribed value on the face), beta_f = 0, so the
//             pressure correction is homogeneous Neumann there as at a wall;
//   Outflow   Dirichlet pressure p = 0 on the face: the face gradient is (0 - p_P) over
//             half a cell, beta_f = 1/rho_P; the face velocity is the cell's (zero normal
//             derivative) corrected by that gradient. The pressure solvers see it as a
//             wall plus the cell sink 2 beta_f / dx^2 of the adjacent cells
//             (solver/pressure/poisson.hpp, PoissonOperator::sink; Sides::pressure()).
//
// Every operator treats a side in one `switch` over its kind, with no `default:`, so that
// adding a kind (e.g. inflow: prescribed normal face velocity; outflow: Dirichlet
// pressure) makes -Wswitch list every place that needs a case. Sides is built once from
// the scene's boundary conditions (solver/model/boundary.hpp: face_sides).
#include <array>

namespace refmap {

enum Side { Left = 0, Right = 1, Bottom = 2, Top = 3 };

enum class FaceKind : unsigned char { Wall, Periodic, Inflow, Outflow };

struct Sides {
  std::array<FaceKind, 4> kind{FaceKind::Wall, FaceKind::Wall, FaceKind::Wall, FaceKind::Wall};

  FaceKind operator[](Side s) const { return kind[s]; }
  /// axis 0 = x (Left/Right), 1 = y (Bottom/Top); a direction that wraps.
  bool periodic(int axis) const { return kind[2 * axis] == FaceKind::Periodic; }
  bool periodic_x() const { return periodic(0); }
  bool periodic_y() const { return periodic(1); }
  bool any(FaceKind k) const { return kind[0] == k || kind[1] == k || kind[2] == k || kind[3] == k; }

  /// The pressure solvers' view: an inflow or outflow side is a wall (beta = 0 on its
  /// faces); the Dirichlet condition of an outflow side enters through the solver's cell
  /// sink, which the caller builds.
  Sides pressure() const {
    Sides s = *this;
    for (FaceKind& k : s.kind)
      if (k == FaceKind::Inflow || k == FaceKind::Outflow) k = FaceKind::Wall;
    return s;
  }

  /// Walls on the non-periodic directions (tests, benchmarks).
  static Sides walls_or_periodic(bool px, bool py) {
    const FaceKind x = px ? FaceKind::Periodic : FaceKind::Wall;
    const FaceKind y = py ? FaceKind::Periodic : FaceKind::Wall;
    return Sides{{x, x, y, y}};
  }

  bool operator==(const Sides&) const = default;
};

}  // namespace refmap
