// Candidate generation: Algorithm 3 (parallel, prefix ⊕ of per-slice object sets) gives exactly
// Algorithm 1's ranks and ranges, and every range covers the object's primary-axis overlaps.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/runner/work_units.h"
#include "core/strategies/small_frame.h"
#include "core/sweep/axis_spread.h"
#include "core/sweep/key_origin.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/sort_keys.h"
#include "core/sweep/sweep.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::TestRandom;

/// The primary-axis order of random intervals (lows at i, highs at i + n), with many ties.
std::vector<uint32_t> primaryOrder(uint32_t inObjects, int inCells, uint64_t inSeed) {
  TestRandom random(inSeed);
  std::vector<uint32_t> keys(2 * inObjects);
  for (uint32_t i = 0; i < inObjects; ++i) {
    const double low = static_cast<double>(random.below(static_cast<uint64_t>(inCells)));
    const double high = low + static_cast<double>(random.below(random.below(10) == 0 ? 200 : 4));
    keys[i] = lowKey(low);
    keys[i + inObjects] = highKey(high);
  }
  std::vector<uint32_t> order(keys.size());
  radixIndexSort(keys.data(), static_cast<uint32_t>(keys.size()), order.data());
  return order;
}

bool sameRanges(const CandidateRanges& inA, const CandidateRanges& inB) {
  if (inA.of_object.size() != inB.of_object.size()) return false;
  for (std::size_t i = 0; i < inA.of_object.size(); ++i) {
    const RankRange& a = inA.of_object[i];
    const RankRange& b = inB.of_object[i];
    if (a.rank != b.rank || a.low != b.low || a.high != b.high) return false;
  }
  return inA.object_of_rank == inB.object_of_rank;
}

/// Ranks form a permutation with R^- its inverse, and each range covers every object whose
/// primary interval (in sorted positions) intersects the object's own.
void expectRangesCoverOverlaps(const std::vector<uint32_t>& inOrder, uint32_t inObjects,
                               const CandidateRanges& inRanges) {
  std::vector<uint32_t> start(inObjects);
  std::vector<uint32_t> end(inObjects);
  for (uint32_t position = 0; position < inOrder.size(); ++position) {
    const uint32_t endpoint = inOrder[position];
    if (endpoint < inObjects)
      start[endpoint] = position;
    else
      end[endpoint - inObjects] = position;
  }
  for (uint32_t i = 0; i < inObjects; ++i) {
    const RankRange& range = inRanges.of_object[i];
    ASSERT_LT(range.rank, inObjects);
    ASSERT_EQ(inRanges.object_of_rank[range.rank], i);
    ASSERT_LE(range.low, range.rank);
    ASSERT_GT(range.high, range.rank);
    for (uint32_t j = 0; j < inObjects; ++j) {
      if (j == i || start[j] > end[i] || start[i] > end[j]) continue;
      const uint32_t rank = inRanges.of_object[j].rank;
      ASSERT_TRUE(range.low <= rank && rank < range.high)
          << "object " << j << " (rank " << rank << ") overlaps " << i << " but is outside ["
          << range.low << ", " << range.high << ")";
    }
  }
}

TEST(Candidates, ParallelEqualsSequentialForEveryThreadCount) {
  for (uint32_t objects : {1u, 2u, 3u, 10u, 100u, 1000u, 20000u}) {
    for (int cells : {1, 10, 1000}) {
      const std::vector<uint32_t> order = primaryOrder(objects, cells, objects * 7 + cells);
      SuccTree active;
      CandidateRanges sequential;
      computeCandidatesSequential(order.data(), objects, active, sequential);
      if (objects <= 1000) expectRangesCoverOverlaps(order, objects, sequential);
      SweepWorkspace work;
      for (int threads : {1, 2, 3, 4, 7, 16}) {
        CandidateRanges parallel;
        const ThreadsScope scope(threads);
        computeCandidatesParallel(order.data(), objects, work, parallel);
        EXPECT_TRUE(sameRanges(sequential, parallel))
            << objects << " objects, " << cells << " cells, " << threads << " threads";
      }
    }
  }
}

TEST(Candidates, ParallelInsideAnotherParallelRegion) {
  // Nested regions inactive (the default): the inner team has one thread, which must then
  // take every slice itself.
  const int saved_levels = omp_get_max_active_levels();
  omp_set_max_active_levels(1);
  const uint32_t objects = 5000;
  const std::vector<uint32_t> order = primaryOrder(objects, 300, 99);
  SuccTree active;
  CandidateRanges sequential;
  computeCandidatesSequential(order.data(), objects, active, sequential);
  int mismatches = 0;
#pragma omp parallel num_threads(2) reduction(+ : mismatches)
  for (int threads : {2, 3, 4}) {
    SweepWorkspace work;
    CandidateRanges parallel;
    const ThreadsScope scope(threads);  // this OpenMP thread's own scope
    computeCandidatesParallel(order.data(), objects, work, parallel);
    mismatches += !sameRanges(sequential, parallel);
  }
  omp_set_max_active_levels(saved_levels);
  EXPECT_EQ(mismatches, 0);
}

TEST(Candidates, ZeroObjectsWithAFreshWorkspace) {
  // Run in a child process: a crash fails this test instead of ending the whole suite. The
  // child re-executes the binary ("threadsafe"): OpenMP's thread pool does not survive fork().
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        SuccTree active;
        CandidateRanges sequential;
        computeCandidatesSequential(nullptr, 0, active, sequential);
        SweepWorkspace work;
        CandidateRanges parallel;
        const ThreadsScope three_threads(3);
        computeCandidatesParallel(nullptr, 0, work, parallel);
        std::exit(sequential.of_object.empty() && parallel.of_object.empty() ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

// ---- The small-frame path: exactly the oracle's pairs, on both sweeps. ----

constexpr double kInf = std::numeric_limits<double>::infinity();

template <typename Boxes>
void addBox(Boxes& ioBoxes, double inX0, double inY0, double inZ0, double inX1, double inY1,
            double inZ1) {
  const double low[3] = {inX0, inY0, inZ0};
  const double high[3] = {inX1, inY1, inZ1};
  ioBoxes.add(static_cast<uint32_t>(ioBoxes.size()), low, high);
}

// Runs the dispatched sweep (AVX2 where the CPU has it) and the portable one, twice each on one
// workspace (the second run reuses grown buffers), against the oracle.
void expectSmallFrameMatches(const BoxColumns& inBoxes, const std::string& inLabel) {
  const PairList oracle = bruteForcePairs(inBoxes);
  SmallFrameWorkspace work;
  PairList pairs;
  for (int run = 0; run < 2; ++run) {
    pairSmallFrame(inBoxes, work, pairs);
    EXPECT_TRUE(test_support::samePairs(oracle, pairs)) << inLabel << " (dispatched)";
    pairSmallFramePortable(inBoxes, work, pairs);
    EXPECT_TRUE(test_support::samePairs(oracle, pairs)) << inLabel << " (portable)";
  }
}

void expectSmallFrameMatches(const BoxSet& inBoxes, const std::string& inLabel) {
  expectSmallFrameMatches(columnsOf(inBoxes), inLabel);
}

TEST(SmallFrame, RandomBoxesOfEverySize) {
  for (std::size_t n : {0u, 1u, 2u, 3u, 7u, 8u, 9u, 17u, 255u, 256u, 1000u, 5000u}) {
    for (double edge : {0.5, 5.0, 40.0}) {
      const BoxSet boxes = test_support::randomBoxes(n, 100.0, edge, n * 31 + 7);
      expectSmallFrameMatches(boxes, std::to_string(n) + " boxes, edge " + std::to_string(edge));
    }
  }
}

// A robot's few thousand 5 cm boxes on a 10 m site in UTM, Earth-centred and 1e9 coordinates:
// exact, and the float keys still tell the boxes apart (keys of the raw coordinates would
// collapse onto a handful of floats and make every box a candidate of every other).
TEST(SmallFrame, SmallBoxesFarFromTheOriginKeepDistinctKeys) {
  const BoxSet site = test_support::randomBoxes(2000, 10.0, 0.05, 11);
  for (double offset : {0.0, 5.4e6, 4.7e6 + 0.25, 1e9}) {
    BoxSet shifted = site;
    for (int axis = 0; axis < 3; ++axis) {
      for (std::size_t i = 0; i < site.size(); ++i) {
        shifted.lo(axis, i) += offset;
        shifted.hi(axis, i) += offset;
      }
    }
    const std::string label = "offset " + std::to_string(offset);
    expectSmallFrameMatches(shifted, label);
    SmallFrameWorkspace work;
    PairList pairs;
    pairSmallFrame(columnsOf(shifted), work, pairs);
    std::vector<float> lows;  // every cell's sweep-axis lows, without the NaN padding
    for (float low : work.lo[0])
      if (!std::isnan(low)) lows.push_back(low);
    std::sort(lows.begin(), lows.end());
    const auto distinct = std::unique(lows.begin(), lows.end()) - lows.begin();
    EXPECT_GT(distinct, 1900) << label;
  }
}

TEST(SmallFrame, TouchingLatticeWithZeroExtents) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    expectSmallFrameMatches(test_support::latticeBoxes(1500, 12, 2, seed), "lattice");
    expectSmallFrameMatches(test_support::latticeBoxes(300, 3, 0, seed), "dense points");
  }
}

TEST(SmallFrame, FiltersIncludingZeroGroupsAndMasks) {
  BoxSet boxes = test_support::randomBoxes(2000, 50.0, 6.0, 11);
  test_support::addRandomFilters(boxes, 12);
  for (std::size_t i = 0; i < boxes.size(); i += 17) boxes.groups[i] = 0;
  for (std::size_t i = 5; i < boxes.size(); i += 23) boxes.masks[i] = 0;
  expectSmallFrameMatches(boxes, "filters");
}

TEST(SmallFrame, IdsOutOfOrderAndSparse) {
  const BoxSet boxes = test_support::randomBoxes(3000, 60.0, 5.0, 21);
  expectSmallFrameMatches(test_support::shuffledSubset(boxes, 0.7, false, 22), "shuffled");
  expectSmallFrameMatches(test_support::shuffledSubset(boxes, 0.7, true, 23), "sparse ids");
}

TEST(SmallFrame, SignedZerosAndInfinities) {
  BoxSet boxes;
  addBox(boxes, -1, -1, -1, -0.0, -0.0, -0.0);
  addBox(boxes, 0.0, 0.0, 0.0, 1, 1, 1);
  addBox(boxes, -1, -1, -1, 0.0, 0.0, 0.0);
  addBox(boxes, -0.0, -0.0, -0.0, 1, 1, 1);
  addBox(boxes, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0);
  addBox(boxes, 1e-320, 1e-320, 1e-320, 1, 1, 1);
  addBox(boxes, -1, -1, -1, -1e-320, 0, 0);
  EXPECT_EQ(bruteForcePairs(boxes).size(), 14u);
  expectSmallFrameMatches(boxes, "signed zeros");
  addBox(boxes, -kInf, -kInf, -kInf, kInf, kInf, 0.0);
  addBox(boxes, 5, -kInf, -kInf, 5, kInf, kInf);
  addBox(boxes, kInf, 0, 0, kInf, 1, 1);
  addBox(boxes, kInf, 0, 0, kInf, 1, 1);
  addBox(boxes, -kInf, 0, 0, -kInf, 1, 1);
  addBox(boxes, 0, -kInf, 0, 1, -1e308, 1);
  addBox(boxes, -1e300, -1e300, -1e300, 1e300, 1e300, 1e300);
  expectSmallFrameMatches(boxes, "infinities");
}

TEST(SmallFrame, GapsSmallerThanAFloat32Step) {
  TestRandom random(10);
  BoxSet boxes;
  for (int i = 0; i < 400; ++i) {
    const double base = random.between(-100.0, 100.0) * (i % 2 ? 1.0 : 1e-30);
    const double touch = random.below(2) ? base : std::nextafter(base, kInf);
    const double y = static_cast<double>(random.below(3));
    addBox(boxes, base - 0.5, y, 0, base, y + 1, 1);
    addBox(boxes, touch, y, 0, touch + 0.5, y + 1, 1);
  }
  expectSmallFrameMatches(boxes, "sub-float32 gaps");
}

TEST(SmallFrame, SweepsTheAxisWhereBoxesAreNarrowest) {
  BoxColumns boxes;
  for (int i = 0; i < 200; ++i) addBox(boxes, 0, i, 0, 100, i + 0.5, 100);  // slices along y
  FrameSpread spread(boxes);
  EXPECT_EQ(chooseSmallFrameAxis(spread), 1);
  expectSmallFrameMatches(boxes, "slices along y");
  BoxColumns flat;
  for (int i = 0; i < 200; ++i) addBox(flat, i, 7, i % 5, i + 3, 7, i % 5 + 1);  // y span 0
  FrameSpread flat_spread(flat);
  EXPECT_NE(chooseSmallFrameAxis(flat_spread), 1);
  expectSmallFrameMatches(flat, "all at one y");
}

// A frame's spread is read by several parts (key origins, slabs, the small frame's axis, the
// cost model): each axis is measured when first asked for and kept for the frame.
TEST(FrameSpread, MeasuresEachAxisOnceWhenFirstAsked) {
  const double inf = std::numeric_limits<double>::infinity();
  BoxColumns boxes;
  addBox(boxes, 0, 2, 0, 1, 5, 1);
  addBox(boxes, 3, -inf, 0, 4, 7, 1);  // infinite low end: not in the span or the extents
  addBox(boxes, 1, 4, 0, 2, inf, 1);
  FrameSpread spread(boxes);
  const AxisSpread expected = measureAxisSpread(boxes, 1);
  const ThreadsScope two_threads(2);
  const AxisSpread& first = spread.axis(1);
  EXPECT_EQ(first.lowest, 2.0);
  EXPECT_EQ(first.highest, 7.0);
  EXPECT_EQ(first.finite_boxes, 1u);
  EXPECT_EQ(first.extent_sum, expected.extent_sum);
  boxes.lo[1][0] = -50.0;  // a change after the measurement is not seen: measured once
  EXPECT_EQ(spread.axis(1).lowest, 2.0);
  boxes.lo[0][0] = -50.0;  // axis 0 was not measured yet: its first reading sees the change
  EXPECT_EQ(spread.axis(0).lowest, -50.0);
}

TEST(KeyOrigin, CentreOfTheFrameOnlyFarFromZero) {
  BoxColumns boxes;
  addBox(boxes, 4.0e6, 995, -1, 4.0e6 + 2, 997, 1);
  addBox(boxes, 4.0e6 + 8, 1003, -3, 4.0e6 + 10, 1005, 3);
  FrameSpread spread(boxes);
  const KeyOrigin origin = keyOriginOf(spread);
  EXPECT_EQ(origin.origin[0], 4.0e6 + 5) << "far from 0 against a span of 10: the centre";
  EXPECT_EQ(origin.origin[1], 1000.0) << "the centre lies 200 half-spans from 0";
  EXPECT_EQ(origin.origin[2], 0.0) << "around 0: the coordinates themselves";
  const BoxColumns no_boxes;
  FrameSpread empty_spread(no_boxes);
  EXPECT_EQ(keyOriginOf(empty_spread).origin[0], 0.0) << "no finite bound: 0";
}

}  // namespace
}  // namespace sap_broadphase
