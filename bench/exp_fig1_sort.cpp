// Fig. 1: time of the sorting phase, sequential (LSD radix) against parallel (Algorithm 2),
// for n = 2^15 .. 2^21 at d = 0.35.
#include "bench_output.h"
#include "bench_paper_runs.h"
#include "bench_scenes.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

using sap_broadphase::FrameReport;

void runFig1Sort(const Options& inOptions) {
  const double density = 0.35;
  const auto sizes = inOptions.sizes(powersOfTwo(15, 21), powersOfTwo(11, 14));
  const int runs = inOptions.runsOr(kPaperRuns);
  const int frames = paperFrames(inOptions);
  Table table("Fig. 1: sort time (ms, median), d = 0.35",
              {"n", "seq_sort_ms", "par_sort_ms", "sort_speedup", "seq_keys_ms", "par_keys_ms",
               "par_threads", "runs", "frames", "check"});
  Series seqTime{"sequential", {}, {}}, parTime{"parallel", {}, {}}, speedup{"speedup", {}, {}};
  Progress progress("fig1_sort", sizes.size() * runs * frames);
  for (std::size_t n : sizes) {
    const SceneRun& run = paperUniformRun(inOptions, n, density, progress);
    const double seqSort = steadyMedian(run, 0, statField(&FrameReport::ms_sort));
    const double parSort = steadyMedian(run, 1, statField(&FrameReport::ms_sort));
    const int threads = run.samples[1].front().front().stats.threads;
    table.addRow({fmtSize(n), fmt(seqSort), fmt(parSort), fmtRatio(seqSort, parSort),
                  fmt(steadyMedian(run, 0, statField(&FrameReport::ms_keys))),
                  fmt(steadyMedian(run, 1, statField(&FrameReport::ms_keys))),
                  std::to_string(threads), std::to_string(runs), std::to_string(frames),
                  countCheck(run)});
    const double x = static_cast<double>(n);
    seqTime.add(x, seqSort);
    parTime.add(x, parSort);
    speedup.add(x, seqSort / parSort);
  }
  Panel time{"Sorting time, d = 0.35", "n (boxes)", "ms per frame", true, true};
  time.series = {seqTime, parTime};
  Panel gain{"Sorting speedup", "n (boxes)", "sequential / parallel", true, false};
  gain.series = {speedup};
  publish(inOptions, table, "fig1_sort", {Figure{"fig1_sort", {time, gain}}});
}

}  // namespace sap_bench
