// The third-axis slabs (slab_grid.h): slabOf is monotone and clamped to the grid, the grid
// spans the boxes' finite bounds, and chooseSlabGrid keeps one slab where slabs cannot help
// (few boxes, no finite span) and honours a requested count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/runner/work_units.h"
#include "core/sweep/slab_grid.h"
#include "core/tuning.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::randomBoxes;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kZ = 2;  // the third axis of the default sweep axes (x, y)

// inCount boxes of edge inEdge on every axis, spread evenly along z over [0, inSpan].
BoxColumns boxesAlongZ(std::size_t inCount, double inSpan, double inEdge) {
  BoxColumns boxes;
  for (std::size_t i = 0; i < inCount; ++i) {
    const double z = inSpan * static_cast<double>(i) / static_cast<double>(inCount - 1);
    const double low[3] = {0.0, 0.0, z}, high[3] = {inEdge, inEdge, z + inEdge};
    boxes.add(static_cast<uint32_t>(i), low, high);
  }
  return boxes;
}

TEST(SlabGrid, SlabOfIsMonotoneAndClampedToTheGrid) {
  SlabGrid grid;
  grid.count = 5;
  grid.origin = -10.0;
  grid.width = 4.0;
  EXPECT_EQ(grid.slabOf(-kInfinity), 0);
  EXPECT_EQ(grid.slabOf(-1.0e300), 0);
  EXPECT_EQ(grid.slabOf(-10.0), 0);
  EXPECT_EQ(grid.slabOf(-6.0), 1);  // a slab's low end is its own
  EXPECT_EQ(grid.slabOf(-6.0000001), 0);
  EXPECT_EQ(grid.slabOf(5.9), 3);
  EXPECT_EQ(grid.slabOf(6.0), 4);
  EXPECT_EQ(grid.slabOf(1.0e300), 4);
  EXPECT_EQ(grid.slabOf(kInfinity), 4);
  EXPECT_EQ(grid.slabOf(-0.0), grid.slabOf(0.0));
  int last = 0;
  for (double z = -20.0; z <= 20.0; z += 0.37) {
    const int slab = grid.slabOf(z);
    EXPECT_GE(slab, last) << "z " << z;
    EXPECT_LT(slab, grid.count) << "z " << z;
    last = slab;
  }
}

TEST(SlabGrid, TheDefaultIsThePapersSingleList) {
  const SlabGrid grid;
  EXPECT_EQ(grid.count, 1);
  EXPECT_EQ(grid.slabOf(-kInfinity), 0);
  EXPECT_EQ(grid.slabOf(12345.0), 0);
}

TEST(SlabGrid, FewBoxesOrOneRequestedSlabKeepOneList) {
  const BoxColumns few = boxesAlongZ(tuning::kMinBoxesForSlabs - 1, 1000.0, 1.0);
  FrameSpread few_spread(few);
  EXPECT_EQ(chooseSlabGrid(few_spread, kZ, 0).count, 1);
  const BoxColumns many = boxesAlongZ(tuning::kMinBoxesForSlabs, 1000.0, 1.0);
  FrameSpread many_spread(many);
  EXPECT_GT(chooseSlabGrid(many_spread, kZ, 0).count, 1);
  EXPECT_EQ(chooseSlabGrid(many_spread, kZ, 1).count, 1);
}

TEST(SlabGrid, AutomaticSlabsAreAboutTwoExtentsWideAndSpanTheBounds) {
  // Span 1001 (lowest 0, highest 1000 + 1), mean extent 1: ceil(1001 / 2) slabs, capped at 64.
  for (double span : {60.0, 1000.0}) {
    const BoxColumns boxes = boxesAlongZ(4096, span, 1.0);
    FrameSpread spread(boxes);
    const ThreadsScope two_threads(2);
    const SlabGrid grid = chooseSlabGrid(spread, kZ, 0);
    const int expected = std::min(
        kMaxSlabs, static_cast<int>(std::ceil((span + 1.0) / (tuning::kSlabWidthInExtents * 1.0))));
    EXPECT_EQ(grid.count, expected) << "span " << span;
    EXPECT_EQ(grid.origin, 0.0);
    EXPECT_DOUBLE_EQ(grid.width * grid.count, span + 1.0);
    EXPECT_EQ(grid.slabOf(0.0), 0);
    EXPECT_EQ(grid.slabOf(span + 1.0), grid.count - 1);
  }
}

TEST(SlabGrid, ARequestedCountIsHonouredUpToTheMaximum) {
  const BoxColumns boxes = columnsOf(randomBoxes(3000, 100.0, 2.0, 8));
  FrameSpread spread(boxes);
  EXPECT_EQ(chooseSlabGrid(spread, kZ, 7).count, 7);
  EXPECT_EQ(chooseSlabGrid(spread, kZ, kMaxSlabs).count, kMaxSlabs);
  // A small frame too: a requested count is not subject to the automatic minimum.
  const BoxColumns few = columnsOf(randomBoxes(10, 100.0, 2.0, 8));
  FrameSpread few_spread(few);
  EXPECT_EQ(chooseSlabGrid(few_spread, kZ, 3).count, 3);
}

TEST(SlabGrid, NoFiniteSpanMeansOneSlab) {
  // Every box the same point on z: a span of 0.
  BoxColumns flat = boxesAlongZ(4096, 100.0, 1.0);
  for (std::size_t i = 0; i < flat.size(); ++i) flat.lo[kZ][i] = flat.hi[kZ][i] = 3.0;
  FrameSpread flat_spread(flat);
  EXPECT_EQ(chooseSlabGrid(flat_spread, kZ, 0).count, 1);
  EXPECT_EQ(chooseSlabGrid(flat_spread, kZ, 8).count, 1);
  // Every box unbounded on z: no finite bound at all.
  BoxColumns unbounded = boxesAlongZ(4096, 100.0, 1.0);
  for (std::size_t i = 0; i < unbounded.size(); ++i) {
    unbounded.lo[kZ][i] = -kInfinity;
    unbounded.hi[kZ][i] = kInfinity;
  }
  FrameSpread unbounded_spread(unbounded);
  EXPECT_EQ(chooseSlabGrid(unbounded_spread, kZ, 0).count, 1);
}

TEST(SlabGrid, InfiniteBoxesFallInTheEndSlabs) {
  BoxColumns boxes = boxesAlongZ(4096, 1000.0, 1.0);
  boxes.lo[kZ][0] = -kInfinity;
  boxes.hi[kZ][4095] = kInfinity;
  FrameSpread spread(boxes);
  const SlabGrid grid = chooseSlabGrid(spread, kZ, 0);
  ASSERT_GT(grid.count, 1);
  EXPECT_EQ(grid.slabOf(boxes.lo[kZ][0]), 0);
  EXPECT_EQ(grid.slabOf(boxes.hi[kZ][4095]), grid.count - 1);
}

}  // namespace
}  // namespace sap_broadphase
