// Peers on the same boxes in the same run: CGAL box_intersection_d, Bullet btDbvtBroadphase,
// FCL DynamicAABBTreeCollisionManager and our uniform grid, against the engine, one-shot
// (everything built from scratch each frame) and steady state (state kept across frames).
// Every peer's count is checked against the engine's.
#include <cmath>
#include <limits>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "engine_runner.h"
#include "experiments.h"
#include "peers/peer.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;

namespace {

/// Times and counts of one contender over the frames of a case.
struct Contender {
  std::string name;
  std::vector<double> one_shot_ms, steady_ms;
  std::size_t count_errors_one_shot = 0, count_errors_steady = 0, frames_checked = 0;
  std::size_t last_pairs = 0;
};

std::string countStatus(std::size_t inErrors, std::size_t inFrames) {
  return inErrors == 0 ? "ok"
                       : "WRONG(" + std::to_string(inErrors) + "/" + std::to_string(inFrames) + ")";
}

std::vector<BenchCase> peerCases(const Options& inOptions) {
  std::vector<BenchCase> cases;
  for (std::size_t n : inOptions.sizes({1u << 17, 1u << 20}, {1u << 12, 1u << 14})) {
    for (double density : {0.05, 0.35}) cases.push_back(uniformCase(n, density, inOptions.seed));
  }
  const int sceneFrames = inOptions.quick ? 100 : 500;
  cases.push_back(ballCase(inOptions.size(1u << 19, 1u << 13), sceneFrames, inOptions.seed));
  const std::size_t planeBoxes = inOptions.size(750 * 750, 100 * 100);
  const auto side = static_cast<std::size_t>(std::sqrt(static_cast<double>(planeBoxes)));
  cases.push_back(planeCase(side, sceneFrames, inOptions.seed));
  return cases;
}

/// Runs every contender over the case's frames; frame 0 only builds the steady state.
std::vector<Contender> runCase(const BenchCase& inCase, int inFrames, int inRuns, int inThreads,
                               std::vector<std::unique_ptr<Peer>>& ioPeers, Progress& ioProgress) {
  std::vector<Contender> contenders(1 + ioPeers.size());
  contenders[0].name = "sap_broadphase";
  for (std::size_t p = 0; p < ioPeers.size(); ++p) contenders[p + 1].name = ioPeers[p]->name();
  for (int run = 0; run < inRuns; ++run) {
    FrameFeed feed = inCase.makeFeed();
    Broadphase steady(parallelConfig(inThreads));
    for (auto& peer : ioPeers) peer->begin();
    for (int f = 0; f < inFrames; ++f) {
      if (f > 0) feed.step();
      const BoxSet& boxes = feed.boxes();
      const bool timed = f > 0 || inFrames == 1;
      Stopwatch clock;
      const std::size_t truth = steady.update(boxes).size();
      const double steadyMs = clock.ms();
      clock.restart();
      std::size_t oneShotPairs = 0;
      {
        Broadphase fresh(parallelConfig(inThreads));
        oneShotPairs = fresh.update(boxes).size();
      }
      const double oneShotMs = clock.ms();
      for (Contender& entry : contenders) ++entry.frames_checked;
      Contender& ours = contenders[0];
      ours.count_errors_one_shot += oneShotPairs != truth;
      ours.last_pairs = truth;
      if (timed) ours.steady_ms.push_back(steadyMs), ours.one_shot_ms.push_back(oneShotMs);
      for (std::size_t p = 0; p < ioPeers.size(); ++p) {
        Contender& entry = contenders[p + 1];
        const PeerResult once = ioPeers[p]->oneShot(boxes);
        const PeerResult kept = ioPeers[p]->step(boxes);
        entry.count_errors_one_shot += once.pairs != truth;
        entry.count_errors_steady += kept.pairs != truth;
        entry.last_pairs = kept.pairs;
        if (timed) entry.one_shot_ms.push_back(once.ms), entry.steady_ms.push_back(kept.ms);
      }
      ioProgress.step(inCase.name);
    }
  }
  return contenders;
}

}  // namespace

void runPeers(const Options& inOptions) {
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  std::vector<std::unique_ptr<Peer>> peers = makePeers(threads);
  const std::vector<BenchCase> cases = peerCases(inOptions);
  const int frames = inOptions.framesOr(6, 3);
  const int runs = inOptions.runsOr(1);
  Table detail("Peers: ms per frame (median of frames >= 1), pair counts checked",
               {"case", "contender", "one_shot_ms", "steady_ms", "pairs", "count_one_shot",
                "count_steady", "semantics"});
  Table summary("Peers: our time / fastest peer's (target <= 0.333)",
                {"case", "ours_one_shot_ms", "fastest_one_shot", "ratio_one_shot", "ours_steady_ms",
                 "fastest_steady", "ratio_steady", "threads"});
  Panel oneShotPanel{"One-shot", "", "ms per frame", false, true, PlotStyle::kPoints};
  Panel steadyPanel{"Steady state", "", "ms per frame", false, true, PlotStyle::kPoints};
  std::vector<Series> oneShotSeries(1 + peers.size()), steadySeries(1 + peers.size());
  Progress progress("peers", cases.size() * frames * runs);
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const auto contenders = runCase(cases[c], frames, runs, threads, peers, progress);
    double bestOnce = std::numeric_limits<double>::infinity(), bestKept = bestOnce;
    std::string bestOnceName = "-", bestKeptName = "-";
    for (std::size_t k = 0; k < contenders.size(); ++k) {
      const Contender& entry = contenders[k];
      const double once = median(entry.one_shot_ms), kept = median(entry.steady_ms);
      const std::string semantics = k == 0 ? "exact, closed intervals" : peers[k - 1]->semantics();
      detail.addRow(
          {cases[c].name, entry.name, fmt(once), fmt(kept), fmtCount(entry.last_pairs),
           countStatus(entry.count_errors_one_shot, entry.frames_checked),
           k == 0 ? "reference" : countStatus(entry.count_errors_steady, entry.frames_checked),
           semantics});
      oneShotSeries[k].title = steadySeries[k].title = entry.name;
      oneShotSeries[k].add(c, once);
      steadySeries[k].add(c, kept);
      if (k == 0) continue;
      if (once < bestOnce) bestOnce = once, bestOnceName = entry.name;
      if (kept < bestKept) bestKept = kept, bestKeptName = entry.name;
    }
    const double oursOnce = median(contenders[0].one_shot_ms);
    const double oursKept = median(contenders[0].steady_ms);
    summary.addRow({cases[c].name, fmt(oursOnce), bestOnceName + " " + fmt(bestOnce),
                    fmtRatio(oursOnce, bestOnce), fmt(oursKept), bestKeptName + " " + fmt(bestKept),
                    fmtRatio(oursKept, bestKept), std::to_string(threads)});
    oneShotPanel.xtics.push_back({static_cast<double>(c), cases[c].name});
    steadyPanel.xtics.push_back({static_cast<double>(c), cases[c].name});
  }
  oneShotPanel.series = oneShotSeries;
  steadyPanel.series = steadySeries;
  publish(inOptions, detail, "peers");
  publish(inOptions, summary, "peers_summary", {Figure{"peers", {oneShotPanel, steadyPanel}}});
}

}  // namespace sap_bench
