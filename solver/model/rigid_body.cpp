#include "solver/model/rigid_body.hpp"

#include <algorithm>
#include <cmath>

#include "solver/io/checkpoint_io.hpp"
#include "solver/model/shape.hpp"
#include "solver/model/solid.hpp"

namespace refmap {


// ---------------------------------------------------------------------------- path

RigidPath::RigidPath(const std::string& x, const std::string& y, const std::string& rate)
    : x_(x), y_(y), w_(rate) {}

std::array<double, 2> RigidPath::centre(double t) const { return {x_.eval(0, 0, t), y_.eval(0, 0, t)}; }

std::array<double, 2> RigidPath::velocity(double t) const {
  const double h = 1e-6 * std::max(1.0, std::abs(t));
  const auto a = centre(t - h), b = centre(t + h);
  return {(b[0] - a[0]) / (2 * h), (b[1] - a[1]) / (2 * h)};
}

double RigidPath::rate(double t) const { return w_.eval(0, 0, t); }

double RigidPath::angle(double t0, double t1) const {
  return (t1 - t0) / 6.0 * (rate(t0) + 4.0 * rate(0.5 * (t0 + t1)) + rate(t1));
}

// ---------------------------------------------------------------------------- pose

std::array<double, 2> RigidPose::xi(double x, double y) const {
  const double c = std::cos(theta), s = std::sin(theta), dx = x - cx, dy = y - cy;
  return {c0x + c * dx + s * dy, c0y - s * dx + c * dy};  // c0 + R(-theta)(x - c)
}

std::array<double, 2> RigidPose::velocity(double x, double y) const {
  return {u - omega * (y - cy), v + omega * (x - cx)};
}

// ---------------------------------------------------------------------------- bodies

bool RigidBodies::needed(const Config& cfg) {
  for (const SolidSpec& s : cfg.solids)
    if (s.rigid()) return true;
  return false;
}

RigidBodies::RigidBodies(const Config& cfg) : specs_(cfg.solids), t0_(cfg.t_start) {
  const std::size_t n = specs_.size();
  paths_.resize(n);
  pose_.resize(n);
  load_.resize(n);
  region_change_.assign(n, {0.0, 0.0, 0.0});
  held_.assign(n, {0.0, 0.0, 0.0});
  end_.resize(n);
  region_.resize(n);
  aperture_faces_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const SolidSpec& s = specs_[k];
    RigidPose& p = pose_[k];
    p.c0x = p.cx = s.shape.cx;
    p.c0y = p.cy = s.shape.cy;
    if (s.motion == SolidMotion::Prescribed) {
      paths_[k] = RigidPath(s.path_x, s.path_y, s.rotation_rate);
      const auto c = paths_[k].centre(t0_);  // equals the centre (checked at load)
      const auto w = paths_[k].velocity(t0_);
      p.c0x = p.cx = c[0];
      p.c0y = p.cy = c[1];
      p.u = w[0];
      p.v = w[1];
      p.omega = paths_[k].rate(t0_);
    } else if (s.motion == SolidMotion::Pinned) {
      p.c0x = p.cx = s.pivot_x;
      p.c0y = p.cy = s.pivot_y;
      p.omega = s.omega;
    }
  }
}

void RigidBodies::advance(double t, double dt) {
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    RigidPose& p = pose_[k];
    switch (specs_[k].motion) {
      case SolidMotion::Free:
      case SolidMotion::Fixed: break;
      case SolidMotion::Prescribed: {
        const RigidPath& path = paths_[k];
        const auto c = path.centre(t + dt);
        const auto w = path.velocity(t + dt);
        p.cx = c[0];
        p.cy = c[1];
        p.u = w[0];
        p.v = w[1];
        p.theta += path.angle(t, t + dt);
        p.omega = path.rate(t + dt);
        break;
      }
      case SolidMotion::Pinned: p.theta += dt * p.omega; break;
    }
  }
}

void RigidBodies::place(int k, const std::vector<std::unique_ptr<Solid>>& solids) const {
  const SolidSpec& s = specs_[std::size_t(k)];
  Solid& solid = *solids[std::size_t(k)];
  if (s.rigid()) {
    const RigidPose& p = pose_[std::size_t(k)];
    solid.overwrite_reference_map([&](double x, double y, double& X, double& Y) {
      const auto xi = p.xi(x, y);
      X = xi[0];
      Y = xi[1];
      return true;
    });
  } else if (s.clamp_index >= 0) {
    const RigidPose& p = pose_[std::size_t(s.clamp_index)];
    const Shape& body = solids[std::size_t(s.clamp_index)]->shape();
    solid.overwrite_reference_map([&](double x, double y, double& X, double& Y) {
      const auto xi = p.xi(x, y);
      if (!(body.phi0(xi[0], xi[1]) < 0.0)) return false;  // outside the body: the solid's own
      X = xi[0];
      Y = xi[1];
      return true;
    });
  }
}

namespace {

/// Bilinear interpolation of a cell-centred quantity q(i, j) at (x, y), the stencil clamped
/// to the grid's cells (an image point beyond a wall takes the nearest row); in a periodic
/// direction the (unwrapped) indices are not clamped: q wraps them.
template <class Q>
double bilinear(const Grid& g, const PeriodicWrap& w, double x, double y, Q&& q) {
  const double fx = (x - g.x0) / g.dx - 0.5, fy = (y - g.y0) / g.dx - 0.5;
  int i = int(std::floor(fx)), j = int(std::floor(fy));
  double a = fx - i, b = fy - j;
  if (!w.px && i < 0) { i = 0; a = 0.0; }
  if (!w.px && i > g.nx - 2) { i = g.nx - 2; a = 1.0; }
  if (!w.py && j < 0) { j = 0; b = 0.0; }
  if (!w.py && j > g.ny - 2) { j = g.ny - 2; b = 1.0; }
  return (1 - a) * (1 - b) * q(i, j) + a * (1 - b) * q(i + 1, j) + (1 - a) * b * q(i, j + 1) + a * b * q(i + 1, j + 1);
}

/// The exact level set phi0 of a body of shape `shape` at pose `pose` at the point (x, y).
double body_phi(const Shape& shape, const RigidPose& pose, double x, double y) {
  const auto xi = pose.xi(x, y);
  return shape.phi0(xi[0], xi[1]);
}

/// forcing_faces = "aperture": the open (phi > 0) part of grid face (axis, i, j) of a body of
/// shape `shape` at pose `pose`, phi linear between the face's ends (the shape's exact phi0
/// there): its fraction a of the face, the centroid (ox, oy) and phi there (phi_o) of the open
/// part, and the centroid (sx, sy) of the closed part (the body's velocity there: its mean over
/// the closed part for a rigid motion).
FaceOpening face_opening(const Shape& shape, const RigidPose& pose, const Grid& g, int axis, int i, int j) {
  double x1, y1, x2, y2;
  if (axis == 0) {
    x1 = x2 = g.xf(i);
    y1 = g.yc(j) - 0.5 * g.dx;
    y2 = y1 + g.dx;
  } else {
    y1 = y2 = g.yf(j);
    x1 = g.xc(i) - 0.5 * g.dx;
    x2 = x1 + g.dx;
  }
  const double p1 = body_phi(shape, pose, x1, y1), p2 = body_phi(shape, pose, x2, y2);
  FaceOpening o;
  o.ox = o.sx = 0.5 * (x1 + x2);
  o.oy = o.sy = 0.5 * (y1 + y2);
  if (p1 <= 0.0 && p2 <= 0.0) return o;  // closed
  if (p1 >= 0.0 && p2 >= 0.0) {          // open over its whole length
    o.a = 1.0;
    o.phi_o = 0.5 * (p1 + p2);
    return o;
  }
  const double t = p1 / (p1 - p2);  // the zero crossing, from end 1
  const double xz = x1 + t * (x2 - x1), yz = y1 + t * (y2 - y1);
  const bool first_open = p1 > 0.0;
  const double xo = first_open ? x1 : x2, yo = first_open ? y1 : y2;  // the open end
  const double xs = first_open ? x2 : x1, ys = first_open ? y2 : y1;  // the closed end
  o.a = first_open ? t : 1.0 - t;
  o.ox = 0.5 * (xo + xz);
  o.oy = 0.5 * (yo + yz);
  o.phi_o = 0.5 * std::max(p1, p2);
  o.sx = 0.5 * (xs + xz);
  o.sy = 0.5 * (ys + yz);
  return o;
}

}  // namespace

std::array<double, 2> normal_profile_weights(double phi, double h, ForcingInterpolation order) {
  // u(phi) = u_b + c1 (u(phi + h) - u_b) + c2 (u(phi + 2h) - u_b): Lagrange through the
  // distances 0, d1 = phi + h, d2 = phi + 2h along the normal, at phi
  if (order == ForcingInterpolation::Linear) return {phi / (phi + h), 0.0};
  return {2.0 * phi / (phi + h), -phi / (phi + 2.0 * h)};
}

double RigidBodies::weight(int k, const Solid& s, int i, int j, double inv_dx) const {
  // the forcing weight of a cell: chi (diffuse) or 1 where the cell centre is inside
  // (interpolated); the moment of inertia and angular momentum of a pinned body use it
  const double phi = s.phi()(i, j);
  if (specs_[std::size_t(k)].forcing != BodyForcing::Diffuse) return phi < 0.0 ? 1.0 : 0.0;
  return std::clamp(0.5 - phi * inv_dx, 0.0, 1.0);
}

void RigidBodies::force(const std::vector<std::unique_ptr<Solid>>& solids, Field& u_grid, Field& v_grid,
                        const Field& rho_grid, const Field& gxf, const Field& gyf, const Field& p_old, const Grid& g,
                        double dt) {
  const double a = g.dx * g.dx, inv_dx = 1.0 / g.dx;
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!specs_[k].rigid()) continue;
    const Solid& s = *solids[k];
    // window cells are unwrapped indices (solver/model/periodic_window.hpp): the global fields at
    // their grid cell, the positions g.xc(gi), g.yc(gj) unwrapped like the pose
    const PeriodicWrap& W = s.wrap();
    auto u = [&](int gi, int gj) -> double& { return u_grid(W.i(gi), W.j(gj)); };
    auto v = [&](int gi, int gj) -> double& { return v_grid(W.i(gi), W.j(gj)); };
    auto rho = [&](int gi, int gj) { return rho_grid(W.i(gi), W.j(gj)); };
    auto gcx = [&](int gi, int gj) { return 0.5 * (gxf(W.i(gi), W.j(gj)) + gxf(W.i(gi) + 1, W.j(gj))); };
    auto gcy = [&](int gi, int gj) { return 0.5 * (gyf(W.i(gi), W.j(gj)) + gyf(W.i(gi), W.j(gj) + 1)); };
    RigidPose& p = pose_[k];
    const bool sharp = specs_[k].forcing != BodyForcing::Diffuse;  // interpolated or sharp
    // the cells of the body region (weight w > 0): chi = clamp(1/2 - phi/dx, 0, 1), the
    // sub-cell area fraction of phi < 0 (as in the solid diagnostics), for the diffuse
    // forcing -- not 1 - H(phi) of eq. (3.5): the forcing is repeated every step, so every
    // cell with chi > 0 ends up moving with the body and the effective surface sits at the
    // edge of chi's support, phi = w_T with the smoothed Heaviside (the circular Couette
    // torque 26% high at R1 = 9.6 dx), phi = dx/2 here (3% low; tests/test_bodies.cpp).
    // Interpolated: w = 1 where the cell centre is inside (phi < 0).
    auto each = [&](auto&& f) {
      for (int j = 0; j < s.nj(); ++j)
        for (int i = 0; i < s.ni(); ++i) {
          const double w = weight(int(k), s, i, j, inv_dx);
          if (w <= 0.0) continue;
          const int gi = s.i0() + i, gj = s.j0() + j;
          f(gi, gj, w, rho(gi, gj), g.xc(gi) - p.cx, g.yc(gj) - p.cy, gcx(gi, gj), gcy(gi, gj));
        }
    };
    if (specs_[k].motion == SolidMotion::Pinned) {
      // the rigid rotation with the angular momentum of the region (no torque from the forcing)
      double num = 0.0, den = 0.0;
      each([&](int gi, int gj, double w, double r, double rx, double ry, double gx, double gy) {
        const double ux = u(gi, gj) - dt * gx, uy = v(gi, gj) - dt * gy;
        num += r * w * (rx * uy - ry * ux);
        den += r * w * (rx * rx + ry * ry);
      });
      if (den > 0.0) p.omega = num / den;
    }
    double dmx = 0, dmy = 0, dl = 0;  // the momentum the forcing adds
    if (specs_[k].forcing_hold) {  // the hold took held_[k] out already (add_held)
      dmx = -held_[k][0];
      dmy = -held_[k][1];
      dl = -held_[k][2];
      held_[k] = {0.0, 0.0, 0.0};
    }
    std::vector<std::pair<int, int>> touched;  // interpolated: the forced cells
    auto apply = [&](int gi, int gj, double tu, double tv, double c) {  // u <- u + c (target - u)
      const double r = rho(gi, gj), rx = g.xc(gi) - p.cx, ry = g.yc(gj) - p.cy;
      const double du = c * (tu - u(gi, gj)), dv = c * (tv - v(gi, gj));
      u(gi, gj) += du;
      v(gi, gj) += dv;
      dmx += r * du;
      dmy += r * dv;
      dl += r * (rx * dv - ry * du);
    };
    if (!sharp) {
      // u <- chi u_t + (1 - chi) u, u_t = u_body + dt G_c
      each([&](int gi, int gj, double chi, double, double rx, double ry, double gx, double gy) {
        apply(gi, gj, p.u - p.omega * ry + dt * gx, p.v + p.omega * rx + dt * gy, chi);
      });
    } else {
      // Sharp interpolated forcing (Fadlun et al. 2000; Balaras 2004): a cell whose centre
      // is inside takes u_body + dt G_c; a fluid cell with a neighbour inside (the interface
      // cells) takes the velocity linearly interpolated along the normal n = grad phi between
      // the surface point x_s = x - phi n (the body's velocity) and the image point
      // x_i = x + h n (h = sqrt(2) dx: for a convex body the image's bilinear stencil has no
      // cell inside), u = u_b(x_s) + phi/(phi + h) (q(x_i) - u_b(x_s)), plus dt G_c for the
      // projection to subtract, as inside. q is the velocity after the projection to come:
      // u - dt G_c for a cell that is not forced, the value the last step's forcing left for
      // after its projection for a forced one (its present value is the forcing's, not the
      // flow's), so a steady state is the same for every dt. No cell is relaxed by a fraction: nothing slips by O(dt), and
      // the no-slip surface is at phi = 0 to second order in dx.
      const int ni = s.ni(), nj = s.nj(), i0 = s.i0(), j0 = s.j0();
      auto phi = [&](int i, int j) { return s.phi()(i, j); };
      auto inside = [&](int i, int j) { return i >= 0 && j >= 0 && i < ni && j < nj && phi(i, j) < 0.0; };
      auto forced = [&](int gi, int gj) {
        const int i = gi - i0, j = gj - j0;
        if (i < 0 || j < 0 || i >= ni || j >= nj) return false;
        return inside(i, j) || inside(i - 1, j) || inside(i + 1, j) || inside(i, j - 1) || inside(i, j + 1);
      };
      const EndVelocity E = end_[k];  // the last step's (end_[k] is replaced below)
      auto stored = [&](int gi, int gj, int c, double& out) {
        const int i = gi - E.i0, j = gj - E.j0;
        if (E.u.empty() || i < 0 || j < 0 || i >= E.ni || j >= E.nj) return false;
        out = (c == 0 ? E.u : E.v)[std::size_t(j) * std::size_t(E.ni) + std::size_t(i)];
        return !std::isnan(out);
      };
      // q from the field before any cell of this body is changed
      auto q = [&](int c) {
        return [&, c](int gi, int gj) {
          double out;
          if (forced(gi, gj) && stored(gi, gj, c, out)) return out;
          return c == 0 ? u(gi, gj) - dt * gcx(gi, gj) : v(gi, gj) - dt * gcy(gi, gj);
        };
      };
      struct Target { int gi, gj; double tu, tv; };
      std::vector<Target> targets;
      const double h = std::sqrt(2.0) * g.dx;
      const bool quadratic = specs_[k].forcing_interpolation == ForcingInterpolation::Quadratic;
      for (int j = 0; j < nj; ++j)
        for (int i = 0; i < ni; ++i) {
          const int gi = i0 + i, gj = j0 + j;
          if (!forced(gi, gj)) continue;
          const double x = g.xc(gi), y = g.yc(gj), ph = phi(i, j);
          double tu, tv;
          if (ph < 0.0) {
            const auto ub = p.velocity(x, y);
            tu = ub[0];
            tv = ub[1];
          } else {
            const int il = std::max(i - 1, 0), ir = std::min(i + 1, ni - 1);
            const int jl = std::max(j - 1, 0), jr = std::min(j + 1, nj - 1);
            double nx = (phi(ir, j) - phi(il, j)) / ((ir - il) * g.dx);
            double ny = (phi(i, jr) - phi(i, jl)) / ((jr - jl) * g.dx);
            const double nn = std::hypot(nx, ny);
            if (!(nn > 1e-12)) continue;
            nx /= nn;
            ny /= nn;
            const auto ub = p.velocity(x - ph * nx, y - ph * ny);
            const double xi = x + h * nx, yi = y + h * ny;
            if (!quadratic) {
              const double c = ph / (ph + h);
              tu = ub[0] + c * (bilinear(g, W, xi, yi, q(0)) - ub[0]);
              tv = ub[1] + c * (bilinear(g, W, xi, yi, q(1)) - ub[1]);
            } else {
              // forcing_interpolation = "quadratic": the parabola through the surface (distance
              // 0 along the normal), the image point (phi + h) and a second one (phi + 2h),
              // evaluated at the cell (phi); Lagrange weights c1 = 2 phi / (phi + h), c2 = -phi /
              // (phi + 2h) (normal_profile_weights). The linear chord's error at the cell is
              // -(1/2) u_nn phi h: with h = sqrt(2) dx a wall whose profile bends (u_nn != 0, the
              // boundary layer) is imposed as if it sat ~ phi h u_nn / (2 u_n) outside phi = 0,
              // second order in dx but with a large constant (results/validation.md: the
              // cylinder's c_D at 10 and 20 cells per diameter). The second image's stencil is
              // farther out and, for a convex body, has no cell inside either.
              const auto w = normal_profile_weights(ph, h, ForcingInterpolation::Quadratic);
              const double x2 = x + 2.0 * h * nx, y2 = y + 2.0 * h * ny;
              tu = ub[0] + w[0] * (bilinear(g, W, xi, yi, q(0)) - ub[0]) + w[1] * (bilinear(g, W, x2, y2, q(0)) - ub[0]);
              tv = ub[1] + w[0] * (bilinear(g, W, xi, yi, q(1)) - ub[1]) + w[1] * (bilinear(g, W, x2, y2, q(1)) - ub[1]);
            }
          }
          targets.push_back({gi, gj, tu + dt * gcx(gi, gj), tv + dt * gcy(gi, gj)});
        }
      if (specs_[k].forcing == BodyForcing::Sharp && specs_[k].forcing_faces == CutFaces::Aperture) {
        // forcing_faces = "aperture": each cut face carries its mean normal velocity over its
        // length, a u_open + (1 - a) u_body: the flux through its open part (phi > 0), u_open
        // the normal profile of the forced cells (same q, same weights) at the open part's
        // centroid, and the body's through the closed part; impose_cut_faces writes them
        // and the projection corrects them with the coefficient a beta (clear_cut_faces).
        // A cut-cell face flux (the fluid fraction of a face weighting its flux and its Poisson
        // coefficient: Ng, Min & Gibou 2009, J. Comput. Phys. 228, 8807), so that the mass
        // sees the wall on phi = 0, as the forced cells' velocities do, not the staircase.
        auto& F = aperture_faces_[k];
        F.clear();
        const Shape& shape = s.shape();
        auto phi0 = [&](double x, double y) { return body_phi(shape, p, x, y); };
        each_cut_face(solids, g, [&](int kk, int axis, int fi, int fj) {
          if (kk != int(k)) return;
          const FaceOpening o = opening(solids, int(k), g, axis, fi, fj);
          const std::size_t c = std::size_t(axis);
          double val = p.velocity(o.sx, o.sy)[c];
          if (o.a > 0.0) {
            const double e = 1e-4 * g.dx;  // the normal: grad phi0 (the exact distance's)
            double nx = phi0(o.ox + e, o.oy) - phi0(o.ox - e, o.oy), ny = phi0(o.ox, o.oy + e) - phi0(o.ox, o.oy - e);
            const double nn = std::hypot(nx, ny);
            double uo = p.velocity(o.ox, o.oy)[c];
            if (nn > 0.0) {
              nx /= nn;
              ny /= nn;
              const double ph = o.phi_o;
              const double ub = p.velocity(o.ox - ph * nx, o.oy - ph * ny)[c];
              const auto w = normal_profile_weights(ph, h, specs_[k].forcing_interpolation);
              uo = ub + w[0] * (bilinear(g, W, o.ox + h * nx, o.oy + h * ny, q(int(c))) - ub);
              if (w[1] != 0.0) uo += w[1] * (bilinear(g, W, o.ox + 2.0 * h * nx, o.oy + 2.0 * h * ny, q(int(c))) - ub);
            }
            val = o.a * uo + (1.0 - o.a) * val;
          }
          F.push_back({double(axis), double(fi), double(fj), val});
        });
      }
      for (const Target& t : targets) {
        apply(t.gi, t.gj, t.tu, t.tv, 1.0);
        touched.emplace_back(t.gi, t.gj);
      }
      // the velocities the forced cells will have after the projection (if the pressure does
      // not change), read as q by the next step's forcing; NaN: not forced
      EndVelocity& En = end_[k];
      En.i0 = i0;
      En.j0 = j0;
      En.ni = ni;
      En.nj = nj;
      En.u.assign(std::size_t(ni) * std::size_t(nj), std::nan(""));
      En.v.assign(En.u.size(), std::nan(""));
      for (const Target& t : targets) {
        const std::size_t c = std::size_t(t.gj - j0) * std::size_t(ni) + std::size_t(t.gi - i0);
        En.u[c] = t.tu - dt * gcx(t.gi, t.gj);
        En.v[c] = t.tv - dt * gcy(t.gi, t.gj);
      }
    }
    // F = (-(momentum the forcing added) + (change of the region's momentum)) / dt. The
    // region R is every cell the forcing changes now (weight 1, not chi); the change is
    // taken cell by cell over these same cells, from the previous step's value, so a cell
    // that enters or leaves R as the body moves carries no momentum in or out with it. The
    // velocities are those the projection will leave if the pressure does not change, u -
    // dt G_c, not the body's: the partly forced cells keep a slip that the next step's
    // forcing takes back; that momentum was lent by this step's forcing, and counting it
    // here makes the force the same for a short step as for a full one (it was not: a step
    // cut short to land on an end time divided the previous step's slip by its own dt; with
    // weight chi a part (1 - chi)^2 of it stayed). Not with the velocities after the
    // projection: its pressure increment removes the forcing's divergence in the band by an
    // impulse that does not scale with dt.
    RegionState& Q = region_[k];
    const int ni = s.ni(), nj = s.nj(), i0 = s.i0(), j0 = s.j0();
    auto before = [&](int gi, int gj, int c, double now) {  // the cell's value one step ago
      const int i = gi - Q.i0, j = gj - Q.j0;
      if (Q.u.empty() || i < 0 || j < 0 || i >= Q.ni || j >= Q.nj) {
        if (have_region_) return now;  // outside the last window: not forced, no change counted
        const auto ub = p.velocity(g.xc(gi), g.yc(gj));  // the first step: the body's velocity
        return ub[std::size_t(c)];
      }
      return (c == 0 ? Q.u : Q.v)[std::size_t(j) * std::size_t(Q.ni) + std::size_t(i)];
    };
    double mx = 0, my = 0, ml = 0;
    auto region = [&](int gi, int gj) {
      const double r = rho(gi, gj), rx = g.xc(gi) - p.cx, ry = g.yc(gj) - p.cy;
      const double qx = u(gi, gj) - dt * gcx(gi, gj), qy = v(gi, gj) - dt * gcy(gi, gj);
      const double dx_ = qx - before(gi, gj, 0, qx), dy_ = qy - before(gi, gj, 1, qy);
      mx += r * dx_;
      my += r * dy_;
      ml += r * (rx * dy_ - ry * dx_);
    };
    if (sharp) {
      for (const auto& c : touched) region(c.first, c.second);
    } else {
      each([&](int gi, int gj, double, double, double, double, double, double) { region(gi, gj); });
    }
    // this step's values over the whole window, for the next step
    Q.i0 = i0;
    Q.j0 = j0;
    Q.ni = ni;
    Q.nj = nj;
    Q.u.resize(std::size_t(ni) * std::size_t(nj));
    Q.v.resize(Q.u.size());
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        const int gi = i0 + i, gj = j0 + j;
        Q.u[std::size_t(j) * std::size_t(ni) + std::size_t(i)] = u(gi, gj) - dt * gcx(gi, gj);
        Q.v[std::size_t(j) * std::size_t(ni) + std::size_t(i)] = v(gi, gj) - dt * gcy(gi, gj);
      }
    const std::array<double, 3> dm = {mx * a, my * a, ml * a};
    BodyLoad& L = load_[k];
    L.fx = (-dmx * a + dm[0]) / dt;
    L.fy = (-dmy * a + dm[1]) / dt;
    L.torque = (-dl * a + dm[2]) / dt;
    region_change_[k] = dm;
    if (specs_[k].forcing == BodyForcing::Sharp) {
      // the pressure does not act across the cut faces, so the pressure difference across
      // the body never reaches the forced cells' momentum: add it, per cut face with a fluid
      // side the pressure on it times the face (momentum balance: the sum of rho G_c dx^2 over
      // all cells telescopes to the domain's boundary, minus p across the body at the fluid
      // cells, plus G_f of the cut faces)
      double px = 0, py = 0, pl = 0;
      auto inside = [&](int gi, int gj) {
        const int i = gi - s.i0(), j = gj - s.j0();
        return i >= 0 && j >= 0 && i < s.ni() && j < s.nj() && s.phi()(i, j) < 0.0;
      };
      each_cut_face(solids, g, [&](int kk, int axis, int i, int j) {
        if (kk != int(k)) return;
        const int li = axis == 0 ? i - 1 : i, lj = axis == 0 ? j : j - 1;  // the cell below the face
        const bool lin = inside(li, lj), hin = inside(i, j);
        if (lin == hin) return;  // between two inside cells
        // (a face with one inside cell is visited once)
        // the fluid's pressure extrapolated by G_f of the cut face (cut_face_accel) over dx
        // into the body, as the cell corrections of the step apply it (so the force is that
        // which the discrete momentum equation exerts)
        const double gc = (axis == 0 ? gxf : gyf)(i, j);
        const double f = lin ? -(p_old(i, j) - rho(i, j) * gc * g.dx) * g.dx
                             : (p_old(li, lj) + rho(li, lj) * gc * g.dx) * g.dx;  // along the axis
        const double fx = axis == 0 ? f : 0.0, fy = axis == 0 ? 0.0 : f;
        const double rx = (axis == 0 ? g.xf(i) : g.xc(i)) - p.cx, ry = (axis == 0 ? g.yc(j) : g.yf(j)) - p.cy;
        px += fx;
        py += fy;
        pl += rx * fy - ry * fx;
      });
      L.fx += px;
      L.fy += py;
      L.torque += pl;
    }
  }
  have_region_ = true;
}

// ---------------------------------------------------------------------------- sharp forcing

bool RigidBodies::holds() const {
  for (const SolidSpec& s : specs_)
    if (s.rigid() && s.forcing_hold) return true;
  return false;
}

void RigidBodies::held_cells(const std::vector<std::unique_ptr<Solid>>& solids, const Grid& g,
                             std::vector<std::array<int, 3>>& out) const {
  out.clear();
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!specs_[k].rigid() || !specs_[k].forcing_hold) continue;
    const Solid& s = *solids[k];
    const int ni = s.ni(), nj = s.nj();
    auto in = [&](int i, int j) { return i >= 0 && j >= 0 && i < ni && j < nj && s.phi()(i, j) < 0.0; };
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        if (!(in(i, j) || in(i - 1, j) || in(i + 1, j) || in(i, j - 1) || in(i, j + 1))) continue;
        const int gi = s.wrap().i(s.i0() + i), gj = s.wrap().j(s.j0() + j);
        if (gi < 0 || gj < 0 || gi >= g.nx || gj >= g.ny) continue;
        out.push_back({gi, gj, int(k)});
      }
  }
}

void RigidBodies::add_held(int k, int i, int j, double mx, double my, const Grid& g) {
  const RigidPose& p = pose_[std::size_t(k)];
  // (a "sharp" body does not cross a periodic side: grid positions are the body's)
  const double rx = g.xc(i) - p.cx, ry = g.yc(j) - p.cy;
  auto& h = held_[std::size_t(k)];
  h[0] += mx;
  h[1] += my;
  h[2] += rx * my - ry * mx;
}

bool RigidBodies::cuts_faces() const {
  for (const SolidSpec& s : specs_)
    if (s.rigid() && s.forcing == BodyForcing::Sharp) return true;
  return false;
}

template <class F>
void RigidBodies::each_cut_face(const std::vector<std::unique_ptr<Solid>>& solids, const Grid& g, F&& f) const {
  // the faces of the cells whose centre is inside (phi < 0) a body with forcing = "sharp":
  // f(k, axis, i, j) for x-face (i, j) (axis 0, between cells i - 1 and i) or y-face (i, j)
  // (axis 1, between rows j - 1 and j); domain boundary faces are left to the boundary
  // conditions. A face shared by two inside cells is visited twice (f is idempotent).
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!specs_[k].rigid() || specs_[k].forcing != BodyForcing::Sharp) continue;
    const Solid& s = *solids[k];
    for (int j = 0; j < s.nj(); ++j)
      for (int i = 0; i < s.ni(); ++i) {
        if (!(s.phi()(i, j) < 0.0)) continue;
        const int gi = s.i0() + i, gj = s.j0() + j;
        // the cut faces are written at unwrapped indices: a body whose inside reaches past a
        // periodic side (solver/model/periodic_window.hpp) is not supported by this forcing yet
        if (gi < 0 || gi >= g.nx || gj < 0 || gj >= g.ny)
          throw std::runtime_error("solid '" + s.spec().name +
                                   "': forcing = \"sharp\" does not yet support a body across a periodic side");
        if (gi > 0) f(int(k), 0, gi, gj);
        if (gi + 1 < g.nx) f(int(k), 0, gi + 1, gj);
        if (gj > 0) f(int(k), 1, gi, gj);
        if (gj + 1 < g.ny) f(int(k), 1, gi, gj + 1);
      }
  }
}

void RigidBodies::clear_cut_faces(const std::vector<std::unique_ptr<Solid>>& solids, Field& fx, Field& fy,
                                  const Grid& g) const {
  each_cut_face(solids, g, [&](int k, int axis, int i, int j) {
    // "staircase": closed; "aperture": times the face's open fraction (a cut cell's face)
    if (specs_[std::size_t(k)].forcing_faces == CutFaces::Aperture)
      (axis == 0 ? fx : fy)(i, j) *= opening(solids, k, g, axis, i, j).a;
    else
      (axis == 0 ? fx : fy)(i, j) = 0.0;
  });
}

bool RigidBodies::inside(const std::vector<std::unique_ptr<Solid>>& solids, int k, int gi, int gj) const {
  const Solid& s = *solids[std::size_t(k)];
  const int i = gi - s.i0(), j = gj - s.j0();
  return i >= 0 && j >= 0 && i < s.ni() && j < s.nj() && s.phi()(i, j) < 0.0;
}

FaceOpening RigidBodies::opening(const std::vector<std::unique_ptr<Solid>>& solids, int k, const Grid& g, int axis,
                                 int i, int j) const {
  // forcing_faces = "aperture": the open part of cut face (axis, i, j). Only a face between a
  // cell inside and a fluid cell opens: one between two cells inside stays closed (a = 0, a
  // corner sliver), so every inside cell that joins the pressure solve borders a fluid cell
  // and no group of inside cells is an island of the solve, whose imposed fluxes need not
  // balance (a translating disc blew up so at 10 cells per diameter)
  const int li = axis == 0 ? i - 1 : i, lj = axis == 0 ? j : j - 1;
  if (inside(solids, k, li, lj) && inside(solids, k, i, j)) return {};
  const FaceOpening o = face_opening(solids[std::size_t(k)]->shape(), pose_[std::size_t(k)], g, axis, i, j);
  // a sliver (a < 1e-2) stays closed too: its flux is O(a^2) of a face's (the velocity on it
  // is O(a dx) from the wall), and a cell joined to the solve by such a face alone has a
  // near-singular row the multigrid did not converge on (a translating and turning disc)
  if (o.a < 1e-2) return {};
  return o;
}

void RigidBodies::cut_face_accel(const std::vector<std::unique_ptr<Solid>>& solids, Field& gx, Field& gy,
                                 const Grid& g) const {
  // G_f on a cut face: that of the open face across the fluid cell it borders (the one-sided
  // gradient, as for an inflow face in kernels/projection.cpp), 0 between two inside cells.
  // So the cell correction (eq. 5.7, the mean of the cell's two faces) of a fluid cell at the
  // surface carries its whole pressure gradient, as its forcing target's dt G_c does. Measured
  // on the cylinder at 10 cells per diameter (results/README.md): G = 0 on the cut faces, this,
  // and the linear extrapolation 2 G_1 - G_2 give c_D 5.731, 5.714, 5.690 and the same change
  // at dt/2 (-0.07 %, -0.07 %, -0.16 %); L_a 0.0707, 0.0689, 0.0658.
  // Two passes: every cut face is cleared first, so a face read is never a cut one.
  each_cut_face(solids, g, [&](int, int axis, int i, int j) { (axis == 0 ? gx : gy)(i, j) = 0.0; });
  struct Copy { int axis, i, j, si, sj; };
  std::vector<Copy> copies;
  each_cut_face(solids, g, [&](int k, int axis, int i, int j) {
    const int li = axis == 0 ? i - 1 : i, lj = axis == 0 ? j : j - 1;  // the cell below the face
    const bool lin = inside(solids, k, li, lj), hin = inside(solids, k, i, j);
    if (lin == hin) return;
    // the fluid cell's other face along the axis (a face of the grid: a boundary face keeps its G)
    const int oi = axis == 0 ? (lin ? i + 1 : i - 1) : i, oj = axis == 0 ? j : (lin ? j + 1 : j - 1);
    const int ci = lin ? i : li, cj = lin ? j : lj;  // the fluid cell
    // the other face is cut (G stays 0) if the cell past it is inside
    const int pi = axis == 0 ? (lin ? ci + 1 : ci - 1) : ci, pj = axis == 0 ? cj : (lin ? cj + 1 : cj - 1);
    if (inside(solids, k, pi, pj)) return;
    copies.push_back({axis, i, j, oi, oj});
  });
  for (const Copy& c : copies) (c.axis == 0 ? gx : gy)(c.i, c.j) = (c.axis == 0 ? gx : gy)(c.si, c.sj);
}

void RigidBodies::impose_cut_faces(const std::vector<std::unique_ptr<Solid>>& solids, Field& uf, Field& vf,
                                   const Grid& g) const {
  // the rigid velocity at the face centre: for every cell whose faces are all cut the
  // discrete divergence is exactly zero (u of a rigid motion does not vary along x, v not
  // along y), so the cells inside are a source-free island of the pressure equation
  each_cut_face(solids, g, [&](int k, int axis, int i, int j) {
    const RigidPose& p = pose_[std::size_t(k)];
    if (axis == 0) uf(i, j) = p.velocity(g.xf(i), g.yc(j))[0];
    else vf(i, j) = p.velocity(g.xc(i), g.yf(j))[1];
  });
  // forcing_faces = "aperture": the mean velocity over the face that the last forcing set
  // (before the first forcing: the body's, above)
  // (empty for every other body)
  for (const auto& faces : aperture_faces_)
    for (const auto& f : faces) (f[0] == 0.0 ? uf : vf)(int(f[1]), int(f[2])) = f[3];
}

void RigidBodies::fill_inside_pressure(const std::vector<std::unique_ptr<Solid>>& solids, Field& p,
                                       const Grid& g) const {
  // the cells inside are cut out of the pressure equation, so their p is not the fluid's:
  // set it to the fluid's pressure at the image point a distance h = sqrt(2) dx outside the
  // surface along the normal (dp/dn = 0 at the wall, the boundary-layer approximation), so
  // that a sample at the surface (the cylinder's probes) and a cell uncovered by a moving
  // body read the fluid's pressure. For a convex body the image's bilinear stencil holds no
  // cell inside (as for the interpolated forcing's image points).
  const double h = std::sqrt(2.0) * g.dx;
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!specs_[k].rigid() || specs_[k].forcing != BodyForcing::Sharp) continue;
    const Solid& s = *solids[k];
    const int ni = s.ni(), nj = s.nj();
    auto phi = [&](int i, int j) { return s.phi()(std::clamp(i, 0, ni - 1), std::clamp(j, 0, nj - 1)); };
    struct Ghost { int gi, gj; double value; };
    std::vector<Ghost> ghosts;
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        const double ph = phi(i, j);
        if (!(ph < 0.0)) continue;
        double nx = phi(i + 1, j) - phi(i - 1, j), ny = phi(i, j + 1) - phi(i, j - 1);
        const double nn = std::hypot(nx, ny);
        if (!(nn > 1e-12)) continue;
        nx /= nn;
        ny /= nn;
        const int gi = s.i0() + i, gj = s.j0() + j;
        const double d = h - ph;  // from the cell centre to the image point
        const double xi = g.xc(gi) + d * nx, yi = g.yc(gj) + d * ny;
        ghosts.push_back({gi, gj, bilinear(g, s.wrap(), xi, yi, [&](int a, int b) { return p(a, b); })});
      }
    for (const Ghost& c : ghosts) p(c.gi, c.gj) = c.value;  // after all reads: no inside cell read
  }
}

void RigidBodies::save_state(CheckpointWriter& w) const {
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!specs_[k].rigid()) continue;
    const std::string t = "body" + std::to_string(k) + ".";
    const RigidPose& p = pose_[k];
    for (auto [n, x] : {std::pair{"cx", p.cx}, {"cy", p.cy}, {"theta", p.theta}, {"u", p.u}, {"v", p.v},
                        {"omega", p.omega}, {"fx", load_[k].fx}, {"fy", load_[k].fy}, {"torque", load_[k].torque},
                        {"mx", region_change_[k][0]}, {"my", region_change_[k][1]}, {"ml", region_change_[k][2]}})
      w.put_f64(t + n, x);
    // the last forcing's cell values (region change, interpolated stencil): a restart
    // continues bit for bit
    for (auto [n, W] : {std::pair{"region.", &region_[k]}, {"end.", &end_[k]}}) {
      for (auto [m, x] : {std::pair{"i0", W->i0}, {"j0", W->j0}, {"ni", W->ni}, {"nj", W->nj}})
        w.put_i64(t + n + m, x);
      w.put_f64s(t + n + "u", W->u);
      w.put_f64s(t + n + "v", W->v);
    }
  }
  w.put_i64("bodies.have_momentum", have_region_ ? 1 : 0);
}

void RigidBodies::load_state(CheckpointReader& r) {
  for (std::size_t k = 0; k < specs_.size(); ++k) {
    if (!specs_[k].rigid()) continue;
    const std::string t = "body" + std::to_string(k) + ".";
    RigidPose& p = pose_[k];
    for (auto [n, x] : {std::pair{"cx", &p.cx}, {"cy", &p.cy}, {"theta", &p.theta}, {"u", &p.u}, {"v", &p.v},
                        {"omega", &p.omega}, {"fx", &load_[k].fx}, {"fy", &load_[k].fy},
                        {"torque", &load_[k].torque}, {"mx", &region_change_[k][0]}, {"my", &region_change_[k][1]},
                        {"ml", &region_change_[k][2]}})
      *x = r.get_f64(t + n);
    for (auto [n, W] : {std::pair{"region.", &region_[k]}, {"end.", &end_[k]}}) {
      for (auto [m, x] : {std::pair{"i0", &W->i0}, {"j0", &W->j0}, {"ni", &W->ni}, {"nj", &W->nj}})
        *x = int(r.get_i64(t + n + m));
      W->u = r.get_f64s(t + n + "u");
      W->v = r.get_f64s(t + n + "v");
    }
  }
  have_region_ = r.get_i64("bodies.have_momentum") != 0;
}

}  // namespace refmap
