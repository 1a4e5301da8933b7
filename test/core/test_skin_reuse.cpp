// SkinReuse on its own against the oracle: a grown sweep's candidates answer the frame, the
// coverage known before planning says yes while every box stays inside its skin and no once
// one box left it, and the sweep's costs are learnt from the sweep's own phases.
#include <gtest/gtest.h>

#include "core/frame/frame_history.h"
#include "core/frame/frame_plan.h"
#include "core/runner/work_units.h"
#include "core/strategies/skin_reuse.h"
#include "core/strategies/small_frame.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

constexpr double kSkin = 0.5;

/// A grown sweep of inBoxes as the engine runs it, with the oracle in the sweep's place.
PairList growSweepAndKeep(SkinReuse& ioSkin, const BoxColumns& inBoxes, FrameReport& ioReport) {
  const ThreadsScope two(2);
  PairList pairs = bruteForcePairs(ioSkin.grow(inBoxes, kSkin, ioReport));
  ioSkin.keepAndAnswer(inBoxes, ioReport, pairs);
  return pairs;
}

/// inBoxes with every bound moved by inShift on the x axis.
BoxColumns shiftedX(const BoxColumns& inBoxes, double inShift) {
  BoxColumns moved = inBoxes;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    moved.lo[0][i] += inShift;
    moved.hi[0][i] += inShift;
  }
  return moved;
}

TEST(SkinReuse, KeptCandidatesAnswerExactlyWhileEveryBoxStaysInsideItsSkin) {
  const BoxColumns first = columnsOf(test_support::randomBoxes(3000, 40.0, 1.5, 11));
  const ThreadsScope two(2);
  SkinReuse skin;
  FrameReport report;
  EXPECT_FALSE(skin.hasCandidates());
  EXPECT_EQ(growSweepAndKeep(skin, first, report), bruteForcePairs(first));
  EXPECT_TRUE(skin.hasCandidates());
  EXPECT_EQ(skin.skin(), kSkin);
  EXPECT_GE(skin.candidates(), bruteForcePairs(first).size());
  // Every box moved by less than skin / 2: covered, and the candidates give the exact pairs.
  const BoxColumns inside = shiftedX(first, 0.2);
  ASSERT_TRUE(skin.coversFrame(inside, report));
  PairList pairs;
  skin.answerFromCandidates(report, pairs);
  EXPECT_EQ(pairs, bruteForcePairs(inside));
  EXPECT_EQ(report.skin_candidates, skin.candidates());
  // One box beyond its skin: not covered, known before any plan is made.
  BoxColumns outside = inside;
  outside.hi[1][7] += 0.3;
  EXPECT_FALSE(skin.coversFrame(outside, report));
  // Other ids are never covered.
  BoxColumns renamed = inside;
  renamed.ids[0] += 100000;
  EXPECT_FALSE(skin.coversFrame(renamed, report));
  skin.forget();
  EXPECT_FALSE(skin.hasCandidates());
  EXPECT_FALSE(skin.coversFrame(inside, report));
}

// The candidate budget: a grown sweep over it keeps nothing, answers the frame exactly, and
// the next grow() at that skin and size grows nothing.
TEST(SkinReuse, OverBudgetKeepsNoCandidatesAndAnswersExactly) {
  const BoxColumns boxes = columnsOf(test_support::randomBoxes(4000, 40.0, 1.5, 5));
  SkinReuse skin;
  FrameReport report;
  PairList pairs = bruteForcePairs(skin.grow(boxes, 1e30, report));
  ASSERT_GT(pairs.size(), keptCandidateBudget(boxes.size()));  // every pair: 7 998 000
  skin.keepAndAnswer(boxes, report, pairs);
  EXPECT_EQ(pairs, bruteForcePairs(boxes));
  EXPECT_EQ(report.skin_choice, SkinChoice::kOverBudget);
  EXPECT_EQ(report.skin_candidates, 0u);
  EXPECT_FALSE(skin.hasCandidates());
  EXPECT_EQ(skin.candidates(), 0u);
  // The next frame at that skin sweeps the boxes as they are.
  FrameReport next;
  const BoxColumns& swept = skin.grow(boxes, 1e30, next);
  EXPECT_EQ(next.skin_choice, SkinChoice::kOverBudget);
  EXPECT_TRUE(skin.overBudget());
  for (std::size_t i = 0; i < boxes.size(); ++i) {  // grown by nothing (rounded outward)
    ASSERT_LE(swept.hi[2][i] - boxes.hi[2][i], 1e-9) << i;
    ASSERT_LE(boxes.lo[0][i] - swept.lo[0][i], 1e-9) << i;
  }
}

// Issue 29, `skin 1e300` at 4000 boxes kept every pair (+515 MB a frame): 1e300 is now refused
// by the table, and the largest skin it accepts stays within the budget through the engine,
// frame after frame, with exact pairs.
TEST(SkinReuse, TheLargestSkinAt4000BoxesStaysWithinTheBudget) {
  BroadphaseConfig config;
  config.skin = 1e300;
  EXPECT_THROW(Broadphase{config}, std::invalid_argument);
  config.skin = kMaxSkin;
  config.threads = 1;
  for (const Method method : {Method::kAuto, Method::kSequential, Method::kParallel}) {
    SCOPED_TRACE(methodName(method));
    config.method = method;
    Broadphase engine(config);
    for (int frame = 0; frame < 3; ++frame) {
      const BoxSet boxes = test_support::randomBoxes(4000, 40.0, 1.5, 21 + frame % 2);
      EXPECT_EQ(engine.update(boxes), bruteForcePairs(boxes)) << "frame " << frame;
      EXPECT_EQ(engine.stats().skin_choice, SkinChoice::kOverBudget) << "frame " << frame;
      EXPECT_LE(engine.stats().skin_candidates, keptCandidateBudget(4000));
    }
  }
}

// The next kept candidates are built a step a frame (snapshot, slabs, adoption) and take over
// when the kept ones stop covering: boxes drifting at their own steady velocities never need a
// grown sweep after the first, and every frame's pairs are the oracle's, on any thread count,
// with sparse shuffled ids and filters.
TEST(SkinReuse, SuccessorsBuiltAStepAFrameTakeOverAndAnswerExactly) {
  constexpr double kMotion = 0.01;  // largest move of a bound a frame: a list lives 25 frames
  for (const int threads : {1, 2}) {
    const ThreadsScope scope(threads);
    for (const bool filtered : {false, true}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, filtered " << filtered);
      BoxColumns boxes = test_support::shuffledSubset(
          columnsOf(test_support::randomBoxes(3000, 40.0, 1.5, 31)), 1.0, true, 7);
      if (filtered) test_support::addRandomFilters(boxes, 9);
      test_support::TestRandom random(13);
      std::vector<double> velocity(3 * boxes.size());
      for (double& v : velocity) v = random.between(-kMotion, kMotion);
      SkinReuse skin;
      FrameReport report;
      PairList pairs = bruteForcePairs(skin.grow(boxes, kSkin, report));
      skin.keepAndAnswer(boxes, report, pairs);
      ASSERT_EQ(pairs, bruteForcePairs(boxes));
      FrameDelta delta;
      delta.relation = FrameRelation::kSameIds;
      delta.max_displacement = kMotion;
      for (int frame = 1; frame <= 120; ++frame) {
        for (std::size_t i = 0; i < boxes.size(); ++i) {
          for (int axis = 0; axis < 3; ++axis) {
            boxes.lo[axis][i] += velocity[3 * i + axis];
            boxes.hi[axis][i] += velocity[3 * i + axis];
          }
        }
        skin.startFrame(delta);
        ASSERT_TRUE(skin.coversFrame(boxes, report)) << "frame " << frame;
        skin.answerFromCandidates(report, pairs);
        ASSERT_EQ(pairs, bruteForcePairs(boxes)) << "frame " << frame;
        skin.advanceSuccessor(boxes, report);
      }
      EXPECT_GE(skin.successorsTaken(), 4u);
      EXPECT_GT(skin.skin(), kSkin);  // grown by the motion of the frames it took to build
      skin.forget();
      EXPECT_FALSE(skin.buildingSuccessor());
    }
  }
}

// The successor's snapshot, slabs and adoption run on the runner's workers: three skins, at
// 1, 2 and 4 threads, fed the same drifting frames (more boxes than one unit of work in each
// slab, sparse shuffled ids and filters), keep the same candidates, laid out the same, at
// every frame, and answer the same pairs (a frame they do not cover is swept grown, by the
// small-frame kernel, as the engine would).
TEST(SkinReuse, SuccessorsAreTheSameForAnyThreadCount) {
  // A list lives 8 frames: a successor of 4 slabs, each of more boxes than a unit of work.
  constexpr double kMotion = 0.03;
  BoxColumns boxes = test_support::shuffledSubset(
      columnsOf(test_support::randomBoxes(80000, 54.0, 1.5, 61)), 0.9, true, 61);
  test_support::addRandomFilters(boxes, 61);
  test_support::TestRandom random(61);
  std::vector<double> velocity(3 * boxes.size());
  for (double& v : velocity) v = random.between(-kMotion, kMotion);
  const int thread_counts[] = {1, 2, 4};
  SkinReuse skins[3];
  FrameDelta delta;
  delta.relation = FrameRelation::kSameIds;
  delta.max_displacement = kMotion;
  int swept_frames = 0;
  for (int frame = 0; frame <= 30; ++frame) {
    for (std::size_t i = 0; frame > 0 && i < boxes.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        boxes.lo[axis][i] += velocity[3 * i + axis];
        boxes.hi[axis][i] += velocity[3 * i + axis];
      }
    }
    PairList one_thread_pairs;
    for (int run = 0; run < 3; ++run) {
      SCOPED_TRACE(testing::Message() << thread_counts[run] << " threads, frame " << frame);
      const ThreadsScope scope(thread_counts[run]);
      FrameReport report;
      PairList pairs;
      if (frame > 0) skins[run].startFrame(delta);
      if (frame > 0 && skins[run].coversFrame(boxes, report)) {
        skins[run].answerFromCandidates(report, pairs);
        skins[run].advanceSuccessor(boxes, report);
      } else {
        SmallFrameWorkspace kernel;
        pairSmallFrame(skins[run].grow(boxes, kSkin, report), kernel, pairs);
        skins[run].keepAndAnswer(boxes, report, pairs);
        swept_frames += run == 0 ? 1 : 0;
      }
      if (run == 0) one_thread_pairs = pairs;
      EXPECT_EQ(pairs, one_thread_pairs);
      EXPECT_EQ(skins[run].successorsTaken(), skins[0].successorsTaken());
      EXPECT_TRUE(skins[run].keptCandidates().sameCandidates(skins[0].keptCandidates()));
    }
  }
  EXPECT_GE(skins[0].successorsTaken(), 2u);
  EXPECT_LT(swept_frames, 8);
}

// The successor's memory through its build: its slab sweep's buffers are held from its snapshot
// to its last slab only (none during the adoption, whose candidate arrays are the build's
// peak), and once it has taken over only the grown boxes' columns of the candidates it replaced
// (the next snapshot's), until the next snapshot; nothing once it is given up.
TEST(SkinReuse, SuccessorGivesBackItsSlabWorkBeforeAdoptingAndAllOfItWhenItTakesOver) {
  constexpr double kMotion = 0.01;
  const ThreadsScope two(2);
  BoxColumns boxes = columnsOf(test_support::randomBoxes(3000, 40.0, 1.5, 41));
  test_support::TestRandom random(17);
  std::vector<double> velocity(3 * boxes.size());
  for (double& v : velocity) v = random.between(-kMotion, kMotion);
  SkinReuse skin;
  FrameReport report;
  PairList pairs = bruteForcePairs(skin.grow(boxes, kSkin, report));
  skin.keepAndAnswer(boxes, report, pairs);
  EXPECT_EQ(skin.successorMemoryUse().total(), 0u) << "no successor yet";
  FrameDelta delta;
  delta.relation = FrameRelation::kSameIds;
  delta.max_displacement = kMotion;
  int slab_frames = 0, adopting_frames = 0, frames_after_takeover = 0;
  for (int frame = 1; frame <= 80; ++frame) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        boxes.lo[axis][i] += velocity[3 * i + axis];
        boxes.hi[axis][i] += velocity[3 * i + axis];
      }
    }
    const std::size_t taken = skin.successorsTaken();
    skin.startFrame(delta);
    ASSERT_TRUE(skin.coversFrame(boxes, report)) << "frame " << frame;
    if (skin.successorsTaken() > taken) {
      ++frames_after_takeover;
      // Only the replaced candidates' grown boxes, for the next snapshot.
      const SkinReuse::SuccessorMemoryUse left = skin.successorMemoryUse();
      EXPECT_EQ(left.list.candidates + left.list.pass, 0u) << "frame " << frame;
      EXPECT_EQ(left.found + left.order + left.slab + left.kernel + left.slab_ids, 0u)
          << "frame " << frame;
      EXPECT_GT(skin.keptMemoryUse().candidates, 0u) << "frame " << frame;
    }
    skin.answerFromCandidates(report, pairs);
    ASSERT_EQ(pairs, bruteForcePairs(boxes)) << "frame " << frame;
    skin.advanceSuccessor(boxes, report);
    const SkinReuse::SuccessorMemoryUse use = skin.successorMemoryUse();
    if (use.found > 0 && use.list.candidates == 0) {
      ++slab_frames;  // slabs swept: the order is held for the next
      EXPECT_GT(use.order, 0u) << "frame " << frame;
    }
    if (use.list.candidates > 0) {
      ++adopting_frames;
      EXPECT_EQ(use.found, 0u) << "frame " << frame << ": taken by the list, not copied";
      EXPECT_EQ(use.order + use.slab + use.kernel + use.slab_ids, 0u) << "frame " << frame;
    }
  }
  EXPECT_GT(slab_frames, 0);
  EXPECT_GT(adopting_frames, 0);
  EXPECT_GT(frames_after_takeover, 0);
  skin.forget();
  EXPECT_EQ(skin.successorMemoryUse().total(), 0u);
}

TEST(SkinReuse, MotionIsTheLargestDisplacementOfTheRecentWindow) {
  SkinReuse skin;
  FrameDelta delta;
  delta.relation = FrameRelation::kSameIds;
  for (double displacement : {0.1, 0.4, 0.2}) {
    delta.max_displacement = displacement;
    skin.startFrame(delta);
  }
  EXPECT_EQ(skin.recentMotion(), 0.4);
  delta.relation = FrameRelation::kOtherIds;  // other ids: the motion is unknown again
  skin.startFrame(delta);
  EXPECT_EQ(skin.recentMotion(), 0.0);
}

TEST(SkinReuse, LearnsTheSweepFromItsOwnPhasesAndThePassFromThePass) {
  const BoxColumns boxes = columnsOf(test_support::randomBoxes(4000, 40.0, 1.5, 12));
  SkinReuse skin;
  FrameReport report;
  report.ms_keys = 1.0;
  report.ms_sort = 2.0;
  report.ms_candidates = 1.0;
  report.ms_pairing = 3.0;
  report.ms_output = 1.0;
  FramePlan plain;
  plain.path = FramePath::kSequential;
  const std::size_t pairs = bruteForcePairs(boxes).size();
  FrameSpread spread(boxes);
  skin.learn(plain, spread, pairs, report);
  EXPECT_DOUBLE_EQ(skin.costs().sweep_ns_per_box, 4.0e6 / 4000.0);
  EXPECT_DOUBLE_EQ(skin.costs().pairing_ns_per_item, 4.0e6 / (4000.0 + pairs));
  EXPECT_EQ(skin.costs().reference_boxes, 4000u);
  EXPECT_EQ(skin.costs().pass_ns_per_box, 0.0) << "no pass ran";
  EXPECT_GT(skin.costs().span[0], 0.0);
  // A grown sweep: its reference is the grown boxes' candidates at its skin.
  FramePlan grown = plain;
  grown.sweep_skin = kSkin;
  growSweepAndKeep(skin, boxes, report);
  skin.learn(grown, spread, 0, report);
  EXPECT_EQ(skin.costs().reference_skin, kSkin);
  EXPECT_EQ(skin.costs().reference_candidates, static_cast<double>(skin.candidates()));
}

}  // namespace
}  // namespace sap_broadphase
