// Figs. 2 and 3: candidate generation (Algorithm 3) and pairing (Algorithm 4), time and
// speedup over the sequential Algorithm 1, vs n for d in {0.05, 0.15, 0.25, 0.35}.
#include "bench_output.h"
#include "bench_paper_runs.h"
#include "bench_scenes.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

using sap_broadphase::FrameReport;

namespace {

/// Time and speedup panels of one phase, one curve per density.
struct PhaseFigure {
  Panel time;
  Panel speedup;
};

PhaseFigure makePhaseFigure(const std::string& inPhase) {
  PhaseFigure figure;
  figure.time = Panel{inPhase + " time", "n (boxes)", "ms per frame", true, true};
  figure.speedup = Panel{inPhase + " speedup", "n (boxes)", "sequential / parallel", true, false};
  return figure;
}

}  // namespace

void runFig23Phases(const Options& inOptions) {
  const std::vector<double> densities = {0.05, 0.15, 0.25, 0.35};
  const auto sizes = inOptions.sizes(powersOfTwo(15, 21), powersOfTwo(11, 14));
  const int runs = inOptions.runsOr(kPaperRuns);
  const int frames = paperFrames(inOptions);
  Table table("Figs. 2-3: candidates and pairing (ms, median)",
              {"d", "n", "seq_cand_ms", "par_cand_ms", "cand_speedup", "seq_pair_ms", "par_pair_ms",
               "pair_speedup", "pairs", "par_threads", "check"});
  PhaseFigure candidates = makePhaseFigure("Candidates");
  PhaseFigure pairing = makePhaseFigure("Pairing");
  Progress progress("fig23_phases", densities.size() * sizes.size() * runs * frames);
  for (double density : densities) {
    const std::string d = fmt(density, 2);
    Series seqCand{"seq d=" + d, {}, {}}, parCand{"par d=" + d, {}, {}}, gainCand{"d=" + d, {}, {}};
    Series seqPair{"seq d=" + d, {}, {}}, parPair{"par d=" + d, {}, {}}, gainPair{"d=" + d, {}, {}};
    for (std::size_t n : sizes) {
      const SceneRun& run = paperUniformRun(inOptions, n, density, progress);
      const double sc = steadyMedian(run, 0, statField(&FrameReport::ms_candidates));
      const double pc = steadyMedian(run, 1, statField(&FrameReport::ms_candidates));
      const double sp = steadyMedian(run, 0, statField(&FrameReport::ms_pairing));
      const double pp = steadyMedian(run, 1, statField(&FrameReport::ms_pairing));
      const auto& last = run.samples[1].front().back().stats;
      table.addRow({d, fmtSize(n), fmt(sc), fmt(pc), fmtRatio(sc, pc), fmt(sp), fmt(pp),
                    fmtRatio(sp, pp), fmtCount(last.pairs), std::to_string(last.threads),
                    countCheck(run)});
      const double x = static_cast<double>(n);
      seqCand.add(x, sc);
      parCand.add(x, pc);
      gainCand.add(x, sc / pc);
      seqPair.add(x, sp);
      parPair.add(x, pp);
      gainPair.add(x, sp / pp);
    }
    candidates.time.series.insert(candidates.time.series.end(), {seqCand, parCand});
    candidates.speedup.series.push_back(gainCand);
    pairing.time.series.insert(pairing.time.series.end(), {seqPair, parPair});
    pairing.speedup.series.push_back(gainPair);
  }
  publish(inOptions, table, "fig23_phases",
          {Figure{"fig2_candidates", {candidates.time, candidates.speedup}},
           Figure{"fig3_pairing", {pairing.time, pairing.speedup}}});
}

}  // namespace sap_bench
