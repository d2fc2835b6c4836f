#pragma once
// The broad phase of contact (solver/model/contact.hpp): which pairs of solids can interact at
// all. Each solid is represented by a box of global cells (its window, inflated by the
// caller's margin); two solids are a candidate pair when their boxes share a cell --
// across a periodic direction, any periodic image of a cell (boxes_meet).
//
// Cell lists: the grid is divided into square bins of B cells, each box is entered in the
// bins it covers, and only solids sharing a bin are tested. With B about the size of a
// typical box a box covers a few bins and a bin holds a few boxes, so a step costs
// O(N + candidates) instead of the N (N - 1) / 2 tests of the all-pairs loop (1000 solids:
// 5e5 tests per step, twice -- force and gaps). A large solid (a wrapped layer) is in many
// bins and meets everything in them, which is what it does.
//
// The result is exactly the pairs (a < b) for which boxes_meet() holds, sorted by a, then
// b: the pairs and the order of the all-pairs loop (all_box_pairs, kept for tests), so
// contact forces summed in this order keep their bits.
//
// Periodic images are handled in one place, periodic_overlap(); the bins only need to be
// a superset (a cell and its periodic images fall in the same bin).
#include <utility>
#include <vector>

namespace refmap {

/// A box of global cells: [lo[d], hi[d]) along x (d = 0) and y (d = 1); may reach outside
/// the grid (an inflated window). Empty when hi <= lo along a direction.
struct CellBox {
  int lo[2] = {0, 0}, hi[2] = {0, 0};
};

/// The grid's cell counts and which directions are periodic.
struct CellDomain {
  int n[2] = {1, 1};
  bool periodic[2] = {false, false};
};

/// Whether the cell intervals [a0, a1) and [b0, b1) share a cell; if `period` > 0, a cell
/// of one may be a periodic image (shifted by k * period) of a cell of the other.
bool periodic_overlap(int a0, int a1, int b0, int b1, int period);

/// Whether two boxes share a cell (modulo the periodic directions of `dom`).
bool boxes_meet(const CellBox& a, const CellBox& b, const CellDomain& dom);

/// Every pair a < b with boxes_meet(boxes[a], boxes[b]), sorted, by the N^2 loop (tests).
std::vector<std::pair<int, int>> all_box_pairs(const std::vector<CellBox>& boxes, const CellDomain& dom);

/// The same pairs, by cell lists; keeps its work space from call to call.
class BoxPairFinder {
 public:
  /// Fills `out` with every pair a < b whose boxes meet, sorted by a, then b.
  void find(const std::vector<CellBox>& boxes, const CellDomain& dom, std::vector<std::pair<int, int>>& out);

 private:
  std::vector<int> start_, entries_, cursor_;  // bins as compressed rows: solids of bin k in entries_[start_[k], start_[k+1])
  std::vector<long long> keys_;                 // candidate pairs a * N + b, sorted and deduplicated
};

}  // namespace refmap
