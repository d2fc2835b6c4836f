#include "solver/model/contact_pairs.hpp"

#include <algorithm>
#include <cmath>

namespace refmap {

namespace {

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int floor_mod(int a, int b) { return a - floor_div(a, b) * b; }

/// The bins [first, last] (at most two ranges: a box across a periodic side wraps) that
/// the cells [lo, hi) fall in along one direction of n cells, bins of size B, nb bins.
/// Across a non-periodic direction the cells outside the grid count as its first or
/// last cell: two boxes sharing a cell outside still share a bin.
template <class F>
void bin_ranges(int lo, int hi, int n, int B, int nb, bool periodic, F&& range) {
  if (hi <= lo) return;
  if (!periodic) {
    range(std::clamp(lo, 0, n - 1) / B, std::clamp(hi - 1, 0, n - 1) / B);
    return;
  }
  if (hi - lo >= n) {
    range(0, nb - 1);
    return;
  }
  const int l = floor_mod(lo, n), h = l + (hi - lo) - 1;  // last cell, maybe past n - 1
  if (h < n) {
    range(l / B, h / B);
  } else {
    range(l / B, nb - 1);
    range(0, (h - n) / B);
  }
}

}  // namespace

bool periodic_overlap(int a0, int a1, int b0, int b1, int period) {
  if (a1 <= a0 || b1 <= b0) return false;
  if (period <= 0) return a0 < b1 && b0 < a1;
  if (a1 - a0 >= period || b1 - b0 >= period) return true;
  // a shift k * period of b with a0 < b1 + k period and b0 + k period < a1: the largest
  // k with k period <= a1 - b0 - 1, if it also exceeds a0 - b1
  const int k = floor_div(a1 - b0 - 1, period);
  return k * period > a0 - b1;
}

bool boxes_meet(const CellBox& a, const CellBox& b, const CellDomain& dom) {
  for (int d = 0; d < 2; ++d)
    if (!periodic_overlap(a.lo[d], a.hi[d], b.lo[d], b.hi[d], dom.periodic[d] ? dom.n[d] : 0)) return false;
  return true;
}

std::vector<std::pair<int, int>> all_box_pairs(const std::vector<CellBox>& boxes, const CellDomain& dom) {
  std::vector<std::pair<int, int>> out;
  const int n = int(boxes.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      if (boxes_meet(boxes[std::size_t(a)], boxes[std::size_t(b)], dom)) out.emplace_back(a, b);
  return out;
}

void BoxPairFinder::find(const std::vector<CellBox>& boxes, const CellDomain& dom,
                         std::vector<std::pair<int, int>>& out) {
  out.clear();
  const int n = int(boxes.size());
  if (n < 2) return;
  // Bin size: the median box extent, so a typical box covers one or two bins per
  // direction; not below sqrt(cells / 4N), so there are at most ~4N bins (few solids on a
  // fine grid would otherwise make most of the work empty bins).
  std::vector<int> ext;
  ext.reserve(std::size_t(n));
  for (const CellBox& b : boxes)
    if (b.hi[0] > b.lo[0] && b.hi[1] > b.lo[1]) ext.push_back(std::max(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1]));
  if (ext.size() < 2) return;  // at most one non-empty box: no pair
  std::nth_element(ext.begin(), ext.begin() + long(ext.size() / 2), ext.end());
  const double cells = double(dom.n[0]) * dom.n[1];
  int B = std::max(ext[ext.size() / 2], int(std::ceil(std::sqrt(cells / (4.0 * n)))));
  B = std::clamp(B, 1, std::max(dom.n[0], dom.n[1]));
  const int nbx = (dom.n[0] + B - 1) / B, nby = (dom.n[1] + B - 1) / B;
  const std::size_t nbins = std::size_t(nbx) * std::size_t(nby);

  // every bin a box covers, once per range of bins along each direction
  auto for_bins = [&](const CellBox& b, auto&& f) {
    bin_ranges(b.lo[1], b.hi[1], dom.n[1], B, nby, dom.periodic[1], [&](int y0, int y1) {
      bin_ranges(b.lo[0], b.hi[0], dom.n[0], B, nbx, dom.periodic[0], [&](int x0, int x1) {
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) f(std::size_t(y) * std::size_t(nbx) + std::size_t(x));
      });
    });
  };
  start_.assign(nbins + 1, 0);
  for (const CellBox& b : boxes) for_bins(b, [&](std::size_t k) { ++start_[k + 1]; });
  for (std::size_t k = 0; k < nbins; ++k) start_[k + 1] += start_[k];
  entries_.resize(std::size_t(start_[nbins]));
  cursor_.assign(start_.begin(), start_.end() - 1);
  for (int s = 0; s < n; ++s) for_bins(boxes[std::size_t(s)], [&](std::size_t k) { entries_[std::size_t(cursor_[k]++)] = s; });

  // candidates: every two solids of a bin (entered in increasing order, so a <= b; a box
  // wrapping a periodic side may enter a bin twice)
  keys_.clear();
  for (std::size_t k = 0; k < nbins; ++k)
    for (int p = start_[k]; p < start_[k + 1]; ++p)
      for (int q = p + 1; q < start_[k + 1]; ++q) {
        const int a = entries_[std::size_t(p)], b = entries_[std::size_t(q)];
        if (a != b) keys_.push_back((long long)a * n + b);
      }
  std::sort(keys_.begin(), keys_.end());
  keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
  for (long long key : keys_) {
    const int a = int(key / n), b = int(key % n);
    if (boxes_meet(boxes[std::size_t(a)], boxes[std::size_t(b)], dom)) out.emplace_back(a, b);
  }
}

}  // namespace refmap
