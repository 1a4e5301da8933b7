// SuccTree operations (paper §3): insert/erase, next, range iteration, ⊕.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/sweep/succ_tree.h"

namespace {

using sap_broadphase::SuccTree;

std::vector<uint32_t> randomValues(uint32_t inUniverse, std::size_t inCount, uint32_t inSeed) {
  std::mt19937 random(inSeed);
  std::uniform_int_distribution<uint32_t> pick(0, inUniverse - 1);
  std::vector<uint32_t> values(inCount);
  for (uint32_t& value : values) value = pick(random);
  return values;
}

// Toggle a random value in and out: the candidate and pairing sweeps' update pattern.
void BM_SuccTreeInsertErase(benchmark::State& state) {
  const auto universe = static_cast<uint32_t>(state.range(0));
  SuccTree tree(universe);
  const auto values = randomValues(universe, 4096, 1);
  std::size_t k = 0;
  for (auto _ : state) {
    const uint32_t value = values[k++ & 4095];
    tree.insert(value);
    tree.erase(value);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SuccTreeInsertErase)->RangeMultiplier(8)->Range(1 << 10, 1 << 22);

// next() in a tree holding 1/64 of the universe, spread at random.
void BM_SuccTreeNext(benchmark::State& state) {
  const auto universe = static_cast<uint32_t>(state.range(0));
  SuccTree tree(universe);
  for (uint32_t value : randomValues(universe, universe / 64, 2)) tree.insert(value);
  const auto queries = randomValues(universe, 4096, 3);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(tree.next(queries[k++ & 4095]));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SuccTreeNext)->RangeMultiplier(8)->Range(1 << 10, 1 << 22);

// forEachInRange over 256-wide windows at a fill of 1/state.range(1).
void BM_SuccTreeRange(benchmark::State& state) {
  const uint32_t universe = 1 << 20;
  const auto sparsity = static_cast<std::size_t>(state.range(0));
  SuccTree tree(universe);
  for (uint32_t value : randomValues(universe, universe / sparsity, 4)) tree.insert(value);
  const auto starts = randomValues(universe - 256, 4096, 5);
  std::size_t k = 0, visited = 0;
  for (auto _ : state) {
    const uint32_t begin = starts[k++ & 4095];
    tree.forEachInRange(begin, begin + 256, [&visited](uint32_t) { ++visited; });
  }
  benchmark::DoNotOptimize(visited);
  state.SetItemsProcessed(static_cast<int64_t>(visited));
}
BENCHMARK(BM_SuccTreeRange)->Arg(2)->Arg(16)->Arg(128);

// The ⊕ of Algorithm 3's all-prefix step.
void BM_SuccTreeSymmetricDifference(benchmark::State& state) {
  const auto universe = static_cast<uint32_t>(state.range(0));
  SuccTree a(universe), b(universe);
  for (uint32_t value : randomValues(universe, universe / 64, 6)) a.insert(value);
  for (uint32_t value : randomValues(universe, universe / 64, 7)) b.insert(value);
  for (auto _ : state) {
    a.symmetricDifference(b);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(universe / 8));
}
BENCHMARK(BM_SuccTreeSymmetricDifference)->RangeMultiplier(8)->Range(1 << 10, 1 << 22);

}  // namespace
