#pragma once
// The classical 4-stage Runge-Kutta step, written once, for a pair of fields (the two
// components of the momentum, eq. (5.1), or of the reference map, eq. (3.3)):
//
//   k1 = R(q0), k2 = R(q0 + dt/2 k1), k3 = R(q0 + dt/2 k2), k4 = R(q0 + dt k3),
//   q1 = q0 + dt/6 (((k1 + 2 k2) + 2 k3) + k4).
//
// The sum is accumulated in one field K as the stages arrive (K = k1, K += 2 k2, K += 2 k3,
// K += k4), so a step needs two k fields per component instead of four; the association
// above is the one of a combined final sum (k1 + 2 k2 + 2 k3 + k4 evaluated left to right),
// and the factors 2 are exact, so both ways give the same bits. Loops run over the ni x nj
// interior (ghosts are the caller's business) through kernels/loop.hpp.
#include "kernels/loop.hpp"
#include "core/field.hpp"

namespace refmap {

/// The fields of one RK-4 step (views of ni x nj interiors).
struct Rk4Fields {
  CView q0x, q0y;    ///< start values q0 (not written unless out aliases them)
  View sx, sy;       ///< stage state q0 + c k, the argument of R at stages 2-4
  View accx, accy;   ///< K = k1 + 2 k2 + 2 k3 + k4 (R writes k1 here)
  View kx, ky;       ///< k of stages 2-4
  View outx, outy;   ///< result q0 + dt/6 K (may be q0 itself or the stage state)
  int ni = 0, nj = 0;
};

/// One RK-4 step. rhs(stage, kx, ky), stage = 1..4, writes R of that stage's state into
/// (kx, ky): at stage 1 R(q0) (read where the caller holds q0), at stages 2-4 R(s) with s
/// = (f.sx, f.sy) just written; the caller does there whatever the state needs before R is
/// evaluated (ghost layers, re-extrapolation).
template <class Rhs>
inline void rk4_step(const Rk4Fields& f, double dt, Rhs&& rhs) {
  const int ni = f.ni;
  rhs(1, f.accx, f.accy);  // K = k1
  // s = q0 + c k (c = dt/2 after k1 and k2, dt after k3); K += w k (w = 2 for k2, k3)
  auto stage = [&](View kx, View ky, double w, double c) {
    parallel_rows(0, f.nj, ni, [&](int j) {
      for (int m = 0; m < 2; ++m) {
        const double* __restrict q0 = m == 0 ? &f.q0x(0, j) : &f.q0y(0, j);
        const double* k = m == 0 ? &kx(0, j) : &ky(0, j);  // may be K itself (stage 1)
        double* acc = m == 0 ? &f.accx(0, j) : &f.accy(0, j);
        double* __restrict s = m == 0 ? &f.sx(0, j) : &f.sy(0, j);
        if (w != 0.0) {
#pragma omp simd
          for (int i = 0; i < ni; ++i) acc[i] += w * k[i];
        }
#pragma omp simd
        for (int i = 0; i < ni; ++i) s[i] = q0[i] + c * k[i];
      }
    });
  };
  stage(f.accx, f.accy, 0.0, 0.5 * dt);  // s = q0 + dt/2 k1
  rhs(2, f.kx, f.ky);
  stage(f.kx, f.ky, 2.0, 0.5 * dt);      // K += 2 k2, s = q0 + dt/2 k2
  rhs(3, f.kx, f.ky);
  stage(f.kx, f.ky, 2.0, dt);            // K += 2 k3, s = q0 + dt k3
  rhs(4, f.kx, f.ky);
  const double c = dt / 6.0;
  parallel_rows(0, f.nj, ni, [&](int j) {
    for (int m = 0; m < 2; ++m) {
      const double* q0 = m == 0 ? &f.q0x(0, j) : &f.q0y(0, j);
      const double* __restrict k = m == 0 ? &f.kx(0, j) : &f.ky(0, j);
      double* __restrict acc = m == 0 ? &f.accx(0, j) : &f.accy(0, j);
      double* out = m == 0 ? &f.outx(0, j) : &f.outy(0, j);
#pragma omp simd
      for (int i = 0; i < ni; ++i) {
        const double a = acc[i] + k[i];  // K += k4
        acc[i] = a;
        out[i] = q0[i] + c * a;
      }
    }
  });
}

}  // namespace refmap
