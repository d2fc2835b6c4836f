#pragma once
// Solid-solid and solid-wall contact: a repulsive body force between the zero level sets
// (the fictitious contact force of the RMT, Valkov et al. 2015, which Jain & Mani adopt),
// the gap diagnostics and the contact / restitution event log.
//
// THE FORCE. Every solid i is pushed by a contact pressure p_c that depends only on the
// distance s from the obstacle (another solid j: s = phi_j; a wall: s = distance of the
// cell centre to the wall):
//
//     p_c(s) = P (1 - s/d)^3  for s < d,   0 for s >= d          (d = range * dx)
//
// acting as a traction -p_c n_i on i's boundary, spread over a thin layer just inside i
// (h = 2 dx) by the smooth ramp chi_i = S(-phi_i / h), S(x) = x^2 (3 - 2x) on [0, 1]:
//
//     f_i = p_c(s) grad chi_i          (= -p_c S'/h n_i, n_i the outward normal of i)
//
// discretised on the faces, F_f = (mean of p_c over the two cells of the face) x
// (difference of chi_i across it) / dx, and applied like gravity in the balanced-force face
// accelerations of the projection (G_f -= F_f / rho_f, eqs. 5.3 and 5.7), so the part of
// the force that is a gradient is cancelled exactly by the pressure instead of leaving a
// collocated residual (a cell-centred version of the same force gained energy in contact).
// Why this form:
//  * it is the variation of the potential U = sum chi_i p_c(s) dx^2 (reported as
//    contact_energy): with p_c fixed (a wall), sum_f F_f u_f = -dU/dt for chi advected by
//    the face velocities, so the contact stores and returns energy instead of creating it;
//  * it is normal to i's surface (no friction), zero beyond the range, C^2 at s = d, grows
//    cubically as the gap closes and further for s < 0, so an approach is stopped before
//    the zero level sets cross as long as P exceeds the dynamic pressure of the approach;
//  * it acts only on i's own layer (-h < phi_i < 0 and the face next to it): it never
//    pushes the other solid's material;
//  * equal and opposite: for a pair, the discrete totals F_ij (on i) and F_ji (on j) agree
//    with -each other only to discretisation accuracy; both are replaced by
//    +-Fbar = +-(F_ij - F_ji)/2, per direction, by adding (Fbar - F_ij) w_f / sum w to each
//    face of i's patch (w_f = |F_f|; likewise for j). The correction stays in the contact
//    patch and the pair's total force is zero to round-off, so contact cannot change the
//    total momentum. If one of the two patches is empty (the other solid's surface not
//    yet resolved on a cell within range) the pair exerts no force at that step.
//
// THE STRENGTH does not depend on the solids' stiffness: P = stiffness * rho_max * U^2,
// rho_max the largest density of the scene (fluid or solid) and U a velocity scale:
// contact.velocity_scale if given, else the larger of the scene's own velocity scales --
// the largest initial speed on the grid and the free-fall speed sqrt(2 |g| L) over the
// domain extent L along g -- and the largest centroid speed of any solid seen so far
// (observe, every step; so P never decreases, and U >= the speed at which a solid can
// approach at any time). Not the run's length: U used to fall back to the domain width
// divided by the run time, so the time step depended on time.end even without contact.
// Not the walls' or the inflow's speeds either: a solid at rest in a sheared layer never
// nears a wall, and the limit below (dt ~ 0.1 dx / U) would then bind for nothing. With
// no scale P = 0 until a solid moves. The default stiffness 20 makes p_c(0) 40
// times the stagnation pressure rho_max U^2 / 2 of the fastest approach the scene can
// produce. (An earlier attempt scaled the strength with mu_s: the restitution of a bounce
// then measured the contact law, not the solid.)
//
// THE TIME STEP. The layer is a spring of stiffness dp_c/ds = 3P/d at s = 0 acting on a
// layer of mass rho h per unit area, rho >= (rho_s + rho_f)/2 there: dt <= cfl / omega,
// omega^2 = 2 * 3P / (d rho h) (the factor 2 is a margin for s < 0, where it stiffens);
// contact.cfl = 0.5 by default, a margin of 4 on the explicit spring's limit omega dt < 2.
// That is about 0.1 dx / U, so it bound most steps of every scene with solids although the
// force is zero while every gap exceeds d; it is applied only in a step that can close a
// gap to d (clear_of_contact: a surface moves at most (|u| + |v|)_max dt in a step, since xi
// is advected with the velocity at the step's start).
//
// PERIODIC BOUNDARIES. Contact is computed on the global grid from the solids' windows.
// A solid that spans a periodic direction has a wrapped window (its phi and normals are
// periodic there), so contact with it across that boundary is handled. Any other solid's
// window is in unwrapped index space and may cross a periodic side
// (solver/model/periodic_window.hpp): phi_at finds a solid's phi at any image of a cell, a
// window across a side is visited over the whole period, and pair_gap takes the overlap
// with every image of the other window (the minimal-image displacement). Outside a
// window phi = +band, so contact.range must be < solids.band (checked when the scene is
// loaded).
//
// PAIRS. Only pairs of solids whose windows come within a cell of each other can exert a
// force or have a gap; they are found by cell lists (solver/model/contact_pairs.hpp), in the order
// of the all-pairs loop (a < b, by a then b), so the work per step is O(N) for N solids
// of similar size and the forces keep the bits of that loop. The contact state is kept
// only for the pairs in contact (a sorted list), not as an N x N table.
//
// THREADS. The work is split into tasks -- one per pair of solids whose windows overlap, one
// per solid and wall side within range -- that only read the solids: their face
// contributions and energy terms are computed concurrently (kernels/loop.hpp,
// parallel_items; with many small solids this is a large share of a step), then applied
// to the face fields and summed serially in the task order of a serial run, so the forces
// and contact_energy have the same bits on any number of threads. The gaps of observe()
// likewise: per solid concurrently, the event logic serially.
//
// GAPS (diagnostics). Between solids i and j: min over the cells where both phi_i and
// phi_j are < band of phi_i + phi_j (for exact distance functions phi_i + phi_j >= gap by
// the triangle inequality, with equality on the segment joining the closest points: the
// cell-centre sampling error is O(dx^2 / R)); negative when the zero level sets overlap.
// "No other solid within reach" (no such cell) gives the domain diagonal as a sentinel.
// To a wall: min over the cells with phi_i < band of (distance of the cell centre to the
// wall + phi_i) (again >= the gap, equal on the wall normal through the closest point);
// with no wall (all sides periodic) the domain diagonal.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "kernels/boundary_kind.hpp"
#include "solver/model/config.hpp"
#include "solver/model/contact_pairs.hpp"
#include "core/field.hpp"
#include "core/grid.hpp"
#include "solver/model/solid.hpp"

namespace refmap {

class CheckpointWriter;
class CheckpointReader;

struct ContactEvent {
  double time = 0.0;
  int solid = 0;
  std::string event;  ///< "contact_start", "contact_end", "restitution"
  double value = 0.0;
  std::string with;   ///< the obstacle: "wall_left", "wall_right", "wall_bottom", "wall_top" or the other solid's name
};

/// Solid-solid and solid-wall contact: the options of the [contact] table, read by the
/// contact component's kind (solver/components/contact_component.cpp: keys, parser).
struct ContactOptions : ComponentOptions {
  bool enabled = true;         ///< repulsion between solids and from walls (FlowMode::Solve only)
  bool walls = true;           ///< also from the non-periodic sides
  double range = 2.5;          ///< d_c in cells: the force acts once a gap is below d_c
  double stiffness = 20.0;     ///< contact pressure at zero gap, in units of rho_max U^2
  double velocity_scale = 0.0; ///< U; 0 = automatic (see above)
  double cfl = 0.5;            ///< dt <= cfl / omega in a step that can reach contact (see above)
};

/// The run's [contact] options: those the kind read from the scene (Config::components),
/// or the defaults (no [contact] table, or a Config made without the scene loader).
const ContactOptions& contact_options(const Config& cfg);

class Contact {
 public:
  /// `velocity_scale`: the U of the pressure scale when o.velocity_scale is 0.
  Contact(const Config& cfg, const ContactOptions& o, double velocity_scale);

  /// Potential energy of the contact force at the last add_force: sum over every solid and
  /// obstacle of chi_i p_c(s) dx^2 (the force p_c grad chi_i is minus its variation).
  double energy() const { return energy_; }
  double pressure() const { return P_; }      ///< P: contact pressure at zero gap
  double velocity_scale() const { return U_; }  ///< U of P = stiffness rho_max U^2
  /// Raises the automatic U to `speed` if larger (contact.velocity_scale = 0 only).
  void see_speed(double speed);
  double range() const { return d_; }         ///< d in length units
  bool force_enabled() const { return force_; }

  /// Adds the contact force density of every pair and every wall on the faces: fxf(i, j)
  /// on the x-face left of cell (i, j) ((nx + 1) x ny), fyf(i, j) on the y-face below it.
  /// On a periodic seam the force is stored at index 0 only.
  /// Returns whether any face received a contribution (the fields are left as they were if not).
  bool add_force(const std::vector<std::unique_ptr<Solid>>& solids, Field& fxf, Field& fyf);
  /// Largest stable dt of the contact spring (1e300 if the force is off).
  double min_dt(double rho_min) const;
  /// Whether no contact force can act in a step of length dt: every gap of the last
  /// observe() exceeds the range d by more than the surfaces can close in the step (a
  /// surface moves at most `speed` dt, xi being advected with the velocity at the step's
  /// start; two solids close at twice that) plus one cell (the gaps are sampled at cell
  /// centres). False before the first observe().
  bool clear_of_contact(double speed, double dt) const;

  /// Gap between two solids' zero level sets (sentinel: the domain diagonal).
  double pair_gap(const Solid& a, const Solid& b) const;
  /// Gaps between a solid and the four sides (left, right, bottom, top; sentinel for a
  /// side without wall contact, e.g. periodic or open).
  std::array<double, 4> wall_gaps(const Solid& s) const;
  double sentinel() const { return sentinel_; }

  /// After each step: gaps, contact state and events. diag[i]: Solid::diagnostics of
  /// solids[i] at time t (computed once per step by the caller, which also writes them).
  void observe(double t, const std::vector<std::unique_ptr<Solid>>& solids,
               const std::vector<SolidDiagnostics>& diag);
  /// At the end of a run: restitution of a rebound still being tracked.
  void finish(double t);
  double gap_solid(int i) const { return gap_solid_.at(i); }
  double gap_wall(int i) const { return gap_wall_.at(i); }
  const std::vector<ContactEvent>& events() const { return events_; }

  /// Pair force totals of the last add_force (x, y of solid a then b, for every pair with
  /// a force), for tests.
  const std::vector<double>& last_pair_totals() const { return pair_totals_; }

  /// Visit only the cells that can contribute (default) or every cell of the overlapping
  /// windows as before the boxes were narrowed: the same bits either way (for tests).
  void set_narrow_boxes(bool on) { narrow_boxes_ = on; }
  /// Find the pairs of solids by cell lists (default) or test every pair as before the
  /// broad phase: the same bits either way (for tests).
  void set_broad_phase(bool on) { broad_phase_ = on; }
  /// The pairs of solids in contact (a < b, sorted), as events.csv last reported them.
  const std::vector<std::pair<int, int>>& touching_pairs() const { return touching_; }

  /// The gap and event tracker's state for a checkpoint (solver/model/checkpoint.cpp).
  void save_state(CheckpointWriter& w) const;
  void load_state(CheckpointReader& r);

 private:
  struct WallState {
    bool in_contact = false, pending = false;
    double vmin = 0.0, vmax = 0.0, v_before = 0.0;
    bool started = false;
  };
  /// One unit of add_force's work (see THREADS): a pair (a, b) or a solid a and a wall side.
  struct Task {
    int a = 0, b = -1, side = -1;
    /// the cell boxes visited for a's and b's layer: i0, i1, j0, j1 (inclusive)
    std::array<std::array<int, 4>, 2> box{};
  };
  /// A face contribution: the left (x) or bottom (y) face of cell (gi, gj), its weight for
  /// the momentum correction and its normal force density.
  struct Contribution {
    int gi, gj;
    double w, f;
  };
  /// The contributions of one solid of a task, and its energy terms in visiting order.
  struct Layer {
    std::vector<Contribution> x, y;
    std::vector<double> energy;
  };
  /// Face contributions of solid a pushed by an obstacle at distance dist(gi, gj) (the
  /// other solid's phi or the distance to a wall), over the cell box `box`. Reads only.
  template <class Dist>
  void fill_layer(const Solid& a, Dist&& dist, const std::array<int, 4>& box, Layer& out) const;
  void emit(double t, int solid, const char* what, double value, const std::string& with);
  void close_rebound(double t, int solid, int side, WallState& w, const char* event = "restitution");

  Grid g_;
  /// phi of s at a global cell, wrapped across periodic directions, +band outside.
  double phi_at(const Solid& s, int gi, int gj) const;
  /// The pairs a < b of solids (not clamped together or not: the caller decides) whose
  /// windows, each inflated by `margin` cells, share a cell; sorted by a, then b.
  void find_pairs(const std::vector<std::unique_ptr<Solid>>& solids, int margin,
                  std::vector<std::pair<int, int>>& out);
  std::array<bool, 4> wall_{};
  Sides sides_;
  bool force_ = false;
  double P_ = 0.0, d_ = 0.0, h_ = 0.0, cfl_ = 0.5, sentinel_ = 0.0;
  double U_ = 0.0, P_unit_ = 0.0;  ///< U and stiffness rho_max (P = P_unit_ U^2)
  bool auto_U_ = true;             ///< contact.velocity_scale = 0: U follows see_speed
  std::vector<double> gap_solid_, gap_wall_;
  bool observed_ = false;  ///< gaps measured at least once (clear_of_contact)
  std::vector<std::array<WallState, 4>> wall_state_;
  std::vector<std::pair<int, int>> touching_;  ///< pairs in contact (a < b), sorted
  std::vector<ContactEvent> events_;
  std::vector<double> pair_totals_;
  double energy_ = 0.0;
  // add_force / observe work space, reused from step to step
  std::vector<Task> tasks_;
  /// Per solid, the global cell boxes {phi < 0} and {phi < d} (inclusive; empty: lo > hi):
  /// a face contribution of a pushed by b needs a cell or its left/bottom neighbour in
  /// the first box of a and one in the second box of b.
  struct Boxes { int in[4], near[4]; };
  std::vector<Boxes> boxes_;
  bool narrow_boxes_ = true;
  bool broad_phase_ = true;
  BoxPairFinder finder_;
  std::vector<CellBox> window_boxes_;
  std::vector<std::pair<int, int>> pairs_, next_touching_;
  std::vector<std::array<Layer, 2>> layers_;
  std::vector<double> pair_gap_;                 ///< observe: the gap of pairs_[k]
  std::vector<std::array<double, 4>> side_gap_;  ///< observe: per solid and side
};

}  // namespace refmap
