// The frame history's pass over a frame (frame_history.h): compare() of a BoxSet and load()
// of records, against a last frame where every box moved (every block compared and copied),
// on one thread and on every core. Two frames alternate, so each pass sees a changed frame.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <optional>
#include <vector>

#include "core/frame_history.h"
#include "sap_broadphase/core/scenes.h"

namespace {

using sap_broadphase::BoxSet;
using sap_broadphase::FrameHistory;
using sap_broadphase::InterleavedBoxes;

// Two consecutive frames of a uniform scene of inBoxes boxes.
std::vector<BoxSet> twoFrames(std::size_t inBoxes) {
  sap_broadphase::SceneConfig config;
  config.n = inBoxes;
  config.density = 0.2;
  config.seed = 5;
  sap_broadphase::SceneSimulator scene(config);
  std::vector<BoxSet> frames{scene.boxes()};
  scene.step();
  frames.push_back(scene.boxes());
  return frames;
}

struct RecordFrame {
  std::vector<double> bounds;
  std::vector<uint32_t> ids;
};

RecordFrame recordsOf(const BoxSet& inBoxes) {
  RecordFrame records;
  records.ids = inBoxes.ids;
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) records.bounds.push_back(inBoxes.lo(axis, i));
    for (int axis = 0; axis < 3; ++axis) records.bounds.push_back(inBoxes.hi(axis, i));
  }
  return records;
}

int threadsOf(const benchmark::State& inState) {
  return inState.range(1) == 0 ? omp_get_max_threads() : static_cast<int>(inState.range(1));
}

void BM_HistoryCompareBoxSet(benchmark::State& state) {
  const std::vector<BoxSet> frames = twoFrames(static_cast<std::size_t>(state.range(0)));
  const int threads = threadsOf(state);
  FrameHistory history;
  history.compare(frames[0], threads);
  history.remember(frames[0]);
  std::size_t k = 1;
  for (auto _ : state) {
    const BoxSet& frame = frames[k++ & 1];
    benchmark::DoNotOptimize(history.compare(frame, threads).moved_boxes);
    history.remember(frame);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_HistoryCompareBoxSet)
    ->ArgsProduct({{1 << 14, 1 << 17, 1 << 20}, {1, 0}})
    ->Unit(benchmark::kMicrosecond);

void BM_HistoryLoadRecords(benchmark::State& state) {
  const std::vector<BoxSet> frames = twoFrames(static_cast<std::size_t>(state.range(0)));
  const RecordFrame records[2] = {recordsOf(frames[0]), recordsOf(frames[1])};
  const int threads = threadsOf(state);
  FrameHistory history;
  std::optional<sap_broadphase::ValidationError> problem;
  std::size_t k = 0;
  for (auto _ : state) {
    const RecordFrame& frame = records[k++ & 1];
    InterleavedBoxes view;
    view.count = frame.ids.size();
    view.bounds = frame.bounds.data();
    view.ids = frame.ids.data();
    benchmark::DoNotOptimize(history.load(view, threads, problem).moved_boxes);
    history.remember(history.loaded());
  }
  if (problem) state.SkipWithError("a frame was refused");
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_HistoryLoadRecords)
    ->ArgsProduct({{1 << 14, 1 << 17, 1 << 20}, {1, 0}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
