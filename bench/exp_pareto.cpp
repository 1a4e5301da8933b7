// Run time against error: each engine mode's time per frame and its missed and extra pairs as
// a fraction of the true pairs, on the uniform scene and on adversarial ones (ball and plane
// clusters, the touching lattice). The oracle is the brute force for small n and, above that,
// our exact uniform grid (itself checked against the brute force in --quick runs).
#include <algorithm>
#include <cmath>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "engine_runner.h"
#include "experiments.h"
#include "pair_diff.h"
#include "peers/uniform_grid.h"
#include "sap_broadphase/core/brute_force.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::PairList;

namespace {

constexpr std::size_t kBruteForceMaxBoxes = std::size_t{1} << 14;

std::vector<EngineSpec> engineModes(int inThreads) {
  EngineSpec exact{"exact", parallelConfig(inThreads)};
  EngineSpec keysOnly{"keys_only", parallelConfig(inThreads)};
  keysOnly.config.exact_final_test = false;
  EngineSpec exactSequential{"exact_sequential", sequentialConfig()};
  EngineSpec keysSequential{"keys_only_sequential", sequentialConfig()};
  keysSequential.config.exact_final_test = false;
  std::vector<EngineSpec> modes = {exact, keysOnly, exactSequential, keysSequential};
  // Skin reuse (exact): skins in mean box edges; the uniform scene moves 0.05 a frame.
  for (double skin : {0.1, 0.3, 1.0}) {
    EngineSpec skinMode{"skin_" + std::to_string(skin).substr(0, 3), parallelConfig(inThreads)};
    skinMode.config.skin = skin;
    modes.push_back(skinMode);
  }
  return modes;
}

/// The true pairs of a frame, and whether the grid agreed with the brute force on it.
PairList oracle(const BoxSet& inBoxes, UniformGrid& ioGrid, std::string& outOracle,
                bool& ioGridChecked, bool& ioGridAgrees) {
  PairList grid = ioGrid.pairs(inBoxes);
  sap_broadphase::sortPairsCanonical(grid);
  if (inBoxes.size() > kBruteForceMaxBoxes) {
    outOracle = "grid";
    return grid;
  }
  outOracle = "brute_force";
  PairList truth = sap_broadphase::bruteForcePairs(inBoxes);
  ioGridChecked = true;
  ioGridAgrees = ioGridAgrees && grid == truth;
  return truth;
}

}  // namespace

void runPareto(const Options& inOptions) {
  const std::size_t n = inOptions.size(std::size_t{1} << 17, std::size_t{1} << 12);
  const std::size_t side = static_cast<std::size_t>(std::sqrt(static_cast<double>(n)));
  const int sceneFrames = inOptions.quick ? 100 : 500;
  const int frames = inOptions.framesOr(6, 3);
  const std::vector<BenchCase> cases = {
      uniformCase(n, 0.05, inOptions.seed), uniformCase(n, 0.35, inOptions.seed),
      ballCase(n, sceneFrames, inOptions.seed), planeCase(side, sceneFrames, inOptions.seed),
      latticeCase(n)};
  const std::vector<EngineSpec> modes = engineModes(inOptions.threads);
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  UniformGrid grid(threads);
  Table table("Run time against error (ms per frame: median of frames >= 1)",
              {"case", "mode", "ms_per_frame", "true_pairs", "missed", "extra", "missed_frac",
               "extra_frac", "oracle", "grid_vs_brute"});
  Figure figure{"pareto", {}, 3};
  Progress progress("pareto", cases.size() * frames);
  for (const BenchCase& benchCase : cases) {
    FrameFeed feed = benchCase.makeFeed();
    std::vector<Broadphase> engines;
    for (const EngineSpec& mode : modes) engines.emplace_back(mode.config);
    std::vector<std::vector<double>> times(modes.size());
    std::vector<PairDiff> totals(modes.size());
    std::string oracleName;
    bool gridChecked = false, gridAgrees = true;
    for (int f = 0; f < frames; ++f) {
      if (f > 0) feed.step();
      const PairList truth = oracle(feed.boxes(), grid, oracleName, gridChecked, gridAgrees);
      for (std::size_t m = 0; m < modes.size(); ++m) {
        Stopwatch clock;
        const PairList& result = engines[m].update(feed.boxes());
        const double ms = clock.ms();
        if (f > 0 || frames == 1) times[m].push_back(ms);
        const PairDiff diff = comparePairs(result, truth);
        totals[m].truth += diff.truth;
        totals[m].missed += diff.missed;
        totals[m].extra += diff.extra;
      }
      progress.step(benchCase.name);
    }
    Panel panel{benchCase.name, "ms per frame", "error (missed + extra) / true",
                false,          false,          PlotStyle::kPoints};
    double worst = 0.0;
    for (std::size_t m = 0; m < modes.size(); ++m) {
      const double truth = std::max<double>(1.0, static_cast<double>(totals[m].truth));
      const double missed = totals[m].missed / truth, extra = totals[m].extra / truth;
      table.addRow({benchCase.name, modes[m].label, fmt(median(times[m])),
                    fmtCount(totals[m].truth / frames), fmtCount(totals[m].missed),
                    fmtCount(totals[m].extra), fmt(missed), fmt(extra), oracleName,
                    gridChecked ? (gridAgrees ? "equal" : "DIFFERENT") : "-"});
      Series point{modes[m].label, {}, {}};
      point.add(median(times[m]), missed + extra);
      worst = std::max(worst, missed + extra);
      panel.series.push_back(point);
    }
    // Time from zero; error from zero with room above (all-exact panels would be flat).
    panel.xrange = "[0:*]";
    panel.yrange = "[-0.05:" + fmt(std::max(0.1, 1.15 * worst)) + "]";
    figure.panels.push_back(panel);
  }
  publish(inOptions, table, "pareto", {figure});
}

}  // namespace sap_bench
