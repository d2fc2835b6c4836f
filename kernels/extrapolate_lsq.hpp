#pragma once
// Least-squares extrapolation of the reference map (Jain & Mani, section 3.2.3, Algorithm 2).
//
// Pass p takes every unknown cell with a known edge or corner neighbour (as of the START of
// the pass, so the cells of a pass are independent: OpenMP-parallel, deterministic), fits a
// plane xi = a X + b Y + c by least squares to all cells known at the start of the pass
// within the fit radius (offsets di^2 + dj^2 <= radius2), and stores c, the plane at the
// target. The paper's radius is 4r, r = sqrt(dx^2 + dy^2) (radius2 = 32, up to 100 cells,
// the default here); the solver uses 2r (radius2 = 8, a 5 x 5 block) by default, see
// SolidsOptions::lsq_radius for why. Coordinates are integer offsets from the
// target, so the moment sums and the 3x3 normal-matrix determinant are exact integers: the
// fit is degenerate exactly when the known stencil cells are collinear (det == 0). One
// factorisation (the first row of the cofactor matrix) serves both components.
// Fallbacks (counted in ExtrapStats::fallbacks, never NaN): collinear known cells -> 1-D
// least-squares line along them, evaluated at the target's projection; a single known cell
// -> its value.
// Passes stop after opt.passes or when a pass fills nothing. During a pass its candidate
// cells are marked known = 2 (pending); none is left on return.
// Cost (Zen 4, 1 core): ~60 ns per filled cell when the stencil lies inside the domain
// (bit-packed geometry moments + one 4-wide masked weighted sum per component); a disc of
// radius 15 cells, 5 passes, 700 cells: ~44 us. Cells within 5 of the domain edge take a
// scalar path (same results to round-off).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "kernels/extrapolate.hpp"

namespace refmap {
/// A pass fills one ring of the band; passes with fewer cells than this run on one thread.
/// A ring of a disc at 256^2-1024^2 (300-1300 cells, ~15 us of fits at 256^2) is too short
/// for a parallel region: splitting from 64 cells made the extrapolation phase of one disc on
/// 2 threads slower, 0.238 s against 0.142 s serially at 256^2 (400 steps) and 0.123 against
/// 0.111 s at 512^2 (120 steps), and no faster at 1024^2, with spinning waits (2026-12-07, AMD
/// EPYC 2 cores; results/threads.md, "The least-squares passes"); with sleeping waits
/// (OMP_WAIT_POLICY=passive) the 1024^2 disc was slower too (0.09-0.11 s against 0.07-0.08 s
/// over 17 steps, 2026-12-02). So only rings of very large solids are split.
inline constexpr int kLsqParallelMin = 8192;
}  // namespace refmap

namespace refmap {

struct LsqOptions {
  int passes = 6;  ///< max passes = band width in cells (Algorithm 2 repeats until flag2)
  /// squared fit radius in cells: known cells with di^2 + dj^2 <= radius2 enter the fit;
  /// clamped to [2, 32]; 32 = the paper's 4 sqrt(2) dx. Below 8 (the 5 x 5 block) band
  /// cells often see only collinear known cells and fall back to a line fit (not exact for
  /// affine fields), so the solver allows 8..32.
  int radius2 = 32;
  /// Optional flag2: only cells with target(i, j) != 0 may be filled (p == nullptr: any).
  /// Same window indexing as `known`.
  View2<const std::uint8_t> target{};
  /// Passes with fewer candidate cells run on one thread; -1: kLsqParallelMin. A pass fills one ring of
  /// the band (about 2 pi R / dx cells), each cell a least-squares fit of a few hundred flops.
  int parallel_min = -1;
};

/// Reusable scratch space (no allocation per call once warmed up). Not thread-safe: one
/// workspace per concurrent call.
struct LsqWorkspace {
  struct Cell { int i, j; };
  std::vector<Cell> cand, next;
  std::vector<double> val;          // 2 per candidate (xi_x, xi_y)
  detail::KnownExtent ext;
};

/// Fills xi_x, xi_y in unknown cells (see kernels/extrapolate.hpp for the window/domain
/// conventions) and sets known = 1 there. `dx` is accepted for symmetry with the PDE
/// kernel; the fit is scale-free (uniform square cells).
ExtrapStats extrapolate_lsq(View xi_x, View xi_y, View2<std::uint8_t> known, int ni, int nj,
                            int ng, double dx, const LsqOptions& opt = {},
                            LsqWorkspace* ws = nullptr);

/// extrapolate_lsq behind the Extrapolator interface, with its options and workspace.
class LsqExtrapolator final : public Extrapolator {
 public:
  explicit LsqExtrapolator(const LsqOptions& opt) : opt_(opt) {}
  ExtrapStats extrapolate(View xi_x, View xi_y, View2<std::uint8_t> known, CView /*phi*/, int ni,
                          int nj, int ng, double dx) override {
    return extrapolate_lsq(xi_x, xi_y, known, ni, nj, ng, dx, opt_, &ws_);
  }
  /// The first min(passes, layers) passes: pass p reads only the cells known before it, so
  /// the layers filled are those of a full call, bit for bit.
  ExtrapStats extrapolate_layers(View xi_x, View xi_y, View2<std::uint8_t> known, CView /*phi*/, int ni,
                                 int nj, int ng, double dx, int layers) override {
    LsqOptions o = opt_;
    o.passes = std::min(o.passes, std::max(layers, 0));
    return extrapolate_lsq(xi_x, xi_y, known, ni, nj, ng, dx, o, &ws_);
  }
  int layers_written(int layers) const override { return std::min(opt_.passes, std::max(layers, 0)); }

 private:
  LsqOptions opt_;
  LsqWorkspace ws_;
};

}  // namespace refmap
