// Shared helpers of the numerical stress suite: engine configurations, the oracle comparison
// (exact mode equal, keys-only mode a superset) and ulp steps.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/tools/random.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase::stress {

/// inValue moved by inSteps representable doubles (negative: downwards); saturates at +-inf.
double ulpStep(double inValue, int inSteps);

/// How many engine configurations a scene is checked with.
enum class Coverage {
  kFull,      ///< methods kParallel, kSequential, kAuto x threads 1, 2, 3 x slabs 0, 1, 7 (27)
  kPairwise,  ///< 9 of those: every pair of (method, threads, slabs) values appears once
};

/// The engine configurations of a stress check: methods kParallel, kSequential and kAuto,
/// threads 1, 2, 3, third_axis_slabs 0, 1, 7 (all 27 combinations, or the 9 of an orthogonal
/// array), the six ordered axis pairs taken in turn.
std::vector<BroadphaseConfig> stressConfigs(Coverage inCoverage = Coverage::kFull);

/// Equal pair lists, or a message with sizes and the first differences (missing and extra).
::testing::AssertionResult samePairList(const PairList& inExpected, const PairList& inActual);
/// inActual holds every pair of inExpected (it may hold more); both in canonical order, and
/// every extra pair must overlap in a fresh engine's outward-rounded key space
/// (firstFrameKeyOrigin) and pass the filters.
::testing::AssertionResult supersetWithKeyOverlap(const BoxSet& inBoxes, const PairList& inExpected,
                                                  const PairList& inActual);

/// Checks inBoxes against bruteForcePairs with every stressConfigs() configuration: a fresh
/// exact engine gets the boxes in reverse order, then in their order (warm partition bounds,
/// possibly swapped axes), then unchanged again (a reuse path); each must give the oracle's
/// pairs exactly. The same configuration with exact_final_test = false must give a superset.
/// inLabel names the scene in messages. Scenes of more than kPairwiseAbove boxes get
/// Coverage::kPairwise, smaller ones kFull.
void expectStressMatch(const BoxSet& inBoxes, const std::string& inLabel);
/// The same with a precomputed oracle.
void expectStressMatch(const BoxSet& inBoxes, const PairList& inOracle, const std::string& inLabel);

/// Above this many boxes a scene is checked with the pairwise configurations only (keeps the
/// suite within its time budget: scenes whose float32 keys collapse cost O(n^2) candidates).
constexpr std::size_t kPairwiseAbove = 2000;

/// Appends one box with the default filters.
void addBox(BoxSet& ioBoxes, uint32_t inId, double inMinX, double inMinY, double inMinZ,
            double inMaxX, double inMaxY, double inMaxZ);

/// True when the set passes validate(); otherwise a failure naming the problem.
::testing::AssertionResult isValidSet(const BoxSet& inBoxes);

}  // namespace sap_broadphase::stress
