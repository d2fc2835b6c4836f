#include "solver/model/picard_anderson.hpp"

#include <cmath>
#include <cstddef>

namespace refmap {

namespace {

std::vector<Field> copies(const std::vector<const Field*>& fs) {
  std::vector<Field> out;
  out.reserve(fs.size());
  for (const Field* f : fs) out.push_back(*f);
  return out;
}

/// sum over the fields of (a_i - b_i) . (c_i - d_i), every stored value (ghosts included)
double dot_diff(const std::vector<Field>& a, const std::vector<Field>& b, const std::vector<Field>& c,
                const std::vector<Field>& d) {
  double s = 0.0;
  for (std::size_t f = 0; f < a.size(); ++f) {
    const double *pa = a[f].raw(), *pb = b[f].raw(), *pc = c[f].raw(), *pd = d[f].raw();
    for (std::size_t n = 0; n < a[f].raw_size(); ++n) s += (pa[n] - pb[n]) * (pc[n] - pd[n]);
  }
  return s;
}

double dot_diff_vec(const std::vector<Field>& a, const std::vector<Field>& b, const std::vector<Field>& c) {
  double s = 0.0;
  for (std::size_t f = 0; f < a.size(); ++f) {
    const double *pa = a[f].raw(), *pb = b[f].raw(), *pc = c[f].raw();
    for (std::size_t n = 0; n < a[f].raw_size(); ++n) s += (pa[n] - pb[n]) * pc[n];
  }
  return s;
}

/// Solves the small symmetric system A y = b by Gaussian elimination with partial pivoting;
/// false if it is singular.
bool solve_small(std::vector<double> a, std::vector<double>& b, std::size_t m) {
  for (std::size_t c = 0; c < m; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < m; ++r)
      if (std::abs(a[r * m + c]) > std::abs(a[p * m + c])) p = r;
    if (a[p * m + c] == 0.0) return false;
    if (p != c) {
      for (std::size_t k = 0; k < m; ++k) std::swap(a[c * m + k], a[p * m + k]);
      std::swap(b[c], b[p]);
    }
    for (std::size_t r = c + 1; r < m; ++r) {
      const double f = a[r * m + c] / a[c * m + c];
      for (std::size_t k = c; k < m; ++k) a[r * m + k] -= f * a[c * m + k];
      b[r] -= f * b[c];
    }
  }
  for (std::size_t c = m; c-- > 0;) {
    double s = b[c];
    for (std::size_t k = c + 1; k < m; ++k) s -= a[c * m + k] * b[k];
    b[c] = s / a[c * m + c];
  }
  return true;
}

}  // namespace

void AndersonMixer::reset() {
  g_.clear();
  r_.clear();
  gamma_.clear();
}

void AndersonMixer::next(const std::vector<const Field*>& g, const std::vector<const Field*>& r,
                         const std::vector<Field*>& x) {
  g_.push_back(copies(g));
  r_.push_back(copies(r));
  while (g_.size() > std::size_t(depth_) + 1) {
    g_.pop_front();
    r_.pop_front();
  }
  const std::size_t m = g_.size() - 1;  // differences available
  gamma_.assign(m, 0.0);
  bool mixed = false;
  if (m > 0) {
    // normal equations of min || r_k - sum_j gamma_j dR_j ||, dR_j = r_{j+1} - r_j, with a
    // relative Tikhonov shift of 1e-13 against near-parallel differences
    std::vector<double> a(m * m), b(m);
    double trace = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t j = 0; j <= i; ++j)
        a[i * m + j] = a[j * m + i] = dot_diff(r_[i + 1], r_[i], r_[j + 1], r_[j]);
      b[i] = dot_diff_vec(r_[i + 1], r_[i], r_.back());
      trace += a[i * m + i];
    }
    for (std::size_t i = 0; i < m; ++i) a[i * m + i] += 1e-13 * trace + 1e-300;
    mixed = solve_small(a, b, m);
    if (mixed) gamma_ = b;
  }
  for (std::size_t f = 0; f < x.size(); ++f) {
    double* px = x[f]->raw();
    const double* pg = g_.back()[f].raw();
    const std::size_t n = x[f]->raw_size();
    for (std::size_t q = 0; q < n; ++q) px[q] = pg[q];
    if (!mixed) continue;
    for (std::size_t j = 0; j < m; ++j) {
      const double* p1 = g_[j + 1][f].raw();
      const double* p0 = g_[j][f].raw();
      const double c = gamma_[j];
      for (std::size_t q = 0; q < n; ++q) px[q] -= c * (p1[q] - p0[q]);
    }
  }
}

}  // namespace refmap
