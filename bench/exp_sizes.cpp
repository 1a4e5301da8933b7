// Frame time against box count, 2^8 to 2^20: the engine's default configuration (on the chosen
// threads and on one thread) and the engine without skin, beside the peers' best-known
// settings (FCL's dynamic AABB tree, CGAL, Bullet's dynamic tree, PhysX's ABP and PABP: those
// built), on uniform scenes at two densities whose boxes move 1 % of a mean edge a frame. Each
// frame is timed one-shot (a fresh engine or structure) and steady (kept across frames), and
// every frame's pairs are checked against the default's. Each contender runs the frames alone
// (a peer that asks for it in a process of its own).
#include <algorithm>
#include <functional>
#include <limits>

#include "bench_output.h"
#include "bench_progress.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "experiments.h"
#include "peer_runs.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::PairList;

namespace {

/// Motion a frame, in mean box edges: the coherent steady state of a robot or a game level.
constexpr double kSpeed = 0.01;
constexpr double kDensities[] = {0.05, 0.35};

/// Frames per case (the first only builds the steady state): many where frames are cheap, so
/// medians are stable, few at 2^18 and up, where a peer's frame takes seconds.
int framesFor(const Options& inOptions, std::size_t inCount) {
  if (inOptions.frames > 0) return inOptions.frames;
  if (inOptions.quick) return 3;
  if (inCount <= (std::size_t{1} << 14)) return 21;
  return inCount <= (std::size_t{1} << 17) ? 8 : 4;
}

/// Frames a case of the peers other than PhysX (FCL, CGAL, Bullet) run at most: the build
/// and 20 timed, as every contender runs up to 2^14 by default. The PhysX run of the page
/// (--frames 201) reads ours beside PhysX's p50, p99 and worst over 200 frames; the other
/// peers' 200 frames took 440 of its 540 s on the 2-core VM and no table reads them.
constexpr int kMostLibraryPeerFrames = 21;

/// Frames inPeer runs of a case of inFrames.
int peerFrames(const Peer& inPeer, int inFrames) {
  return inPeer.family() == "physx" ? inFrames : std::min(inFrames, kMostLibraryPeerFrames);
}

/// The engine's rows: the default on the chosen threads (the reference), the default on one
/// thread, and the chosen threads without skin (every frame swept).
struct OursRow {
  std::string name;
  BroadphaseConfig config;
};

std::vector<OursRow> oursRows(int inThreads) {
  BroadphaseConfig chosen;
  chosen.threads = inThreads;
  BroadphaseConfig one = chosen;
  one.threads = 1;
  BroadphaseConfig noSkin = chosen;
  noSkin.skin = 0.0;
  noSkin.reuse_unchanged_frames = false;
  return {{"sap_broadphase_t" + std::to_string(inThreads), chosen},
          {"sap_broadphase_t1", one},
          {"sap_broadphase_no_skin_t" + std::to_string(inThreads), noSkin}};
}

/// Of the peers built, the setting of each library the peer experiment found fastest on uniform
/// scenes; the others (FCL's sweep-and-prune and interval tree, CGAL's other cutoffs) would
/// cost minutes at 2^20 and lead nowhere.
Peers sizePeers(int inThreads) {
  Peers kept;
  for (auto& peer : makePeers(inThreads)) {
    const std::string name = peer->name();
    const bool cgal1000 = peer->family().rfind("cgal", 0) == 0 && name.size() > 6 &&
                          name.compare(name.size() - 6, 6, "_c1000") == 0;
    const bool physxAbp = peer->family() == "physx" && name != "physx_mbp";
    if (name == "fcl_dynamic_aabb" || name == "bullet_dbvt" || cgal1000 || physxAbp)
      kept.push_back(std::move(peer));
  }
  return kept;
}

BenchCase movingCase(std::size_t inCount, double inDensity, uint64_t inSeed) {
  sap_broadphase::SceneConfig scene = uniformScene(inCount, inDensity, inSeed);
  scene.speed = kSpeed;
  BenchCase bench = uniformCase(inCount, inDensity, inSeed);
  bench.makeFeed = [scene] { return FrameFeed(scene, 0); };
  return bench;
}

/// Every contender over one case's frames: ours first, then the peers. Each runs the frames
/// alone, in a pass of its own over the same scene (so a kept engine's buffers and an OpenMP
/// team spinning after a two-thread frame do not slow the contender after it); the default's
/// pass keeps every frame's pairs, the truth the other passes are checked against.
std::vector<Contender> runCase(const BenchCase& inCase, int inFrames,
                               const std::vector<OursRow>& inOurs, Peers& ioPeers,
                               std::vector<double>& ioCosts, Progress& ioProgress) {
  std::vector<Contender> contenders(inOurs.size() + ioPeers.size());
  for (std::size_t k = 0; k < inOurs.size(); ++k)
    contenders[k].name = contenders[k].family = inOurs[k].name;
  for (std::size_t p = 0; p < ioPeers.size(); ++p) {
    Contender& entry = contenders[inOurs.size() + p];
    entry.name = ioPeers[p]->name();
    entry.family = ioPeers[p]->family();
    entry.skipped_slow = ioCosts[p] * inCase.n > kSlowFrameMs;
  }
  // inFrame(f, boxes, timed) for each frame of one pass over the scene.
  auto pass = [&](const std::function<void(int, const BoxSet&, bool)>& inFrame) {
    FrameFeed feed = inCase.makeFeed();
    for (int f = 0; f < inFrames; ++f) {
      if (f > 0) feed.step();
      inFrame(f, feed.boxes(), f > 0 || inFrames == 1);
      ioProgress.step(inCase.name);
    }
  };
  std::vector<PairList> truth(inFrames);
  Broadphase reference(inOurs[0].config);
  pass([&](int f, const BoxSet& boxes, bool timed) {
    truth[f] = runReferenceFrame(reference, inOurs[0].config, boxes, timed, contenders[0]);
  });
  for (std::size_t k = 1; k < inOurs.size(); ++k) {
    Broadphase engine(inOurs[k].config);
    pass([&](int f, const BoxSet& boxes, bool timed) {
      runOursFrame(engine, inOurs[k].config, boxes, truth[f], timed, contenders[k]);
    });
  }
  for (std::size_t p = 0; p < ioPeers.size(); ++p)
    runPeerPass(*ioPeers[p], inCase, peerFrames(*ioPeers[p], inFrames), truth,
                contenders[inOurs.size() + p], ioCosts[p], ioProgress);
  return contenders;
}

std::string densityName(double inDensity) {
  return "d=" + fmt(inDensity, 2);
}

}  // namespace

void runSizes(const Options& inOptions) {
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  const std::vector<std::size_t> sizes = inOptions.sizes(powersOfTwo(8, 20), powersOfTwo(8, 12));
  const std::vector<OursRow> ours = oursRows(threads);
  Peers peers = sizePeers(threads);
  std::size_t totalFrames = 0;
  for (std::size_t n : sizes) {
    std::size_t caseFrames = ours.size() * framesFor(inOptions, n);
    for (const auto& peer : peers) caseFrames += peerFrames(*peer, framesFor(inOptions, n));
    totalFrames += std::size(kDensities) * caseFrames;
  }
  Progress progress("sizes", totalFrames);
  Table table(
      "Sizes: ms per frame (median of frames >= 1; steady also its 99th percentile and worst), "
      "uniform scene moving 1 % of an edge a frame; every frame's pairs checked against the "
      "default's; ratio = contender / default",
      {"n", "density", "contender", "one_shot_ms", "ratio_one_shot", "steady_ms", "ratio_steady",
       "pairs", "pairs_one_shot", "pairs_steady", "frames", "steady_p99_ms", "steady_worst_ms",
       "first_frame_ms"});
  std::vector<Panel> panels;
  for (double density : kDensities) {
    std::map<std::string, Series> once, kept;
    std::vector<double> costs(peers.size(), 0.0);
    for (std::size_t n : sizes) {
      const BenchCase bench = movingCase(n, density, inOptions.seed);
      const std::vector<Contender> contenders =
          runCase(bench, framesFor(inOptions, n), ours, peers, costs, progress);
      const double refOnce = median(contenders[0].one_shot_ms);
      const double refKept = median(contenders[0].steady_ms);
      for (std::size_t k = 0; k < contenders.size(); ++k) {
        const Contender& entry = contenders[k];
        const bool ran = !entry.one_shot_ms.empty();
        const double oneShot = median(entry.one_shot_ms), steady = median(entry.steady_ms);
        table.addRow({fmtSize(n), fmt(density, 2), entry.name, ran ? fmt(oneShot) : "-",
                      ran ? fmtRatio(oneShot, refOnce) : "-", ran ? fmt(steady) : "-",
                      ran ? fmtRatio(steady, refKept) : "-", fmtCount(entry.last_pairs),
                      pairStatus(entry.wrong_one_shot, entry.frames_checked),
                      k == 0 ? "reference" : pairStatus(entry.wrong_steady, entry.frames_checked),
                      entry.skipped_slow ? "skipped (slow)"
                                         : std::to_string(entry.one_shot_ms.size()) +
                                               (entry.stopped_slow ? " (slow)" : ""),
                      ran ? fmt(percentile(entry.steady_ms, 0.99)) : "-",
                      ran ? fmt(maximum(entry.steady_ms)) : "-",
                      entry.first_frame_ms >= 0 ? fmt(entry.first_frame_ms) : "-"});
        if (!ran) continue;
        once[entry.name].add(static_cast<double>(n), oneShot);
        kept[entry.name].add(static_cast<double>(n), steady);
      }
    }
    for (auto* mode : {&once, &kept}) {
      Panel panel((mode == &once ? "One-shot, " : "Steady at 1 % motion, ") + densityName(density),
                  "boxes", "ms per frame", true, true, PlotStyle::kLinesPoints);
      const std::size_t tick_step = sizes.size() > 7 ? 2 : 1;  // labels that do not collide
      for (std::size_t k = 0; k < sizes.size(); k += tick_step)
        panel.xtics.push_back({static_cast<double>(sizes[k]), fmtSize(sizes[k])});
      for (auto& [name, series] : *mode) {
        series.title = name;
        panel.series.push_back(series);
      }
      panels.push_back(panel);
    }
  }
  publish(inOptions, table, "sizes", {Figure{"sizes", panels, 2}});
}

}  // namespace sap_bench
