// The kept-candidate pass of skin reuse on the uniform scene: a frame after the sweep, every
// box still inside its skin, answered from the candidates. The per-candidate time (counter
// "per_candidate") is what the pass costs; the baseline is the pass as it was before the
// spatial rows (candidates as index pairs in canonical order, the second box read at random),
// kept here so that both run side by side on the same frames.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/runner/work_units.h"
#include "core/strategies/skin_list.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/scenes.h"

namespace {

using namespace sap_broadphase;

/// The former pass: containment, then each canonical (index, index) candidate tested in turn.
class BaselineSkinList {
 public:
  void adopt(const BoxColumns& inInflated, const PairList& inCandidates) {
    reference_ = inInflated;
    std::vector<uint32_t> index_of_id(inInflated.size());
    for (std::size_t i = 0; i < inInflated.size(); ++i)
      index_of_id[inInflated.ids[i]] = static_cast<uint32_t>(i);  // the scene's ids: 0..n-1
    candidate_indexes_.resize(inCandidates.size());
    for (std::size_t k = 0; k < inCandidates.size(); ++k)
      candidate_indexes_[k] = {index_of_id[inCandidates[k].a], index_of_id[inCandidates[k].b]};
  }
  /// Containment, then the candidates that overlap; kept out of line so that a profiler
  /// (callgrind --toggle-collect) sees the pass on its own.
  [[gnu::noinline]] bool collect(const BoxColumns& inBoxes, PairList& outPairs) const {
    bool inside = true;
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis)
        inside = inside && inBoxes.lo[axis][i] >= reference_.lo[axis][i] &&
                 inBoxes.hi[axis][i] <= reference_.hi[axis][i];
    }
    if (!inside) return false;
    outPairs.clear();
    for (const auto& [a, b] : candidate_indexes_)
      if (boxesOverlap(inBoxes, a, b))
        outPairs.push_back(makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
    return true;
  }

 private:
  BoxColumns reference_;
  std::vector<std::pair<uint32_t, uint32_t>> candidate_indexes_;
};

double skinArg(const benchmark::State& inState) {
  return static_cast<double>(inState.range(1)) / 100.0;
}

/// Frame 0 of the uniform scene swept with the skin, and frame 1 to answer from it, as the
/// skin list reads them.
struct SkinScene {
  BoxColumns swept;     // frame 0
  BoxColumns inflated;  // frame 0 grown by the skin
  PairList kept;        // the pairs of the inflated boxes: the candidates
  BoxColumns next;      // frame 1, every box inside its skin
  PairList exact;       // frame 1's pairs
};

/// inBoxes as records, for the engine that finds the inflated boxes' pairs.
BoxSet recordsOf(const BoxColumns& inBoxes) {
  BoxSet records;
  records.reserve(inBoxes.size());
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    const double lo[3] = {inBoxes.lo[0][i], inBoxes.lo[1][i], inBoxes.lo[2][i]};
    const double hi[3] = {inBoxes.hi[0][i], inBoxes.hi[1][i], inBoxes.hi[2][i]};
    records.add(inBoxes.ids[i], lo, hi);
  }
  return records;
}

/// The scene of a benchmark's arguments (log2 boxes, skin and density in hundredths), built
/// once.
const SkinScene& skinScene(const benchmark::State& inState) {
  const int log2_boxes = static_cast<int>(inState.range(0));
  const double skin = skinArg(inState);
  const double density = static_cast<double>(inState.range(3)) / 100.0;
  static std::map<std::tuple<int, double, double>, std::unique_ptr<SkinScene>> cache;
  auto& slot = cache[{log2_boxes, skin, density}];
  if (slot) return *slot;
  slot = std::make_unique<SkinScene>();
  SceneConfig config;
  config.n = std::size_t{1} << log2_boxes;
  config.density = density;
  SceneSimulator simulator(config);
  slot->swept = columnsOf(simulator.boxes());
  simulator.step();
  const BoxSet next = simulator.boxes();
  slot->next = columnsOf(next);
  SkinList list;
  slot->inflated = list.inflate(slot->swept, skin);
  BroadphaseConfig sweep;
  sweep.skin = 0.0;
  Broadphase engine(sweep);
  slot->kept = engine.update(recordsOf(slot->inflated));
  slot->exact = engine.update(next);
  return *slot;
}

void reportPerCandidate(benchmark::State& ioState, const SkinScene& inScene) {
  ioState.counters["candidates"] = static_cast<double>(inScene.kept.size());
  ioState.counters["pairs"] = static_cast<double>(inScene.exact.size());
  ioState.counters["per_candidate"] = benchmark::Counter(
      static_cast<double>(inScene.kept.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Containment, gather, rows and the canonical copy: the whole frame from the candidates.
void BM_SkinPass(benchmark::State& state) {
  const SkinScene& scene = skinScene(state);
  const int threads = static_cast<int>(state.range(2));
  const ThreadsScope scope(threads);
  SkinList list;
  list.inflate(scene.swept, skinArg(state));
  list.adopt(scene.swept, scene.kept);
  PairList pairs;
  for (auto _ : state) {
    if (!list.gather(scene.next)) {
      state.SkipWithError("a box left its skin");
      break;
    }
    list.collectGathered(pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  if (pairs != scene.exact) state.SkipWithError("pairs differ from the sweep's");
  reportPerCandidate(state, scene);
}

void BM_SkinPassBaseline(benchmark::State& state) {
  const SkinScene& scene = skinScene(state);
  BaselineSkinList list;
  list.adopt(scene.inflated, scene.kept);
  PairList pairs;
  for (auto _ : state) {
    if (!list.collect(scene.next, pairs)) state.SkipWithError("a box left its skin");
    benchmark::DoNotOptimize(pairs.data());
  }
  if (pairs != scene.exact) state.SkipWithError("pairs differ from the sweep's");
  reportPerCandidate(state, scene);
}

// What a sweep frame adds to keep the candidates: inflate, then the rows.
void BM_SkinAdopt(benchmark::State& state) {
  const SkinScene& scene = skinScene(state);
  SkinList list;
  for (auto _ : state) {
    benchmark::DoNotOptimize(list.inflate(scene.swept, skinArg(state)).size());
    list.adopt(scene.swept, scene.kept);
  }
  reportPerCandidate(state, scene);
}

// (log2 boxes, skin in hundredths of the mean edge, threads, density in hundredths): the
// scene's default density 0.05 has about half a candidate per box, 0.5 about five.
void skinArgs(benchmark::internal::Benchmark* ioBenchmark) {
  for (int density : {5, 50})
    for (int log2_boxes : {17, 20})
      for (int skin : {25, 50}) ioBenchmark->Args({log2_boxes, skin, 1, density});
  ioBenchmark->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_SkinPass)->Apply(skinArgs)->Args({20, 25, 2, 50});
BENCHMARK(BM_SkinPassBaseline)->Apply(skinArgs);
BENCHMARK(BM_SkinAdopt)->Args({17, 25, 1, 5})->Args({20, 25, 1, 50})->Unit(benchmark::kMillisecond);

}  // namespace
