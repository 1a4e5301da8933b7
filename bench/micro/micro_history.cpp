// The frame history's pass over a frame (frame_history.h): load() of a BoxSet's records, the
// one copy and check a frame gets, against a last frame where every box moved (every block
// compared and copied), on one thread and on every core. Two frames alternate, so each pass
// sees a changed frame.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <optional>
#include <vector>

#include "core/frame/frame_history.h"
#include "core/runner/work_units.h"
#include "sap_broadphase/core/scenes.h"

namespace {

using sap_broadphase::BoxSet;
using sap_broadphase::FrameHistory;
using sap_broadphase::ThreadsScope;

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

int threadsOf(const benchmark::State& inState) {
  return inState.range(1) == 0 ? omp_get_max_threads() : static_cast<int>(inState.range(1));
}

void BM_HistoryLoadRecords(benchmark::State& state) {
  const std::vector<BoxSet> frames = twoFrames(static_cast<std::size_t>(state.range(0)));
  const ThreadsScope threads(threadsOf(state));
  FrameHistory history;
  std::optional<sap_broadphase::ValidationError> problem;
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(history.load(frames[k++ & 1], problem).moved_boxes);
    history.remember();
  }
  if (problem) state.SkipWithError("a frame was refused");
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_HistoryLoadRecords)
    ->ArgsProduct({{1 << 14, 1 << 17, 1 << 20}, {1, 0}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
