// The small frame's cell grid: boxes laid into cells over the two axes other than the sweep
// axis, each cell swept alone, each pair reported in one cell only. Every case checks that the
// grid really ran (more than one cell) and that both sweeps give exactly the oracle's pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/runner/work_units.h"
#include "core/strategies/small_frame.h"
#include "core/sweep/key_origin.h"
#include "core/sweep/sort_keys.h"
#include "core/tuning.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void addBox(BoxColumns& ioBoxes, const double (&inLow)[3], const double (&inHigh)[3]) {
  ioBoxes.add(static_cast<uint32_t>(ioBoxes.size()), inLow, inHigh);
}

// Both sweeps, twice each on one workspace (the second run reuses its buffers), on a grid, on
// one to four threads.
void expectGridMatches(const BoxColumns& inBoxes, const std::string& inLabel) {
  const PairList oracle = bruteForcePairs(inBoxes);
  SmallFrameWorkspace work;
  PairList pairs;
  for (int threads = 1; threads <= 4; ++threads) {
    const std::string label = inLabel + ", " + std::to_string(threads) + " threads";
    const ThreadsScope scope(threads);
    for (int run = 0; run < 2; ++run) {
      pairSmallFrame(inBoxes, work, pairs);
      EXPECT_GT(work.grid_cells, 1u) << label << ": the grid did not run";
      EXPECT_TRUE(test_support::samePairs(oracle, pairs)) << label << " (dispatched)";
      pairSmallFramePortable(inBoxes, work, pairs);
      EXPECT_TRUE(test_support::samePairs(oracle, pairs)) << label << " (portable)";
    }
  }
}

// bytesHeld() counts the workspace's buffers: none when fresh, some once a frame sized them,
// the same when a frame of the same boxes reuses them.
TEST(SmallFrameWorkspace, BytesHeldCountsItsBuffers) {
  const BoxColumns boxes = columnsOf(test_support::randomBoxes(3000, 40.0, 1.5, 5));
  SmallFrameWorkspace work;
  EXPECT_EQ(work.bytesHeld(), 0u);
  PairList pairs;
  const ThreadsScope two(2);
  pairSmallFrame(boxes, work, pairs);
  const std::size_t held = work.bytesHeld();
  EXPECT_GE(held, boxes.size() * 6 * sizeof(float)) << "at least the boxes' rounded bounds";
  pairSmallFrame(boxes, work, pairs);
  EXPECT_EQ(work.bytesHeld(), held);
  work = SmallFrameWorkspace();
  EXPECT_EQ(work.bytesHeld(), 0u);
}

TEST(SmallFrameGrid, RandomScenesOfManyCellCounts) {
  const auto per_cell = static_cast<std::size_t>(tuning::kSmallFrameBoxesPerCell);
  for (std::size_t n : {4 * per_cell + 100, 9 * per_cell + 100, 40 * per_cell}) {
    for (double edge : {0.5, 2.0, 6.0}) {
      const BoxColumns boxes = columnsOf(test_support::randomBoxes(n, 100.0, edge, n + 3));
      expectGridMatches(boxes, std::to_string(n) + " boxes, edge " + std::to_string(edge));
    }
  }
}

// Boxes reaching across many cells, or infinitely far on a grid axis (first to last cell), and
// boxes beyond the finite span: each pair once, however many cells the two boxes share.
// Frames of several units of boxes (kUnitBoxes), so that every pass of the kernel hands units
// to the runner's workers: the bounds, the key sort, the per-unit cell counts, the cells'
// prefix and padding, the copies, and runs of cells swept by different workers, on one to four
// threads, over several seeds and densities. The layout of the cells is the same on every thread
// count, as are the pairs.
TEST(SmallFrameGrid, ParallelPassesMatchTheOracleOnOneToFourThreads) {
  const std::size_t n = 2 * kUnitBoxes + 2500;
  const std::pair<uint64_t, double> cases[] = {{11, 1.0}, {12, 3.0}, {13, 2.0}};
  for (const auto& [seed, edge] : cases) {
    const BoxColumns boxes = columnsOf(test_support::randomBoxes(n, 200.0, edge, seed));
    const std::string label = "seed " + std::to_string(seed) + ", edge " + std::to_string(edge);
    const PairList oracle = bruteForcePairs(boxes);
    SmallFrameWorkspace one_thread;
    PairList pairs;
    pairSmallFrame(boxes, one_thread, pairs);
    ASSERT_TRUE(test_support::samePairs(oracle, pairs)) << label << ", 1 thread";
    for (int threads = 2; threads <= 4; ++threads) {
      SmallFrameWorkspace work;
      const ThreadsScope scope(threads);
      const uint64_t regions = parallelRegionsOpened();
      pairSmallFrame(boxes, work, pairs);
      const std::string at = label + ", " + std::to_string(threads) + " threads";
      EXPECT_GT(parallelRegionsOpened(), regions) << at << ": no pass was handed out";
      EXPECT_GT(work.unit_first_cell.size(), 2u) << at << ": one run of cells";
      EXPECT_TRUE(test_support::samePairs(oracle, pairs)) << at;
      EXPECT_TRUE(std::equal(one_thread.box_of.begin(), one_thread.box_of.end(),
                             work.box_of.begin(), work.box_of.end()))
          << at << ": the cells' layout depends on the threads";
      EXPECT_TRUE(std::equal(one_thread.cell_start.begin(), one_thread.cell_start.end(),
                             work.cell_start.begin(), work.cell_start.end()))
          << at << ": the cells' runs depend on the threads";
      pairSmallFramePortable(boxes, work, pairs);
      EXPECT_TRUE(test_support::samePairs(oracle, pairs)) << at << " (portable)";
    }
  }
}

TEST(SmallFrameGrid, WideAndInfiniteBoxesReachEveryCell) {
  BoxColumns boxes = columnsOf(test_support::randomBoxes(4000, 100.0, 1.0, 41));
  for (int axis = 0; axis < 3; ++axis) {
    for (double at : {10.0, 50.0, 90.0}) {
      double low[3] = {at, at, at}, high[3] = {at + 1, at + 1, at + 1};
      low[axis] = -kInf;
      high[axis] = kInf;
      addBox(boxes, low, high);
      low[axis] = -5.0;  // wider than the span, but finite
      high[axis] = 105.0;
      addBox(boxes, low, high);
    }
  }
  addBox(boxes, {-kInf, -kInf, -kInf}, {kInf, kInf, kInf});
  addBox(boxes, {20, -kInf, 30}, {21, -kInf, 31});  // a plane at -inf
  addBox(boxes, {20, kInf, 30}, {21, kInf, 31});    // a plane at +inf
  addBox(boxes, {20, kInf, 30}, {22, kInf, 32});
  expectGridMatches(boxes, "wide and infinite");
}

// Finite coordinates beyond the float range round outward to the largest float or infinity
// (the four-lane conversion steps +inf down to the largest float for a low): boxes touching
// out there, and boxes crossing the largest float, still pair exactly.
TEST(SmallFrameGrid, CoordinatesBeyondTheFloatRange) {
  BoxColumns boxes = columnsOf(test_support::randomBoxes(3000, 100.0, 1.0, 45));
  const double max_float = 3.4028234663852886e38;
  for (double at : {1e39, -1e39, max_float, -max_float}) {
    addBox(boxes, {at, 10, 10}, {at, 11, 11});
    addBox(boxes, {at, 10.5, 10.5}, {at * 1.5, 12, 12});
    addBox(boxes, {at * 0.5, 11, 11}, {at * 0.75, 12, 12});
  }
  addBox(boxes, {-max_float, 60, 60}, {max_float, 61, 61});
  addBox(boxes, {-1e39, 60.5, 60.5}, {-max_float, 62, 62});
  addBox(boxes, {max_float * 1.0000001, 60.5, 60.5}, {1e39, 62, 62});
  expectGridMatches(boxes, "beyond the float range");
}

// The float bounds both sweeps test are the key origin's outward keys (KeyOrigin::low/high),
// value for value, whichever conversion made them (four lanes at a time or one by one): values
// that are floats, that fall between floats (above and below), that lose bits to the origin,
// signed zeros, denormals, values beyond the float range and infinities.
TEST(SmallFrameGrid, BoundsAreTheKeyOriginsOutwardKeys) {
  test_support::TestRandom random(91);
  BoxColumns boxes;
  const double awkward[] = {0.0,     -0.0, 1e-45,  -1e-45,  1e-300, 0.1,        -0.1,
                            1.0 / 3, 3e38, 3.5e38, -3.5e38, 1e300,  5.4e6 + 0.1};
  for (uint32_t i = 0; i < 1001; ++i) {
    double low[3], high[3];
    for (int axis = 0; axis < 3; ++axis) {
      const double base = 5.4e6 + random.unit() * 1000.0;
      low[axis] = i % 3 == 0 ? awkward[random.below(std::size(awkward))] : base;
      high[axis] = std::max(
          low[axis], i % 5 == 0 ? awkward[random.below(std::size(awkward))] : base + random.unit());
    }
    if (i % 97 == 0) low[i % 3] = -kInf, high[(i + 1) % 3] = kInf;
    addBox(boxes, low, high);
  }
  FrameSpread spread(boxes);
  const int axis = chooseSmallFrameAxis(spread);
  const KeyOrigin origin = keyOriginOf(spread);
  SmallFrameWorkspace work;
  PairList pairs;
  for (int sweep = 0; sweep < 2; ++sweep) {
    if (sweep == 0)
      pairSmallFrame(boxes, work, pairs);
    else
      pairSmallFramePortable(boxes, work, pairs);
    EXPECT_TRUE(test_support::samePairs(bruteForcePairs(boxes), pairs));
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      for (int slot = 0; slot < 3; ++slot) {
        const int a = (axis + slot) % 3;
        const float low = keyToFloat(origin.low(a, boxes.lo[a][i]));
        const float high = keyToFloat(origin.high(a, boxes.hi[a][i]));
        ASSERT_EQ(low, work.bounds[6 * i + 2 * slot]) << "box " << i << " axis " << a;
        ASSERT_EQ(high, work.bounds[6 * i + 2 * slot + 1]) << "box " << i << " axis " << a;
      }
    }
  }
}

// Boxes that miss or overlap by less than a float's resolution, on every axis, around 50 and
// around 0 (where -0.0 has no key of its own): the floats cannot tell these pairs, so each
// hit must go to the float64 test, and every miss stays a miss.
TEST(SmallFrameGrid, NearMissesBelowTheFloatResolution) {
  BoxColumns boxes = columnsOf(test_support::randomBoxes(3000, 100.0, 1.0, 95));
  const double gaps[] = {-3e-6, -1e-7, -1e-12, 0.0, 1e-12, 1e-9, 1e-7, 3e-6, 8e-6};
  double at = 20.0;
  for (int axis = 0; axis < 3; ++axis) {
    for (double gap : gaps) {
      at += 2.5;
      double low[3] = {at, at, at}, high[3] = {at + 1, at + 1, at + 1};
      addBox(boxes, low, high);
      low[axis] = high[axis] + gap;
      high[axis] = low[axis] + 1.0;
      addBox(boxes, low, high);
    }
    for (double below : {-2e-50, -1e-45, -0.0}) {
      double low[3] = {90, 90, 90}, high[3] = {91, 91, 91};
      low[axis] = -1.0;
      high[axis] = below;
      addBox(boxes, low, high);
      low[axis] = -1e-50;
      high[axis] = 1.0;
      addBox(boxes, low, high);
    }
  }
  expectGridMatches(boxes, "near misses");
}

// Integer lattice boxes: many faces touch exactly, some on the grid's cell edges, many have
// zero extent; closed intervals make every touch a pair.
TEST(SmallFrameGrid, TouchingFacesOnCellEdges) {
  for (uint64_t seed : {1u, 2u}) {
    expectGridMatches(columnsOf(test_support::latticeBoxes(6000, 64, 2, seed)), "lattice");
  }
}

// A scene spanning exactly [-64, 64] on each axis, with boxes enough for a 4-cell grid axis
// whose cell edges are exact floats, 0 among them: boxes ending at -0.0 touch boxes starting
// at 0.0 on each grid axis, right on a cell edge, and must pair across it.
TEST(SmallFrameGrid, SignedZerosOnACellEdge) {
  const auto count = static_cast<std::size_t>(16 * tuning::kSmallFrameBoxesPerCell + 100);
  BoxColumns boxes = columnsOf(test_support::randomBoxes(count, 120.0, 1.0, 51));
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      boxes.lo[axis][i] -= 60.0;
      boxes.hi[axis][i] -= 60.0;
    }
  }
  addBox(boxes, {-64, -64, -64}, {-63, -63, -63});
  addBox(boxes, {63, 63, 63}, {64, 64, 64});
  for (int axis = 0; axis < 3; ++axis) {
    for (double at : {-20.0, 5.0}) {
      double low[3] = {at, at, at}, high[3] = {at + 1, at + 1, at + 1};
      low[axis] = -1.0;
      high[axis] = -0.0;
      addBox(boxes, low, high);
      low[axis] = 0.0;
      high[axis] = 1.0;
      addBox(boxes, low, high);
      low[axis] = -0.0;
      high[axis] = 0.0;
      addBox(boxes, low, high);
    }
  }
  SmallFrameWorkspace work;
  PairList pairs;
  pairSmallFrame(boxes, work, pairs);
  ASSERT_EQ(work.grid_cells, 16u) << "0 is a cell edge of a 4 x 4 grid only";
  expectGridMatches(boxes, "signed zeros");
}

// Identical boxes (equal keys on every axis) in clumps across the scene: every pair of a
// clump, including clumps that straddle cell edges.
TEST(SmallFrameGrid, IdenticalBoxesInClumps) {
  BoxColumns boxes = columnsOf(test_support::randomBoxes(3000, 100.0, 1.0, 61));
  for (double at : {0.0, 25.0, 33.3, 50.0, 99.0}) {
    for (int copy = 0; copy < 12; ++copy) addBox(boxes, {at, at, at}, {at + 2, at + 2, at + 2});
  }
  expectGridMatches(boxes, "identical clumps");
}

// Group and mask filters decide after the grid's float test, in whichever cell owns the pair.
TEST(SmallFrameGrid, Filters) {
  BoxSet filtered = test_support::randomBoxes(5000, 80.0, 4.0, 71);
  test_support::addRandomFilters(filtered, 72);
  BoxColumns boxes = columnsOf(filtered);
  for (std::size_t i = 0; i < boxes.size(); i += 13) boxes.groups[i] = 0;
  expectGridMatches(boxes, "filters");
}

// Cells of every small count (0 to a few blocks), so that a cell's NaN padding ends each
// block: a clustered scene with empty, nearly empty and full cells.
TEST(SmallFrameGrid, CellsOfEveryOccupancy) {
  BoxColumns boxes = columnsOf(test_support::randomBoxes(3000, 20.0, 0.5, 81));
  const BoxColumns sparse = columnsOf(test_support::randomBoxes(300, 100.0, 0.5, 82));
  for (std::size_t i = 0; i < sparse.size(); ++i) {
    const double low[3] = {sparse.lo[0][i], sparse.lo[1][i], sparse.lo[2][i]};
    const double high[3] = {sparse.hi[0][i], sparse.hi[1][i], sparse.hi[2][i]};
    addBox(boxes, low, high);
  }
  expectGridMatches(boxes, "clustered");
}

}  // namespace
}  // namespace sap_broadphase
