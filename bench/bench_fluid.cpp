// Benchmarks of the stateless fluid and solid-stress stencil kernels (Google Benchmark).
// Thread count: OMP_NUM_THREADS. Grids N x N with N = 128, 256 (0.13 / 0.5 MB per array: in
// cache), 512 (2.1 MB per array: the 5-14 arrays of a kernel need 10-30 MB, about the 32 MB
// L3), 1024 and 2048 (8.4 / 34 MB per array: from DRAM).
//
//   AdvectionStage/N/S    one advect_rhs2 call (both momentum components: one RK-4 stage
//                         right-hand side), S = 0 central, 1 Superbee
//   ViscousForce/N        viscous_force (divergence of mu (grad u + grad u^T))
//   StressDivergence/N    add_stress_divergence (f += div S, cell-centred S)
//   NeoHookeanStress/N    cell_stress<NeoHookean> on a full N x N window (every cell inside the
//                         solid) with an affine deformed xi
//   ProjectionFaces/N     face_accel + predict_face_velocity + face_divergence (step 5 of
//                         Algorithm 1: the Poisson right-hand side from the cell velocity)
//
// Counters (per call, N^2 cells; set by bench/bench_counters.hpp):
//   cells_per_s     N^2 * iterations / wall time (kIsRate)
//   GFlop/s         flops_per_cell * cells_per_s (roofline point: GFlop/s at
//                   flops_per_cell / bytes_per_cell flop/byte)
//   GB/s            bytes_per_cell * cells_per_s. bytes_per_cell is the compulsory memory
//                   traffic under the assumption that neighbouring rows stay in cache: every
//                   array the kernel reads or writes is counted once per cell, 8 bytes each
//                   (a read-modify-write array counts once; face arrays count as one value
//                   per cell; write-allocate traffic is not counted):
//                     AdvectionStage    reads a, b, uf, vf; writes ra, rb         6 x 8 = 48
//                     ViscousForce      reads u, v, mu; writes fx, fy             5 x 8 = 40
//                     StressDivergence  reads sxx, sxy, syy; updates fx, fy       5 x 8 = 40
//                     NeoHookeanStress  reads xi_x, xi_y, phi; writes sxx,sxy,syy 6 x 8 = 48
//                     ProjectionFaces   three passes: face_accel reads p, bx, by, writes
//                                       gx, gy (5); predict reads u, v, gx, gy, writes uf,
//                                       vf (6); divergence reads uf, vf, writes rhs (3)
//                                                                               14 x 8 = 112
//   flops_per_cell  floating-point operations per cell counted from the source (add, sub,
//                   mul, div, and for Superbee the min/max/compare selects each as one):
//                     AdvectionStage central   8 face values x 2 (add, mul) + 2 x 8
//                                              (4 mul, 3 add, 1 mul by 1/dx)        = 32
//                     AdvectionStage Superbee  8 face values x 17 (3 upwind selects,
//                                              2 sub, sign, 5 mul, 2 min, 2 max, add;
//                                              the division-free form of
//                                              kernels/advection.hpp) + 16          = 152
//                     ViscousForce             4 face mu x 2 + 2 x 24 (per component:
//                                              2 normal fluxes x 3, 2 cross averages
//                                              x 4, 2 tangential fluxes x 3, sum 4) = 56
//                     StressDivergence         2 x (3 add, 1 mul, 1 accumulate)    = 10
//                     NeoHookeanStress         4 gradients x 2, b = (g^T g)^-1 16
//                                              (one division), 2 mu_s (b - I) 5,
//                                              phi test 1                           = 30
//                     ProjectionFaces          face_accel 2 x 7, predict 2 x 4,
//                                              divergence 4                         = 26
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>

#include "bench/bench_counters.hpp"
#include "kernels/advection.hpp"
#include "kernels/projection.hpp"
#include "kernels/solid_stress.hpp"
#include "kernels/viscous.hpp"
#include "core/field.hpp"

namespace {

using namespace refmap;

void set_counters(benchmark::State& state, double cells_per_iter, double bytes_per_cell,
                  double flops_per_cell) {
  bench::set_kernel_counters(state, cells_per_iter, bytes_per_cell, flops_per_cell);
}

/// Fills every value of f (ghosts included) with fn(i, j); the smooth fields below change
/// sign so both upwind branches of Superbee are exercised.
template <class Fn>
void fill_all(Field& f, Fn&& fn) {
  for (int j = -f.ng(); j < f.ny() + f.ng(); ++j)
    for (int i = -f.ng(); i < f.nx() + f.ng(); ++i) f(i, j) = fn(i, j);
}

double wave(int i, int j, int n, double kx, double ky, double phase) {
  const double x = (i + 0.5) / n, y = (j + 0.5) / n;
  return std::sin(2.0 * M_PI * kx * x + phase) * std::cos(2.0 * M_PI * ky * y);
}

void BM_Advection(benchmark::State& state) {
  const int n = int(state.range(0));
  const FluxScheme scheme = state.range(1) == 0 ? FluxScheme::Central : FluxScheme::Superbee;
  Field a(n, n, 2), b(n, n, 2), uf(n + 1, n, 2), vf(n, n + 1, 2), ra(n, n, 2), rb(n, n, 2);
  fill_all(a, [n](int i, int j) { return 1.0 + 0.3 * wave(i, j, n, 2, 3, 0.1); });
  fill_all(b, [n](int i, int j) { return 0.5 * wave(i, j, n, 3, 1, 0.7); });
  fill_all(uf, [n](int i, int j) { return wave(i, j, n, 1, 2, 0.3); });
  fill_all(vf, [n](int i, int j) { return -wave(i, j, n, 2, 1, 1.1); });
  const double dx = 1.0 / n;
  for (auto _ : state) {
    advect_rhs2(a.cview(), b.cview(), uf.cview(), vf.cview(), ra.view(), rb.view(), n, n, dx,
                scheme);
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 48, scheme == FluxScheme::Central ? 32 : 152);
}

void BM_Viscous(benchmark::State& state) {
  const int n = int(state.range(0));
  Field u(n, n, 2), v(n, n, 2), mu(n, n, 2), fx(n, n, 2), fy(n, n, 2);
  fill_all(u, [n](int i, int j) { return wave(i, j, n, 1, 1, 0.0); });
  fill_all(v, [n](int i, int j) { return -wave(i, j, n, 1, 1, 1.5); });
  fill_all(mu, [n](int i, int j) { return 1e-3 * (1.0 + 0.5 * wave(i, j, n, 2, 2, 0.4)); });
  const double dx = 1.0 / n;
  for (auto _ : state) {
    viscous_force(u.cview(), v.cview(), mu.cview(), fx.view(), fy.view(), n, n, dx);
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 40, 56);
}

void BM_StressDivergence(benchmark::State& state) {
  const int n = int(state.range(0));
  Field sxx(n, n, 2), sxy(n, n, 2), syy(n, n, 2), fx(n, n, 2), fy(n, n, 2);
  fill_all(sxx, [n](int i, int j) { return wave(i, j, n, 1, 2, 0.2); });
  fill_all(sxy, [n](int i, int j) { return 0.3 * wave(i, j, n, 2, 1, 0.9); });
  fill_all(syy, [n](int i, int j) { return -wave(i, j, n, 2, 2, 0.5); });
  const double dx = 1.0 / n;
  for (auto _ : state) {
    // accumulates into fx, fy; the values grow linearly but stay finite, which is all the
    // timing needs
    add_stress_divergence(sxx.cview(), sxy.cview(), syy.cview(), fx.view(), fy.view(), n, n, dx);
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 40, 10);
}

void BM_NeoHookean(benchmark::State& state) {
  const int n = int(state.range(0));
  const double dx = 1.0 / n;
  Field xix(n, n, 2), xiy(n, n, 2), phi(n, n, 2), sxx(n, n, 2), sxy(n, n, 2), syy(n, n, 2);
  // affine deformation xi = A x + c (det A = 1.1 * 0.95 + 0.2 * 0.1 = 1.065): the whole
  // window is solid (phi < 0 everywhere), so every cell evaluates the stress
  fill_all(xix, [dx](int i, int j) { return 1.1 * (i + 0.5) * dx + 0.2 * (j + 0.5) * dx + 0.01; });
  fill_all(xiy, [dx](int i, int j) { return -0.1 * (i + 0.5) * dx + 0.95 * (j + 0.5) * dx; });
  phi.fill(-1.0);
  for (auto _ : state) {
    cell_stress(NeoHookean(0.5), xix.cview(), xiy.cview(), phi.cview(), n, n, dx, 6.0 * dx,
                sxx.view(), sxy.view(), syy.view());
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 48, 30);
}

void BM_ProjectionFaces(benchmark::State& state) {
  const int n = int(state.range(0));
  const double dx = 1.0 / n, dt = 0.5 * dx;
  Field p(n, n, 2), rho(n, n, 2), u(n, n, 2), v(n, n, 2), rhs(n, n, 2);
  Field bx(n + 1, n, 2), by(n, n + 1, 2), gx(n + 1, n, 2), gy(n, n + 1, 2);
  Field uf(n + 1, n, 2), vf(n, n + 1, 2);
  fill_all(p, [n](int i, int j) { return wave(i, j, n, 1, 1, 0.3); });
  fill_all(rho, [n](int i, int j) { return 1.0 + 0.5 * (1.0 + wave(i, j, n, 1, 1, 0.0)); });
  fill_all(u, [n](int i, int j) { return wave(i, j, n, 1, 1, 0.0); });
  fill_all(v, [n](int i, int j) { return -wave(i, j, n, 1, 1, 1.5); });
  const Sides walls{};  // all four sides walls, as in the cavity
  face_beta(rho.cview(), bx.view(), by.view(), n, n, walls);
  for (auto _ : state) {
    face_accel(p.cview(), bx.cview(), by.cview(), gx.view(), gy.view(), n, n, dx, 0.0, 0.0, 1.0,
               walls);
    predict_face_velocity(u.cview(), v.cview(), gx.cview(), gy.cview(), uf.view(), vf.view(), n,
                          n, dt, walls);
    face_divergence(uf.cview(), vf.cview(), rhs.view(), n, n, dx, 1.0 / dt);
    benchmark::ClobberMemory();
  }
  set_counters(state, double(n) * n, 112, 26);
}

void grids(benchmark::internal::Benchmark* b) {
  for (int n : {128, 256, 512, 1024, 2048}) b->Arg(n);
  b->UseRealTime();
}

}  // namespace

BENCHMARK(BM_Advection)
    ->Name("AdvectionStage")
    ->ArgsProduct({{128, 256, 512, 1024, 2048}, {0, 1}})
    ->UseRealTime();
BENCHMARK(BM_Viscous)->Name("ViscousForce")->Apply(grids);
BENCHMARK(BM_StressDivergence)->Name("StressDivergence")->Apply(grids);
BENCHMARK(BM_NeoHookean)->Name("NeoHookeanStress")->Apply(grids);
BENCHMARK(BM_ProjectionFaces)->Name("ProjectionFaces")->Apply(grids);
