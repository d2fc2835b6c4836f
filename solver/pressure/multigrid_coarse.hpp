#pragma once
// The exact solve on the coarsest multigrid level, one home for the 5-point hierarchy
// (solver/pressure/poisson_multigrid.*) and the Galerkin levels (solver/pressure/multigrid_galerkin.*).
//
// The matrix is M = -L (+ diag(c) with a sink) of an nx x ny level, cells numbered i + nx j.
// With a sink M is definite and factored as it is. Without one M is singular with the
// constants as its null space: the dense form (up to 512 cells) factors M + alpha 1 1^T
// (alpha = trace / n^2), the sparse form pins cell 0; the right-hand side's mean is removed
// first and the solution's mean afterwards.
#include <memory>
#include <string>
#include <vector>

#include "core/field.hpp"

namespace refmap {

class CoarseDirect {
 public:
  /// One entry of M: row k, column m, value v (entries of one (k, m) are summed in order).
  struct Entry {
    int k, m;
    double v;
  };

  CoarseDirect();
  ~CoarseDirect();

  /// Factors M given by its entries. `who` prefixes the error when M is not positive
  /// definite (e.g. "multigrid"; the message names disconnected cells or a negative beta).
  void factor(int nx, int ny, bool definite, const std::vector<Entry>& entries, const std::string& who);

  /// x (interior) = the solution of M x = -f (f minus its mean, x of zero mean when singular).
  void solve(View x, CView f);

 private:
  struct Impl;
  std::unique_ptr<Impl> p_;
};

}  // namespace refmap
