// Radix sorts (paper §4.1): the sequential LSD index sort and Algorithm 2's partitioned sort,
// cold (bounds from the span) and warm (bounds from the previous frame).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/runner/work_units.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/sort_keys.h"

namespace {

using sap_broadphase::AxisBounds;
using sap_broadphase::PartitionedSorter;
using sap_broadphase::ThreadsScope;

/// Endpoint keys of inBoxes random intervals (lows then highs), as the engine makes them.
std::vector<uint32_t> endpointKeys(uint32_t inBoxes) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> where(-1.0, 1.0), length(0.001, 0.003);
  std::vector<uint32_t> keys(2 * std::size_t{inBoxes});
  for (uint32_t i = 0; i < inBoxes; ++i) {
    const double low = where(random);
    keys[i] = sap_broadphase::lowKey(low);
    keys[i + inBoxes] = sap_broadphase::highKey(low + length(random));
  }
  return keys;
}

void BM_RadixIndexSort(benchmark::State& state) {
  const auto boxes = static_cast<uint32_t>(state.range(0));
  const auto keys = endpointKeys(boxes);
  std::vector<uint32_t> order(keys.size());
  for (auto _ : state) {
    sap_broadphase::radixIndexSort(keys.data(), static_cast<uint32_t>(keys.size()), order.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(keys.size()));
}
BENCHMARK(BM_RadixIndexSort)
    ->RangeMultiplier(4)
    ->Range(1 << 15, 1 << 21)
    ->Unit(benchmark::kMillisecond);

// Algorithm 2 with 16 partitions on state.range(1) threads; warm: B kept between iterations.
void BM_PartitionedSortWarm(benchmark::State& state) {
  const auto boxes = static_cast<uint32_t>(state.range(0));
  const ThreadsScope threads(static_cast<int>(state.range(1)));
  const auto keys = endpointKeys(boxes);
  std::vector<uint32_t> order(keys.size());
  PartitionedSorter sorter;
  AxisBounds bounds;
  sorter.sort(keys.data(), static_cast<uint32_t>(keys.size()), 16, bounds, order.data());
  double dispersion = 0.0;
  for (auto _ : state) {
    dispersion =
        sorter.sort(keys.data(), static_cast<uint32_t>(keys.size()), 16, bounds, order.data());
  }
  state.counters["D"] = dispersion;
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(keys.size()));
}
BENCHMARK(BM_PartitionedSortWarm)
    ->ArgsProduct({{1 << 15, 1 << 17, 1 << 19, 1 << 21}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The first frame: B initialised from the key span each time.
void BM_PartitionedSortCold(benchmark::State& state) {
  const auto boxes = static_cast<uint32_t>(state.range(0));
  const ThreadsScope threads(static_cast<int>(state.range(1)));
  const auto keys = endpointKeys(boxes);
  std::vector<uint32_t> order(keys.size());
  PartitionedSorter sorter;
  for (auto _ : state) {
    AxisBounds bounds;
    sorter.sort(keys.data(), static_cast<uint32_t>(keys.size()), 16, bounds, order.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(keys.size()));
}
BENCHMARK(BM_PartitionedSortCold)
    ->ArgsProduct({{1 << 17, 1 << 20}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
