// The broad phase of contact (solver/model/contact_pairs.hpp): the cell lists must find exactly
// the pairs of boxes that the all-pairs loop finds, in its order, on random
// configurations -- walls or periodic sides, boxes of mixed sizes, many touching, some
// reaching across a periodic side or beyond a wall, one wider than the domain.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "solver/model/contact_pairs.hpp"

using namespace refmap;

TEST(ContactPairs, PeriodicOverlapOfIntervals) {
  // by hand: [0, 5) and [8, 12) on a period of 10 share cells 0 and 1 (b shifted by -10)
  EXPECT_TRUE(periodic_overlap(0, 5, 8, 12, 10));
  EXPECT_FALSE(periodic_overlap(0, 5, 8, 12, 0));
  EXPECT_FALSE(periodic_overlap(0, 5, 5, 10, 0));  // adjacent, no common cell
  EXPECT_FALSE(periodic_overlap(0, 5, 5, 10, 10));
  EXPECT_TRUE(periodic_overlap(0, 5, 4, 10, 10));
  EXPECT_TRUE(periodic_overlap(-1, 2, 9, 10, 10));  // cell -1 is cell 9
  EXPECT_FALSE(periodic_overlap(-1, 2, 8, 9, 10));
  EXPECT_TRUE(periodic_overlap(3, 4, 23, 24, 10));  // two periods apart
  EXPECT_TRUE(periodic_overlap(3, 4, 0, 10, 10));   // a full period meets everything
  EXPECT_FALSE(periodic_overlap(3, 3, 0, 10, 10));  // an empty interval meets nothing
}

TEST(ContactPairs, CellListsFindExactlyTheAllPairsPairs) {
  std::mt19937 rng(27);
  long total_pairs = 0;
  for (int trial = 0; trial < 48; ++trial) {
    CellDomain dom;
    dom.n[0] = 64 + int(rng() % 200);
    dom.n[1] = 64 + int(rng() % 200);
    dom.periodic[0] = trial % 2;
    dom.periodic[1] = (trial / 2) % 2;
    const int n = 1 + int(rng() % 300);
    // sizes: mostly small, a few large (an occasional box wider than the domain)
    std::vector<CellBox> boxes(static_cast<std::size_t>(n));
    for (CellBox& b : boxes)
      for (int d = 0; d < 2; ++d) {
        const int size = rng() % 10 == 0 ? 1 + int(rng() % (dom.n[d] + 20)) : 1 + int(rng() % 24);
        b.lo[d] = -12 + int(rng() % (dom.n[d] + 12));
        b.hi[d] = b.lo[d] + size;
      }
    if (trial % 5 == 0) boxes[0].hi[0] = boxes[0].lo[0];  // an empty box
    const auto ref = all_box_pairs(boxes, dom);
    BoxPairFinder f;
    std::vector<std::pair<int, int>> got;
    f.find(boxes, dom, got);
    EXPECT_EQ(got, ref) << "trial " << trial << ", " << n << " boxes on " << dom.n[0] << " x " << dom.n[1];
    f.find(boxes, dom, got);  // the work space reused
    EXPECT_EQ(got, ref) << "trial " << trial << " (second call)";
    total_pairs += long(ref.size());
  }
  EXPECT_GT(total_pairs, 2000);  // the configurations do touch: the comparison is not of empty lists
}
