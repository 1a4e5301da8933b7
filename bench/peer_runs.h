// One frame of a contender, timed and checked: our engine (a kept engine and a fresh one on
// the same boxes) or a peer. Shared by the peer and size-sweep experiments.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "bench_progress.h"
#include "bench_scenes.h"
#include "peers/peer.h"
#include "sap_broadphase/core/broadphase.h"

namespace sap_bench {

/// A peer that took longer than this for one frame (one-shot and steady together) is not run
/// on the rest of the case's frames: its median then covers the frames it did run (the build
/// frame, when it was stopped there). A peer whose cost per box on an earlier case predicts
/// more than this for a frame is not run on the case at all.
constexpr double kSlowFrameMs = 20000.0;
/// A peer whose first kSlowPeerTimedFrames timed frames (one-shot and steady together) took
/// longer than this on average stops there, marked "(slow)" (its median is of those). Such peers
/// (CGAL's cutoffs, the grid and FCL's trees at 2^20) are 3-20x slower than the default there,
/// and their further frames took most of the peer experiment's 15 minutes on the 2-core VM
/// (peers.csv's times, --frames 4) while moving no ratio the page reads.
constexpr double kSlowPeerFrameMs = 1000.0;
constexpr std::size_t kSlowPeerTimedFrames = 2;
/// A peer whose first timed frame took longer than this (FCL's sweep-and-prune and interval
/// tree at 2^17, Bullet on the 2^19-box ball: 10-600x the default) stops after it.
constexpr double kVerySlowPeerFrameMs = 4000.0;

/// FCL's sweep-and-prune and interval-tree managers keep, per box, every box overlapping it
/// along one axis: on a clustered scene that is most of the scene. registerObjects() of the
/// 2^19-box ball frame did not finish in ten minutes on the 2-core VM (perf: all of it in
/// SaPCollisionManager::registerObjects), and one frame of the 2^17-box ball and plane frames
/// took 120-180 s, so they are not run on clustered scenes (ball, plane) above this size
/// (uniform and lattice cases predict their cost).
constexpr std::size_t kMostClusteredBoxesForQuadratic = std::size_t{1} << 14;

/// True when inPeerName is one of those managers and inCase a clustered scene above that size.
bool quadraticOnClusters(const std::string& inPeerName, const BenchCase& inCase);

/// Times, checks and memory of one contender over the frames of a case.
struct Contender {
  std::string name;
  std::string family;
  std::vector<double> one_shot_ms, steady_ms;
  std::size_t wrong_one_shot = 0, wrong_steady = 0, frames_checked = 0;
  std::size_t last_pairs = 0;
  std::size_t memory_bytes = 0;
  double first_frame_ms = -1.0;  ///< the steady state's first frame (the build), -1 when not run
  bool stopped_slow = false;
  bool skipped_slow = false;  ///< not run: its cost per box on a smaller case predicts > limit
};

/// Per scene (kind and density) and peer, the most milliseconds per box one frame (one-shot and
/// steady together) has cost so far. On the same scene, broad phases get no cheaper per box as
/// n grows, so this times a larger case's n is a lower bound of that case's frame time.
using PeerCosts = std::map<std::string, std::vector<double>>;

/// "ok", "WRONG(k/frames)", or "-" when no frame was checked.
std::string pairStatus(std::size_t inWrong, std::size_t inFrames);

/// The reference run of a frame: ioSteady (the kept engine) answers it, then a fresh engine of
/// inConfig (one-shot), checked against it. Returns the kept engine's pairs, the truth the
/// other contenders are checked against (the copy is untimed).
sap_broadphase::PairList runReferenceFrame(sap_broadphase::Broadphase& ioSteady,
                                           const sap_broadphase::BroadphaseConfig& inConfig,
                                           const sap_broadphase::BoxSet& inBoxes, bool inTimed,
                                           Contender& ioEntry);

/// Runs one frame of an engine configuration both ways: a fresh engine (one-shot) and the
/// kept one (steady), checking both against inTruth.
void runOursFrame(sap_broadphase::Broadphase& ioSteady,
                  const sap_broadphase::BroadphaseConfig& inConfig,
                  const sap_broadphase::BoxSet& inBoxes, const sap_broadphase::PairList& inTruth,
                  bool inTimed, Contender& ioEntry);

/// Runs one peer on one frame, checking its pairs against inTruth; ioCostPerBox keeps the most
/// ms per box a frame has cost it.
void runPeerFrame(Peer& ioPeer, const sap_broadphase::BoxSet& inBoxes,
                  const sap_broadphase::PairList& inTruth, bool inTimed, Contender& ioEntry,
                  double& ioCostPerBox);

/// Runs one peer over inFrames frames of inCase (frame 0 builds its steady state, untimed
/// unless it is the only frame), each checked against inTruth[f], and sets ioEntry.memory_bytes
/// to the growth of the peak resident memory over the first frame. A peer that asks for a
/// process of its own (Peer::ownProcess) runs the whole pass in a forked child, which sends its
/// Contender back: its allocations, page faults and peak memory are not the harness's.
void runPeerPass(Peer& ioPeer, const BenchCase& inCase, int inFrames,
                 const std::vector<sap_broadphase::PairList>& inTruth, Contender& ioEntry,
                 double& ioCostPerBox, Progress& ioProgress);

}  // namespace sap_bench
