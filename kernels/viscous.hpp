#pragma once
// Divergence of the Newtonian viscous stress, eq. (2.10) without the pressure:
//     tau = mu (grad u + grad u^T),  f = div tau,
// in flux form on cell faces (so the blended/conservative form telescopes): normal
// stresses use the compact face difference, tangential stresses the compact normal
// difference plus the average of the two cells' central differences. mu is a cell field
// (blended fluid/solid viscosity), averaged arithmetically to faces. u, v and mu need one
// ghost layer filled (including corners).
#include "core/field.hpp"

namespace refmap {

void viscous_force(CView u, CView v, CView mu, View fx, View fy, int nx, int ny, double dx);

/// Explicit split viscous step of eq. (5.2): u += dt * fx / rho, v += dt * fy / rho.
void apply_force(View u, View v, CView fx, CView fy, CView rho, double dt, int nx, int ny);

}  // namespace refmap
