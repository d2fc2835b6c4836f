#pragma once
// Rigid and driven bodies, and soft solids clamped to them (docs/bodies.md).
//
// A [[solid]] with motion = "fixed", "prescribed" or "pinned" is a RIGID BODY. The fluid
// sees it through the same blended fields as a soft solid (density and viscosity by eq.
// 3.6 with its smoothed Heaviside); instead of an elastic stress its velocity is IMPOSED:
//
//  * Reference map: set exactly from the pose, xi(x) = c0 + R(-theta)(x - c) on its whole
//    window (no advection, no extrapolation), and phi = phi0(xi) rebuilt as for any solid.
//  * Direct forcing (Uhlmann 2005, J. Comput. Phys. 209): after the momentum advection
//    and the viscous step, with chi = clamp(1/2 - phi/dx, 0, 1) the body's sub-cell area
//    fraction (not the smoothed Heaviside of eq. 3.5: a forcing repeated every step makes
//    the whole support of chi move with the body, and that of 1 - H reaches phi = w_T),
//        u <- chi u_t + (1 - chi) u,   u_t = u_body(x) + dt G_c,
//    G_c the cell average of the face accelerations (pressure gradient of the previous
//    step over rho, gravity, contact) that the predictor (eq. 5.3) and step 9 (eq. 5.7)
//    subtract: so the face velocities predicted inside the body are u_body and, after the
//    projection, the cell velocity there is u_body + dt (G_c^n - G_c^{n+1}), i.e. u_body
//    to O(dt |grad dp|), exactly u_body in a steady state.
//    Divergence: the forced cell field is not divergence-free in the one-cell band
//    |phi| < dx/2 (a blend of two divergence-free fields); the projection removes that,
//    so the face velocities stay exactly divergence-free, and the no-slip surface is
//    located to O(dx) (first order). The density and viscosity still blend with the
//    smoothed Heaviside like any solid's.
//  * Interpolated forcing (forcing = "interpolated"; Fadlun et al. 2000, J. Comput. Phys.
//    161; Balaras 2004, Comput. Fluids 33): sharp -- cells inside (phi < 0) take u_body +
//    dt G_c, the fluid cells next to the surface the velocity interpolated along the
//    normal between the surface and an image point (rigid_body.cpp); no O(dt) slip.
//  * Sharp forcing (forcing = "sharp", not for a pinned body): the interpolated forcing with
//    the cells inside (phi < 0) CUT out of the pressure equation. Their faces carry the body's
//    velocity at the face centre and have beta = 0 and G_f = 0 (no pressure acts across them,
//    the projection does not correct them), so the flux through the body's staircase surface
//    is the body's whatever dt, and the inside cells, whose faces are all fixed and exactly
//    divergence-free for a rigid motion, drop out of the solve. Why: with the other forcings
//    the cells inside are part of the pressure equation with fixed (forced) velocities, so
//    the divergence of the forced field is removed by a pressure that scales as 1/dt (the
//    predictor's Rhie-Chow term is all it can act through), and that pressure leaks into the
//    flow (the interpolated forcing's Delta p grows as dt falls). The fluid's pressure acts on
//    the body through the cut faces only: it is added to the force (p of the fluid cell times
//    the face), and the pressure inside is set from the fluid's at an image point (for output,
//    probes at the surface and cells a moving body uncovers).
//  * Force on the body from the fluid (reported as solidK_fx, solidK_fy, solidK_torque):
//        F = -(1/dt) sum rho (u_new - u_old) dx^2 + (1/dt) Delta sum_R rho (u - dt G_c) dx^2,
//    the momentum the forcing removes per step plus the change of the momentum of the
//    forced cells R as the projection will leave them (docs/bodies.md: so that a step cut
//    short gives the force of a full one); the torque likewise, about the reference point.
//  * fixed: u_body = 0. prescribed: the centre follows path_x(t), path_y(t) (expressions
//    of t; velocity by a centred difference) and the body turns at rotation_rate(t)
//    (theta by Simpson's rule per step). pinned: the pivot is fixed; the rotation rate is
//    the rigid rotation that keeps the angular momentum of the body region about the pivot,
//        Omega = sum rho chi r x u~ / sum rho chi |r|^2   (u~ = u - dt G_c),
//    so the forcing exerts no torque (Sharma & Patankar 2005, J. Comput. Phys. 205: the
//    rigidity constraint), the pin's reaction is the force. The moment of inertia is that
//    of the blended density over the smoothed shape (rho_s inside); the body's own
//    density enters through it, so no added-mass instability at low density ratio.
//
// A CLAMPED soft solid (clamp = "<rigid body>") has its reference map held at the rigid
// map of that body wherever its cell centres lie inside the body (phi_body < 0) — the
// material points there move with the body — after its own advection and extrapolation;
// contact between the two is off (solver/model/contact.cpp).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/model/config.hpp"
#include "solver/io/expression.hpp"

namespace refmap {

class Solid;
class CheckpointWriter;
class CheckpointReader;

/// The prescribed motion of a body: the centre's path and the rotation rate (expressions of t).
class RigidPath {
 public:
  RigidPath() = default;
  RigidPath(const std::string& x, const std::string& y, const std::string& rate);
  std::array<double, 2> centre(double t) const;
  /// d/dt of the path, centred difference (relative step 1e-6: error ~1e-12 |x'''|).
  std::array<double, 2> velocity(double t) const;
  double rate(double t) const;
  /// The angle turned over [t0, t1]: Simpson's rule (exact for rates up to cubic in t).
  double angle(double t0, double t1) const;

 private:
  Expression x_, y_, w_;
};

/// Where a rigid body is: the material point at reference position X sits at
/// x = c + R(theta) (X - c0), so xi(x) = c0 + R(-theta) (x - c).
struct RigidPose {
  double c0x = 0, c0y = 0;  ///< reference point (centre, or the pivot)
  double cx = 0, cy = 0;    ///< where it is now
  double theta = 0;         ///< angle turned since the start, counter-clockwise
  double u = 0, v = 0, omega = 0;  ///< velocity of the reference point and rotation rate
  std::array<double, 2> xi(double x, double y) const;
  std::array<double, 2> velocity(double x, double y) const;
};

/// The weights (c1, c2) by which the interpolated and sharp forcings set a fluid cell at a
/// distance phi > 0 from the surface: u = u_b + c1 (u(phi + h) - u_b) + c2 (u(phi + 2h) - u_b),
/// u_b the body's velocity at the surface point, u(d) the flow's at the image points a distance
/// d from the surface along the normal (h = sqrt(2) dx). Linear: the chord to the first image
/// (c2 = 0); Quadratic: the parabola through all three (exact for u = a n + b n^2).
std::array<double, 2> normal_profile_weights(double phi, double h, ForcingInterpolation order);

/// forcing_faces = "aperture": the open (phi > 0) part of a cut face: its fraction a of the
/// face, its centroid (ox, oy) and phi there, and the centroid (sx, sy) of the closed part.
struct FaceOpening {
  double a = 0, ox = 0, oy = 0, phi_o = 0, sx = 0, sy = 0;
};

/// The fluid's force and torque (about the reference point) on a body at the last step.
struct BodyLoad {
  double fx = 0, fy = 0, torque = 0;
};

class RigidBodies {
 public:
  explicit RigidBodies(const Config& cfg);
  /// True if the scene has a rigid body (else Simulation keeps none of this).
  static bool needed(const Config& cfg);

  bool rigid(int k) const { return specs_[std::size_t(k)].rigid(); }
  const RigidPose& pose(int k) const { return pose_[std::size_t(k)]; }
  const BodyLoad& load(int k) const { return load_[std::size_t(k)]; }

  /// Moves every body from t to t + dt (prescribed: its path; pinned: theta += dt Omega
  /// with the rate of the last forcing). Before the solids are updated.
  void advance(double t, double dt);
  /// Solid k's reference map at the current poses: a rigid body on its whole window; a
  /// clamped soft solid where it lies inside its body. Touches only solid k (call it for
  /// the solids concurrently); reads the other solids' shapes only.
  void place(int k, const std::vector<std::unique_ptr<Solid>>& solids) const;
  /// The direct forcing of every body on the cell velocities (see the header comment);
  /// gxf, gyf: the face accelerations the predictor will use; rho: the new density.
  /// p_old: the pressure of the last step (forcing = "sharp": its force on the cut faces).
  void force(const std::vector<std::unique_ptr<Solid>>& solids, Field& u, Field& v, const Field& rho,
             const Field& gxf, const Field& gyf, const Field& p_old, const Grid& g, double dt);
  /// The change over the last step of sum rho (u - dt G_c) dx^2 over the cells body k's
  /// forcing changed (x, y, angular about its reference point): the force is the momentum
  /// the forcing removed plus this, over dt (docs/bodies.md)
  const std::array<double, 3>& region_change(int k) const { return region_change_[std::size_t(k)]; }

  /// forcing = "sharp" (docs/bodies.md): true if a body has it. The faces of its cells
  /// inside (phi < 0) are CUT: clear_cut_faces zeroes a face field there (the Poisson
  /// coefficients beta and the face accelerations G_f: no pressure acts across them, the
  /// projection leaves them alone), impose_cut_faces sets the face velocities to the body's,
  /// (forcing_faces = "aperture": clear_cut_faces multiplies beta by the face's open fraction
  /// and impose_cut_faces sets the face's mean velocity, the flux of its open part from the
  /// forced cells' profile plus the body's over the rest; inside cells with an open face
  /// then stay in the solve),
  /// fill_inside_pressure sets the pressure of the cells inside from the fluid's.
  bool cuts_faces() const;
  void clear_cut_faces(const std::vector<std::unique_ptr<Solid>>& solids, Field& fx, Field& fy, const Grid& g) const;
  /// G_f of the cut faces: 0, or the fluid cell's one-sided value (rigid_body.cpp).
  void cut_face_accel(const std::vector<std::unique_ptr<Solid>>& solids, Field& gx, Field& gy, const Grid& g) const;
  void impose_cut_faces(const std::vector<std::unique_ptr<Solid>>& solids, Field& uf, Field& vf,
                        const Grid& g) const;
  void fill_inside_pressure(const std::vector<std::unique_ptr<Solid>>& solids, Field& p, const Grid& g) const;

  /// forcing_hold (a "sharp" body): true if a body has it. held_cells lists the cells the
  /// next forcing sets (inside, or with a 4-neighbour inside: force()'s own choice) of every
  /// such body as (i, j, body); the flow solver keeps them at their values of the step's
  /// start through the advection and the viscous step (so the fluid next to them never
  /// sees a forced cell's intermediate value, which moves with dt) and books with add_held
  /// the momentum per unit volume, sum rho du, that the hold took from body k's cells
  /// (and its moment about the reference point); the next force() counts it as momentum
  /// the forcing removed, and clears it.
  bool holds() const;
  void held_cells(const std::vector<std::unique_ptr<Solid>>& solids, const Grid& g,
                  std::vector<std::array<int, 3>>& out) const;
  void add_held(int k, int i, int j, double mx, double my, const Grid& g);

  void save_state(CheckpointWriter& w) const;
  void load_state(CheckpointReader& r);

 private:
  std::vector<SolidSpec> specs_;
  std::vector<RigidPath> paths_;
  std::vector<RigidPose> pose_;
  std::vector<BodyLoad> load_;
  double weight(int k, const Solid& s, int i, int j, double inv_dx) const;
  bool inside(const std::vector<std::unique_ptr<Solid>>& solids, int k, int gi, int gj) const;
  FaceOpening opening(const std::vector<std::unique_ptr<Solid>>& solids, int k, const Grid& g, int axis, int i,
                      int j) const;
  template <class F>
  void each_cut_face(const std::vector<std::unique_ptr<Solid>>& solids, const Grid& g, F&& f) const;
  /// region_change of the last step
  std::vector<std::array<double, 3>> region_change_;
  /// u - dt G_c over each body's window after the last forcing (the region's momentum then)
  struct RegionState {
    int i0 = 0, j0 = 0, ni = 0, nj = 0;
    std::vector<double> u, v;
  };
  std::vector<RegionState> region_;
  /// interpolated forcing: the velocities the last forcing left for after the projection
  using EndVelocity = RegionState;
  std::vector<EndVelocity> end_;
  std::vector<std::array<double, 3>> held_;  ///< add_held's sums of this step (x, y, angular)
  /// forcing_faces = "aperture": each cut face's mean velocity (axis, i, j, value), set by
  /// the last forcing and imposed by impose_cut_faces
  std::vector<std::vector<std::array<double, 4>>> aperture_faces_;
  bool have_region_ = false;  ///< region_ holds a previous step (false before the first)
  double t0_ = 0.0;
};

}  // namespace refmap
