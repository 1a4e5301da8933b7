// Memory of the engine, two tables.
//
// memory.csv: the peak of the default engine in steady use (uniform scene moving 1 % of a mean
// edge a frame, enough frames for the kept candidates to be rebuilt at least once), against the
// target of 120 bytes per box plus 8 per pair, and beside it PhysX's PABP (on the same threads)
// and ABP over the same frames when PhysX is built (up to 2^20 boxes). Each contender runs in a
// forked process of its own that makes the scene and then resets its peak resident set (VmHWM,
// through /proc/self/clear_refs), so the growth during the frames is the contender's own: the
// engine's buffers and pair output; PhysX's structures, the input arrays it reads (float bounds,
// groups, distances, handles) and the found and lost pairs it reports, no pair set accumulated from
// them.
//
// memory_parts.csv: bytes per box of each structure the default holds, measured on the same
// scene with the engine's parts run one after the other on one thread, as a sweep frame with the
// engine's chosen skin runs them: the history (the engine's copy of the frame and its change
// flags), the sweep's working buffers (keys, ranks, candidate ranges, sort and pairing scratch:
// the resident growth of one plain sweep beyond its pair list), one pair list, the grown boxes,
// the kept candidates, a kept-candidate pass's buffers and the skin's sorting scratch; the
// small-frame kernel's workspace on the grown boxes (the grown sweep of two threads or fewer);
// then the successor that the kept-candidate frames build a step a frame, beside the kept
// candidates it will replace: at the slab step where it held most, its grown boxes, the
// candidates its slabs found, its order, one slab's buffers, the slab kernel's workspace and
// the slab's ids; at the adoption step where it held most, its candidates and adoption scratch
// (each phase's total includes its grown boxes). Capacities where the engine's part can tell them
// (history, skin, kernel, successor), resident growth for the sweep.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <utility>

#include "bench_memory.h"
#include "bench_output.h"
#include "bench_scenes.h"
#include "core/frame/frame_history.h"
#include "core/strategies/skin_list.h"
#include "core/strategies/skin_reuse.h"
#include "core/strategies/small_frame.h"
#include "core/sweep/axis_spread.h"
#include "core/sweep/sweep_and_prune.h"
#include "engine_runner.h"
#include "experiments.h"
#include "peers/peer.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxColumns;
using sap_broadphase::PairList;

/// Motion a frame, in mean box edges, as in the size sweep (exp_sizes.cpp).
constexpr double kSpeed = 0.01;

sap_broadphase::SceneConfig movingScene(std::size_t inCount, double inDensity, uint64_t inSeed) {
  sap_broadphase::SceneConfig scene = uniformScene(inCount, inDensity, inSeed);
  scene.speed = kSpeed;
  return scene;
}

std::string perBox(std::size_t inBytes, std::size_t inBoxes) {
  return fmt(static_cast<double>(inBytes) / static_cast<double>(inBoxes), 3);
}

/// The skin the default chooses for this scene: the engine run for a few frames.
double chosenSkin(const sap_broadphase::SceneConfig& inScene, int inThreads) {
  sap_broadphase::SceneSimulator simulator(inScene);
  sap_broadphase::BroadphaseConfig config;
  config.threads = inThreads;
  sap_broadphase::Broadphase engine(config);
  double skin = 0.0;
  for (int f = 0; f < 4 && skin == 0.0; ++f) {
    if (f > 0) simulator.step();
    engine.update(simulator.boxes());
    skin = engine.stats().skin;
  }
  return skin;
}

/// What a successor held at its largest step, while its slabs were swept and while it was
/// adopted (all zero if it never took over).
struct LargestSuccessor {
  sap_broadphase::SkinReuse::SuccessorMemoryUse sweeping;
  sap_broadphase::SkinReuse::SuccessorMemoryUse adopting;
};

/// The successor of kept candidates grown by inSkin from ioHistory's loaded frame, built over
/// the frames of ioSimulator that follow (kept-candidate frames, as the engine runs them) until it
/// takes over.
LargestSuccessor largestSuccessor(sap_broadphase::SceneSimulator& ioSimulator,
                                  sap_broadphase::FrameHistory& ioHistory, double inSkin) {
  using namespace sap_broadphase;
  constexpr int kMostFrames = 400;
  SkinReuse skin;
  FrameReport report;
  PairList pairs;
  {
    const BoxColumns& boxes = ioHistory.loaded();
    const BoxColumns& grown = skin.grow(boxes, inSkin, report);
    FrameSpread grown_spread(grown);
    SmallFrameWorkspace kernel;
    pairSmallFrame(grown, grown_spread, kernel, pairs);
    skin.keepAndAnswer(boxes, report, pairs);
  }
  ioHistory.remember();
  LargestSuccessor largest;
  std::optional<ValidationError> problem;
  for (int frame = 0; frame < kMostFrames && skin.successorsTaken() == 0; ++frame) {
    ioSimulator.step();
    const FrameDelta& delta = ioHistory.load(ioSimulator.boxes(), problem);
    skin.startFrame(delta);
    if (!skin.coversFrame(ioHistory.loaded(), report)) return LargestSuccessor();
    skin.answerFromCandidates(report, pairs);
    skin.advanceSuccessor(ioHistory.loaded(), report);
    const SkinReuse::SuccessorMemoryUse use = skin.successorMemoryUse();
    // Adopting once the slabs' candidates are the list's: the adoption's arrays are sized.
    auto& phase = use.list.candidates > 0 ? largest.adopting : largest.sweeping;
    if (use.total() > phase.total()) phase = use;
    ioHistory.remember();
  }
  return skin.successorsTaken() > 0 ? largest : LargestSuccessor();
}

/// One row per structure of the parts table.
void addParts(const sap_broadphase::SceneConfig& inScene, double inSkin, Table& ioTable) {
  using namespace sap_broadphase;
  SceneSimulator simulator(inScene);
  const std::size_t n = inScene.n;
  FrameHistory history;
  std::optional<ValidationError> problem;
  history.load(simulator.boxes(), problem);
  const BoxColumns& boxes = history.loaded();
  BroadphaseConfig config;
  SweepAndPrune sweep(config);
  FrameReport report;
  PairList pairs;
  PeakMeter meter;
  meter.start();
  {
    FrameSpread spread(boxes);
    sweep.run(boxes, spread, FramePath::kParallel, report, pairs);
  }
  const std::size_t pair_bytes = pairs.capacity() * sizeof(IdPair);
  const std::size_t sweep_bytes =
      meter.grownBytes() > pair_bytes ? meter.grownBytes() - pair_bytes : 0;
  const std::size_t frame_pairs = pairs.size();
  SkinList kept;
  const BoxColumns& grown = kept.inflate(boxes, inSkin);
  {
    FrameSpread grown_spread(grown);
    sweep.run(grown, grown_spread, FramePath::kParallel, report, pairs);
  }
  const std::size_t candidates = pairs.size();
  SmallFrameWorkspace kernel;
  {
    FrameSpread grown_spread(grown);
    PairList kernel_pairs;
    pairSmallFrame(grown, grown_spread, kernel, kernel_pairs);
  }
  const std::size_t kernel_bytes = kernel.bytesHeld();
  kernel = SmallFrameWorkspace();
  kept.adopt(boxes, std::move(pairs));
  if (kept.gather(boxes)) kept.collectGathered(pairs);
  const SkinList::MemoryUse skin = kept.memoryUse();
  kept = SkinList();
  const LargestSuccessor successor = largestSuccessor(simulator, history, inSkin);
  const auto row = [&](const std::string& inPart, std::size_t inBytes, const std::string& inHow) {
    ioTable.addRow({fmtSize(n), fmt(inScene.density, 2), fmt(inSkin, 3), fmtCount(frame_pairs),
                    fmtCount(candidates), inPart, fmtCount(inBytes), perBox(inBytes, n), inHow});
  };
  row("history", history.bytesHeld(), "capacity");
  row("sweep_buffers", sweep_bytes, "resident growth");
  row("pair_list", frame_pairs * sizeof(IdPair), "size");
  row("grown_boxes", skin.reference, "capacity");
  row("kept_candidates", skin.candidates, "capacity");
  row("pass_buffers", skin.pass, "capacity");
  row("skin_scratch", skin.scratch, "capacity");
  row("small_frame_kernel", kernel_bytes, "capacity");
  const std::string sweeping = "capacity at its largest slab step";
  const SkinReuse::SuccessorMemoryUse& slabs = successor.sweeping;
  row("successor_grown_boxes", slabs.list.reference, sweeping);
  row("successor_found", slabs.found, sweeping);
  row("successor_order", slabs.order, sweeping);
  row("successor_slab", slabs.slab, sweeping);
  row("successor_slab_kernel", slabs.kernel, sweeping);
  row("successor_slab_ids", slabs.slab_ids, sweeping);
  row("successor_sweeping_total", slabs.total(), sweeping);
  const std::string adopting = "capacity at its largest adoption step";
  const SkinReuse::SuccessorMemoryUse& adoption = successor.adopting;
  row("successor_candidates", adoption.list.candidates, adopting);
  row("successor_adopt_scratch", adoption.list.scratch, adopting);
  row("successor_adopting_total", adoption.total(), adopting);
}

/// The peak memory of one contender's steady frames, measured in a process of its own.
struct SteadyPeak {
  std::size_t grown = 0;    ///< peak resident growth above the process with its scene made
  std::size_t process = 0;  ///< the process's peak resident set
  std::size_t pairs = 0;    ///< the most pairs of a frame (the engine's)
  int grown_sweeps = 0;     ///< frames after the first that grew and kept candidates (engine)
  bool peak_reset = false;
  bool ran = false;
};

/// Runs inFrames(simulator, peak) in a forked child that makes the scene, resets its peak and
/// sends its SteadyPeak back through a pipe: every contender's heap, pages and peak are its own,
/// and each starts from the same process. ran stays false when the child failed.
template <class Frames>
SteadyPeak peakInChild(const sap_broadphase::SceneConfig& inScene, Frames&& inFrames) {
  SteadyPeak peak;
  int fds[2];
  if (pipe(fds) != 0) return peak;
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0) {
    close(fds[0]), close(fds[1]);
    return peak;
  }
  if (child == 0) {
    close(fds[0]);
    SteadyPeak measured;
    {
      sap_broadphase::SceneSimulator simulator(inScene);
      PeakMeter meter;
      meter.start();
      inFrames(simulator, measured);
      measured.grown = meter.grownBytes();
      measured.process = meter.processPeakBytes();
      measured.peak_reset = meter.peakReset();
      measured.ran = true;
    }
    const char* at = reinterpret_cast<const char*>(&measured);
    std::size_t left = sizeof(measured);
    while (left > 0) {
      const ssize_t written = write(fds[1], at, left);
      if (written <= 0) break;
      at += written, left -= static_cast<std::size_t>(written);
    }
    close(fds[1]);
    _exit(0);  // no destructors or atexit handlers of the parent's objects
  }
  close(fds[1]);
  SteadyPeak received;
  char* at = reinterpret_cast<char*>(&received);
  std::size_t left = sizeof(received);
  while (left > 0) {
    const ssize_t got = read(fds[0], at, left);
    if (got <= 0) break;
    at += got, left -= static_cast<std::size_t>(got);
  }
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (left == 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0) peak = received;
  return peak;
}

/// A peer's steady frames keeping no pair set (Peer::stepKeepingNoPairs), in a child of its own;
/// not run (ran false) without the peer.
/// Most boxes PhysX's contenders are measured at: at 2^23 their 40 frames took 8-10 minutes a
/// contender and density on the 2-core VM (the scene's steps included), four times the rest of
/// `bench.sh --all`'s memory runs; above it their columns read "-".
constexpr std::size_t kMostPeerBoxes = std::size_t{1} << 20;

SteadyPeak peerPeak(Peer* ioPeer, const sap_broadphase::SceneConfig& inScene, int inFrames) {
  if (!ioPeer || inScene.n > kMostPeerBoxes) return SteadyPeak();
  return peakInChild(inScene, [&](sap_broadphase::SceneSimulator& ioSimulator, SteadyPeak&) {
    ioPeer->begin();
    for (int f = 0; f < inFrames; ++f) {
      if (f > 0) ioSimulator.step();
      if (!ioPeer->stepKeepingNoPairs(ioSimulator.boxes())) _exit(1);
    }
    ioPeer->begin();
  });
}

}  // namespace

void runMemory(const Options& inOptions) {
  const auto sizes = inOptions.sizes({1u << 17, 1u << 20}, {1u << 14, 1u << 16});
  const int frames = inOptions.framesOr(40, 3);
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  Table table(
      "Peak memory of the default engine over steady frames at 1 % motion, beside PhysX's PABP "
      "and ABP on the same frames (bytes; each in a process of its own; target 120/box + "
      "8/pair)",
      {"n", "d", "pairs", "frames", "grown_sweeps", "engine_peak_bytes", "bytes_per_box",
       "budget_bytes", "within_budget", "process_peak_bytes", "peak_reset", "pabp_peak_bytes",
       "pabp_process_peak_bytes", "abp_peak_bytes", "abp_process_peak_bytes", "ratio_to_pabp",
       "process_ratio_to_pabp"});
  Table parts(
      "Bytes per box of each structure of the default (one thread; sweep frame with the "
      "chosen skin)",
      {"n", "d", "skin", "pairs", "candidates", "structure", "bytes", "bytes_per_box",
       "measured_as"});
  // The PhysX peers the size sweep runs (ABP on one thread, PABP on the chosen threads); none
  // when PhysX is not built.
  std::unique_ptr<Peer> pabp, abp;
  for (auto& peer : makePeers(threads)) {
    if (peer->family() != "physx") continue;
    if (peer->name() == "physx_abp")
      abp = std::move(peer);
    else if (peer->name() != "physx_mbp")
      pabp = std::move(peer);
  }
  // Every contender's frames in a forked child, before this process runs an engine (a child
  // must not inherit an OpenMP team); the parts table afterwards, in this process.
  const std::vector<double> densities = {0.05, 0.35};
  for (std::size_t n : sizes) {
    for (double density : densities) {
      const sap_broadphase::SceneConfig scene = movingScene(n, density, inOptions.seed);
      const SteadyPeak ours =
          peakInChild(scene, [&](sap_broadphase::SceneSimulator& ioSimulator, SteadyPeak& ioPeak) {
            sap_broadphase::BroadphaseConfig config;
            config.threads = threads;
            sap_broadphase::Broadphase engine(config);
            for (int f = 0; f < frames; ++f) {
              if (f > 0) ioSimulator.step();
              ioPeak.pairs = std::max(ioPeak.pairs, engine.update(ioSimulator.boxes()).size());
              const auto& stats = engine.stats();
              ioPeak.grown_sweeps += f > 0 && stats.path != sap_broadphase::FramePath::kSkin &&
                                     stats.skin_choice == sap_broadphase::SkinChoice::kChosen;
            }
          });
      const SteadyPeak pabp_peak = peerPeak(pabp.get(), scene, frames);
      const SteadyPeak abp_peak = peerPeak(abp.get(), scene, frames);
      const std::size_t budget = 120 * n + 8 * ours.pairs;
      const auto bytesOr = [](const SteadyPeak& inPeak, std::size_t inBytes) {
        return inPeak.ran ? fmtCount(inBytes) : std::string("-");
      };
      const auto ratio = [](const SteadyPeak& inOurs, const SteadyPeak& inPeer,
                            std::size_t SteadyPeak::*inField) {
        return inOurs.ran && inPeer.ran && inPeer.*inField > 0
                   ? fmt(static_cast<double>(inOurs.*inField) / inPeer.*inField, 3)
                   : std::string("-");
      };
      table.addRow({fmtSize(n), fmt(density, 2), fmtCount(ours.pairs), std::to_string(frames),
                    std::to_string(ours.grown_sweeps), bytesOr(ours, ours.grown),
                    ours.ran ? fmt(static_cast<double>(ours.grown) / n) : "-", fmtCount(budget),
                    !ours.ran              ? "-"
                    : ours.grown <= budget ? "yes"
                                           : "NO",
                    bytesOr(ours, ours.process), ours.peak_reset ? "yes" : "no",
                    bytesOr(pabp_peak, pabp_peak.grown), bytesOr(pabp_peak, pabp_peak.process),
                    bytesOr(abp_peak, abp_peak.grown), bytesOr(abp_peak, abp_peak.process),
                    ratio(ours, pabp_peak, &SteadyPeak::grown),
                    ratio(ours, pabp_peak, &SteadyPeak::process)});
    }
  }
  for (std::size_t n : sizes) {
    for (double density : densities) {
      const sap_broadphase::SceneConfig scene = movingScene(n, density, inOptions.seed);
      const double skin = chosenSkin(scene, threads);
      if (skin > 0.0) addParts(scene, skin, parts);
    }
  }
  publish(inOptions, table, "memory");
  publish(inOptions, parts, "memory_parts");
}

}  // namespace sap_bench
