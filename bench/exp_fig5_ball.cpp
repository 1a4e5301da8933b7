// Fig. 5: the ball cluster (n = 2^19, 500 frames): per-frame time of the parallel and the
// sequential engine, the mean over all frames and the speedup over the intense frames.
#include <algorithm>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

void runFig5Ball(const Options& inOptions) {
  const std::size_t n = inOptions.size(std::size_t{1} << 19, std::size_t{1} << 13);
  const int frames = inOptions.framesOr(500, 100);
  const int runs = inOptions.runs > 0 ? inOptions.runs : 1;
  const std::vector<EngineSpec> engines = {{"parallel", parallelConfig(inOptions.threads)},
                                           {"sequential", sequentialConfig()}};
  Progress progress("fig5_ball", static_cast<std::size_t>(runs) * frames);
  const SceneRun run =
      runScene(ballScene(n, frames, inOptions.seed), engines, runs, frames, 0, &progress);
  const std::vector<double> par = perFrameMedian(run, 0, wallMs());
  const std::vector<double> seq = perFrameMedian(run, 1, wallMs());
  const auto& pairSamples = run.samples[0].front();

  Table perFrame("Ball cluster per frame", {"frame", "par_ms", "seq_ms", "speedup", "pairs",
                                            "primary_axis", "secondary_axis"});
  Series parSeries{"parallel", {}, {}}, seqSeries{"sequential", {}, {}}, gain{"speedup", {}, {}};
  std::vector<double> intenseGain;
  const int intenseBegin = ballIntenseBegin(frames), intenseEnd = ballIntenseEnd(frames);
  for (int f = 0; f < frames; ++f) {
    const auto& stats = pairSamples[f].stats;
    perFrame.addRow({std::to_string(f), fmt(par[f]), fmt(seq[f]), fmtRatio(seq[f], par[f]),
                     fmtCount(stats.pairs), std::to_string(stats.primary_axis),
                     std::to_string(stats.secondary_axis)});
    parSeries.add(f, par[f]);
    seqSeries.add(f, seq[f]);
    gain.add(f, seq[f] / par[f]);
    if (f >= intenseBegin && f <= intenseEnd) intenseGain.push_back(seq[f] / par[f]);
  }
  Table summary(
      "Fig. 5: ball cluster, n = " + fmtSize(n) + ", " + std::to_string(frames) + " frames",
      {"n", "frames", "runs", "threads", "par_mean_ms", "seq_mean_ms", "mean_speedup",
       "intense_frames", "intense_speedup_min", "intense_speedup_max", "check"});
  const double parMean = mean(par), seqMean = mean(seq);
  const auto [lowGain, highGain] = std::minmax_element(intenseGain.begin(), intenseGain.end());
  summary.addRow({fmtSize(n), std::to_string(frames), std::to_string(runs),
                  std::to_string(pairSamples.front().stats.threads), fmt(parMean), fmt(seqMean),
                  fmtRatio(seqMean, parMean),
                  std::to_string(intenseBegin) + "-" + std::to_string(intenseEnd),
                  intenseGain.empty() ? "-" : fmt(*lowGain),
                  intenseGain.empty() ? "-" : fmt(*highGain), countCheck(run)});
  Panel time{
      "Ball cluster, n = " + fmtSize(n), "frame", "ms per frame", false, true, PlotStyle::kLines};
  time.series = {parSeries, seqSeries};
  Panel speed{"Speedup per frame", "frame", "sequential / parallel", false, false,
              PlotStyle::kLines};
  speed.series = {gain};
  publish(inOptions, perFrame, "fig5_ball_frames", {}, false);
  publish(inOptions, summary, "fig5_ball", {Figure{"fig5_ball", {time, speed}}});
}

}  // namespace sap_bench
