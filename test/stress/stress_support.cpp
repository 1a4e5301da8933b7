#include "stress_support.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "sap_broadphase/core/brute_force.h"
#include "stress_sequences.h"

namespace sap_broadphase::stress {
namespace {

constexpr int kShownDifferences = 8;

std::string pairText(const IdPair& inPair) {
  return "(" + std::to_string(inPair.a) + ", " + std::to_string(inPair.b) + ")";
}

// Pairs in inLeft but not in inRight (both canonical), at most kShownDifferences of them.
std::string firstMissing(const PairList& inLeft, const PairList& inRight, std::size_t& outCount) {
  PairList difference;
  std::set_difference(inLeft.begin(), inLeft.end(), inRight.begin(), inRight.end(),
                      std::back_inserter(difference));
  outCount = difference.size();
  std::string text;
  for (std::size_t k = 0; k < difference.size() && k < kShownDifferences; ++k)
    text += " " + pairText(difference[k]);
  return text;
}

// Canonical order, a < b, no repeats.
::testing::AssertionResult inCanonicalOrder(const PairList& inPairs) {
  for (std::size_t k = 0; k < inPairs.size(); ++k) {
    if (!(inPairs[k].a < inPairs[k].b))
      return ::testing::AssertionFailure()
             << "pair " << k << " " << pairText(inPairs[k]) << " does not have a < b";
    if (k > 0 && !(inPairs[k - 1] < inPairs[k]))
      return ::testing::AssertionFailure()
             << "pairs " << k - 1 << " and " << k
             << " out of canonical order or repeated: " << pairText(inPairs[k - 1]) << " "
             << pairText(inPairs[k]);
  }
  return ::testing::AssertionSuccess();
}

// Maps ids to box indexes: a direct table for dense ids, a sorted table otherwise.
class IdIndex {
 public:
  explicit IdIndex(const BoxSet& inBoxes) {
    uint32_t largest = 0;
    for (uint32_t id : inBoxes.ids) largest = std::max(largest, id);
    dense_ = inBoxes.size() > 0 && largest < 4 * inBoxes.size() + 1024;
    if (dense_) {
      direct_.assign(std::size_t{largest} + 1, kNone);
      for (std::size_t i = 0; i < inBoxes.size(); ++i) direct_[inBoxes.ids[i]] = i;
      return;
    }
    sorted_.resize(inBoxes.size());
    for (std::size_t i = 0; i < inBoxes.size(); ++i) sorted_[i] = {inBoxes.ids[i], i};
    std::sort(sorted_.begin(), sorted_.end());
  }
  /// False for an id no box has.
  bool find(uint32_t inId, std::size_t& outIndex) const {
    if (dense_) {
      if (inId >= direct_.size() || direct_[inId] == kNone) return false;
      outIndex = direct_[inId];
      return true;
    }
    const auto found =
        std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(inId, std::size_t{0}));
    if (found == sorted_.end() || found->first != inId) return false;
    outIndex = found->second;
    return true;
  }

 private:
  static constexpr std::size_t kNone = ~std::size_t{0};
  bool dense_ = false;
  std::vector<std::size_t> direct_;
  std::vector<std::pair<uint32_t, std::size_t>> sorted_;
};

}  // namespace

double ulpStep(double inValue, int inSteps) {
  const double target = inSteps < 0 ? -std::numeric_limits<double>::infinity()
                                    : std::numeric_limits<double>::infinity();
  for (int k = 0; k < std::abs(inSteps); ++k) inValue = std::nextafter(inValue, target);
  return inValue;
}

std::vector<BroadphaseConfig> stressConfigs(Coverage inCoverage) {
  static const int kAxisPairs[6][2] = {{0, 1}, {1, 2}, {2, 0}, {1, 0}, {2, 1}, {0, 2}};
  static const Method kMethods[3] = {Method::kParallel, Method::kSequential, Method::kAuto};
  static const int kThreads[3] = {1, 2, 3};
  static const int kSlabs[3] = {0, 1, 7};
  std::vector<BroadphaseConfig> configs;
  int turn = 0;
  for (int m = 0; m < 3; ++m) {
    const Method method = kMethods[m];
    for (int t = 0; t < 3; ++t) {
      const int threads = kThreads[t];
      for (int s = 0; s < 3; ++s) {
        const int slabs = kSlabs[s];
        // Orthogonal array OA(9, 3 factors, 3 levels, strength 2): s = (m + t) mod 3.
        if (inCoverage == Coverage::kPairwise && s != (m + t) % 3) continue;
        BroadphaseConfig config;
        config.method = method;
        config.threads = threads;
        config.third_axis_slabs = slabs;
        config.primary_axis = kAxisPairs[turn % 6][0];
        config.secondary_axis = kAxisPairs[turn % 6][1];
        ++turn;
        configs.push_back(config);
      }
    }
  }
  return configs;
}

::testing::AssertionResult samePairList(const PairList& inExpected, const PairList& inActual) {
  if (inExpected == inActual) return ::testing::AssertionSuccess();
  std::size_t missing_count = 0;
  std::size_t extra_count = 0;
  const std::string missing = firstMissing(inExpected, inActual, missing_count);
  const std::string extra = firstMissing(inActual, inExpected, extra_count);
  return ::testing::AssertionFailure()
         << "expected " << inExpected.size() << " pairs, got " << inActual.size() << "; "
         << missing_count << " missing:" << missing << "; " << extra_count << " extra:" << extra
         << (missing_count + extra_count == 0 ? " (same set, different order)" : "");
}

::testing::AssertionResult supersetWithKeyOverlap(const BoxSet& inBoxes, const PairList& inExpected,
                                                  const PairList& inActual) {
  if (auto canonical = inCanonicalOrder(inActual); !canonical) return canonical;
  std::size_t missing_count = 0;
  const std::string missing = firstMissing(inExpected, inActual, missing_count);
  if (missing_count > 0)
    return ::testing::AssertionFailure() << "keys-only mode missed " << missing_count << " of "
                                         << inExpected.size() << " pairs:" << missing;
  const IdIndex index(inBoxes);
  const KeyOrigin frame_origin = firstFrameKeyOrigin(inBoxes);
  std::size_t next_expected = 0;
  for (const IdPair& pair : inActual) {
    if (next_expected < inExpected.size() && inExpected[next_expected] == pair) {
      ++next_expected;
      continue;
    }
    std::size_t a = 0;
    std::size_t b = 0;
    if (!index.find(pair.a, a) || !index.find(pair.b, b))
      return ::testing::AssertionFailure()
             << "extra pair " << pairText(pair) << " names an unknown id";
    // Keys from the origin 0 or from the frame's centre: the engine uses the latter only for
    // frames far from 0.
    const bool keys_overlap =
        keysOverlap(KeyOrigin(), inBoxes, a, b) || keysOverlap(frame_origin, inBoxes, a, b);
    if (!keys_overlap || !filtersAllow(inBoxes, a, b))
      return ::testing::AssertionFailure() << "extra pair " << pairText(pair)
                                           << " neither overlaps in key space nor passes filters";
  }
  return ::testing::AssertionSuccess();
}

void expectStressMatch(const BoxSet& inBoxes, const std::string& inLabel) {
  expectStressMatch(inBoxes, bruteForcePairs(inBoxes), inLabel);
}

void expectStressMatch(const BoxSet& inBoxes, const PairList& inOracle,
                       const std::string& inLabel) {
  ASSERT_TRUE(isValidSet(inBoxes)) << inLabel;
  ASSERT_TRUE(inCanonicalOrder(inOracle)) << inLabel << ": the oracle's own output";
  const Coverage coverage = inBoxes.size() > kPairwiseAbove ? Coverage::kPairwise : Coverage::kFull;
  const BoxSet reversed = reversedOrder(inBoxes);
  for (BroadphaseConfig config : stressConfigs(coverage)) {
    Broadphase engine(config);
    EXPECT_TRUE(samePairList(inOracle, engine.update(reversed)))
        << inLabel << ", boxes in reverse order, " << describeConfig(config);
    // The boxes in their own order: a changed frame, swept with partition bounds (and maybe
    // axes) carried over from the reversed one.
    EXPECT_TRUE(samePairList(inOracle, engine.update(inBoxes)))
        << inLabel << ", second frame, " << describeConfig(config);
    // Unchanged: may take a reuse path, which must give the same pairs.
    EXPECT_TRUE(samePairList(inOracle, engine.update(inBoxes)))
        << inLabel << ", third (unchanged) frame, " << describeConfig(config);

    config.exact_final_test = false;
    Broadphase keys_only(config);
    EXPECT_TRUE(supersetWithKeyOverlap(inBoxes, inOracle, keys_only.update(inBoxes)))
        << inLabel << ", " << describeConfig(config);
  }
}

void addBox(BoxSet& ioBoxes, uint32_t inId, double inMinX, double inMinY, double inMinZ,
            double inMaxX, double inMaxY, double inMaxZ) {
  const double low[3] = {inMinX, inMinY, inMinZ};
  const double high[3] = {inMaxX, inMaxY, inMaxZ};
  ioBoxes.add(inId, low, high);
}

::testing::AssertionResult isValidSet(const BoxSet& inBoxes) {
  if (auto error = validate(inBoxes))
    return ::testing::AssertionFailure() << "invalid test scene: " << error->message();
  return ::testing::AssertionSuccess();
}

}  // namespace sap_broadphase::stress
