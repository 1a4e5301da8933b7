// Fig. 6: the plane cluster (750^2 boxes, 500 frames), u = x and u = y, parallel engine with
// x primary and y secondary at the start, with and without axis swapping (§5).
#include <cmath>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

namespace {

EngineSpec planeEngine(int inThreads, bool inSwapping) {
  EngineSpec spec{inSwapping ? "swap" : "fixed", parallelConfig(inThreads)};
  spec.config.primary_axis = 0;
  spec.config.secondary_axis = 1;
  spec.config.axis_swapping = inSwapping;
  return spec;
}

/// First frame whose stats report a swap, or -1.
int firstSwapFrame(const std::vector<FrameSample>& inFrames) {
  for (std::size_t f = 0; f < inFrames.size(); ++f) {
    if (inFrames[f].stats.axes_swapped) return static_cast<int>(f);
  }
  return -1;
}

}  // namespace

void runFig6Plane(const Options& inOptions) {
  const std::size_t side = inOptions.quick ? 100 : 750;
  const std::size_t cappedSide =
      inOptions.max_n > 0 && side * side > inOptions.max_n
          ? static_cast<std::size_t>(std::sqrt(static_cast<double>(inOptions.max_n)))
          : side;
  const int frames = inOptions.framesOr(500, 100);
  const int runs = inOptions.runs > 0 ? inOptions.runs : 1;
  const std::vector<EngineSpec> engines = {planeEngine(inOptions.threads, true),
                                           planeEngine(inOptions.threads, false)};
  Table perFrame("Plane cluster per frame",
                 {"u", "frame", "swap_ms", "fixed_ms", "swap_primary", "swap_secondary", "pairs"});
  Table summary("Fig. 6: plane cluster, " + std::to_string(cappedSide) + "^2 boxes",
                {"u", "swapping", "median_ms", "mean_ms", "max_ms", "max_over_median",
                 "first_swap_frame", "threads", "check"});
  Panel panel{"Plane cluster, " + std::to_string(cappedSide) + "^2 boxes",
              "frame",
              "ms per frame",
              false,
              true,
              PlotStyle::kLines};
  Progress progress("fig6_plane", 2 * static_cast<std::size_t>(runs) * frames);
  for (int axis : {0, 1}) {
    const std::string u = axis == 0 ? "x" : "y";
    const SceneRun run = runScene(planeScene(cappedSide, axis, frames, inOptions.seed), engines,
                                  runs, frames, 0, &progress);
    const auto& swapFrames = run.samples[0].front();
    for (std::size_t e = 0; e < engines.size(); ++e) {
      const std::vector<double> times = perFrameMedian(run, e, wallMs());
      Series series{"u=" + u + (e == 0 ? ", swapping" : ", fixed axes"), {}, {}};
      for (std::size_t f = 0; f < times.size(); ++f) series.add(f, times[f]);
      panel.series.push_back(series);
      const double mid = median(times);
      summary.addRow({u, e == 0 ? "on" : "off", fmt(mid), fmt(mean(times)), fmt(maximum(times)),
                      fmtRatio(maximum(times), mid),
                      std::to_string(firstSwapFrame(run.samples[e].front())),
                      std::to_string(swapFrames.front().stats.threads), countCheck(run)});
    }
    const std::vector<double> swapTimes = perFrameMedian(run, 0, wallMs());
    const std::vector<double> fixedTimes = perFrameMedian(run, 1, wallMs());
    for (std::size_t f = 0; f < swapFrames.size(); ++f) {
      const auto& stats = swapFrames[f].stats;
      perFrame.addRow({u, std::to_string(f), fmt(swapTimes[f]), fmt(fixedTimes[f]),
                       std::to_string(stats.primary_axis), std::to_string(stats.secondary_axis),
                       fmtCount(stats.pairs)});
    }
  }
  publish(inOptions, perFrame, "fig6_plane_frames", {}, false);
  publish(inOptions, summary, "fig6_plane", {Figure{"fig6_plane", {panel}}});
}

}  // namespace sap_bench
