// The runs of the paper's uniform sweeps, kept for the process (bench_paper_runs.h).
#include "bench_paper_runs.h"

#include <map>
#include <tuple>

#include "bench_scenes.h"

namespace sap_bench {

int paperFrames(const Options& inOptions) {
  return inOptions.framesOr(10, 4);
}

const SceneRun& paperUniformRun(const Options& inOptions, std::size_t inCount, double inDensity,
                                Progress& ioProgress) {
  const int runs = inOptions.runsOr(kPaperRuns);
  const int frames = paperFrames(inOptions);
  // Everything the run depends on besides the fixed engines and scene kind.
  using Key = std::tuple<std::size_t, double, uint64_t, int, int, int>;
  static std::map<Key, SceneRun> kept;
  const Key key{inCount, inDensity, inOptions.seed, inOptions.threads, runs, frames};
  auto found = kept.find(key);
  if (found != kept.end()) {
    for (int step = 0; step < runs * frames; ++step) ioProgress.step();
    return found->second;
  }
  const std::vector<EngineSpec> engines = {{"sequential", sequentialConfig()},
                                           {"parallel", parallelConfig(inOptions.threads)}};
  return kept
      .emplace(key, runScene(uniformScene(inCount, inDensity, inOptions.seed), engines, runs,
                             frames, 0, &ioProgress))
      .first->second;
}

}  // namespace sap_bench
