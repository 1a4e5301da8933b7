// One frame of a contender, timed and checked (peer_runs.h).
#include "peer_runs.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "bench_memory.h"
#include "bench_stats.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::PairList;

namespace {

/// True when inPairs (any order) are exactly inTruth (canonical order). std::sort, not the
/// engine's parallel sort: a forked child must not open an OpenMP team (libgomp's threads are
/// the parent's).
bool samePairs(PairList inPairs, const PairList& inTruth) {
  std::sort(inPairs.begin(), inPairs.end());
  return inPairs == inTruth;
}

/// Every frame of the pass in this process, the memory of the first frame measured.
void runPassHere(Peer& ioPeer, const BenchCase& inCase, int inFrames,
                 const std::vector<PairList>& inTruth, Contender& ioEntry, double& ioCostPerBox) {
  FrameFeed feed = inCase.makeFeed();
  PeakMeter meter;
  meter.start();
  ioPeer.begin();
  for (int f = 0; f < inFrames; ++f) {
    if (f > 0) feed.step();
    runPeerFrame(ioPeer, feed.boxes(), inTruth[f], f > 0 || inFrames == 1, ioEntry, ioCostPerBox);
    if (f == 0) ioEntry.memory_bytes = meter.grownBytes();
  }
  ioPeer.begin();  // frees the steady state
}

/// The Contender's results through a pipe, as raw values (both ends are this program).
void writeAll(int inFd, const void* inData, std::size_t inBytes) {
  const char* at = static_cast<const char*>(inData);
  while (inBytes > 0) {
    const ssize_t written = write(inFd, at, inBytes);
    if (written <= 0) return;
    at += written, inBytes -= static_cast<std::size_t>(written);
  }
}

bool readAll(int inFd, void* outData, std::size_t inBytes) {
  char* at = static_cast<char*>(outData);
  while (inBytes > 0) {
    const ssize_t got = read(inFd, at, inBytes);
    if (got <= 0) return false;
    at += got, inBytes -= static_cast<std::size_t>(got);
  }
  return true;
}

template <class T>
void writeValue(int inFd, const T& inValue) {
  writeAll(inFd, &inValue, sizeof(T));
}

void writeTimes(int inFd, const std::vector<double>& inTimes) {
  writeValue(inFd, inTimes.size());
  writeAll(inFd, inTimes.data(), inTimes.size() * sizeof(double));
}

bool readTimes(int inFd, std::vector<double>& outTimes) {
  std::size_t count = 0;
  if (!readAll(inFd, &count, sizeof(count))) return false;
  outTimes.resize(count);
  return readAll(inFd, outTimes.data(), count * sizeof(double));
}

void writeContender(int inFd, const Contender& inEntry, double inCostPerBox) {
  writeTimes(inFd, inEntry.one_shot_ms);
  writeTimes(inFd, inEntry.steady_ms);
  for (std::size_t value : {inEntry.wrong_one_shot, inEntry.wrong_steady, inEntry.frames_checked,
                            inEntry.last_pairs, inEntry.memory_bytes})
    writeValue(inFd, value);
  writeValue(inFd, inEntry.first_frame_ms);
  writeValue(inFd, inEntry.stopped_slow);
  writeValue(inFd, inCostPerBox);
}

bool readContender(int inFd, Contender& ioEntry, double& ioCostPerBox) {
  bool ok = readTimes(inFd, ioEntry.one_shot_ms) && readTimes(inFd, ioEntry.steady_ms);
  for (std::size_t* value : {&ioEntry.wrong_one_shot, &ioEntry.wrong_steady,
                             &ioEntry.frames_checked, &ioEntry.last_pairs, &ioEntry.memory_bytes})
    ok = ok && readAll(inFd, value, sizeof(*value));
  double cost = 0.0;
  ok = ok && readAll(inFd, &ioEntry.first_frame_ms, sizeof(double)) &&
       readAll(inFd, &ioEntry.stopped_slow, sizeof(bool)) && readAll(inFd, &cost, sizeof(cost));
  if (ok) ioCostPerBox = std::max(ioCostPerBox, cost);
  return ok;
}

/// The pass in a forked child; false (ioEntry untouched) when the child could not be made or
/// died without its results.
bool runPassInChild(Peer& ioPeer, const BenchCase& inCase, int inFrames,
                    const std::vector<PairList>& inTruth, Contender& ioEntry,
                    double& ioCostPerBox) {
  int fds[2];
  if (pipe(fds) != 0) return false;
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0) {
    close(fds[0]), close(fds[1]);
    return false;
  }
  if (child == 0) {
    close(fds[0]);
    Contender entry = ioEntry;
    double cost = ioCostPerBox;
    runPassHere(ioPeer, inCase, inFrames, inTruth, entry, cost);
    writeContender(fds[1], entry, cost);
    close(fds[1]);
    _exit(0);  // no destructors or atexit handlers of the parent's objects
  }
  close(fds[1]);
  Contender received = ioEntry;
  double cost = ioCostPerBox;
  const bool ok = readContender(fds[0], received, cost);
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (!ok || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return false;
  ioEntry = std::move(received);
  ioCostPerBox = cost;
  return true;
}

}  // namespace

bool quadraticOnClusters(const std::string& inPeerName, const BenchCase& inCase) {
  const bool quadratic =
      inPeerName.rfind("fcl_sap", 0) == 0 || inPeerName.rfind("fcl_interval_tree", 0) == 0;
  return quadratic && inCase.n > kMostClusteredBoxesForQuadratic &&
         (inCase.scene == "ball" || inCase.scene == "plane");
}

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
  if (!inTimed && ioEntry.first_frame_ms < 0) ioEntry.first_frame_ms = steadyMs;
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
  if (!inTimed && ioEntry.first_frame_ms < 0) ioEntry.first_frame_ms = steadyMs;
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
  PeerResult once = ioPeer.oneShot(inBoxes);
  ioEntry.wrong_one_shot += !samePairs(once.pairs, inTruth);
  double steadyMs = once.ms;
  if (ioPeer.incremental()) {
    // The one-shot answer is freed first, so that a peak measured around this frame is of
    // the larger of the two builds, not of both answers held at once.
    sap_broadphase::PairList().swap(once.pairs);
    const PeerResult kept = ioPeer.step(inBoxes);
    ioEntry.wrong_steady += !samePairs(kept.pairs, inTruth);
    ioEntry.last_pairs = kept.pairs.size();
    steadyMs = kept.ms;
  } else {
    ioEntry.wrong_steady += !samePairs(once.pairs, inTruth);
    ioEntry.last_pairs = once.pairs.size();
  }
  if (!inTimed && ioEntry.first_frame_ms < 0) ioEntry.first_frame_ms = once.ms;
  const double frameMs = once.ms + steadyMs;
  ioEntry.stopped_slow = frameMs > kSlowFrameMs;
  ioCostPerBox = std::max(ioCostPerBox, frameMs / std::max<std::size_t>(1, inBoxes.size()));
  // A peer stopped on the build frame keeps that frame's times: the only ones it has.
  if (inTimed || (ioEntry.stopped_slow && ioEntry.one_shot_ms.empty()))
    ioEntry.one_shot_ms.push_back(once.ms), ioEntry.steady_ms.push_back(steadyMs);
  // Decided once a peer has one timed frame and once it has kSlowPeerTimedFrames, on their
  // mean, so that one slow frame later does not stop a peer that is fast on the others.
  const std::size_t timed = ioEntry.one_shot_ms.size();
  if (inTimed && (timed == 1 || timed == kSlowPeerTimedFrames)) {
    double total = 0.0;
    for (std::size_t k = 0; k < timed; ++k) total += ioEntry.one_shot_ms[k] + ioEntry.steady_ms[k];
    const double meanMs = total / static_cast<double>(timed);
    if (meanMs > (timed == 1 ? kVerySlowPeerFrameMs : kSlowPeerFrameMs))
      ioEntry.stopped_slow = true;
  }
}

void runPeerPass(Peer& ioPeer, const BenchCase& inCase, int inFrames,
                 const std::vector<PairList>& inTruth, Contender& ioEntry, double& ioCostPerBox,
                 Progress& ioProgress) {
  if (!ioEntry.skipped_slow) {
    if (!ioPeer.ownProcess()) {
      runPassHere(ioPeer, inCase, inFrames, inTruth, ioEntry, ioCostPerBox);
    } else if (!runPassInChild(ioPeer, inCase, inFrames, inTruth, ioEntry, ioCostPerBox)) {
      std::fprintf(stderr, "sap_bench: %s on %s: its child process failed; no figures\n",
                   ioPeer.name().c_str(), inCase.name.c_str());
    }
  }
  for (int f = 0; f < inFrames; ++f) ioProgress.step(inCase.name);
}

}  // namespace sap_bench
