#pragma once
// Ghost-cell boundary conditions of the cell-centred fields (two ghost layers).
//  - velocity (a vector: x component a, y component b):
//      no-slip / moving wall: ghost = 2 U_wall - mirror (normal component: U_wall = 0),
//      free slip: normal component odd, tangential even about the wall,
//      periodic: wrapped copy;
//      inflow: ghost = 2 U_in(face, t) - mirror for both components, so the mean of the
//        cell and its ghost is the prescribed velocity on the face;
//      outflow: ghost = mirror (zero normal derivative of both components);
//  - scalars (pressure, density, viscosity): even (homogeneous Neumann) at walls, inflow
//    and outflow sides, wrapped when periodic. (The projection imposes the outflow's p = 0
//    on the face itself, kernels/projection.cpp.)
// The x sides are filled first over the interior rows, then the y sides over the full
// padded width, so corner ghosts are consistent with both.
#include <array>

#include "kernels/boundary_kind.hpp"
#include "solver/model/config.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"

namespace refmap {

/// scale multiplies the wall speeds (e.g. by a density to fill momentum ghosts). The
/// grid places an inflow side's profile; the overload without it throws
/// std::logic_error if a side is an inflow.
void fill_vector_ghosts(Field& a, Field& b, const std::array<SideBc, 4>& bc, const Grid& g, double t,
                        double scale = 1.0);
void fill_vector_ghosts(Field& a, Field& b, const std::array<SideBc, 4>& bc, double t,
                        double scale = 1.0);
void fill_scalar_ghosts(Field& s, const std::array<SideBc, 4>& bc);

/// The projection's and pressure solvers' view of the sides (kernels/boundary_kind.hpp):
/// every wall type (no-slip, moving, free-slip) is a FaceKind::Wall.
Sides face_sides(const std::array<SideBc, 4>& bc);

/// Is the velocity component normal (normal_component) or tangential to side bc given on
/// the side (Dirichlet: no-slip and moving walls, a free-slip wall's normal component, an
/// inflow)? Read from the ghost rule of fill_vector_ghosts (a ghost that mirrors the
/// inside with the sign -1 holds a value on the face), so the implicit velocity step
/// (solver/model/implicit_step.hpp) and the ghost fill cannot disagree.
bool velocity_prescribed(const SideBc& bc, bool normal_component);

/// Largest |normal velocity| of the inflow sides at time t over their faces (0 without
/// an inflow side): the CFL bound must see the velocity that enters.
double max_inflow_speed(const std::array<SideBc, 4>& bc, const Grid& g, double t);

/// The pressure solvers' cell sink of the outflow sides (p = 0 on the face, half a cell
/// from the centre): c_P = 2 beta_f / dx^2 for every cell next to an outflow face f, 0
/// elsewhere (solver/pressure/poisson.hpp, PoissonOperator::sink). Resizes `sink` to the grid.
/// Returns false (and leaves `sink` empty) when no side is an outflow.
bool outflow_sink(const Field& beta_x, const Field& beta_y, Sides sides, const Grid& g, Field& sink);


}  // namespace refmap
