#pragma once
// Ghost-cell boundary conditions of the cell-centred fields (two ghost layers).
//  - velocity (a vector: x component a, y component b):
//      no-slip / moving wall: ghost = 2 U_wall - mirror (normal component: U_wall = 0),
//      free slip: normal component odd, tangential even about the wall,
//      periodic: wrapped copy;
//  - scalars (pressure, density, viscosity): even (homogeneous Neumann) at walls,
//    wrapped when periodic.
// The x sides are filled first over the interior rows, then the y sides over the full
// padded width, so corner ghosts are consistent with both.
#include <array>

#include "kernels/boundary_kind.hpp"
#include "solver/config.hpp"
#include "core/field.hpp"

namespace refmap {

/// scale multiplies the wall speeds (e.g. by a density to fill momentum ghosts).
void fill_vector_ghosts(Field& a, Field& b, const std::array<SideBc, 4>& bc, double t,
                        double scale = 1.0);
void fill_scalar_ghosts(Field& s, const std::array<SideBc, 4>& bc);

/// The projection's and pressure solvers' view of the sides (kernels/boundary_kind.hpp):
/// every wall type (no-slip, moving, free-slip) is a FaceKind::Wall.
Sides face_sides(const std::array<SideBc, 4>& bc);


}  // namespace refmap
