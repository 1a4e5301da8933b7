// One frame of a contender, timed and checked (peer_runs.h).
#include "peer_runs.h"

#include <algorithm>

#include "bench_stats.h"
#include "core/pair_sort.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::PairList;

namespace {

/// True when inPairs (any order) are exactly inTruth (canonical order).
bool samePairs(PairList inPairs, const PairList& inTruth) {
  sap_broadphase::sortPairsCanonical(inPairs);
  return inPairs == inTruth;
}

}  // namespace

std::string pairStatus(std::size_t inWrong, std::size_t inFrames) {
  if (inFrames == 0) return "-";
  return inWrong == 0 ? "ok"
                      : "WRONG(" + std::to_string(inWrong) + "/" + std::to_string(inFrames) + ")";
}

PairList runReferenceFrame(Broadphase& ioSteady, const BroadphaseConfig& inConfig,
                           const BoxSet& inBoxes, bool inTimed, Contender& ioEntry) {
  Stopwatch clock;
  const PairList& kept = ioSteady.update(inBoxes);
  const double steadyMs = clock.ms();
  PairList truth = kept;
  clock.restart();
  Broadphase fresh(inConfig);
  const PairList& freshPairs = fresh.update(inBoxes);
  const double oneShotMs = clock.ms();
  ++ioEntry.frames_checked;
  ioEntry.wrong_one_shot += freshPairs != truth;
  ioEntry.last_pairs = truth.size();
  if (inTimed) ioEntry.steady_ms.push_back(steadyMs), ioEntry.one_shot_ms.push_back(oneShotMs);
  return truth;
}

void runOursFrame(Broadphase& ioSteady, const BroadphaseConfig& inConfig, const BoxSet& inBoxes,
                  const PairList& inTruth, bool inTimed, Contender& ioEntry) {
  ++ioEntry.frames_checked;
  Stopwatch clock;
  const PairList& kept = ioSteady.update(inBoxes);
  const double steadyMs = clock.ms();
  ioEntry.wrong_steady += kept != inTruth;
  clock.restart();
  Broadphase fresh(inConfig);
  const PairList& once = fresh.update(inBoxes);
  const double oneShotMs = clock.ms();
  ioEntry.wrong_one_shot += once != inTruth;
  ioEntry.last_pairs = kept.size();
  if (inTimed) ioEntry.steady_ms.push_back(steadyMs), ioEntry.one_shot_ms.push_back(oneShotMs);
}

void runPeerFrame(Peer& ioPeer, const BoxSet& inBoxes, const PairList& inTruth, bool inTimed,
                  Contender& ioEntry, double& ioCostPerBox) {
  if (ioEntry.stopped_slow || ioEntry.skipped_slow) return;
  ++ioEntry.frames_checked;
  const PeerResult once = ioPeer.oneShot(inBoxes);
  ioEntry.wrong_one_shot += !samePairs(once.pairs, inTruth);
  double steadyMs = once.ms;
  if (ioPeer.incremental()) {
    const PeerResult kept = ioPeer.step(inBoxes);
    ioEntry.wrong_steady += !samePairs(kept.pairs, inTruth);
    ioEntry.last_pairs = kept.pairs.size();
    steadyMs = kept.ms;
  } else {
    ioEntry.wrong_steady += !samePairs(once.pairs, inTruth);
    ioEntry.last_pairs = once.pairs.size();
  }
  ioEntry.stopped_slow = once.ms + steadyMs > kSlowFrameMs;
  ioCostPerBox =
      std::max(ioCostPerBox, (once.ms + steadyMs) / std::max<std::size_t>(1, inBoxes.size()));
  // A peer stopped on the build frame keeps that frame's times: the only ones it has.
  if (inTimed || (ioEntry.stopped_slow && ioEntry.one_shot_ms.empty()))
    ioEntry.one_shot_ms.push_back(once.ms), ioEntry.steady_ms.push_back(steadyMs);
}

}  // namespace sap_bench
