// Each phase of the pipeline on one uniform frame. Keys and candidates (Algorithms 1 and 3) are
// called directly; every phase is also timed inside update() through FrameReport (manual time),
// which keeps these benchmarks valid while the pairing internals change.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/frame/pair_sort.h"
#include "core/runner/work_units.h"
#include "core/strategies/small_frame.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/sort_keys.h"
#include "core/sweep/sweep.h"  // Algorithms 1 and 3 (candidates)
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"

namespace {

using namespace sap_broadphase;

/// One uniform frame prepared up to each phase's input; built once per (n, density).
struct PreparedFrame {
  BoxSet boxes;        // what update() reads
  BoxColumns columns;  // the same boxes as the engine's parts read them
  std::vector<uint32_t> primary_order, secondary_order;
};

std::vector<uint32_t> sortedEndpoints(const BoxColumns& inBoxes, int inAxis) {
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
  slot->columns = columnsOf(slot->boxes);
  slot->primary_order = sortedEndpoints(slot->columns, 0);
  slot->secondary_order = sortedEndpoints(slot->columns, 1);
  return *slot;
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
      keys[i] = lowKey(frame.columns.lo[0][i]);
      keys[i + n] = highKey(frame.columns.hi[0][i]);
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
  const ThreadsScope threads(static_cast<int>(state.range(2)));
  SweepWorkspace work;
  CandidateRanges ranges;
  for (auto _ : state) {
    computeCandidatesParallel(frame.primary_order.data(), static_cast<uint32_t>(frame.boxes.size()),
                              work, ranges);
  }
}
BENCHMARK(BM_CandidatesParallel)
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_SortPairsCanonical(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), 0.35);
  Broadphase engine;
  PairList unsorted = engine.update(frame.boxes);
  std::reverse(unsorted.begin(), unsorted.end());
  PairList pairs;
  for (auto _ : state) {
    pairs = unsorted;
    sortPairsCanonical(pairs);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(unsorted.size()));
}
BENCHMARK(BM_SortPairsCanonical)->Arg(1 << 17)->Arg(1 << 20)->Unit(benchmark::kMillisecond);

/// Which FrameReport field a phase benchmark reports.
enum Phase : int64_t { kSort, kCandidates, kPairing, kOutput, kTotal };

double phaseMs(const FrameReport& inStats, int64_t inPhase) {
  switch (inPhase) {
    case kSort:
      return inStats.ms_keys + inStats.ms_sort;
    case kCandidates:
      return inStats.ms_candidates;
    case kPairing:
      return inStats.ms_pairing;
    case kOutput:
      return inStats.ms_output;
    default:
      return inStats.ms_total;
  }
}

// One phase of a steady-state frame, timed by the engine. Args: n, density %, threads (0: the
// sequential engine), phase.
void BM_Phase(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  BroadphaseConfig config;
  config.method = state.range(2) == 0 ? Method::kSequential : Method::kParallel;
  config.threads = state.range(2) == 0 ? 1 : static_cast<int>(state.range(2));
  Broadphase engine(config);
  engine.update(frame.boxes);
  for (auto _ : state) {
    benchmark::DoNotOptimize(engine.update(frame.boxes).size());
    state.SetIterationTime(phaseMs(engine.stats(), state.range(3)) / 1000.0);
  }
  state.counters["pairs"] = static_cast<double>(engine.stats().pairs);
}
BENCHMARK(BM_Phase)
    ->ArgNames({"n", "d_pct", "threads", "phase"})
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}, {0, 1, 2}, {kSort, kCandidates, kPairing, kOutput}})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// A whole steady-state frame by wall clock; args as BM_Phase without the phase.
void BM_Update(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  BroadphaseConfig config;
  config.method = state.range(2) == 0 ? Method::kSequential : Method::kParallel;
  config.threads = state.range(2) == 0 ? 1 : static_cast<int>(state.range(2));
  Broadphase engine(config);
  engine.update(frame.boxes);
  for (auto _ : state) benchmark::DoNotOptimize(engine.update(frame.boxes).size());
}
BENCHMARK(BM_Update)
    ->ArgNames({"n", "d_pct", "threads"})
    ->ArgsProduct({{1 << 17, 1 << 20}, {5, 35}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// What BM_SmallFrame runs on one frame.
enum SmallFrameVariant : int64_t {
  kEngineSteady,   // the sequential engine, same frame again (its skips disabled)
  kEngineOneShot,  // a fresh sequential engine per frame
  kSmallFrame,     // pairSmallFrame (AVX2 blocks where the CPU has them)
  kSmallPortable,  // pairSmallFramePortable
  kBruteForce,     // bruteForcePairs
  kEngineAuto,     // the default engine on all cores (parallel from parallel_min_boxes), steady
};

// Small frames by wall clock, one thread except kEngineAuto. Args: n, density %, variant. The
// small-frame path keeps no state, so its steady state and one-shot are the same thing.
void BM_SmallFrame(benchmark::State& state) {
  const PreparedFrame& frame = preparedFrame(state.range(0), densityArg(state));
  BroadphaseConfig config;
  config.method = Method::kSequential;
  config.threads = 1;
  config.skin = 0.0;
  std::size_t pairs = 0;
  SmallFrameWorkspace work;
  PairList out;
  switch (state.range(2)) {
    case kEngineSteady:
    case kEngineAuto: {
      if (state.range(2) == kEngineAuto) {
        config.method = Method::kAuto;
        config.threads = 0;
      }
      Broadphase engine(config);
      engine.update(frame.boxes);
      for (auto _ : state) benchmark::DoNotOptimize(pairs = engine.update(frame.boxes).size());
      break;
    }
    case kEngineOneShot:
      for (auto _ : state) {
        Broadphase engine(config);
        benchmark::DoNotOptimize(pairs = engine.update(frame.boxes).size());
      }
      break;
    case kSmallFrame:
    case kSmallPortable:
      for (auto _ : state) {
        if (state.range(2) == kSmallFrame)
          pairSmallFrame(frame.columns, work, out);
        else
          pairSmallFramePortable(frame.columns, work, out);
        benchmark::DoNotOptimize(pairs = out.size());
      }
      break;
    default:
      for (auto _ : state) benchmark::DoNotOptimize(pairs = bruteForcePairs(frame.boxes).size());
  }
  state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_SmallFrame)
    ->ArgNames({"n", "d_pct", "variant"})
    ->ArgsProduct({{1 << 6, 1 << 8, 1 << 10, 1 << 12, 1 << 13, 1 << 14, 1 << 15, 1 << 16},
                   {5, 35},
                   {kEngineSteady, kEngineOneShot, kSmallFrame, kSmallPortable, kBruteForce,
                    kEngineAuto}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
