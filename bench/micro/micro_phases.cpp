// Each phase of the pipeline on one uniform frame: keys, candidates (Algorithms 1 and 3),
// pairing (Algorithms 1 and 4), canonical pair order, and the whole update().
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/radix_sort.h"
#include "sap_broadphase/core/scenes.h"
#include "sap_broadphase/core/sort_keys.h"
#include "sap_broadphase/core/sweep.h"

namespace {

using namespace sap_broadphase;

/// One uniform frame prepared up to each phase's input; built once per (n, density).
struct PreparedFrame {
  BoxSet boxes;
  std::vector<uint32_t> primary_order, secondary_order;
  CandidateRanges ranges;
  std::vector<RankedBox> ranked;
};

std::vector<uint32_t> sortedEndpoints(const BoxSet& inBoxes, int inAxis) {
  const auto n = static_cast<uint32_t>(inBoxes.size());
  std::vector<uint32_t> keys(2 * std::size_t{n}), order(2 * std::size_t{n});
  for (uint32_t i = 0; i < n; ++i) {
    keys[i] = lowKey(inBoxes.lo[inAxis][i]);
    keys[i + n] = highKey(inBoxes.hi[inAxis][i]);
  }
  radixIndexSort(keys.data(), 2 * n, order.data());
  return order;
}

const PreparedFrame& preparedFrame(std::size_t inCount, double inDensity) {
  static std::map<std::pair<std::size_t, double>, std::unique_ptr<PreparedFrame>> cache;
  auto& slot = cache[{inCount, inDensity}];
  if (slot) return *slot;
  slot = std::make_unique<PreparedFrame>();
  SceneConfig scene;
  scene.n = inCount;
  scene.density = inDensity;
  slot->boxes = makeSceneFrame(scene, 0);
  slot->primary_order = sortedEndpoints(slot->boxes, 0);
  slot->secondary_order = sortedEndpoints(slot->boxes, 1);
  SuccTree tree;
  computeCandidatesSequential(slot->primary_order.data(), static_cast<uint32_t>(inCount), tree,
                              slot->ranges);
  slot->ranked.resize(inCount);
  for (uint32_t rank = 0; rank < inCount; ++rank) {
    const uint32_t i = slot->ranges.object_of_rank[rank];
    for (int axis = 0; axis < 3; ++axis) {
      slot->ranked[rank].lo[axis] = slot->boxes.lo[axis][i];
      slot->ranked[rank].hi[axis] = slot->boxes.hi[axis][i];
    }
  }
  return *slot;
}

PairingInput pairingInput(const PreparedFrame& inFrame) {
  PairingInput input;
  input.secondary_order = inFrame.secondary_order.data();
  input.objects = static_cast<uint32_t>(inFrame.boxes.size());
  input.ranges = &inFrame.ranges;
  input.boxes = inFrame.ranked.data();
  input.ids = inFrame.boxes.ids.data();
  return input;
}

double densityArg(const benchmark::State& inState) {
  return inState.range(1) / 100.0;
}

void BM_Keys(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), 0.05);
  const auto n = static_cast<uint32_t>(frame.boxes.size());
  std::vector<uint32_t> keys(2 * std::size_t{n});
  for (auto _ : state) {
    for (uint32_t i = 0; i < n; ++i) {
      keys[i] = lowKey(frame.boxes.lo[0][i]);
      keys[i + n] = highKey(frame.boxes.hi[0][i]);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 2 * static_cast<int64_t>(n));
}
BENCHMARK(BM_Keys)->Arg(1 << 17)->Arg(1 << 20)->Unit(benchmark::kMillisecond);

void BM_CandidatesSequential(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  SuccTree tree;
  CandidateRanges ranges;
  for (auto _ : state) {
    computeCandidatesSequential(frame.primary_order.data(),
                                static_cast<uint32_t>(frame.boxes.size()), tree, ranges);
  }
}
BENCHMARK(BM_CandidatesSequential)
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}})
    ->Unit(benchmark::kMillisecond);

void BM_CandidatesParallel(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  const int threads = static_cast<int>(state.range(2));
  SweepWorkspace work;
  CandidateRanges ranges;
  for (auto _ : state) {
    computeCandidatesParallel(frame.primary_order.data(), static_cast<uint32_t>(frame.boxes.size()),
                              threads, work, ranges);
  }
}
BENCHMARK(BM_CandidatesParallel)
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_PairingSequential(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  const PairingInput input = pairingInput(frame);
  SuccTree tree;
  PairList pairs;
  for (auto _ : state) {
    pairs.clear();
    pairSequential(input, tree, pairs);
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
}
BENCHMARK(BM_PairingSequential)
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}})
    ->Unit(benchmark::kMillisecond);

void BM_PairingParallel(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  const PairingInput input = pairingInput(frame);
  const int threads = static_cast<int>(state.range(2));
  SweepWorkspace work;
  std::vector<PairList> perThread;
  for (auto _ : state) pairParallel(input, threads, work, perThread);
}
BENCHMARK(BM_PairingParallel)
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_SortPairsCanonical(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), 0.35);
  SuccTree tree;
  PairList unsorted, scratch;
  pairSequential(pairingInput(frame), tree, unsorted);
  PairList pairs;
  for (auto _ : state) {
    pairs = unsorted;
    sortPairsCanonical(pairs, scratch);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(unsorted.size()));
}
BENCHMARK(BM_SortPairsCanonical)->Arg(1 << 17)->Arg(1 << 20)->Unit(benchmark::kMillisecond);

// A whole steady-state frame; range(2) = 0: sequential engine, else the parallel one on that
// many threads.
void BM_Update(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  BroadphaseConfig config;
  config.method = state.range(2) == 0 ? Method::kSequential : Method::kParallel;
  config.threads = state.range(2) == 0 ? 1 : static_cast<int>(state.range(2));
  Broadphase engine(config);
  engine.update(frame.boxes);
  for (auto _ : state) benchmark::DoNotOptimize(engine.update(frame.boxes).size());
  state.counters["ms_sort"] = engine.stats().ms_sort;
  state.counters["ms_candidates"] = engine.stats().ms_candidates;
  state.counters["ms_pairing"] = engine.stats().ms_pairing;
}
BENCHMARK(BM_Update)
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
