// SkinList on its own against the brute-force oracle: candidates kept from the oracle's pairs
// of the inflated boxes, then frames whose boxes move inside their skins (exact pairs for every
// thread count), and every change that must force a new sweep.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/runner/work_units.h"
#include "core/strategies/skin_list.h"
#include "core/strategies/small_frame.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::TestRandom;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Keeps the candidates of inBoxes grown by inSkin, as a sweep of the inflated boxes would.
void keepCandidates(SkinList& ioList, const BoxColumns& inBoxes, double inSkin) {
  const BoxColumns& inflated = ioList.inflate(inBoxes, inSkin);
  ioList.adopt(inBoxes, bruteForcePairs(inflated));
}

/// Moves and reshapes every box by less than inReach on each side (infinite bounds stay).
BoxColumns movedWithin(const BoxColumns& inBoxes, double inReach, TestRandom& ioRandom) {
  BoxColumns moved = inBoxes;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      double& low = moved.lo[axis][i];
      double& high = moved.hi[axis][i];
      const double shift = ioRandom.between(-0.5, 0.5) * inReach;
      const double grow = ioRandom.between(0.0, 0.5) * inReach;
      low += shift - grow;
      high = std::max(low, high + shift + (ioRandom.unit() < 0.5 ? grow : -grow));
    }
  }
  return moved;
}

/// Expects gather() and collectGathered() to answer inBoxes with the oracle's pairs for 1 to 4
/// threads.
void expectExactForAllThreadCounts(SkinList& ioList, const BoxColumns& inBoxes,
                                   const char* inLabel) {
  const PairList oracle = bruteForcePairs(inBoxes);
  for (int threads = 1; threads <= 4; ++threads) {
    const ThreadsScope scope(threads);
    EXPECT_TRUE(ioList.covers(inBoxes)) << inLabel << ", threads " << threads;
    PairList pairs;
    ASSERT_TRUE(ioList.gather(inBoxes)) << inLabel << ", threads " << threads;
    ioList.collectGathered(pairs);
    EXPECT_TRUE(test_support::samePairs(oracle, pairs)) << inLabel << ", threads " << threads;
  }
}

TEST(SkinList, MovingFramesMatchOracle) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    BoxColumns boxes = columnsOf(test_support::randomBoxes(1500, 40.0, 4.0, seed));
    if (seed % 2 == 0) test_support::addRandomFilters(boxes, seed);
    if (seed % 3 == 0) boxes = test_support::shuffledSubset(boxes, 0.8, true, seed);  // sparse ids
    const double skin = 0.6;
    SkinList list;
    keepCandidates(list, boxes, skin);
    EXPECT_GT(list.candidates(), bruteForcePairs(boxes).size()) << "seed " << seed;
    expectExactForAllThreadCounts(list, boxes, "the swept frame");
    TestRandom random(seed);
    for (int step = 0; step < 4; ++step)
      expectExactForAllThreadCounts(list, movedWithin(boxes, skin / 2, random),
                                    "a frame inside the skins");
  }
}

TEST(SkinList, BoxThatLeavesItsSkinForcesASweep) {
  const BoxColumns boxes = columnsOf(test_support::randomBoxes(800, 20.0, 3.0, 11));
  const double skin = 0.5;
  SkinList list;
  keepCandidates(list, boxes, skin);
  for (const std::size_t leaver : {std::size_t{0}, std::size_t{417}, boxes.size() - 1}) {
    BoxColumns frame = boxes;
    frame.hi[1][leaver] += skin;  // past the margin of skin / 2
    for (int threads = 1; threads <= 4; ++threads) {
      const ThreadsScope scope(threads);
      EXPECT_FALSE(list.covers(frame));
      EXPECT_FALSE(list.gather(frame)) << "box " << leaver;
    }
    SkinList swept;
    keepCandidates(swept, frame, skin);
    expectExactForAllThreadCounts(swept, frame, "after the new sweep");
  }
}

TEST(SkinList, ChangedIdsOrFiltersForceASweep) {
  BoxColumns boxes = columnsOf(test_support::randomBoxes(300, 10.0, 2.0, 5));
  test_support::addRandomFilters(boxes, 5);
  SkinList list;
  keepCandidates(list, boxes, 0.4);
  BoxColumns reordered = boxes;
  std::swap(reordered.ids[3], reordered.ids[4]);
  EXPECT_FALSE(list.gather(reordered));
  BoxColumns regrouped = boxes;
  regrouped.groups[9] ^= 0x4u;
  EXPECT_FALSE(list.gather(regrouped));
  BoxColumns remasked = boxes;
  remasked.masks[0] ^= 0x1u;
  EXPECT_FALSE(list.gather(remasked));
  BoxColumns fewer = boxes;
  for (auto* column : {&fewer.ids, &fewer.groups, &fewer.masks}) column->pop_back();
  for (int axis = 0; axis < 3; ++axis) {
    fewer.lo[axis].pop_back();
    fewer.hi[axis].pop_back();
  }
  EXPECT_FALSE(list.gather(fewer));
  EXPECT_TRUE(list.gather(boxes));
  list.clear();
  EXPECT_FALSE(list.gather(boxes));
  EXPECT_FALSE(list.covers(boxes));
}

// Boxes that touch at zero from both sides, with zeros of either sign swapped between frames:
// -0.0 == 0.0, so touching pairs stay pairs and no box leaves its skin.
TEST(SkinList, SignedZerosTouch) {
  BoxColumns boxes;
  const double left_lo[3] = {-1.0, -1.0, -1.0}, left_hi[3] = {-0.0, 0.0, -0.0};
  const double right_lo[3] = {0.0, -0.0, 0.0}, right_hi[3] = {1.0, 1.0, 1.0};
  const double far_lo[3] = {5.0, 5.0, 5.0}, far_hi[3] = {6.0, 6.0, 6.0};
  boxes.add(10, left_lo, left_hi);
  boxes.add(20, right_lo, right_hi);
  boxes.add(30, far_lo, far_hi);
  SkinList list;
  keepCandidates(list, boxes, 0.0);  // inflated by one step outward only
  expectExactForAllThreadCounts(list, boxes, "touching at signed zeros");
  BoxColumns flipped = boxes;
  for (int axis = 0; axis < 3; ++axis) {
    flipped.hi[axis][0] = -flipped.hi[axis][0];
    flipped.lo[axis][1] = -flipped.lo[axis][1];
  }
  expectExactForAllThreadCounts(list, flipped, "zeros of the other sign");
  PairList pairs;
  ASSERT_TRUE(list.gather(flipped));
  list.collectGathered(pairs);
  EXPECT_EQ(pairs, (PairList{{10, 20}}));
}

// Planes and slabs that reach infinity on some axes among finite boxes.
TEST(SkinList, InfiniteBoundsStayInsideAndPair) {
  BoxColumns boxes = columnsOf(test_support::randomBoxes(400, 20.0, 2.0, 23));
  for (std::size_t i = 0; i < boxes.size(); i += 37) {
    boxes.lo[i % 3][i] = -kInfinity;
    if (i % 2 == 0) boxes.hi[(i + 1) % 3][i] = kInfinity;
  }
  SkinList list;
  keepCandidates(list, boxes, 0.5);
  expectExactForAllThreadCounts(list, boxes, "infinite bounds");
  TestRandom random(23);
  expectExactForAllThreadCounts(list, movedWithin(boxes, 0.25, random), "infinite, moved");
}

TEST(SkinList, FewBoxesAndNoCandidates) {
  for (std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{2}}) {
    const BoxColumns boxes = columnsOf(test_support::randomBoxes(count, 1000.0, 1.0, 3));
    SkinList list;
    keepCandidates(list, boxes, 0.1);
    expectExactForAllThreadCounts(list, boxes, "few boxes");
  }
}

// Many candidates per box (dense, with filters): every thread count gives the same list.
TEST(SkinList, DenseFramesAgreeAcrossThreadCounts) {
  BoxColumns boxes = columnsOf(test_support::latticeBoxes(2000, 12, 3, 41));
  test_support::addRandomFilters(boxes, 41);
  SkinList list;
  keepCandidates(list, boxes, 1.0);
  TestRandom random(41);
  expectExactForAllThreadCounts(list, movedWithin(boxes, 0.5, random), "dense lattice");
}

// Boxes that meet hundreds of others (runs of one first position longer than the insertion
// sort takes), kept by taking the sweep's list: the taken list is left empty, the candidates
// are the oracle's, and every frame inside the skins is answered exactly.
TEST(SkinList, HubBoxesAndTakenListsMatchOracle) {
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    BoxColumns boxes = columnsOf(test_support::randomBoxes(1200, 30.0, 2.0, seed));
    for (std::size_t hub = 0; hub < boxes.size(); hub += 300) {
      for (int axis = 0; axis < 3; ++axis) {
        boxes.lo[axis][hub] -= 8.0 + static_cast<double>(seed);
        boxes.hi[axis][hub] += 8.0;
      }
    }
    if (seed % 2 == 0) boxes = test_support::shuffledSubset(boxes, 0.9, true, seed);
    const double skin = 0.4;
    SkinList list;
    PairList candidates = bruteForcePairs(list.inflate(boxes, skin));
    const std::size_t count = candidates.size();
    list.adopt(boxes, std::move(candidates));
    EXPECT_TRUE(candidates.empty()) << "seed " << seed;
    EXPECT_EQ(list.candidates(), count) << "seed " << seed;
    expectExactForAllThreadCounts(list, boxes, "the swept frame with hub boxes");
    TestRandom random(seed);
    for (int step = 0; step < 3; ++step)
      expectExactForAllThreadCounts(list, movedWithin(boxes, skin / 2, random),
                                    "a frame with hub boxes inside the skins");
  }
}

// The adoption's parts run on the runner's workers: kept at 1, 2 and 4 threads (with more
// candidates and boxes than one unit of work, hub boxes among them, sparse shuffled ids and
// filters), the lists are the same in every array, and exact.
TEST(SkinList, AdoptionIsTheSameForAnyThreadCount) {
  BoxColumns boxes = test_support::shuffledSubset(
      columnsOf(test_support::randomBoxes(24000, 36.0, 2.0, 51)), 0.95, true, 51);
  for (std::size_t hub = 0; hub < boxes.size(); hub += 2000) {
    for (int axis = 0; axis < 3; ++axis) {
      boxes.lo[axis][hub] -= 6.0;
      boxes.hi[axis][hub] += 6.0;
    }
  }
  test_support::addRandomFilters(boxes, 51);
  const double skin = 0.5;
  SkinList one_thread;
  SmallFrameWorkspace kernel;
  PairList candidates;
  pairSmallFrame(one_thread.inflate(boxes, skin), kernel, candidates);
  ASSERT_GT(candidates.size(), 2 * kUnitBoxes);  // several units in every pass over them
  {
    const ThreadsScope scope(1);
    one_thread.adopt(boxes, candidates);
  }
  for (const int threads : {2, 4}) {
    const ThreadsScope scope(threads);
    SkinList list;
    list.inflate(boxes, skin);
    list.adopt(boxes, candidates);
    EXPECT_TRUE(list.sameCandidates(one_thread)) << threads << " threads";
  }
  TestRandom random(51);
  expectExactForAllThreadCounts(one_thread, movedWithin(boxes, skin / 2, random),
                                "a list adopted on one thread");
}

// Kept again and again (as every rebuild does), of other sizes: each list is exact.
TEST(SkinList, KeptAgainAfterEachSweepMatchesOracle) {
  SkinList list;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const std::size_t count = 400 * static_cast<std::size_t>(6 - seed);
    const BoxColumns boxes = columnsOf(test_support::randomBoxes(count, 25.0, 3.0, seed));
    keepCandidates(list, boxes, 0.3 * static_cast<double>(seed));
    expectExactForAllThreadCounts(list, boxes, "a list kept again");
  }
}

// releaseCandidates() gives back the candidates and a pass's buffers but keeps the grown
// boxes' columns, which the next inflate() reuses; the list answers nothing until the next
// adopt(), then exactly.
TEST(SkinList, ReleasedCandidatesKeepTheGrownBoxesForTheNextInflate) {
  const BoxColumns boxes = columnsOf(test_support::randomBoxes(2000, 25.0, 3.0, 7));
  SkinList list;
  keepCandidates(list, boxes, 0.5);
  expectExactForAllThreadCounts(list, boxes, "kept");
  const SkinList::MemoryUse kept = list.memoryUse();
  ASSERT_GT(kept.candidates, 0u);
  ASSERT_GT(kept.pass, 0u);
  list.releaseCandidates();
  EXPECT_FALSE(list.valid());
  EXPECT_EQ(list.candidates(), 0u);
  EXPECT_FALSE(list.covers(boxes));
  const SkinList::MemoryUse released = list.memoryUse();
  EXPECT_EQ(released.candidates, 0u);
  EXPECT_EQ(released.pass, 0u);
  EXPECT_EQ(released.reference, kept.reference);
  const BoxColumns moved = columnsOf(test_support::randomBoxes(2000, 25.0, 3.0, 8));
  keepCandidates(list, moved, 0.5);
  EXPECT_EQ(list.memoryUse().reference, kept.reference) << "the same columns, reused";
  expectExactForAllThreadCounts(list, moved, "kept after a release");
}

}  // namespace
}  // namespace sap_broadphase
