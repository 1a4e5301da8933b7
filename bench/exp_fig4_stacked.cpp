// Fig. 4: the parallel engine's phase times stacked over density, for n = 2^19, 2^20, 2^21,
// with the overall speedup over the sequential engine written above each density.
#include "bench_output.h"
#include "bench_paper_runs.h"
#include "bench_scenes.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

using sap_broadphase::FrameReport;

namespace {

double keysAndSort(const FrameSample& inSample) {
  return inSample.stats.ms_keys + inSample.stats.ms_sort;
}

}  // namespace

void runFig4Stacked(const Options& inOptions) {
  // Figs. 2-3's densities, so that after them (as a full run orders them) this figure reads
  // their runs (paperUniformRun) and runs none of its own; the three densities between them
  // cost 9 runs of 2^19-2^21 boxes for bars between bars whose phases change steadily with d
  // (the page reads d = 0.05 and 0.35).
  const std::vector<double> densities = {0.05, 0.15, 0.25, 0.35};
  const auto sizes = inOptions.sizes(powersOfTwo(19, 21), powersOfTwo(12, 14));
  const int runs = inOptions.runsOr(kPaperRuns);
  const int frames = paperFrames(inOptions);
  Table table("Fig. 4: parallel phases (ms, median) and overall speedup",
              {"n", "d", "keys_sort_ms", "candidates_ms", "pairing_ms", "output_ms", "par_total_ms",
               "seq_total_ms", "speedup", "pairs", "check"});
  Figure figure{"fig4_stacked", {}};
  Progress progress("fig4_stacked", densities.size() * sizes.size() * runs * frames);
  for (std::size_t n : sizes) {
    Panel panel{"Parallel phases, n = " + fmtSize(n),
                "density d",
                "ms per frame",
                false,
                false,
                PlotStyle::kStacked};
    Series sort{"keys + sort", {}, {}}, cand{"candidates", {}, {}}, pair{"pairing", {}, {}},
        out{"output", {}, {}};
    for (double density : densities) {
      const SceneRun& run = paperUniformRun(inOptions, n, density, progress);
      const double ks = steadyMedian(run, 1, keysAndSort);
      const double pc = steadyMedian(run, 1, statField(&FrameReport::ms_candidates));
      const double pp = steadyMedian(run, 1, statField(&FrameReport::ms_pairing));
      const double po = steadyMedian(run, 1, statField(&FrameReport::ms_output));
      const double parTotal = steadyMedian(run, 1, statField(&FrameReport::ms_total));
      const double seqTotal = steadyMedian(run, 0, statField(&FrameReport::ms_total));
      table.addRow({fmtSize(n), fmt(density, 2), fmt(ks), fmt(pc), fmt(pp), fmt(po), fmt(parTotal),
                    fmt(seqTotal), fmtRatio(seqTotal, parTotal),
                    fmtCount(run.samples[1].front().back().stats.pairs), countCheck(run)});
      sort.add(density, ks);
      cand.add(density, pc);
      pair.add(density, pp);
      out.add(density, po);
      panel.labels.push_back({density, fmtRatio(seqTotal, parTotal, 2) + "x"});
    }
    panel.series = {sort, cand, pair, out};
    figure.panels.push_back(panel);
  }
  publish(inOptions, table, "fig4_stacked", {figure});
}

}  // namespace sap_bench
