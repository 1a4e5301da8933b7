// §6.1: the dispersion D of eq. (1) per frame of the uniform scene, primary and secondary
// sort; the paper measured D < 0.01 in every frame.
#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

using sap_broadphase::FrameReport;

void runDispersion(const Options& inOptions) {
  const std::vector<double> densities = {0.05, 0.35};
  const std::size_t n = inOptions.size(std::size_t{1} << 20, std::size_t{1} << 14);
  const int frames = inOptions.framesOr(100, 30);
  const std::vector<EngineSpec> engines = {{"parallel", parallelConfig(inOptions.threads)}};
  Table perFrame("Dispersion per frame", {"d", "frame", "D_primary", "D_secondary", "swapped"});
  Table summary("Dispersion D in steady state (frames >= 1), n = " + fmtSize(n),
                {"d", "n", "frames", "threads", "median_D_primary", "max_D_primary",
                 "median_D_secondary", "max_D_secondary", "frames_D_ge_0.01", "swaps"});
  Panel panel{"Dispersion D per frame, n = " + fmtSize(n), "frame", "D", false, true};
  Progress progress("dispersion", densities.size() * frames);
  for (double density : densities) {
    const SceneRun run =
        runScene(uniformScene(n, density, inOptions.seed), engines, 1, frames, 0, &progress);
    const auto& samples = run.samples[0].front();
    std::vector<double> primary, secondary;
    int over = 0, swaps = 0;
    Series p{"primary d=" + fmt(density, 2), {}, {}}, s{"secondary d=" + fmt(density, 2), {}, {}};
    for (std::size_t f = 0; f < samples.size(); ++f) {
      const FrameReport& stats = samples[f].stats;
      perFrame.addRow({fmt(density, 2), std::to_string(f), fmt(stats.dispersion_primary),
                       fmt(stats.dispersion_secondary), stats.axes_swapped ? "1" : "0"});
      swaps += stats.axes_swapped ? 1 : 0;
      if (f == 0) continue;  // the first frame has no partition bounds from a previous frame
      primary.push_back(stats.dispersion_primary);
      secondary.push_back(stats.dispersion_secondary);
      over += (stats.dispersion_primary >= 0.01 || stats.dispersion_secondary >= 0.01) ? 1 : 0;
      p.add(static_cast<double>(f), stats.dispersion_primary);
      s.add(static_cast<double>(f), stats.dispersion_secondary);
    }
    summary.addRow({fmt(density, 2), fmtSize(n), std::to_string(frames),
                    std::to_string(samples.front().stats.threads), fmt(median(primary)),
                    fmt(maximum(primary)), fmt(median(secondary)), fmt(maximum(secondary)),
                    std::to_string(over), std::to_string(swaps)});
    panel.series.push_back(p);
    panel.series.push_back(s);
  }
  panel.style = PlotStyle::kLines;
  publish(inOptions, perFrame, "dispersion_frames", {}, false);
  publish(inOptions, summary, "dispersion", {Figure{"dispersion", {panel}}});
}

}  // namespace sap_bench
