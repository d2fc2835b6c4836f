// The boundary treatment of the projection (kernels/projection.hpp) per side kind
// (kernels/boundary_kind.hpp), and the map from a scene's boundary conditions to those
// kinds (solver/model/boundary.hpp: face_sides):
//  - wall faces carry no beta, no face acceleration and no normal velocity, before and
//    after the correction;
//  - on a periodic direction face n is face 0 (bit for bit) and is computed from the
//    wrapped neighbours;
//  - the whole approximate projection (predict, divergence, Poisson solve, correct)
//    leaves the face velocities divergence-free to the solver tolerance with every
//    combination of walls and periodic directions, which needs beta, the Poisson operator
//    and the correction to agree on each side.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "kernels/boundary_kind.hpp"
#include "kernels/projection.hpp"
#include "solver/model/boundary.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/pressure/poisson.hpp"

using namespace refmap;

namespace {

std::array<SideBc, 4> bcs(bool px, bool py) {
  std::array<SideBc, 4> bc{};
  bc[Left].type = bc[Right].type = px ? BcType::Periodic : BcType::NoSlip;
  bc[Bottom].type = py ? BcType::Periodic : BcType::FreeSlip;
  bc[Top].type = py ? BcType::Periodic : BcType::MovingWall;
  bc[Top].velocity = py ? 0.0 : 0.7;
  return bc;
}

struct Faces {
  int nx, ny;
  double dx = 0.1, dt = 0.05;
  Field rho, u, v, p, dp, rhs, bx, by, gx, gy, uf, vf;
  Faces(int nx_, int ny_) : nx(nx_), ny(ny_) {
    for (Field* f : {&rho, &u, &v, &p, &dp, &rhs}) f->resize(nx, ny, Grid::ng);
    for (Field* f : {&bx, &gx, &uf}) f->resize(nx + 1, ny, Grid::ng);
    for (Field* f : {&by, &gy, &vf}) f->resize(nx, ny + 1, Grid::ng);
  }
};

/// Random density (1..3), velocity and pressure with ghosts filled for the boundary
/// conditions bc; beta, the face acceleration (with gravity) and the predicted face
/// velocity computed for sides.
void predict(Faces& F, const std::array<SideBc, 4>& bc, Sides sides, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int j = 0; j < F.ny; ++j)
    for (int i = 0; i < F.nx; ++i) {
      F.rho(i, j) = 2.0 + U(rng);
      F.u(i, j) = U(rng);
      F.v(i, j) = U(rng);
      F.p(i, j) = U(rng);
    }
  fill_scalar_ghosts(F.rho, bc);
  fill_scalar_ghosts(F.p, bc);
  fill_vector_ghosts(F.u, F.v, bc, 0.0);
  face_beta(F.rho.view(), F.bx.view(), F.by.view(), F.nx, F.ny, sides);
  face_accel(F.p.view(), F.bx.view(), F.by.view(), F.gx.view(), F.gy.view(), F.nx, F.ny, F.dx,
             0.3, -9.8, 1.0, sides);
  predict_face_velocity(F.u.view(), F.v.view(), F.gx.view(), F.gy.view(), F.uf.view(),
                        F.vf.view(), F.nx, F.ny, F.dt, sides);
}

/// Wall faces are 0; periodic face n equals face 0 exactly.
void expect_boundary_faces(const Faces& F, Sides sides, const char* stage) {
  for (const Field* f : {&F.bx, &F.gx, &F.uf})
    for (int j = 0; j < F.ny; ++j) {
      if (sides.periodic_x()) {
        EXPECT_EQ((*f)(F.nx, j), (*f)(0, j)) << stage << " j=" << j;
      } else {
        EXPECT_EQ((*f)(0, j), 0.0) << stage << " j=" << j;
        EXPECT_EQ((*f)(F.nx, j), 0.0) << stage << " j=" << j;
      }
    }
  for (const Field* f : {&F.by, &F.gy, &F.vf})
    for (int i = 0; i < F.nx; ++i) {
      if (sides.periodic_y()) {
        EXPECT_EQ((*f)(i, F.ny), (*f)(i, 0)) << stage << " i=" << i;
      } else {
        EXPECT_EQ((*f)(i, 0), 0.0) << stage << " i=" << i;
        EXPECT_EQ((*f)(i, F.ny), 0.0) << stage << " i=" << i;
      }
    }
}

}  // namespace

TEST(Projection, FaceSidesFromBoundaryConditions) {
  const Sides walls = face_sides(bcs(false, false));
  for (FaceKind k : walls.kind) EXPECT_EQ(k, FaceKind::Wall);  // no-slip, free-slip, moving
  EXPECT_FALSE(walls.periodic_x());
  EXPECT_FALSE(walls.periodic_y());
  const Sides px = face_sides(bcs(true, false));
  EXPECT_EQ(px[Left], FaceKind::Periodic);
  EXPECT_EQ(px[Right], FaceKind::Periodic);
  EXPECT_EQ(px[Bottom], FaceKind::Wall);
  EXPECT_EQ(px[Top], FaceKind::Wall);
  EXPECT_TRUE(px.periodic(0));
  EXPECT_FALSE(px.periodic(1));
  EXPECT_EQ(px, Sides::walls_or_periodic(true, false));
  EXPECT_EQ(face_sides(bcs(false, true)), Sides::walls_or_periodic(false, true));
  EXPECT_EQ(face_sides(bcs(true, true)), Sides::walls_or_periodic(true, true));
}

TEST(Projection, PeriodicBoundaryFaceUsesWrappedNeighbours) {
  Faces F(7, 5);
  const auto bc = bcs(true, true);
  const Sides sides = face_sides(bc);
  predict(F, bc, sides, 3);
  for (int j = 0; j < F.ny; ++j)
    EXPECT_EQ(F.bx(0, j), 2.0 / (F.rho(F.nx - 1, j) + F.rho(0, j))) << j;
  for (int i = 0; i < F.nx; ++i)
    EXPECT_EQ(F.by(i, 0), 2.0 / (F.rho(i, F.ny - 1) + F.rho(i, 0))) << i;
  for (int j = 0; j < F.ny; ++j)
    EXPECT_NEAR(F.uf(0, j), 0.5 * (F.u(F.nx - 1, j) + F.u(0, j)) - F.dt * F.gx(0, j), 1e-15);
}

TEST(Projection, EverySideCombinationProjectsToZeroDivergence) {
  for (auto [px, py] : {std::pair{false, false}, std::pair{true, false}, std::pair{false, true},
                        std::pair{true, true}}) {
    SCOPED_TRACE(std::string("px=") + (px ? "1" : "0") + " py=" + (py ? "1" : "0"));
    Faces F(12, 9);
    const auto bc = bcs(px, py);
    const Sides sides = face_sides(bc);
    predict(F, bc, sides, 17);
    expect_boundary_faces(F, sides, "predicted");
    face_divergence(F.uf.view(), F.vf.view(), F.rhs.view(), F.nx, F.ny, F.dx, 1.0 / F.dt);
    const double before = max_abs_face_divergence(F.uf.view(), F.vf.view(), F.nx, F.ny, F.dx);
    ASSERT_GT(before, 1.0);  // random data: far from divergence-free

    PoissonOptions opt;
    opt.tol = 1e-13;
    auto solver = make_poisson_solver(opt);
    PoissonOperator op;
    op.grid.nx = F.nx;
    op.grid.ny = F.ny;
    op.grid.dx = F.dx;
    op.sides = sides;
    op.beta_x = &F.bx;
    op.beta_y = &F.by;
    solver->setup(op);
    F.dp.fill(0.0);
    const SolveStats st = solver->solve(F.rhs, F.dp);
    ASSERT_TRUE(st.converged);
    fill_scalar_ghosts(F.dp, bc);
    correct_face_velocity(F.uf.view(), F.vf.view(), F.dp.view(), F.bx.view(), F.by.view(), F.nx,
                          F.ny, F.dx, F.dt, sides);
    expect_boundary_faces(F, sides, "corrected");
    // div u_f after = dt (rhs - A dp): the net boundary flux is 0 on walls and periodic
    // sides, so the zero-mean projection of rhs changes nothing and the relative residual
    // 1e-13 bounds the divergence (2-norm, hence max norm up to sqrt(108) ~ 10)
    const double after = max_abs_face_divergence(F.uf.view(), F.vf.view(), F.nx, F.ny, F.dx);
    EXPECT_LT(after, 1e-11 * before);
  }
}
