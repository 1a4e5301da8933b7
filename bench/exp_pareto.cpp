// Run time against error: the engine's exact modes and its fast inexact ones (keys only, keys
// quantised to 16 bits, fat margins without the exact test, temporal sub-sampling), and the
// peers' raw candidates (what each library reports before a narrow phase), each with its
// mean time per frame and its missed and extra pairs as a fraction of the true pairs on the
// same frames. Scenes: the uniform ones, the touching lattice, the ball and plane frames; one
// chart per scene. The oracle is the brute force for small n and, above that, our exact
// uniform grid (itself checked against the brute force in --quick runs).

#include <algorithm>
#include <cmath>
#include <limits>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "core/frame/pair_sort.h"
#include "core/runner/work_units.h"
#include "engine_runner.h"
#include "experiments.h"
#include "pair_diff.h"
#include "peer_runs.h"
#include "peers/peer.h"
#include "peers/uniform_grid.h"
#include "sap_broadphase/core/brute_force.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::PairList;

namespace {

constexpr std::size_t kBruteForceMaxBoxes = std::size_t{1} << 14;
/// A contender that took longer than this for one frame is not run on the case's later frames.
constexpr double kStopFrameMs = 10000.0;
/// A contender whose timed frame took longer than this (FCL's sweep-and-prune and interval
/// tree: 3-8 s a frame at 2^17 on the 2-core VM, 100-400x the exact engine and 25-60x FCL's
/// own tree) stops after kSlowContenderFrames frames: their 16 frames took most of the
/// experiment's 16 minutes (pareto.csv's times), to place a point that one timed frame places as
/// well (its errors are fractions of the frames it ran). Bullet and FCL's tree (at most 1.3 s) run
/// every frame.
constexpr double kSlowContenderFrameMs = 2000.0;
/// The build frame and one timed frame.
constexpr int kSlowContenderFrames = 2;
/// Times below this are drawn at it (the time axis is logarithmic, decades marked).
constexpr double kLeastPlottedMs = 0.01;
/// The harness's own passes (quantising, refitting) go parallel where the engine's do.
const std::size_t kParallelMinBoxes = BroadphaseConfig().parallel_min_boxes;

/// One point of a chart: a way to get a frame's pairs and what that costs.
class Contender {
 public:
  virtual ~Contender() = default;
  virtual std::string name() const = 0;
  /// "ours" or "peer".
  virtual std::string kind() const { return "ours"; }
  /// Computes the frame's pairs into outPairs (canonical order, without duplicates) and
  /// returns the milliseconds of the work a user pays for (the harness's copies excluded).
  virtual double frame(const BoxSet& inBoxes, PairList& outPairs) = 0;
};

/// The engine in one configuration.
class EngineContender : public Contender {
 public:
  EngineContender(std::string inName, const BroadphaseConfig& inConfig)
      : name_(std::move(inName)), engine_(inConfig) {}
  std::string name() const override { return name_; }
  double frame(const BoxSet& inBoxes, PairList& outPairs) override {
    Stopwatch clock;
    const PairList& pairs = engine_.update(inBoxes);
    const double ms = clock.ms();
    outPairs = pairs;
    return ms;
  }

 private:
  std::string name_;
  Broadphase engine_;
};

BroadphaseConfig keysOnlyConfig(int inThreads) {
  BroadphaseConfig config;
  config.threads = inThreads;
  config.exact_final_test = false;
  return config;
}

/// Keys quantised to 16 bits over the frame's bounds, rounded outward, without the exact test.
/// Coordinates become 2^23 + q (q in [0, 65535]): floats in [2^23, 2^24) are the integers, so
/// the engine's float32 keys hold q exactly in their low 16 bits and the rest is the same for
/// every box; the radix sort skips digits that are equal for all keys, so it runs two passes
/// of its 11-bit digits instead of three. Never misses a pair; reports boxes closer than a
/// 65536th of the scene's extent.
class QuantisedContender : public EngineContender {
 public:
  explicit QuantisedContender(int inThreads)
      : EngineContender("keys_16bit", keysOnlyConfig(inThreads)),
        threads_(sap_broadphase::resolveThreadCount(inThreads)) {}
  double frame(const BoxSet& inBoxes, PairList& outPairs) override {
    Stopwatch clock;
    quantise(inBoxes);
    const double quantiseMs = clock.ms();
    return quantiseMs + EngineContender::frame(quantised_, outPairs);
  }

 private:
  void quantise(const BoxSet& inBoxes) {
    const std::size_t n = inBoxes.size();
    quantised_.ids = inBoxes.ids;
    quantised_.groups = inBoxes.groups;
    quantised_.masks = inBoxes.masks;
    quantised_.bounds.resize(sap_broadphase::kBoundsPerBox * n);
    constexpr double kOffset = 8388608.0;  // 2^23
    for (int axis = 0; axis < 3; ++axis) {
      double origin = n ? inBoxes.lo(axis, 0) : 0.0;
      double top = n ? inBoxes.hi(axis, 0) : 0.0;
      for (std::size_t i = 1; i < n; ++i) {
        origin = std::min(origin, inBoxes.lo(axis, i));
        top = std::max(top, inBoxes.hi(axis, i));
      }
      const double scale = top > origin ? 65535.0 / (top - origin) : 0.0;
      const sap_broadphase::ThreadsScope threads(n >= kParallelMinBoxes ? threads_ : 1);
      sap_broadphase::runOverItems(
          sap_broadphase::WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
            for (std::size_t i = inBegin; i < inEnd; ++i) {
              quantised_.lo(axis, i) = kOffset + std::floor((inBoxes.lo(axis, i) - origin) * scale);
              quantised_.hi(axis, i) =
                  kOffset + std::min(65535.0, std::ceil((inBoxes.hi(axis, i) - origin) * scale));
            }
          });
    }
  }

  int threads_;
  BoxSet quantised_;
};

/// Fat boxes as Bullet and Box2D keep them: each box grown by a margin a side, refitted only
/// when the box leaves its fat box; the pairs of overlapping fat boxes are reported (keys
/// only, no exact test). Never misses a pair; reports pairs up to two margins apart.
class FatMarginContender : public EngineContender {
 public:
  FatMarginContender(double inMarginEdges, double inMeanEdge, int inThreads)
      : EngineContender("fat_margin_" + fmt(inMarginEdges, 2), keysOnlyConfig(inThreads)),
        margin_(inMarginEdges * inMeanEdge),
        threads_(sap_broadphase::resolveThreadCount(inThreads)) {}
  double frame(const BoxSet& inBoxes, PairList& outPairs) override {
    Stopwatch clock;
    refit(inBoxes);
    const double refitMs = clock.ms();
    return refitMs + EngineContender::frame(fat_, outPairs);
  }

 private:
  void refit(const BoxSet& inBoxes) {
    const std::size_t n = inBoxes.size();
    if (fat_.ids != inBoxes.ids) {
      fat_ = inBoxes;
      for (int axis = 0; axis < 3; ++axis)
        for (std::size_t i = 0; i < n; ++i)
          fat_.lo(axis, i) -= margin_, fat_.hi(axis, i) += margin_;
      return;
    }
    const sap_broadphase::ThreadsScope threads(n >= kParallelMinBoxes ? threads_ : 1);
    sap_broadphase::runOverItems(sap_broadphase::WorkUnits{n},
                                 [&](std::size_t inBegin, std::size_t inEnd) {
                                   for (std::size_t i = inBegin; i < inEnd; ++i) {
                                     bool inside = true;
                                     for (int axis = 0; axis < 3; ++axis)
                                       inside = inside && inBoxes.lo(axis, i) >= fat_.lo(axis, i) &&
                                                inBoxes.hi(axis, i) <= fat_.hi(axis, i);
                                     if (inside) continue;
                                     for (int axis = 0; axis < 3; ++axis) {
                                       fat_.lo(axis, i) = inBoxes.lo(axis, i) - margin_;
                                       fat_.hi(axis, i) = inBoxes.hi(axis, i) + margin_;
                                     }
                                   }
                                 });
  }

  double margin_;
  int threads_;
  BoxSet fat_;
};

/// Temporal sub-sampling: the exact engine every inEvery-th frame; in between, the last
/// frame's pairs are reported again (misses: pairs that began since; extras: pairs that
/// ended).
class SubsampleContender : public EngineContender {
 public:
  SubsampleContender(int inEvery, int inThreads)
      : EngineContender("subsample_every_" + std::to_string(inEvery),
                        [inThreads] {
                          BroadphaseConfig config;
                          config.threads = inThreads;
                          return config;
                        }()),
        every_(inEvery) {}
  double frame(const BoxSet& inBoxes, PairList& outPairs) override {
    const double ms = frames_++ % every_ == 0 ? EngineContender::frame(inBoxes, last_) : 0.0;
    outPairs = last_;  // the harness's copy: a user keeps the last list, at no cost
    return ms;
  }

 private:
  int every_;
  long frames_ = 0;
  PairList last_;
};

/// A peer's raw candidates in steady state.
class PeerContender : public Contender {
 public:
  explicit PeerContender(std::unique_ptr<Peer> inPeer) : peer_(std::move(inPeer)) {}
  std::string name() const override { return peer_->name(); }
  std::string kind() const override { return "peer"; }
  double frame(const BoxSet& inBoxes, PairList& outPairs) override {
    PeerResult result = peer_->step(inBoxes);
    outPairs = std::move(result.pairs);
    sap_broadphase::sortPairsCanonical(outPairs);
    outPairs.erase(std::unique(outPairs.begin(), outPairs.end()), outPairs.end());
    return result.ms;
  }

 private:
  std::unique_ptr<Peer> peer_;
};

double meanEdge(const BoxSet& inBoxes) {
  double sum = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    for (std::size_t i = 0; i < inBoxes.size(); ++i)
      sum += inBoxes.hi(axis, i) - inBoxes.lo(axis, i);
  return sum / (3.0 * std::max<std::size_t>(1, inBoxes.size()));
}

std::vector<std::unique_ptr<Contender>> makeContenders(int inThreads, double inMeanEdge) {
  std::vector<std::unique_ptr<Contender>> contenders;
  BroadphaseConfig exact;
  exact.threads = inThreads;
  contenders.push_back(std::make_unique<EngineContender>("exact", exact));
  contenders.push_back(std::make_unique<EngineContender>("exact_sequential", sequentialConfig()));
  contenders.push_back(std::make_unique<EngineContender>("keys_only", keysOnlyConfig(inThreads)));
  contenders.push_back(std::make_unique<QuantisedContender>(inThreads));
  for (double margin : {0.05, 0.2})
    contenders.push_back(std::make_unique<FatMarginContender>(margin, inMeanEdge, inThreads));
  for (int every : {2, 4, 8})
    contenders.push_back(std::make_unique<SubsampleContender>(every, inThreads));
  for (auto& peer : makeRawPeers())
    contenders.push_back(std::make_unique<PeerContender>(std::move(peer)));
  return contenders;
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

/// File stem of a case's chart: "pareto_uniform_d0.05", "pareto_lattice", ...
std::string chartName(const BenchCase& inCase) {
  if (inCase.scene != "uniform") return "pareto_" + inCase.scene;
  return "pareto_uniform_d" + fmt(inCase.density, 2);
}

}  // namespace

void runPareto(const Options& inOptions) {
  const std::size_t n = inOptions.size(std::size_t{1} << 17, std::size_t{1} << 12);
  const std::size_t side = static_cast<std::size_t>(std::sqrt(static_cast<double>(n)));
  const int sceneFrames = inOptions.quick ? 100 : 500;
  // Frame 0 builds; the means cover frames 1.. (two sweeps of the every-8th sub-sampling).
  const int frames = inOptions.framesOr(17, 9);
  const std::vector<BenchCase> cases = {
      uniformCase(n, 0.05, inOptions.seed), uniformCase(n, 0.35, inOptions.seed),
      ballCase(n, sceneFrames, inOptions.seed), planeCase(side, sceneFrames, inOptions.seed),
      latticeCase(n)};
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  UniformGrid grid(threads);
  Table table(
      "Run time against error (ms per frame: mean of frames >= 1; errors summed over "
      "all frames)",
      {"case", "contender", "kind", "ms_per_frame", "frames", "true_pairs", "missed", "extra",
       "missed_frac", "extra_frac", "frac_of", "oracle", "grid_vs_brute"});
  std::vector<Figure> figures;
  Progress progress("pareto", cases.size() * frames);
  for (const BenchCase& benchCase : cases) {
    FrameFeed feed = benchCase.makeFeed();
    auto contenders = makeContenders(inOptions.threads, meanEdge(feed.boxes()));
    std::vector<std::vector<double>> times(contenders.size());
    std::vector<PairDiff> totals(contenders.size());
    std::vector<std::size_t> framesRun(contenders.size(), 0);
    std::vector<bool> stopped(contenders.size(), false), skipped(contenders.size(), false);
    for (std::size_t m = 0; m < contenders.size(); ++m)
      skipped[m] = stopped[m] = quadraticOnClusters(contenders[m]->name(), benchCase);
    std::string oracleName;
    bool gridChecked = false, gridAgrees = true;
    PairList pairs;
    for (int f = 0; f < frames; ++f) {
      if (f > 0) feed.step();
      const PairList truth = oracle(feed.boxes(), grid, oracleName, gridChecked, gridAgrees);
      for (std::size_t m = 0; m < contenders.size(); ++m) {
        if (stopped[m]) continue;
        const double ms = contenders[m]->frame(feed.boxes(), pairs);
        ++framesRun[m];
        stopped[m] = ms > kStopFrameMs || (f > 0 && ms > kSlowContenderFrameMs &&
                                           static_cast<int>(framesRun[m]) >= kSlowContenderFrames);
        // One stopped on the build frame keeps that frame's time: the only one it has.
        if (f > 0 || frames == 1 || (stopped[m] && times[m].empty())) times[m].push_back(ms);
        const PairDiff diff = comparePairs(pairs, truth);
        totals[m].truth += diff.truth;
        totals[m].missed += diff.missed;
        totals[m].extra += diff.extra;
      }
      progress.step(benchCase.name);
    }
    // Errors per true pair; a scene without pairs (the plane before it crosses) has them per
    // box instead.
    const bool perBox = totals.empty() || totals[0].truth == 0;
    Panel panel{benchCase.name,
                "ms per frame (mean)",
                perBox ? "error: (missed + extra) / boxes (no true pairs)"
                       : "error: (missed + extra) / true pairs",
                true,
                false,
                PlotStyle::kPoints};
    double worst = 0.0;
    for (std::size_t m = 0; m < contenders.size(); ++m) {
      if (skipped[m]) {
        table.addRow({benchCase.name, contenders[m]->name(), contenders[m]->kind(), "-",
                      "skipped (slow)", "-", "-", "-", "-", "-", "-", oracleName, "-"});
        continue;
      }
      const std::size_t boxFrames = feed.boxes().size() * framesRun[m];
      const double per =
          static_cast<double>(std::max<std::size_t>(1, perBox ? boxFrames : totals[m].truth));
      const double missed = totals[m].missed / per, extra = totals[m].extra / per;
      table.addRow({benchCase.name, contenders[m]->name(), contenders[m]->kind(),
                    fmt(mean(times[m])),
                    std::to_string(framesRun[m]) + (stopped[m] ? " (slow)" : ""),
                    fmtCount(totals[m].truth / std::max<std::size_t>(1, framesRun[m])),
                    fmtCount(totals[m].missed), fmtCount(totals[m].extra), fmt(missed), fmt(extra),
                    perBox ? "box" : "true_pair", oracleName,
                    gridChecked ? (gridAgrees ? "equal" : "DIFFERENT") : "-"});
      Series point{contenders[m]->name(), {}, {}};
      // Sub-sampled frames cost nothing on their own; the mean stays positive (log axis).
      point.add(std::max(mean(times[m]), kLeastPlottedMs), missed + extra);
      worst = std::max(worst, missed + extra);
      panel.series.push_back(point);
    }
    for (double ms = kLeastPlottedMs; ms < 1e5; ms *= 10) panel.xtics.push_back({ms, fmt(ms)});
    panel.yrange = "[-0.02:" + fmt(std::max(0.1, 1.15 * worst)) + "]";
    figures.push_back(Figure{chartName(benchCase), {panel}});
  }
  publish(inOptions, table, "pareto", figures);
}

}  // namespace sap_bench
