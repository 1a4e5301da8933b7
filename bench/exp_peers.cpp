// Peers on the same boxes in the same run, each driven the way its documentation advises and
// each knob setting its own row (CGAL's cutoff, CGAL's TBB version, FCL's four managers,
// Bullet's dynamic tree with a dispatcher, our uniform grid), against the engine with its
// default configuration: one-shot (everything built from scratch each frame) and steady state
// (state kept across frames), the peak memory per box of each, and every frame's pairs
// compared with ours. PhysX's broad phases (ABP, PABP, MBP), when built, each run in a process
// of their own. The engine also runs without skin (every frame swept) on the chosen
// threads and on one thread, the per-core comparison with the single-threaded peers.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>

#include "bench_memory.h"
#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "core/frame/pair_sort.h"
#include "engine_runner.h"
#include "experiments.h"
#include "peer_runs.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::PairList;

namespace {

/// A CGAL cutoff (a knob of one algorithm, unlike FCL's managers or PhysX's broad phases)
/// whose median frame cost over this many times the family's best cutoff's a box on a smaller
/// case of the same scene is not run on the larger one (skipped (slow)): at 2^17 and at 2^20
/// cutoffs 10, 100 and 300 were 1.7-3.8x cutoff 3000 on the uniform scenes (peers.csv), and at
/// 2^20 they took 1.7-3.8 s a frame each. The best cutoff stays within this of itself, so it is
/// still run.
constexpr double kKnobSlowerThanBest = 1.5;

/// Per scene (kind and density) and peer, the median ms a box of a frame (one-shot and steady
/// together) on the scene's last case; 0 for a peer that did not run there.
using MedianCosts = std::map<std::string, std::vector<double>>;

/// True when peer inPeer of inPeers is such a cutoff, by inCosts (empty on a scene's first
/// case).
bool slowKnob(const Peers& inPeers, const std::vector<double>& inCosts, std::size_t inPeer) {
  if (inCosts.empty() || inPeers[inPeer]->family().rfind("cgal", 0) != 0) return false;
  double familyBest = 0.0;
  for (std::size_t q = 0; q < inPeers.size(); ++q) {
    if (inPeers[q]->family() != inPeers[inPeer]->family() || !(inCosts[q] > 0.0)) continue;
    familyBest = familyBest > 0.0 ? std::min(familyBest, inCosts[q]) : inCosts[q];
  }
  // A cutoff without a cost where its family has one was not run on the smaller case.
  return familyBest > 0.0 && !(inCosts[inPeer] <= kKnobSlowerThanBest * familyBest);
}

/// How many peers run in processes of their own (each a pass of its own over a case's frames).
std::size_t ownProcessPeers(const Peers& inPeers) {
  std::size_t count = 0;
  for (const auto& peer : inPeers) count += peer->ownProcess();
  return count;
}

std::string sceneKey(const BenchCase& inCase) {
  return inCase.scene + " " + fmt(inCase.density);
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
  cases.push_back(latticeCase(inOptions.size(1u << 17, 1u << 12)));
  return cases;
}

/// Our engine as a user runs it: the default configuration on the chosen threads.
BroadphaseConfig oursConfig(int inThreads) {
  BroadphaseConfig config;
  config.threads = inThreads;
  return config;
}

/// Our engine on frames that must each be swept (no skin, no reuse of an identical frame): on
/// the chosen threads, and on one thread for the per-core comparison with the single-threaded
/// peers. Rows after the default's, before the peers'.
struct OursVariant {
  std::string name;
  BroadphaseConfig config;
};

std::vector<OursVariant> oursVariants(int inThreads) {
  std::vector<OursVariant> variants;
  for (int threads : {inThreads, 1}) {
    if (threads == 1 && inThreads == 1 && !variants.empty()) break;
    BroadphaseConfig config = oursConfig(threads);
    config.skin = 0.0;
    config.reuse_unchanged_frames = false;
    variants.push_back({"sap_broadphase_no_skin_t" + std::to_string(threads), config});
  }
  return variants;
}

/// Peak memory of our default engine while a fresh one answers inBoxes (its pairs included).
std::size_t oursMemory(const BoxSet& inBoxes, int inThreads) {
  PeakMeter meter;
  meter.start();
  Broadphase engine(oursConfig(inThreads));
  engine.update(inBoxes);
  return meter.grownBytes();
}

/// Runs every contender over the case's frames; frame 0 only builds the steady state. Peers
/// that ask for a process of their own run each run's frames after the others, in a child,
/// checked against the frames' pairs kept from the reference. The first run's frame 0 also
/// measures each contender's peak memory while it builds its structures and answers that
/// frame (pairs included): a separate pass over frame 0 for the memory alone cost every peer
/// one more build, seconds each at 2^20.
std::vector<Contender> runCase(const BenchCase& inCase, int inFrames, int inRuns, int inThreads,
                               Peers& ioPeers, PeerCosts& ioCosts, MedianCosts& ioMedianCosts,
                               Progress& ioProgress) {
  std::vector<double>& costs = ioCosts[sceneKey(inCase)];
  costs.resize(ioPeers.size(), 0.0);
  const std::vector<OursVariant> variants = oursVariants(inThreads);
  const std::size_t first_peer = 1 + variants.size();
  std::vector<Contender> contenders(first_peer + ioPeers.size());
  contenders[0].name = contenders[0].family = "sap_broadphase";
  for (std::size_t v = 0; v < variants.size(); ++v)
    contenders[1 + v].name = contenders[1 + v].family = variants[v].name;
  for (std::size_t p = 0; p < ioPeers.size(); ++p) {
    contenders[first_peer + p].name = ioPeers[p]->name();
    contenders[first_peer + p].family = ioPeers[p]->family();
    contenders[first_peer + p].skipped_slow = costs[p] * inCase.n > kSlowFrameMs ||
                                              quadraticOnClusters(ioPeers[p]->name(), inCase) ||
                                              slowKnob(ioPeers, ioMedianCosts[sceneKey(inCase)], p);
  }
  for (int run = 0; run < inRuns; ++run) {
    FrameFeed feed = inCase.makeFeed();
    Broadphase steady(oursConfig(inThreads));
    std::vector<Broadphase> variant_engines;
    for (const OursVariant& variant : variants) variant_engines.emplace_back(variant.config);
    for (auto& peer : ioPeers) peer->begin();
    for (Contender& entry : contenders) entry.stopped_slow = false;
    std::vector<PairList> truths;  // every frame's, for the peers in processes of their own
    for (int f = 0; f < inFrames; ++f) {
      if (f > 0) feed.step();
      const BoxSet& boxes = feed.boxes();
      const bool timed = f > 0 || inFrames == 1;
      const bool measureMemory = run == 0 && f == 0;
      if (measureMemory) contenders[0].memory_bytes = oursMemory(boxes, inThreads);
      const PairList truth =
          runReferenceFrame(steady, oursConfig(inThreads), boxes, timed, contenders[0]);
      for (std::size_t v = 0; v < variants.size(); ++v)
        runOursFrame(variant_engines[v], variants[v].config, boxes, truth, timed,
                     contenders[1 + v]);
      for (std::size_t p = 0; p < ioPeers.size(); ++p) {
        // A peer in a process of its own measures its memory there (runPeerPass).
        if (ioPeers[p]->ownProcess()) continue;
        Contender& entry = contenders[first_peer + p];
        PeakMeter meter;
        if (measureMemory) meter.start();
        runPeerFrame(*ioPeers[p], boxes, truth, timed, entry, costs[p]);
        if (measureMemory && !entry.skipped_slow) entry.memory_bytes = meter.grownBytes();
      }
      if (ownProcessPeers(ioPeers) > 0) truths.push_back(truth);
      ioProgress.step(inCase.name);
    }
    for (std::size_t p = 0; p < ioPeers.size(); ++p) {
      if (ioPeers[p]->ownProcess())
        runPeerPass(*ioPeers[p], inCase, inFrames, truths, contenders[first_peer + p], costs[p],
                    ioProgress);
    }
  }
  std::vector<double>& medians = ioMedianCosts[sceneKey(inCase)];
  medians.assign(ioPeers.size(), 0.0);
  for (std::size_t p = 0; p < ioPeers.size(); ++p) {
    const Contender& entry = contenders[first_peer + p];
    if (!entry.one_shot_ms.empty())
      medians[p] = (median(entry.one_shot_ms) + median(entry.steady_ms)) / inCase.n;
  }
  return contenders;
}

/// Threads a peer uses, read from its name ("grid_t2", "cgal_tbb_t2_c1000"); 1 otherwise.
int peerThreads(const std::string& inName) {
  const std::size_t at = inName.find("_t");
  if (at == std::string::npos || at + 2 >= inName.size() || !std::isdigit(inName[at + 2])) return 1;
  return std::atoi(inName.c_str() + at + 2);
}

/// The fastest median among contenders [inFirst, end) on at most inMaxThreads threads:
/// outName its name ("-" when none ran).
double fastestOf(const std::vector<Contender>& inContenders, std::size_t inFirst,
                 std::vector<double> Contender::*inTimes, int inMaxThreads, std::string& outName) {
  double best = std::numeric_limits<double>::infinity();
  outName = "-";
  for (std::size_t k = inFirst; k < inContenders.size(); ++k) {
    const Contender& entry = inContenders[k];
    if ((entry.*inTimes).empty() || peerThreads(entry.name) > inMaxThreads) continue;
    const double ms = median(entry.*inTimes);
    if (ms < best) best = ms, outName = entry.name;
  }
  return best;
}

/// Fastest median of each family (knob sweeps: the best setting), by family name.
std::map<std::string, double> familyBest(const std::vector<Contender>& inContenders,
                                         std::vector<double> Contender::*inTimes) {
  std::map<std::string, double> best;
  for (const Contender& entry : inContenders) {
    if ((entry.*inTimes).empty()) continue;
    const double ms = median(entry.*inTimes);
    auto found = best.find(entry.family);
    if (found == best.end() || ms < found->second) best[entry.family] = ms;
  }
  return best;
}

}  // namespace

void runPeers(const Options& inOptions) {
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  Peers peers = makePeers(threads);
  const std::vector<BenchCase> cases = peerCases(inOptions);
  const int frames = inOptions.framesOr(6, 3);
  const int runs = inOptions.runsOr(1);
  Table detail(
      "Peers: ms per frame (median of frames >= 1), every frame's pairs checked "
      "against ours; ratio = ours / peer",
      {"case", "contender", "one_shot_ms", "ratio_one_shot", "steady_ms", "ratio_steady", "pairs",
       "pairs_one_shot", "pairs_steady", "bytes_per_box", "frames", "semantics", "steady_p99_ms",
       "steady_worst_ms", "first_frame_ms"});
  Table summary(
      "Peers: our time / fastest peer's (any knob setting); one thread without skin "
      "against the fastest single-threaded peer",
      {"case", "ours_one_shot_ms", "fastest_one_shot", "ratio_one_shot", "ours_steady_ms",
       "fastest_steady", "ratio_steady", "threads", "ours_no_skin_one_shot_ms",
       "ours_no_skin_steady_ms", "ours_1t_no_skin_one_shot_ms", "fastest_1t_one_shot",
       "ratio_1t_one_shot", "ours_1t_no_skin_steady_ms", "fastest_1t_steady", "ratio_1t_steady"});
  const std::size_t firstPeer = 1 + oursVariants(threads).size();
  Panel oneShotPanel{
      "One-shot (best knob of each library)", "", "ms per frame", false, true, PlotStyle::kPoints};
  Panel steadyPanel{"Steady state (best knob of each library)",
                    "",
                    "ms per frame",
                    false,
                    true,
                    PlotStyle::kPoints};
  std::map<std::string, Series> oneShotSeries, steadySeries;
  Progress progress("peers", cases.size() * frames * runs * (1 + ownProcessPeers(peers)));
  PeerCosts costs;
  MedianCosts medianCosts;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const auto contenders =
        runCase(cases[c], frames, runs, threads, peers, costs, medianCosts, progress);
    const double oursOnce = median(contenders[0].one_shot_ms);
    const double oursKept = median(contenders[0].steady_ms);
    double bestOnce = std::numeric_limits<double>::infinity(), bestKept = bestOnce;
    std::string bestOnceName = "-", bestKeptName = "-";
    for (std::size_t k = 0; k < contenders.size(); ++k) {
      const Contender& entry = contenders[k];
      const double once = median(entry.one_shot_ms), kept = median(entry.steady_ms);
      const bool ours = k == 0;
      const bool variant = k > 0 && k < firstPeer;
      const bool ran = !entry.one_shot_ms.empty();
      detail.addRow(
          {cases[c].name, entry.name, ran ? fmt(once) : "-", ours ? "1" : fmtRatio(oursOnce, once),
           ran ? fmt(kept) : "-", ours ? "1" : fmtRatio(oursKept, kept), fmtCount(entry.last_pairs),
           pairStatus(entry.wrong_one_shot, entry.frames_checked),
           ours ? "reference" : pairStatus(entry.wrong_steady, entry.frames_checked),
           ran && !variant ? fmt(static_cast<double>(entry.memory_bytes) / cases[c].n) : "-",
           entry.skipped_slow
               ? "skipped (slow)"
               : std::to_string(entry.one_shot_ms.size()) + (entry.stopped_slow ? " (slow)" : ""),
           k < firstPeer ? "exact, closed intervals" : peers[k - firstPeer]->semantics(),
           ran ? fmt(percentile(entry.steady_ms, 0.99)) : "-",
           ran ? fmt(maximum(entry.steady_ms)) : "-",
           entry.first_frame_ms >= 0 ? fmt(entry.first_frame_ms) : "-"});
      if (k < firstPeer || entry.one_shot_ms.empty()) continue;
      if (once < bestOnce) bestOnce = once, bestOnceName = entry.name;
      if (kept < bestKept) bestKept = kept, bestKeptName = entry.name;
    }
    for (const auto& [family, ms] : familyBest(contenders, &Contender::one_shot_ms))
      oneShotSeries[family].add(c, ms);
    for (const auto& [family, ms] : familyBest(contenders, &Contender::steady_ms))
      steadySeries[family].add(c, ms);
    const Contender& noSkin = contenders[1];
    const Contender& oneThread = contenders[firstPeer - 1];
    const double oneOnce = median(oneThread.one_shot_ms), oneKept = median(oneThread.steady_ms);
    std::string singleOnceName, singleKeptName;
    const double singleOnce =
        fastestOf(contenders, firstPeer, &Contender::one_shot_ms, 1, singleOnceName);
    const double singleKept =
        fastestOf(contenders, firstPeer, &Contender::steady_ms, 1, singleKeptName);
    summary.addRow({cases[c].name, fmt(oursOnce), bestOnceName + " " + fmt(bestOnce),
                    fmtRatio(oursOnce, bestOnce), fmt(oursKept), bestKeptName + " " + fmt(bestKept),
                    fmtRatio(oursKept, bestKept), std::to_string(threads),
                    fmt(median(noSkin.one_shot_ms)), fmt(median(noSkin.steady_ms)), fmt(oneOnce),
                    singleOnceName + " " + fmt(singleOnce), fmtRatio(oneOnce, singleOnce),
                    fmt(oneKept), singleKeptName + " " + fmt(singleKept),
                    fmtRatio(oneKept, singleKept)});
    oneShotPanel.xtics.push_back({static_cast<double>(c), cases[c].name});
    steadyPanel.xtics.push_back({static_cast<double>(c), cases[c].name});
  }
  for (auto& [family, series] : oneShotSeries) {
    series.title = family;
    oneShotPanel.series.push_back(series);
  }
  for (auto& [family, series] : steadySeries) {
    series.title = family;
    steadyPanel.series.push_back(series);
  }
  publish(inOptions, detail, "peers");
  publish(inOptions, summary, "peers_summary", {Figure{"peers", {oneShotPanel, steadyPanel}}});
}

}  // namespace sap_bench
