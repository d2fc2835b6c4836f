#include "solver/pressure/multigrid_coarse.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <stdexcept>

namespace refmap {

struct CoarseDirect::Impl {
  int nx = 0, ny = 0, n = 0;
  bool dense = true;
  bool definite = false;
  std::vector<double> chol;  ///< dense: lower Cholesky factor, row-major
  std::vector<double> b;
  Eigen::SparseMatrix<double> A;  ///< sparse: M with cell 0 pinned unless definite
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt;
  Eigen::VectorXd vb, ve;
};

CoarseDirect::CoarseDirect() : p_(std::make_unique<Impl>()) {}
CoarseDirect::~CoarseDirect() = default;

void CoarseDirect::factor(int nx, int ny, bool definite, const std::vector<Entry>& entries,
                          const std::string& who) {
  Impl& c = *p_;
  const int n = nx * ny;
  c.nx = nx;
  c.ny = ny;
  c.n = n;
  c.dense = n <= 512;
  c.definite = definite;
  c.b.assign(std::size_t(n), 0.0);
  if (c.dense) {
    std::vector<double>& A = c.chol;
    A.assign(std::size_t(n) * n, 0.0);
    for (const Entry& e : entries) A[std::size_t(e.k) * n + e.m] += e.v;
    if (!definite) {  // lift the constants' null space
      double tr = 0.0;
      for (int k = 0; k < n; ++k) tr += A[std::size_t(k) * n + k];
      const double alpha = (tr > 0 ? tr / n : 1.0) / n;
      for (auto& a : A) a += alpha;
    }
    for (int k = 0; k < n; ++k) {  // in-place Cholesky (lower triangle)
      double d = A[std::size_t(k) * n + k];
      for (int p = 0; p < k; ++p) d -= A[std::size_t(k) * n + p] * A[std::size_t(k) * n + p];
      if (!(d > 0))
        throw std::runtime_error(who + ": coarse matrix is not positive definite "
                                       "(disconnected cells or negative beta?)");
      d = std::sqrt(d);
      A[std::size_t(k) * n + k] = d;
      for (int m = k + 1; m < n; ++m) {
        double v = A[std::size_t(m) * n + k];
        for (int p = 0; p < k; ++p) v -= A[std::size_t(m) * n + p] * A[std::size_t(k) * n + p];
        A[std::size_t(m) * n + k] = v / d;
      }
    }
  } else {
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(entries.size() + 1);
    const int pin = definite ? -1 : 0;  // singular: cell 0 pinned, the mean removed after
    for (const Entry& e : entries)
      if (e.k != pin && e.m != pin) trip.emplace_back(e.k, e.m, e.v);
    if (!definite) trip.emplace_back(0, 0, 1.0);
    c.A.resize(n, n);
    c.A.setFromTriplets(trip.begin(), trip.end());
    c.llt.compute(c.A);
    if (c.llt.info() != Eigen::Success)
      throw std::runtime_error(who + ": sparse Cholesky of the coarse matrix failed");
    c.vb.resize(n);
    c.ve.resize(n);
  }
}

void CoarseDirect::solve(View x, CView f) {
  Impl& c = *p_;
  const int nx = c.nx, ny = c.ny, n = c.n;
  double mean = 0.0;  // definite: f is solved as it is
  if (!c.definite) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) mean += f(i, j);
    mean /= n;
  }
  // M e = -(f - mean)
  if (c.dense) {
    double* b = c.b.data();
    const double* A = c.chol.data();
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) b[i + nx * j] = mean - f(i, j);
    for (int k = 0; k < n; ++k) {  // forward: L y = b
      double v = b[k];
      const double* row = A + std::size_t(k) * n;
      for (int p = 0; p < k; ++p) v -= row[p] * b[p];
      b[k] = v / row[k];
    }
    for (int k = n - 1; k >= 0; --k) {  // backward: L^T e = y
      double v = b[k];
      for (int m = k + 1; m < n; ++m) v -= A[std::size_t(m) * n + k] * b[m];
      b[k] = v / A[std::size_t(k) * n + k];
    }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) x(i, j) = b[i + nx * j];
  } else {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) c.vb[i + nx * j] = mean - f(i, j);
    if (!c.definite) c.vb[0] = 0.0;
    c.ve = c.llt.solve(c.vb);
    // mean by a plain loop (Eigen's vectorised mean() trips a false -Wmaybe-uninitialized
    // of GCC 12 with AVX-512)
    double em = 0.0;
    if (!c.definite) {
      for (Eigen::Index k = 0; k < c.ve.size(); ++k) em += c.ve[k];
      em /= double(c.ve.size());
    }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) x(i, j) = c.ve[i + nx * j] - em;
  }
}

}  // namespace refmap
