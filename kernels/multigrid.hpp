#pragma once
// Stateless OpenMP stencil kernels for the matrix-free Poisson solvers
// (solver/pressure/poisson_multigrid.*, solver/pressure/poisson_cg.*).
//
// Every multigrid level is written in cell-integrated (finite-volume) form
//
//     (L x)_P = sum_faces T_f (x_nb - x_P),
//
// where T_f = beta_f * face_length / centre_distance with lengths in units of the finest
// cell. On the finest level T = beta and L = dx^2 * A (A the operator of solver/pressure/poisson.hpp),
// and the right-hand side f is the cell-integrated source dx^2 * rhs. Coarse right-hand
// sides f_c = P^T r are again cell integrated, so no level carries a 1/h^2 factor.
// Optional sink (Stencil::c, PoissonOperator::sink): (L x)_P = sum_f T_f (x_nb - x_P) - c_P x_P
// with the cell-integrated c_P >= 0 (finest level dx^2 * sink, a coarse cell the sum over
// the fine cells it covers); invd then is 1 / (sum_f T_f + c_P), so the relaxation kernels
// need nothing else. Without a sink (c.p == nullptr) the kernels run the arithmetic they
// always ran, bit for bit.
//
// Conventions shared by all kernels:
//  * arrays are View/CView (pointer to (0,0) + row stride) with at least ONE ghost layer;
//  * tx(i,j), i in [0,nx], is the x-face between cells (i-1,j) and (i,j); ty(i,j), j in
//    [0,ny], the y-face between (i,j-1) and (i,j). Wall faces carry T = 0; a periodic
//    direction has T(0) == T(n) and reads the wrapped value through the ghost layer;
//  * a kernel that reads neighbours of x expects the first ghost layer of x to be
//    "consistent": periodic ghosts hold the wrapped interior value, wall ghosts any finite
//    number (they are multiplied by T = 0). Kernels that write x leave it consistent;
//  * Stencil::threads is the OpenMP team size (1 = serial, no parallel region is opened).
//    Kernels taking a Scratch need threads <= Scratch::nthreads.
#include <cstddef>
#include <vector>

#include "kernels/boundary_kind.hpp"
#include "core/field.hpp"

namespace refmap::mg {

/// One level's 5-point operator (non-owning).
struct Stencil {
  int nx = 0, ny = 0;
  Sides sides;                  ///< the kind of each side (wall or periodic)
  CView tx;                     ///< (nx+1) x ny face coefficients
  CView ty;                     ///< nx x (ny+1) face coefficients
  CView invd;                   ///< nx x ny: 1 / (sum_f T_f + c) (0 for a cell with neither)
  CView c;                      ///< nx x ny cell-integrated sink >= 0; c.p == nullptr: none
  int threads = 1;              ///< OpenMP team size for this level's kernels
};

/// Per-thread work space: thread t owns [p + t*per_thread, p + (t+1)*per_thread).
struct Scratch {
  double* p = nullptr;
  std::size_t per_thread = 0;
  int nthreads = 0;
  double* thread(int t) const { return p + std::size_t(t) * per_thread; }
};

/// Transfer operators between a fine and a coarse 1-D cell partition (one per direction).
/// Prolongation (per fine index i):  e_f(i) = w0[i] e_c(p0[i]) + w1[i] e_c(p1[i]),
/// linear interpolation between coarse centres (Neumann reflection at walls: weight 1 on
/// the parent, periodic: wrapped neighbour). Restriction is exactly P^T, stored per coarse
/// index I as K (fine index, weight) pairs padded with zero weights.
/// On the "regular" coarse range [p_lo,p_hi) fine cells 2I, 2I+1 interpolate with the
/// standard 3/4, 1/4 weights from I and I-1 / I+1; on [r_lo,r_hi) the restriction is the
/// standard (1/4, 3/4, 3/4, 1/4) on fine 2I-1..2I+2. Kernels use vectorised fast paths there.
struct Transfer1D {
  static constexpr int K = 5;
  int nf = 0, nc = 0;
  std::vector<int> p0, p1;
  std::vector<double> w0, w1;
  int p_lo = 0, p_hi = 0;
  std::vector<int> ri;     ///< nc*K
  std::vector<double> rw;  ///< nc*K
  int r_lo = 0, r_hi = 0;
};

/// Build the 1-D transfer from a fine partition (cell centres and widths in finest-cell
/// units, total length `length`) to the coarse partition obtained by pairing cells
/// (coarse I covers fine 2I, 2I+1; when nf is odd the last coarse cell covers three).
/// lo, hi: the kinds of the sides at index 0 and nf. Returns coarse centres/widths through
/// cc, cw. Requires nf >= 2.
Transfer1D build_transfer(const std::vector<double>& cf, const std::vector<double>& wf,
                          double length, FaceKind lo, FaceKind hi, std::vector<double>& cc,
                          std::vector<double>& cw);

/// Per-thread scratch (doubles) the kernels below need for a fine row of nxf cells and a
/// coarse row of nxc cells.
std::size_t scratch_per_thread(int nxf, int nxc);

/// Fill the first ghost layer of x: periodic -> wrapped value, wall -> copy of the interior.
void fill_ghosts(const Stencil& s, View x);

/// `sweeps` red-black Gauss-Seidel sweeps (red = (i+j) even), over-relaxed by omega
/// (x <- x + omega (x_GS - x); omega = 1: plain Gauss-Seidel). black_first reverses the
/// colour order (red-black before and black-red after the coarse correction make the
/// V-cycle symmetric). One fused pass over memory per sweep: the second colour trails the
/// first by one row. On a periodic direction of odd length the two cells meeting across
/// the periodic boundary may have the same colour; they are then updated Jacobi-like
/// (both from old values), which keeps every half-sweep symmetric.
/// Walls in y: all sweeps are pipelined into a single pass over memory (bitwise the same
/// result). With res2 != nullptr, *res2 = ||f - L x||^2 of the final iterate (fused into
/// the same pass when walls in y, a separate pass otherwise).
void smooth_rbgs(const Stencil& s, View x, CView f, int sweeps, bool black_first,
                 double omega = 1.0, double* res2 = nullptr);

/// smooth_rbgs (pre-smoothing) followed by fc = P^T (f - L x) (residual_restrict), with
/// the same result bit for bit. Walls in y: one pass over memory -- the residual of each
/// fine row is computed one row behind the last sweep and restricted at once, so neither
/// the fine residual nor a second pass over x, f, tx, ty is needed. Periodic y: the two
/// separate kernels.
void smooth_rbgs_restrict(const Stencil& s, View x, CView f, int sweeps, bool black_first,
                          double omega, const Transfer1D& trx, const Transfer1D& try_, View fc,
                          const Scratch& sc);

/// prolong_add (x += P xc) followed by smooth_rbgs (post-smoothing, res2 as there), with
/// the same result bit for bit. Walls in y: one pass over memory, the prolongation of
/// fine row r being the first stage of the smoothing pipeline, one row ahead of the first
/// half-sweep. Periodic y: the two separate kernels.
void prolong_smooth_rbgs(const Stencil& s, const Transfer1D& trx, const Transfer1D& try_,
                         CView xc, View x, CView f, int sweeps, bool black_first, double omega,
                         const Scratch& sc, double* res2 = nullptr);

/// `sweeps` weighted-Jacobi sweeps x <- x + omega D^{-1} (f - L x), one pass per sweep
/// (old rows kept in per-thread row buffers).
void smooth_jacobi(const Stencil& s, View x, CView f, int sweeps, double omega,
                   const Scratch& sc);

/// Row j of f - L x into out[0, nx) (x ghosts consistent): the one residual of a row that
/// every kernel computing a residual uses.
void residual_row(const Stencil& s, CView x, CView f, int j, double* out);

/// r = f - L x (r may be a null view: only the norm), returns sum r^2.
double residual(const Stencil& s, CView x, CView f, View r);

/// fc = P^T (f - L x) on the coarse grid described by (tx, ty); fused: the fine residual
/// is never stored (row-wise, cached in scratch).
void residual_restrict(const Stencil& s, CView x, CView f, const Transfer1D& trx,
                       const Transfer1D& try_, View fc, const Scratch& sc);

/// x_f += P x_c (bilinear), ghosts of x_f refreshed.
void prolong_add(const Stencil& fine, const Transfer1D& trx, const Transfer1D& try_, CView xc,
                 View xf, const Scratch& sc);

// ---- vector helpers on the nx x ny interior (team size s.threads) ----
double sum(const Stencil& s, CView a);
double dot(const Stencil& s, CView a, CView b);
void fill(const Stencil& s, View a, double v);            ///< interior only
void fill_all(Field& a, double v);                         ///< including ghosts
void add_scalar(const Stencil& s, View a, double v);      ///< interior only
/// out = scale * (in - shift); returns sum out^2.
double shift_scale(const Stencil& s, CView in, double shift, double scale, View out);

// ---- conjugate-gradient building blocks (operator L, negative semi-definite) ----
/// q = L p, returns p.q (p ghosts consistent).
double apply_dot(const Stencil& s, CView p, View q);
/// x += alpha p; r -= alpha q; returns r.r.
double cg_update(const Stencil& s, double alpha, View x, CView p, View r, CView q);
/// Same with Jacobi preconditioning z = D^{-1} r (D = diag L = -1/invd): also rz = r.z.
double cg_update_jacobi(const Stencil& s, double alpha, View x, CView p, View r, CView q,
                        double& rz);
/// p = z + beta p, ghosts refreshed.
void cg_direction(const Stencil& s, CView z, double beta, View p);
/// p = D^{-1} r + beta p, ghosts refreshed.
void cg_direction_jacobi(const Stencil& s, CView r, double beta, View p);
/// z = D^{-1} r; returns r.z.
double jacobi_precondition(const Stencil& s, CView r, View z);

}  // namespace refmap::mg
