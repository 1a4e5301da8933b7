// StaticIndex on the target scene: 10^6 static boxes of the uniform scene and
// 10^3 moving ones. Build once, then the per-frame query of the moving boxes, next to what a
// full sweep of all boxes and a sweep of the moving boxes alone cost.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/runner/work_units.h"
#include "core/strategies/static_index.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/scenes.h"

namespace {

using namespace sap_broadphase;

constexpr std::size_t kStatic = 1000000;
constexpr std::size_t kMoving = 1000;

/// The uniform scene's first frame: boxes [0, kStatic) static (group 0x2, mask 0x1: never
/// pairs among themselves), the last kMoving moving (default filters). Built once.
struct StaticScene {
  BoxSet all;
  BoxColumns all_columns;  // the same boxes as the index reads them
  BoxSet moving;
  std::vector<uint32_t> static_indexes;
  std::vector<uint32_t> moving_indexes;
};

const StaticScene& staticScene() {
  static const std::unique_ptr<StaticScene> scene = [] {
    auto built = std::make_unique<StaticScene>();
    SceneConfig config;
    config.n = kStatic + kMoving;
    built->all = makeSceneFrame(config, 0);
    built->all.groups.assign(config.n, kDefaultGroup);
    built->all.masks.assign(config.n, kDefaultMask);
    for (uint32_t i = 0; i < config.n; ++i) {
      if (i < kStatic) {
        built->all.groups[i] = 0x2u;
        built->all.masks[i] = 0x1u;
        built->static_indexes.push_back(i);
      } else {
        built->moving_indexes.push_back(i);
        const double lo[3] = {built->all.lo(0, i), built->all.lo(1, i), built->all.lo(2, i)};
        const double hi[3] = {built->all.hi(0, i), built->all.hi(1, i), built->all.hi(2, i)};
        built->moving.add(built->all.ids[i], lo, hi);
      }
    }
    built->all_columns = columnsOf(built->all);
    return built;
  }();
  return *scene;
}

// Building the index of 10^6 static boxes (once per static set in the engine).
void BM_StaticIndexBuild(benchmark::State& state) {
  const StaticScene& scene = staticScene();
  const ThreadsScope threads(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    StaticIndex index;
    index.build(scene.all_columns, scene.static_indexes);
    benchmark::DoNotOptimize(index.size());
  }
  state.SetItemsProcessed(state.iterations() * kStatic);
}
BENCHMARK(BM_StaticIndexBuild)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The per-frame work for the static side: every moving x static pair.
void BM_StaticIndexQueryAll(benchmark::State& state) {
  const StaticScene& scene = staticScene();
  StaticIndex index;
  {
    const ThreadsScope all_cores(resolveThreadCount(0));
    index.build(scene.all_columns, scene.static_indexes);
  }
  const ThreadsScope threads(static_cast<int>(state.range(0)));
  PairList pairs;
  for (auto _ : state) {
    pairs.clear();
    index.queryAll(scene.all_columns, scene.moving_indexes, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.counters["large"] = static_cast<double>(index.largeCount());
  state.counters["index_MiB"] = static_cast<double>(index.memoryBytes()) / (1 << 20);
  state.SetItemsProcessed(state.iterations() * kMoving);
}
BENCHMARK(BM_StaticIndexQueryAll)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

// For scale: the moving boxes' own sweep (the other half of a frame) ...
void BM_SweepMovingOnly(benchmark::State& state) {
  const StaticScene& scene = staticScene();
  BroadphaseConfig config;
  config.threads = static_cast<int>(state.range(0));
  Broadphase engine(config);
  for (auto _ : state) benchmark::DoNotOptimize(engine.update(scene.moving).data());
}
BENCHMARK(BM_SweepMovingOnly)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

// ... and the full sweep of all 1,001,000 boxes that the index replaces.
void BM_SweepAllBoxes(benchmark::State& state) {
  const StaticScene& scene = staticScene();
  BroadphaseConfig config;
  config.threads = static_cast<int>(state.range(0));
  Broadphase engine(config);
  for (auto _ : state) benchmark::DoNotOptimize(engine.update(scene.all).data());
}
BENCHMARK(BM_SweepAllBoxes)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
