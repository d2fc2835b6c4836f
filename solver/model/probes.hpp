#pragma once
// Line probes: bilinear samples of a cell-centred field along a segment, written as CSV.
#include <string>

#include "solver/model/config.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"

namespace refmap {

/// Bilinear interpolation of a cell-centred field from the four cell centres around
/// (x, y), USING ghost cells: the caller fills the ghosts from the boundary conditions
/// (a no-slip wall's ghost is minus the interior value, so the interpolated value on the
/// wall is the wall value; a periodic direction's ghosts are copies from the other side).
/// Valid for any point in [x0, x0+lx] x [y0, y0+ly] (walls included); points within
/// 1e-9 dx outside are clamped onto the boundary, points further out throw
/// std::out_of_range. The field needs at least one ghost layer.
double sample_bilinear(const Grid& g, const Field& f, double x, double y);

/// Writes `p.points` samples from (p.x0, p.y0) to (p.x1, p.y1) inclusive, evenly spaced:
/// header "x,y,value", every number with 17 significant digits (%.17g).
/// Throws std::runtime_error if the file cannot be written.
void write_probe_csv(const std::string& path, const ProbeSpec& p, const Grid& g, const Field& f);

}  // namespace refmap
