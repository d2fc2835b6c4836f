// The broad phase of contact (solver/model/contact_pairs.hpp): cell lists against the all-pairs
// loop they replace, on N random boxes of 20-40 cells (discs of ~10 cells' radius with
// their band, as bench/scenes/many_discs_1000.toml) in a 1024^2 grid with walls.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "solver/model/contact_pairs.hpp"

using namespace refmap;

namespace {

std::vector<CellBox> random_boxes(int n) {
  std::mt19937 rng(27);
  std::vector<CellBox> b(static_cast<std::size_t>(n));
  for (CellBox& x : b)
    for (int d = 0; d < 2; ++d) {
      x.lo[d] = int(rng() % 1000);
      x.hi[d] = x.lo[d] + 20 + int(rng() % 21);
    }
  return b;
}

CellDomain walls() {
  CellDomain d;
  d.n[0] = d.n[1] = 1024;
  return d;
}

void BM_PairsCellLists(benchmark::State& state) {
  const auto boxes = random_boxes(int(state.range(0)));
  BoxPairFinder f;
  std::vector<std::pair<int, int>> out;
  for (auto _ : state) {
    f.find(boxes, walls(), out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["pairs"] = double(out.size());
}

void BM_PairsAll(benchmark::State& state) {
  const auto boxes = random_boxes(int(state.range(0)));
  std::vector<std::pair<int, int>> out;
  for (auto _ : state) {
    out = all_box_pairs(boxes, walls());
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["pairs"] = double(out.size());
}

}  // namespace

BENCHMARK(BM_PairsCellLists)->Name("ContactPairs/cells")->Arg(64)->Arg(1000)->Arg(8000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PairsAll)->Name("ContactPairs/all")->Arg(64)->Arg(1000)->Arg(8000)->Unit(benchmark::kMicrosecond);
