// Shared helpers of the core tests: box generators, engine configs, pair comparison and hashing.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase::test_support {

/// A small, fast, platform-independent generator (splitmix64).
class TestRandom {
 public:
  explicit TestRandom(uint64_t inSeed) : state_(inSeed) {}
  uint64_t bits() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double unit() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }
  /// Uniform in [inLow, inHigh).
  double between(double inLow, double inHigh) { return inLow + (inHigh - inLow) * unit(); }
  /// Uniform integer in [0, inBound).
  uint64_t below(uint64_t inBound) { return inBound == 0 ? 0 : bits() % inBound; }

 private:
  uint64_t state_;
};

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
