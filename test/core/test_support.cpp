// Shared helpers of the core tests.
#include "test_support.h"

#include "sap_broadphase/core/brute_force.h"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <string>
#include <unordered_set>

namespace sap_broadphase::test_support {

BoxSet randomBoxes(std::size_t inCount, double inWorld, double inMaxEdge, uint64_t inSeed) {
  TestRandom random(inSeed);
  BoxSet boxes;
  boxes.reserve(inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    double lo[3];
    double hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = random.between(0.0, inWorld);
      hi[axis] = lo[axis] + random.between(0.0, inMaxEdge);
    }
    boxes.add(static_cast<uint32_t>(i), lo, hi);
  }
  return boxes;
}

BoxSet latticeBoxes(std::size_t inCount, int inCells, int inMaxEdge, uint64_t inSeed) {
  TestRandom random(inSeed);
  BoxSet boxes;
  boxes.reserve(inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    double lo[3];
    double hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = static_cast<double>(random.below(static_cast<uint64_t>(inCells)));
      hi[axis] = lo[axis] + static_cast<double>(random.below(static_cast<uint64_t>(inMaxEdge) + 1));
    }
    boxes.add(static_cast<uint32_t>(i), lo, hi);
  }
  return boxes;
}

BoxSet shuffledSubset(const BoxSet& inBoxes, double inKeep, bool inSparseIds, uint64_t inSeed) {
  TestRandom random(inSeed);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < inBoxes.size(); ++i)
    if (random.unit() < inKeep) kept.push_back(i);
  for (std::size_t k = kept.size(); k > 1; --k) std::swap(kept[k - 1], kept[random.below(k)]);
  std::unordered_set<uint32_t> used;
  BoxSet subset;
  subset.reserve(kept.size());
  for (std::size_t i : kept) {
    uint32_t id = inBoxes.ids[i];
    if (inSparseIds) {
      do id = static_cast<uint32_t>(random.bits());
      while (!used.insert(id).second);
    }
    const double lo[3] = {inBoxes.lo(0, i), inBoxes.lo(1, i), inBoxes.lo(2, i)};
    const double hi[3] = {inBoxes.hi(0, i), inBoxes.hi(1, i), inBoxes.hi(2, i)};
    if (inBoxes.hasFilters())
      subset.add(id, lo, hi, inBoxes.group(i), inBoxes.mask(i));
    else
      subset.add(id, lo, hi);
  }
  return subset;
}

namespace {

template <typename Boxes>
void addRandomFiltersTo(Boxes& ioBoxes, uint64_t inSeed) {
  TestRandom random(inSeed);
  ioBoxes.groups.resize(ioBoxes.size());
  ioBoxes.masks.resize(ioBoxes.size());
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    ioBoxes.groups[i] = 1u << random.below(3);
    ioBoxes.masks[i] = static_cast<uint32_t>(random.below(8));  // 0 collides with nothing
  }
}

}  // namespace

void addRandomFilters(BoxSet& ioBoxes, uint64_t inSeed) {
  addRandomFiltersTo(ioBoxes, inSeed);
}

void addRandomFilters(BoxColumns& ioBoxes, uint64_t inSeed) {
  addRandomFiltersTo(ioBoxes, inSeed);
}

std::vector<BoxSpan> cutIntoSpans(const BoxSet& inBoxes, std::size_t inSpanBoxes) {
  std::vector<BoxSpan> spans;
  const BoxSpan whole = inBoxes.span();
  for (std::size_t first = 0; first < inBoxes.size(); first += inSpanBoxes) {
    BoxSpan span = whole;
    span.count = std::min(inSpanBoxes, inBoxes.size() - first);
    span.bounds += kBoundsPerBox * first;
    span.ids += first;
    if (span.groups) span.groups += first;
    if (span.masks) span.masks += first;
    spans.push_back(span);
  }
  return spans;
}

BoxSet recordsOf(const BoxColumns& inBoxes) {
  BoxSet records;
  records.reserve(inBoxes.size());
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    const double low[3] = {inBoxes.lo[0][i], inBoxes.lo[1][i], inBoxes.lo[2][i]};
    const double high[3] = {inBoxes.hi[0][i], inBoxes.hi[1][i], inBoxes.hi[2][i]};
    records.add(inBoxes.ids[i], low, high);
  }
  records.groups = inBoxes.groups;
  records.masks = inBoxes.masks;
  return records;
}

BoxColumns shuffledSubset(const BoxColumns& inBoxes, double inKeep, bool inSparseIds,
                          uint64_t inSeed) {
  return columnsOf(shuffledSubset(recordsOf(inBoxes), inKeep, inSparseIds, inSeed));
}

SceneConfig movingScene(SceneKind inKind, uint64_t inSeed, std::size_t inCount, double inDensity,
                        int inFrames) {
  SceneConfig scene;
  scene.kind = inKind;
  scene.n = inCount;
  scene.density = inDensity;
  scene.seed = inSeed;
  scene.frames = inFrames;
  return scene;
}

BroadphaseConfig engineConfig(Method inMethod, int inThreads, int inPrimary, int inSecondary,
                              int inSlabs) {
  BroadphaseConfig config;
  config.third_axis_slabs = inSlabs;
  config.method = inMethod;
  config.threads = inThreads;
  config.primary_axis = inPrimary;
  config.secondary_axis = inSecondary;
  return config;
}

std::vector<std::pair<int, int>> allAxisPairs() {
  return {{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}};
}

::testing::AssertionResult samePairs(const PairList& inExpected, const PairList& inActual) {
  if (inExpected == inActual) return ::testing::AssertionSuccess();
  std::ostringstream message;
  message << "expected " << inExpected.size() << " pairs, got " << inActual.size();
  PairList missing;
  PairList extra;
  PairList expectedSorted = inExpected;
  PairList actualSorted = inActual;
  std::sort(expectedSorted.begin(), expectedSorted.end());
  std::sort(actualSorted.begin(), actualSorted.end());
  std::set_difference(expectedSorted.begin(), expectedSorted.end(), actualSorted.begin(),
                      actualSorted.end(), std::back_inserter(missing));
  std::set_difference(actualSorted.begin(), actualSorted.end(), expectedSorted.begin(),
                      expectedSorted.end(), std::back_inserter(extra));
  message << "; missing " << missing.size() << ", extra " << extra.size();
  for (std::size_t k = 0; k < missing.size() && k < 5; ++k)
    message << "; missing (" << missing[k].a << "," << missing[k].b << ")";
  for (std::size_t k = 0; k < extra.size() && k < 5; ++k)
    message << "; extra (" << extra[k].a << "," << extra[k].b << ")";
  if (missing.empty() && extra.empty()) {
    const bool sorted = std::is_sorted(inActual.begin(), inActual.end());
    const bool unique =
        std::adjacent_find(actualSorted.begin(), actualSorted.end()) == actualSorted.end();
    message << "; same set but " << (sorted ? "" : "not sorted ")
            << (unique ? "" : "with duplicates");
  }
  return ::testing::AssertionFailure() << message.str();
}

namespace {

constexpr uint64_t kFnvOffsetBasis = 1469598103934665603ull;

// FNV-1a over the four bytes of inValue, least significant first.
void hashWord(uint64_t& ioHash, uint32_t inValue) {
  for (int byte = 0; byte < 4; ++byte) {
    ioHash ^= (inValue >> (8 * byte)) & 0xFFu;
    ioHash *= 1099511628211ull;
  }
}

void hashPairsInto(uint64_t& ioHash, const PairList& inPairs) {
  for (const IdPair& pair : inPairs) {
    hashWord(ioHash, pair.a);
    hashWord(ioHash, pair.b);
  }
}

std::string pairText(const IdPair& inPair) {
  return "(" + std::to_string(inPair.a) + ", " + std::to_string(inPair.b) + ")";
}

}  // namespace

uint64_t hashPairs(const PairList& inPairs) {
  uint64_t hash = kFnvOffsetBasis;
  hashPairsInto(hash, inPairs);
  return hash;
}

uint64_t hashPairSequence(const std::vector<PairList>& inFrames) {
  uint64_t hash = kFnvOffsetBasis;
  for (const PairList& pairs : inFrames) {
    hashWord(hash, static_cast<uint32_t>(pairs.size()));
    hashPairsInto(hash, pairs);
  }
  return hash;
}

std::string firstDifference(const PairList& inExpected, const PairList& inActual) {
  const std::size_t common = std::min(inExpected.size(), inActual.size());
  const auto differs =
      std::mismatch(inExpected.begin(), inExpected.begin() + common, inActual.begin());
  const std::size_t k = static_cast<std::size_t>(differs.first - inExpected.begin());
  if (k < common)
    return "pair " + std::to_string(k) + ": expected " + pairText(inExpected[k]) + ", got " +
           pairText(inActual[k]);
  if (inExpected.size() > common)
    return "pair " + std::to_string(k) + ": expected " + pairText(inExpected[k]) + ", got none";
  if (inActual.size() > common)
    return "pair " + std::to_string(k) + ": expected none, got " + pairText(inActual[k]);
  return "";
}

std::string PathCounts::summary() const {
  std::string text;
  for (std::size_t path = 0; path < counts_.size(); ++path) {
    if (counts_[path] == 0) continue;
    if (!text.empty()) text += ", ";
    text += std::string(framePathName(static_cast<FramePath>(path))) + " " +
            std::to_string(counts_[path]);
  }
  return text.empty() ? "no frames" : text;
}

const std::vector<int>& testThreadCounts() {
  static const std::vector<int> kThreads = {1, 2, 3, 4, 7};
  return kThreads;
}

void expectAllConfigsMatch(const BoxSet& inBoxes, const PairList& inOracle,
                           const std::string& inLabel) {
  std::vector<BroadphaseConfig> configs;
  for (const auto& [primary, secondary] : allAxisPairs()) {
    for (int threads : testThreadCounts())
      configs.push_back(engineConfig(Method::kParallel, threads, primary, secondary));
    configs.push_back(engineConfig(Method::kSequential, 1, primary, secondary));
    configs.push_back(engineConfig(Method::kAuto, 2, primary, secondary));
  }
  for (int slabs : {1, 2, 5, 64}) {
    configs.push_back(engineConfig(Method::kParallel, 3, 1, 2, slabs));
    configs.push_back(engineConfig(Method::kSequential, 1, 2, 0, slabs));
  }
  configs.push_back(engineConfig(Method::kAuto, 1, 0, 1));
  configs.push_back(engineConfig(Method::kBruteForce, 1, 0, 1));
  for (const BroadphaseConfig& config : configs) {
    Broadphase broadphase(config);
    EXPECT_TRUE(samePairs(inOracle, broadphase.update(inBoxes)))
        << inLabel << " (" << inBoxes.size() << " boxes), " << describe(config);
    const int slabs = broadphase.stats().slabs;
    EXPECT_TRUE(slabs >= 1 && slabs <= 64) << slabs << " slabs";
  }
}

void expectAllConfigsMatch(const BoxSet& inBoxes, const std::string& inLabel) {
  expectAllConfigsMatch(inBoxes, bruteForcePairs(inBoxes), inLabel);
}

std::string describe(const BroadphaseConfig& inConfig) {
  return describeConfig(inConfig);
}

}  // namespace sap_broadphase::test_support
