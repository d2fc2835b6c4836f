#pragma once
// Stateless kernels of the Galerkin multigrid (solver/pressure/multigrid_galerkin.*,
// solver.coarse_operator = "galerkin"): 9-point cell-integrated operators on the coarse
// levels, operator-dependent ("matrix-dependent") prolongation, and the Galerkin product
// A_c = P^T A_f P.
//
// Coarsening is vertex-style on the cell unknowns: coarse point I sits on fine point 2I
// (walls: n_c = (n_f + 1) / 2; a periodic direction needs an even n_f, n_c = n_f / 2).
// With this coarsening, 3x3 prolongation stencils and R = P^T, the Galerkin product of a
// 9-point (or 5-point) operator is again 9-point on every level (Dendy 1982; de Zeeuw 1990,
// J. Comput. Appl. Math. 33), which cell-centred bilinear transfers do not give (their
// R A P is 25-point).
//
// Operators are in the sign convention of kernels/multigrid.hpp: (L x)_P = sum_k a_k x_k
// with a_C < 0 (minus the sum of the face coefficients and the sink), off-diagonals >= 0.
// A 9-point operator is stored as 9 planes of nx*ny doubles without ghosts:
// a[k * nx*ny + i + nx*j], k = (dj+1)*3 + (di+1) (k = 4 the centre). Neighbours are found
// through the index tables im/ip/jm/jp (periodic: wrapped; wall: the cell itself, whose
// coefficient across the wall is 0), so the kernels read no ghost cells of the 9-point
// levels' vectors.
//
// Prolongation (Dendy's black-box weights, the symmetric case of de Zeeuw's): a fine point
// on a coarse x-line between coarse W and E takes the weights of the operator collapsed
// along y, w_W = -(a_W + a_NW + a_SW) / (a_C + a_S + a_N), likewise in y; a fine point in
// a coarse cell's middle solves its own equation for the 8 neighbours' interpolated values.
// For a constant-coefficient operator these are the bilinear weights 1/2, 1/4; across a
// density jump they follow the flux (the light side's values carry the heavy side).
// Stored per coarse block (I, J) (fine points 2I..2I+1 x 2J..2J+1) as 8 planes of
// ncx*ncy: q0, q1 = point (2I+1, 2J) from (I, J), (I+1, J); q2, q3 = point (2I, 2J+1)
// from (I, J), (I, J+1); q4..q7 = point (2I+1, 2J+1) from (I, J), (I+1, J), (I, J+1),
// (I+1, J+1). Point (2I, 2J) is injected (weight 1).
#include <vector>

#include "core/field.hpp"
#include "kernels/multigrid.hpp"

namespace refmap::mg {

/// Neighbour index tables of one direction of n points (periodic: wrap; else self).
struct Neighbours1D {
  std::vector<int> m, p;
  bool periodic = false;
  void build(int n, bool per);
};

/// One level's 9-point operator (non-owning).
struct Stencil9 {
  int nx = 0, ny = 0;
  const double* a = nullptr;  ///< 9 planes of nx*ny
  const Neighbours1D* nbx = nullptr;
  const Neighbours1D* nby = nullptr;
  int threads = 1;
  std::size_t n() const { return std::size_t(nx) * std::size_t(ny); }
  double coef(int k, int i, int j) const { return a[std::size_t(k) * n() + std::size_t(i) + std::size_t(nx) * j]; }
};

/// Operator-dependent prolongation from a coarse to a fine level (non-owning).
struct Prolong9 {
  int nfx = 0, nfy = 0, ncx = 0, ncy = 0;
  bool px = false, py = false;
  const double* q = nullptr;  ///< 8 planes of ncx*ncy
  double w(int k, int I, int J) const {
    return q[std::size_t(k) * std::size_t(ncx) * ncy + std::size_t(I) + std::size_t(ncx) * J];
  }
};

/// Coarse count of a direction of nf points: (nf + 1) / 2 with walls, nf / 2 periodic.
inline int coarse_count(int nf, bool periodic) { return periodic ? nf / 2 : (nf + 1) / 2; }

/// The prolongation weights (q, 8 * ncx * ncy doubles) of the fine operator, a 5-point
/// Stencil (the finest level) or a 9-point one.
void build_prolongation(const Stencil& fine, int ncx, int ncy, std::vector<double>& q);
void build_prolongation(const Stencil9& fine, int ncx, int ncy, std::vector<double>& q);

/// The 5-point operator written as 9 planes (corners 0): for a finest level that is
/// itself the coarsest (no coarsening possible), to build its direct solve.
void five_to_nine(const Stencil& s, std::vector<double>& a);

/// a_c = P^T A_f P (9 planes of ncx*ncy), for a 5-point or 9-point fine operator.
void galerkin_product(const Stencil& fine, const Prolong9& P, std::vector<double>& ac);
void galerkin_product(const Stencil9& fine, const Prolong9& P, std::vector<double>& ac);

/// `sweeps` four-colour Gauss-Seidel sweeps (colour (i%2, j%2); points of one colour do not
/// couple through a 9-point stencil, so each colour is a parallel update), over-relaxed by
/// omega. reverse: colours in the opposite order (post-smoothing of a symmetric cycle).
/// With res2: *res2 = ||f - L x||^2 after the sweeps (a separate pass).
void smooth9(const Stencil9& s, View x, CView f, int sweeps, bool reverse, double omega,
             double* res2 = nullptr);

/// r = f - L x (r may be a null view: only the norm); returns sum r^2.
double residual9(const Stencil9& s, CView x, CView f, View r);

/// fc = P^T r (r on the fine level, any stencil).
void restrict9(const Prolong9& P, CView r, View fc, int threads);

/// Per-thread scratch (doubles) of residual_restrict5 and of the two fused passes below
/// for a finest level of nxf cells a row.
std::size_t scratch9_per_thread(int nxf);

/// fc = P^T (f - L x) for the finest 5-point operator s, fused: the fine residual is
/// computed row by row into the threads' scratch and restricted at once, never stored
/// whole. x ghosts consistent. Team size min(s.threads, sc.nthreads).
void residual_restrict5(const Stencil& s, CView x, CView f, const Prolong9& P, View fc,
                        const Scratch& sc);

/// The finest level's passes of a Galerkin V-cycle, fused as smooth_rbgs_restrict and
/// prolong_smooth_rbgs fuse the default ones (kernels/multigrid.hpp; implemented in
/// multigrid.cpp beside them): smooth_rbgs followed by residual_restrict5, and
/// prolong9_add (with the ghosts refreshed) followed by smooth_rbgs, each in one pass over
/// memory when the walls are in y, with the same result bit for bit. Periodic y: the
/// separate kernels.
void smooth_rbgs_restrict9(const Stencil& s, View x, CView f, int sweeps, bool black_first,
                           double omega, const Prolong9& P, View fc, const Scratch& sc);
void prolong9_smooth_rbgs(const Stencil& s, const Prolong9& P, CView xc, View x, CView f,
                          int sweeps, bool black_first, double omega, const Scratch& sc,
                          double* res2 = nullptr);

/// xf += P xc (interior of xf only; the caller refreshes ghosts where needed).
void prolong9_add(const Prolong9& P, CView xc, View xf, int threads);

}  // namespace refmap::mg
