// StaticIndex against brute force over query x index pairs: random and adversarial boxes,
// filters, remove(), empty sides, thread counts, and a 10^5-static x 10^3-moving scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/frame/pair_sort.h"
#include "core/runner/work_units.h"
#include "core/strategies/static_index.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// splitmix64, shared with the other engine tests: the same boxes on every platform.
using Random = test_support::TestRandom;

/// Every overlapping, filter-allowed (query, indexed) pair, by testing all of them.
PairList bruteForceCross(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexed,
                         const BoxColumns& inQueries, const std::vector<uint32_t>& inQueryIndexes,
                         const std::vector<uint32_t>& inRemovedIds = {}) {
  PairList pairs;
  for (uint32_t q : inQueryIndexes)
    for (uint32_t s : inIndexed) {
      if (std::find(inRemovedIds.begin(), inRemovedIds.end(), inBoxes.ids[s]) != inRemovedIds.end())
        continue;
      bool overlap = true;
      for (int axis = 0; axis < 3; ++axis)
        overlap = overlap && !(inQueries.lo[axis][q] > inBoxes.hi[axis][s] ||
                               inBoxes.lo[axis][s] > inQueries.hi[axis][q]);
      const bool allowed = (inQueries.group(q) & inBoxes.mask(s)) != 0 &&
                           (inBoxes.group(s) & inQueries.mask(q)) != 0;
      if (overlap && allowed) pairs.push_back(makeIdPair(inQueries.ids[q], inBoxes.ids[s]));
    }
  sortPairsCanonical(pairs);
  return pairs;
}

/// Equal lists, or the sizes and the first differences.
::testing::AssertionResult samePairs(const PairList& inExpected, PairList inActual) {
  sortPairsCanonical(inActual);
  if (inExpected == inActual) return ::testing::AssertionSuccess();
  auto failure = ::testing::AssertionFailure()
                 << "expected " << inExpected.size() << " pairs, got " << inActual.size();
  PairList missing, extra;
  std::set_difference(inExpected.begin(), inExpected.end(), inActual.begin(), inActual.end(),
                      std::back_inserter(missing));
  std::set_difference(inActual.begin(), inActual.end(), inExpected.begin(), inExpected.end(),
                      std::back_inserter(extra));
  for (std::size_t k = 0; k < std::min<std::size_t>(missing.size(), 5); ++k)
    failure << "; missing (" << missing[k].a << "," << missing[k].b << ")";
  for (std::size_t k = 0; k < std::min<std::size_t>(extra.size(), 5); ++k)
    failure << "; extra or repeated (" << extra[k].a << "," << extra[k].b << ")";
  if (missing.empty() && extra.empty()) failure << "; same set, repeated pairs";
  return failure;
}

/// One interval of an adversarial kind: ordinary, zero extent, on a lattice (shared faces),
/// huge, an infinite slab or half-slab, ±0 ends, or one ulp away from a lattice point.
void adversarialInterval(Random& ioRandom, double inWorld, double& outLow, double& outHigh) {
  const double start = std::floor(ioRandom.unit() * inWorld);
  switch (ioRandom.below(10)) {
    case 0:
      outLow = outHigh = ioRandom.unit() * inWorld;
      return;
    case 1:
      outLow = start;
      outHigh = start + static_cast<double>(ioRandom.below(3));
      return;
    case 2:
      outLow = -1e300 * ioRandom.unit();
      outHigh = 1e300 * ioRandom.unit();
      return;
    case 3:
      outLow = -kInf;
      outHigh = ioRandom.below(2) ? kInf : start;
      return;
    case 4:
      outLow = start;
      outHigh = kInf;
      return;
    case 5:  // ±0 touching: [-x, -0.0] against [0.0, y]
      if (ioRandom.below(2)) {
        outLow = -ioRandom.unit() * 3.0;
        outHigh = -0.0;
      } else {
        outLow = 0.0;
        outHigh = ioRandom.unit() * 3.0;
      }
      return;
    case 6:  // one ulp short of, or past, a lattice point
      outLow = std::nextafter(start, ioRandom.below(2) ? kInf : -kInf);
      outHigh = std::nextafter(start + 1.0, ioRandom.below(2) ? kInf : -kInf);
      return;
    default:
      outLow = ioRandom.unit() * inWorld;
      outHigh = outLow + ioRandom.unit() * inWorld * 0.1;
      return;
  }
}

/// inCount boxes with ids inFirstId.., each axis's interval of an adversarial kind with
/// probability inOddShare, ordinary otherwise; every 7th box repeats an earlier one exactly.
BoxColumns adversarialBoxes(std::size_t inCount, double inWorld, double inOddShare,
                            uint32_t inFirstId, uint64_t inSeed) {
  Random random(inSeed);
  BoxColumns boxes;
  for (std::size_t i = 0; i < inCount; ++i) {
    double lo[3], hi[3];
    if (i > 0 && i % 7 == 0) {
      const std::size_t copy = random.below(i);
      for (int axis = 0; axis < 3; ++axis) {
        lo[axis] = boxes.lo[axis][copy];
        hi[axis] = boxes.hi[axis][copy];
      }
    } else {
      for (int axis = 0; axis < 3; ++axis) {
        if (random.unit() < inOddShare) {
          adversarialInterval(random, inWorld, lo[axis], hi[axis]);
        } else {
          lo[axis] = random.unit() * inWorld;
          hi[axis] = lo[axis] + random.unit() * 2.0;
        }
      }
    }
    boxes.add(inFirstId + static_cast<uint32_t>(i), lo, hi);
  }
  return boxes;
}

/// Random groups and masks from a few bits, so some pairs are filtered out.
void addFilters(BoxColumns& ioBoxes, uint64_t inSeed) {
  Random random(inSeed);
  ioBoxes.groups.resize(ioBoxes.size());
  ioBoxes.masks.resize(ioBoxes.size());
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    ioBoxes.groups[i] = 1u << random.below(3);
    ioBoxes.masks[i] = static_cast<uint32_t>(random.below(8));
  }
}

std::vector<uint32_t> allIndexes(const BoxColumns& inBoxes) {
  std::vector<uint32_t> indexes(inBoxes.size());
  for (std::size_t i = 0; i < indexes.size(); ++i) indexes[i] = static_cast<uint32_t>(i);
  return indexes;
}

/// StaticIndex::build on inThreads threads (the runner's scope).
void buildOnThreads(StaticIndex& ioIndex, const BoxColumns& inBoxes,
                    const std::vector<uint32_t>& inIndexes, int inThreads) {
  const ThreadsScope scope(inThreads);
  ioIndex.build(inBoxes, inIndexes);
}

/// StaticIndex::queryAll on inThreads threads (the runner's scope).
void queryAllOnThreads(const StaticIndex& inIndex, const BoxColumns& inQueries,
                       const std::vector<uint32_t>& inQueryIndexes, int inThreads,
                       PairList& outPairs) {
  const ThreadsScope scope(inThreads);
  inIndex.queryAll(inQueries, inQueryIndexes, outPairs);
}

/// Builds the index on inIndexed of inBoxes and expects the oracle from query() one by one and
/// from queryAll() with 1, 2 and 3 threads.
void expectMatches(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexed,
                   const BoxColumns& inQueries, const std::vector<uint32_t>& inQueryIndexes,
                   const std::string& inLabel) {
  const PairList expected = bruteForceCross(inBoxes, inIndexed, inQueries, inQueryIndexes);
  for (int build_threads : {1, 2}) {
    StaticIndex index;
    buildOnThreads(index, inBoxes, inIndexed, build_threads);
    ASSERT_EQ(index.size(), inIndexed.size()) << inLabel;
    PairList one_by_one;
    for (uint32_t q : inQueryIndexes) index.query(inQueries, q, one_by_one);
    EXPECT_TRUE(samePairs(expected, one_by_one)) << inLabel << ", query()";
    for (int threads : {1, 2, 3}) {
      PairList all;
      queryAllOnThreads(index, inQueries, inQueryIndexes, threads, all);
      EXPECT_TRUE(samePairs(expected, all)) << inLabel << ", queryAll threads " << threads;
    }
  }
}

TEST(StaticIndex, OrdinaryRandomBoxesManySeeds) {
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const BoxColumns indexed = adversarialBoxes(600, 20.0, 0.0, 0, seed);
    BoxColumns queries = adversarialBoxes(200, 20.0, 0.0, 10000, seed + 1000);
    expectMatches(indexed, allIndexes(indexed), queries, allIndexes(queries),
                  "seed " + std::to_string(seed));
  }
}

TEST(StaticIndex, AdversarialBoxesManySeeds) {
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    const double odd_share = (seed % 4 + 1) * 0.1;
    BoxColumns indexed = adversarialBoxes(500, 8.0, odd_share, 0, seed);
    BoxColumns queries = adversarialBoxes(150, 8.0, odd_share, 5000, seed + 777);
    if (seed % 2 == 0) {
      addFilters(indexed, seed);
      addFilters(queries, seed + 1);
    }
    expectMatches(indexed, allIndexes(indexed), queries, allIndexes(queries),
                  "seed " + std::to_string(seed));
  }
}

TEST(StaticIndex, SubsetsOfOneBoxColumns) {
  // Index and queries drawn from one set by position, as the engine will use it.
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    BoxColumns boxes = adversarialBoxes(800, 10.0, 0.2, 0, seed);
    addFilters(boxes, seed);
    Random random(seed);
    std::vector<uint32_t> indexed, moving;
    for (uint32_t i = 0; i < boxes.size(); ++i) (random.below(5) ? indexed : moving).push_back(i);
    expectMatches(boxes, indexed, boxes, moving, "seed " + std::to_string(seed));
  }
}

TEST(StaticIndex, TouchingLattice) {
  // Unit cubes on an integer lattice: every neighbour touches by a face, edge or corner.
  BoxColumns indexed, queries;
  uint32_t id = 0;
  for (int x = 0; x < 12; ++x)
    for (int y = 0; y < 12; ++y)
      for (int z = 0; z < 3; ++z) {
        const double lo[3] = {double(x), double(y), double(z)};
        const double hi[3] = {x + 1.0, y + 1.0, z + 1.0};
        indexed.add(id++, lo, hi);
      }
  for (int x = 0; x < 13; ++x)
    for (int y = 0; y < 13; ++y) {
      const double lo[3] = {double(x), double(y), 1.0};
      const double point[3] = {double(x), double(y), 1.0};
      queries.add(id++, lo, point);  // lattice points: touch up to 8 cubes
      const double wide_lo[3] = {x - 0.5, y - 0.5, -0.0};
      const double wide_hi[3] = {x + 0.5, y + 0.5, 0.0};
      queries.add(id++, wide_lo, wide_hi);  // flat squares on the bottom faces
    }
  expectMatches(indexed, allIndexes(indexed), queries, allIndexes(queries), "lattice");
}

TEST(StaticIndex, SignedZeroAndUlpGaps) {
  BoxColumns indexed, queries;
  const double lo_a[3] = {-1.0, -1.0, -1.0}, hi_a[3] = {-0.0, -0.0, -0.0};
  indexed.add(1, lo_a, hi_a);
  const double lo_b[3] = {1.0, 1.0, 1.0}, hi_b[3] = {2.0, 2.0, 2.0};
  indexed.add(2, lo_b, hi_b);
  const double lo_q[3] = {0.0, 0.0, 0.0};
  const double hi_q[3] = {std::nextafter(1.0, 0.0), 1.0, 1.0};  // 1 ulp short of box 2 on x
  queries.add(10, lo_q, hi_q);
  const double hi_r[3] = {1.0, 1.0, 1.0};  // touches box 2 at a corner
  queries.add(11, lo_q, hi_r);
  const double lo_s[3] = {std::nextafter(-0.0, 1.0), -5.0, -5.0};  // 1 ulp past box 1 on x
  const double hi_s[3] = {5.0, 5.0, 5.0};
  queries.add(12, lo_s, hi_s);
  StaticIndex index;
  buildOnThreads(index, indexed, allIndexes(indexed), 1);
  PairList pairs;
  queryAllOnThreads(index, queries, allIndexes(queries), 1, pairs);
  sortPairsCanonical(pairs);
  const PairList expected = {{1, 10}, {1, 11}, {2, 11}, {2, 12}};
  EXPECT_EQ(pairs, expected);
  expectMatches(indexed, allIndexes(indexed), queries, allIndexes(queries), "signed zero");
}

TEST(StaticIndex, InfiniteSlabsAndHugeBoxes) {
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    BoxColumns indexed = adversarialBoxes(400, 50.0, 0.0, 0, seed);
    BoxColumns queries = adversarialBoxes(100, 50.0, 0.0, 1000, seed + 50);
    Random random(seed);
    for (uint32_t k = 0; k < 20; ++k) {
      double lo[3], hi[3];
      for (int axis = 0; axis < 3; ++axis) {
        lo[axis] = random.below(3) ? -kInf : random.unit() * 50.0;
        hi[axis] = random.below(3) ? kInf : lo[axis] + 1e300;
      }
      indexed.add(2000 + k, lo, hi);
      queries.add(3000 + k, lo, hi);
    }
    expectMatches(indexed, allIndexes(indexed), queries, allIndexes(queries),
                  "seed " + std::to_string(seed));
  }
}

TEST(StaticIndex, DegenerateIndexes) {
  // All points; all identical; all on one plane; one far outlier stretching the grid.
  BoxColumns queries = adversarialBoxes(300, 10.0, 0.3, 100000, 9);
  BoxColumns points, identical, plane, outlier;
  Random random(3);
  for (uint32_t i = 0; i < 500; ++i) {
    const double p[3] = {std::floor(random.unit() * 10), random.unit() * 10, 2.0};
    points.add(i, p, p);
    const double lo[3] = {1.0, 1.0, 1.0}, hi[3] = {2.0, 2.0, 2.0};
    identical.add(i, lo, hi);
    const double plo[3] = {random.unit() * 10, random.unit() * 10, 3.0};
    const double phi[3] = {plo[0] + random.unit(), plo[1] + random.unit(), 3.0};
    plane.add(i, plo, phi);
    outlier.add(i, plo, phi);
  }
  const double far_lo[3] = {1e12, 1e12, 1e12}, far_hi[3] = {1e12 + 1, 1e12 + 1, 1e12 + 1};
  outlier.add(500, far_lo, far_hi);
  for (const BoxColumns* indexed : {&points, &identical, &plane, &outlier})
    expectMatches(*indexed, allIndexes(*indexed), queries, allIndexes(queries), "degenerate");
}

TEST(StaticIndex, Remove) {
  BoxColumns indexed = adversarialBoxes(700, 10.0, 0.2, 0, 5);
  addFilters(indexed, 5);
  const BoxColumns queries = adversarialBoxes(200, 10.0, 0.2, 10000, 6);
  StaticIndex index;
  buildOnThreads(index, indexed, allIndexes(indexed), 2);
  std::vector<uint32_t> removed;
  Random random(7);
  for (int k = 0; k < 150; ++k) {
    const uint32_t id = static_cast<uint32_t>(random.below(700));
    const bool fresh = std::find(removed.begin(), removed.end(), id) == removed.end();
    EXPECT_EQ(index.remove(id), fresh) << "id " << id;
    if (fresh) removed.push_back(id);
  }
  EXPECT_FALSE(index.remove(700));
  EXPECT_FALSE(index.remove(0xFFFFFFFFu));
  EXPECT_EQ(index.size(), 700 - removed.size());
  const PairList expected =
      bruteForceCross(indexed, allIndexes(indexed), queries, allIndexes(queries), removed);
  for (int threads : {1, 2, 3}) {
    PairList pairs;
    queryAllOnThreads(index, queries, allIndexes(queries), threads, pairs);
    EXPECT_TRUE(samePairs(expected, pairs)) << "threads " << threads;
  }
}

TEST(StaticIndex, EmptySides) {
  const BoxColumns boxes = adversarialBoxes(100, 10.0, 0.2, 0, 11);
  StaticIndex empty;
  buildOnThreads(empty, boxes, {}, 2);
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_FALSE(empty.remove(3));
  PairList pairs;
  queryAllOnThreads(empty, boxes, allIndexes(boxes), 2, pairs);
  EXPECT_TRUE(pairs.empty());
  StaticIndex never_built;
  queryAllOnThreads(never_built, boxes, allIndexes(boxes), 3, pairs);
  EXPECT_TRUE(pairs.empty());

  StaticIndex full;
  buildOnThreads(full, boxes, allIndexes(boxes), 2);
  queryAllOnThreads(full, boxes, {}, 3, pairs);
  EXPECT_TRUE(pairs.empty());
  BoxColumns no_boxes;
  queryAllOnThreads(full, no_boxes, {}, 1, pairs);
  EXPECT_TRUE(pairs.empty());
}

TEST(StaticIndex, KeepsItsOwnCopyAndRebuilds) {
  BoxColumns indexed = adversarialBoxes(300, 10.0, 0.2, 0, 21);
  const BoxColumns queries = adversarialBoxes(100, 10.0, 0.2, 1000, 22);
  const PairList expected =
      bruteForceCross(indexed, allIndexes(indexed), queries, allIndexes(queries));
  StaticIndex index;
  buildOnThreads(index, adversarialBoxes(50, 3.0, 0.5, 0, 99), {0, 1, 2}, 1);  // replaced below
  buildOnThreads(index, indexed, allIndexes(indexed), 2);
  indexed.clear();
  PairList pairs;
  queryAllOnThreads(index, queries, allIndexes(queries), 2, pairs);
  EXPECT_TRUE(samePairs(expected, pairs));
}

TEST(StaticIndex, FilteredOutQueriesAndAppending) {
  // Static boxes that cannot pair with each other (group 0x2, mask 0x1), as in the target scene.
  BoxColumns boxes = adversarialBoxes(500, 10.0, 0.1, 0, 31);
  boxes.groups.assign(boxes.size(), 0x2u);
  boxes.masks.assign(boxes.size(), 0x1u);
  BoxColumns queries = adversarialBoxes(100, 10.0, 0.1, 1000, 32);
  addFilters(queries, 33);
  StaticIndex index;
  buildOnThreads(index, boxes, allIndexes(boxes), 2);
  PairList pairs = {{7, 8}};  // appended to, never cleared
  queryAllOnThreads(index, queries, allIndexes(queries), 2, pairs);
  ASSERT_FALSE(pairs.empty());
  EXPECT_EQ(pairs.front(), (IdPair{7, 8}));
  pairs.erase(pairs.begin());
  EXPECT_TRUE(
      samePairs(bruteForceCross(boxes, allIndexes(boxes), queries, allIndexes(queries)), pairs));
}

TEST(StaticIndex, UniformSceneHundredThousandStatic) {
  SceneConfig scene;
  scene.n = 101000;
  scene.seed = 4;
  BoxColumns boxes = columnsOf(makeSceneFrame(scene, 0));
  std::vector<uint32_t> indexed, moving;
  for (uint32_t i = 0; i < boxes.size(); ++i) (i < 100000 ? indexed : moving).push_back(i);
  boxes.groups.assign(boxes.size(), 0x2u);
  boxes.masks.assign(boxes.size(), 0x1u);
  for (uint32_t i : moving) {
    boxes.groups[i] = 0x1u;
    boxes.masks[i] = 0xFFFFFFFFu;
  }
  const PairList expected = bruteForceCross(boxes, indexed, boxes, moving);
  EXPECT_GT(expected.size(), 0u);
  StaticIndex index;
  buildOnThreads(index, boxes, indexed, 2);
  EXPECT_GT(index.cellsOnAxis(0), 1u);
  EXPECT_EQ(index.largeCount(), 0u);
  for (int threads : {1, 2, 3}) {
    PairList pairs;
    queryAllOnThreads(index, boxes, moving, threads, pairs);
    EXPECT_TRUE(samePairs(expected, pairs)) << "threads " << threads;
  }
}

}  // namespace
}  // namespace sap_broadphase
