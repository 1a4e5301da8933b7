// Candidate generation: Algorithm 3 (parallel, prefix ⊕ of per-slice SuccTrees) gives exactly
// Algorithm 1's ranks and ranges, and every range covers the object's primary-axis overlaps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "core/radix_sort.h"
#include "core/sort_keys.h"
#include "core/sweep.h"
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
        computeCandidatesParallel(order.data(), objects, threads, work, parallel);
        EXPECT_TRUE(sameRanges(sequential, parallel))
            << objects << " objects, " << cells << " cells, " << threads << " threads";
      }
    }
  }
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
        computeCandidatesParallel(nullptr, 0, 3, work, parallel);
        std::exit(sequential.of_object.empty() && parallel.of_object.empty() ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace sap_broadphase
