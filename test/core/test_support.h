// Shared helpers of the core tests: box generators, engine configs, pair comparison and hashing.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/tools/random.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/pair_set.h"
#include "sap_broadphase/core/scenes.h"

namespace sap_broadphase::test_support {

/// The project's one generator (splitmix64): the same boxes from a seed on every platform.
using TestRandom = SplitMix64;

/// inCount boxes, corners uniform in [0, inWorld)^3, edges uniform in [0, inMaxEdge) per axis.
BoxSet randomBoxes(std::size_t inCount, double inWorld, double inMaxEdge, uint64_t inSeed);
/// inCount boxes with integer corners in [0, inCells) and integer edges in [0, inMaxEdge]:
/// many boxes share faces, edges and corners exactly, and many have zero extent.
BoxSet latticeBoxes(std::size_t inCount, int inCells, int inMaxEdge, uint64_t inSeed);
/// A random subset (each box kept with probability inKeep) in random order; with inSparseIds
/// the ids are replaced by unique random 32-bit values.
BoxSet shuffledSubset(const BoxSet& inBoxes, double inKeep, bool inSparseIds, uint64_t inSeed);
/// Gives box i a random group and mask (from a few bits, so some pairs are filtered out).
void addRandomFilters(BoxSet& ioBoxes, uint64_t inSeed);

/// The same helpers on the engine's internal layout, for the tests of its parts.
BoxColumns shuffledSubset(const BoxColumns& inBoxes, double inKeep, bool inSparseIds,
                          uint64_t inSeed);
void addRandomFilters(BoxColumns& ioBoxes, uint64_t inSeed);
/// inBoxes cut into spans of inSpanBoxes boxes (the last one shorter), over inBoxes' memory:
/// the frame as several sources would give it.
std::vector<BoxSpan> cutIntoSpans(const BoxSet& inBoxes, std::size_t inSpanBoxes);
/// inBoxes as records (the inverse of columnsOf()).
BoxSet recordsOf(const BoxColumns& inBoxes);

/// A moving scene of the paper's kinds: inCount boxes at density inDensity, inFrames frames.
SceneConfig movingScene(SceneKind inKind, uint64_t inSeed, std::size_t inCount = 3000,
                        double inDensity = 0.2, int inFrames = 80);

/// An engine configuration for one method, thread count, axis pair and third-axis slab count
/// (0 = the engine's choice, 1 = the paper's single active list).
BroadphaseConfig engineConfig(Method inMethod, int inThreads, int inPrimary, int inSecondary,
                              int inSlabs = 0);
/// The six ordered (primary, secondary) axis pairs.
std::vector<std::pair<int, int>> allAxisPairs();

/// Equal pair lists, or a message with the sizes and the first few differences.
::testing::AssertionResult samePairs(const PairList& inExpected, const PairList& inActual);
/// FNV-1a hash of the pair list (order-sensitive).
uint64_t hashPairs(const PairList& inPairs);
/// FNV-1a hash of a sequence of frames' pair lists: every frame's pair count, then its pairs,
/// so that moving a pair from one frame to the next changes the hash.
uint64_t hashPairSequence(const std::vector<PairList>& inFrames);
/// Where inActual first departs from inExpected: "pair 17: expected (3, 9), got (3, 11)", or
/// the first pair one list has beyond the other's end; empty when the lists are equal.
std::string firstDifference(const PairList& inExpected, const PairList& inActual);

/// How many frames took each path (FrameReport::path), so that a sequence test can assert
/// that the path it means to exercise really ran instead of passing by never taking it.
class PathCounts {
 public:
  /// Counts inReport's path.
  void add(const FrameReport& inReport) { ++counts_[static_cast<std::size_t>(inReport.path)]; }
  /// Frames that took inPath.
  int operator[](FramePath inPath) const { return counts_[static_cast<std::size_t>(inPath)]; }
  /// "sequential 3, skin 12": the paths taken, by framePathName, for failure messages.
  std::string summary() const;

 private:
  std::vector<int> counts_ = std::vector<int>(256);  // every value a uint8_t FramePath can take
};
/// Thread counts every parallel check runs with (2 cores here: 3, 4 and 7 oversubscribe).
const std::vector<int>& testThreadCounts();
/// Runs a fresh Broadphase for every method, thread count and ordered axis pair on inBoxes and
/// expects inOracle each time (inLabel names the case in failure messages).
void expectAllConfigsMatch(const BoxSet& inBoxes, const PairList& inOracle,
                           const std::string& inLabel);
/// The same with the oracle computed here.
void expectAllConfigsMatch(const BoxSet& inBoxes, const std::string& inLabel);
/// A one-line description of a configuration for failure messages.
std::string describe(const BroadphaseConfig& inConfig);

}  // namespace sap_broadphase::test_support
