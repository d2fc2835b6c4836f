// make_extrapolator: the one mapping from SolidsOptions::extrapolation to a method
// (kernels/extrapolate.hpp). It lives in solver/ because it reads the scene's options;
// the methods themselves are kernels.
#include <cmath>
#include <stdexcept>

#include "solver/model/extrapolation.hpp"
#include "kernels/extrapolate_lsq.hpp"
#include "kernels/extrapolate_pde.hpp"
#include "solver/model/config.hpp"

namespace refmap {

namespace {

std::unique_ptr<Extrapolator> make_lsq(const SolidsOptions& opt) {
  LsqOptions lo;
  lo.passes = int(std::ceil(opt.band - 1e-9));  // Algorithm 2 until the band is filled
  lo.radius2 = int(std::floor(opt.lsq_radius * opt.lsq_radius + 1e-9));
  return std::make_unique<LsqExtrapolator>(lo);
}

std::unique_ptr<Extrapolator> make_pde(const SolidsOptions& opt) {
  PdeOptions po;
  po.tol = opt.pde_tol;
  po.max_iter = opt.pde_max_iter;
  return std::make_unique<PdeExtrapolator>(po, opt.band);
}

}  // namespace

std::unique_ptr<Extrapolator> make_extrapolator(const SolidsOptions& opt) {
  switch (opt.extrapolation) {
    case ExtrapolationMethod::Lsq: return make_lsq(opt);
    case ExtrapolationMethod::Pde: return make_pde(opt);
  }
  throw std::invalid_argument("make_extrapolator: unknown extrapolation method");
}

}  // namespace refmap
