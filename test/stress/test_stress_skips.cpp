// The paths where the engine skips work, each switched on alone and then all together, over
// multi-frame sequences (rest, drift, jumps, boxes appearing, vanishing and reordered,
// identical frames, one-ulp changes, -0.0 after 0.0, filter changes): every frame equals the
// oracle for every stress configuration (methods, threads 1-3, slabs, axis pairs), and each
// test asserts that the path it exercises really ran, so that none passes by never taking it.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "stress_sequences.h"
#include "stress_support.h"
#include "test_support.h"

namespace sap_broadphase::stress {
namespace {

using test_support::PathCounts;

constexpr std::size_t kSceneryBoxes = 400;

// The boxes a sequence starts from.
struct WorldShape {
  std::size_t boxes;
  double resting_share;
  bool filters;
};
// Small: every path.
WorldShape smallWorld(bool inFilters) {
  return {600, 0.5, inFilters};
}
// Above tuning::kMinSkinBoxes, so that the automatic skin weighs the measured motion.
WorldShape skinWorld(bool inFilters) {
  return {1500, 0.5, inFilters};
}
// Mostly resting boxes that, with filters, pair with movers only.
WorldShape restingWorld() {
  return {4800, 0.9, true};
}

// A skip switch: what it changes in a configuration.
using Switch = void (*)(BroadphaseConfig&);

void noSkips(BroadphaseConfig& ioConfig) {
  ioConfig.skin = 0.0;
  ioConfig.reuse_unchanged_frames = false;
}
void fixedSkin(BroadphaseConfig& ioConfig) {
  ioConfig.skin = 1.0;  // 16 drift steps: kept over several frames, left by jumps
}
void automaticSkin(BroadphaseConfig& ioConfig) {
  ioConfig.skin.reset();
}
void reuseUnchangedFrames(BroadphaseConfig& ioConfig) {
  noSkips(ioConfig);
  ioConfig.reuse_unchanged_frames = true;
}
void everySkip(BroadphaseConfig& ioConfig) {
  automaticSkin(ioConfig);
  ioConfig.reuse_unchanged_frames = true;
}
void everySkipWithFixedSkin(BroadphaseConfig& ioConfig) {
  everySkip(ioConfig);
  fixedSkin(ioConfig);
}

// What one configuration did over a sequence.
struct SequenceOutcome {
  BroadphaseConfig config;
  PathCounts paths;
  int frames = 0;
  int scenery_frames = 0;    // frames whose report counts every declared static box
  int filtered_frames = 0;   // frames with boxes left out for group 0 or mask 0
  int identical_frames = 0;  // frames bit for bit equal to the one before
  SkinChoice first_choice = SkinChoice::kOff;
  int measured_choices = 0;  // frames whose skin was decided from measured motion
};

// The automatic skin weighed this frame's measured motion (which way it went depends on
// measured costs, so it is not asserted), or kept the candidates of such a decision.
bool decidedFromMotion(SkinChoice inChoice) {
  return inChoice == SkinChoice::kChosen || inChoice == SkinChoice::kTooFast ||
         inChoice == SkinChoice::kKept;
}

// Bit for bit equal (so -0.0 differs from 0.0): what unchanged-frame reuse may skip.
bool sameBits(const BoxSet& inA, const BoxSet& inB) {
  const auto same = [](const auto& inX, const auto& inY) {
    return inX.size() == inY.size() &&
           (inX.empty() || std::memcmp(inX.data(), inY.data(), inX.size() * sizeof inX[0]) == 0);
  };
  return same(inA.bounds, inB.bounds) && same(inA.ids, inB.ids) && same(inA.groups, inB.groups) &&
         same(inA.masks, inB.masks);
}

// The scenery is replaced before this frame, which repeats the one before it (the script's
// kNone at 19): unchanged-frame reuse must not return pairs computed against the old scenery.
constexpr std::size_t kSceneryChangeFrame = 20;

// The scenery of the first frames, then of the others.
struct Scenery {
  BoxSet first = sceneryBoxes(kSceneryBoxes, 31);
  BoxSet second = sceneryBoxes(kSceneryBoxes, 32);
};

// Every pairwise stress configuration, switched by inSwitch, goes through skipScript() on a
// SkipWorld (with or without filters, with or without declared scenery); every frame is
// checked against the oracle. Returns what each configuration did (nothing after a failure).
std::vector<SequenceOutcome> runSequence(const std::string& inLabel, Switch inSwitch,
                                         const WorldShape& inWorld, bool inDeclaredScenery) {
  std::vector<SequenceOutcome> outcomes;
  std::vector<Broadphase> engines;
  const Scenery scenery;
  for (BroadphaseConfig config : stressConfigs(Coverage::kPairwise)) {
    config.parallel_min_boxes = 256;  // kAuto with 2 or 3 threads takes the parallel path
    inSwitch(config);
    engines.emplace_back(config);
    if (inDeclaredScenery) engines.back().setStaticBoxes(scenery.first);
    outcomes.push_back({config, {}, 0, 0, 0, 0, SkinChoice::kOff, 0});
  }
  SkipWorld world(inWorld.boxes, inWorld.resting_share, inWorld.filters, 17);
  const std::vector<FrameChange>& script = skipScript();
  EXPECT_EQ(script[kSceneryChangeFrame - 1], FrameChange::kNone);
  BoxSet previous;
  PairList oracle;
  for (std::size_t frame = 0; frame <= script.size(); ++frame) {
    const bool second_scenery = inDeclaredScenery && frame == kSceneryChangeFrame;
    if (frame > 0) world.apply(script[frame - 1]);
    const BoxSet boxes = world.boxes();
    const bool identical = frame > 0 && sameBits(previous, boxes);
    previous = boxes;
    const BoxSet& current_scenery = frame >= kSceneryChangeFrame ? scenery.second : scenery.first;
    // The O(n^2) oracle dominates the run time; an identical frame (same scenery) has the
    // same pairs.
    if (!identical || second_scenery)
      oracle = inDeclaredScenery ? declaredSceneryOracle(current_scenery, boxes)
                                 : bruteForcePairs(boxes);
    for (std::size_t e = 0; e < engines.size(); ++e) {
      if (second_scenery) engines[e].setStaticBoxes(scenery.second);
      const PairList& pairs = engines[e].update(boxes);
      const FrameReport& report = engines[e].stats();
      const ::testing::AssertionResult same = samePairList(oracle, pairs);
      // Later frames would only repeat the failure, and counts of a cut-short run would add
      // misleading failures: nothing is returned.
      if (!same) {
        ADD_FAILURE() << inLabel << ", frame " << frame << " after "
                      << (frame > 0 ? frameChangeName(script[frame - 1]) : "nothing") << ", path "
                      << framePathName(report.path) << ", " << describeConfig(outcomes[e].config)
                      << ": " << same.message();
        return {};
      }
      SequenceOutcome& outcome = outcomes[e];
      outcome.paths.add(report);
      ++outcome.frames;
      outcome.scenery_frames += inDeclaredScenery && report.static_boxes >= kSceneryBoxes;
      outcome.filtered_frames += report.boxes_filtered_out > 0;
      outcome.identical_frames += identical;
      if (frame == 0) outcome.first_choice = report.skin_choice;
      outcome.measured_choices += decidedFromMotion(report.skin_choice);
      if (report.path == FramePath::kSkin) {
        EXPECT_GT(report.skin, 0.0) << inLabel << ", frame " << frame;
      }
    }
  }
  return outcomes;
}

// inPath ran in at least inMinimum frames of every configuration.
void expectPathTaken(const std::vector<SequenceOutcome>& inOutcomes, FramePath inPath,
                     int inMinimum, const std::string& inLabel) {
  for (const SequenceOutcome& outcome : inOutcomes)
    EXPECT_GE(outcome.paths[inPath], inMinimum)
        << inLabel << ": " << framePathName(inPath) << " path expected, "
        << describeConfig(outcome.config) << " took " << outcome.paths.summary();
}

TEST(StressSkips, NoSkipSweepsEveryFrame) {
  for (bool filters : {false, true}) {
    for (const SequenceOutcome& outcome :
         runSequence("no skips", noSkips, smallWorld(filters), false)) {
      const PathCounts& paths = outcome.paths;
      EXPECT_EQ(paths[FramePath::kSequential] + paths[FramePath::kParallel] +
                    paths[FramePath::kSmallFrame],
                outcome.frames)
          << describeConfig(outcome.config) << " took " << paths.summary();
    }
  }
}

TEST(StressSkips, FixedSkinKeepsCandidatesWhileBoxesStayInside) {
  for (bool filters : {false, true})
    expectPathTaken(runSequence("fixed skin", fixedSkin, smallWorld(filters), false),
                    FramePath::kSkin, 10, filters ? "fixed skin, filters" : "fixed skin");
}

// Whether the automatic skin pays depends on measured costs, so the test asserts that the
// decision ran (the first frame is a plain sweep, later ones weigh the motion), not its outcome.
TEST(StressSkips, AutomaticSkinIsExactEveryFrame) {
  for (bool filters : {false, true}) {
    for (const SequenceOutcome& outcome :
         runSequence("automatic skin", automaticSkin, skinWorld(filters), false)) {
      if (outcome.paths[FramePath::kSmallFrame] > 0) continue;  // one-axis path: no skin
      EXPECT_EQ(outcome.first_choice, SkinChoice::kFirstFrame) << describeConfig(outcome.config);
      EXPECT_GT(outcome.measured_choices, 0)
          << describeConfig(outcome.config) << " took " << outcome.paths.summary();
    }
  }
}

TEST(StressSkips, UnchangedFramesAreReused) {
  for (bool filters : {false, true}) {
    const auto outcomes = runSequence("reuse", reuseUnchangedFrames, smallWorld(filters), false);
    // Exactly the frames equal bit for bit to the one before are reused: every kNone of the
    // script at least, never a frame after a -0.0 for a 0.0 or a one-ulp change.
    int repeats = 0;
    for (FrameChange change : skipScript()) repeats += change == FrameChange::kNone;
    for (const SequenceOutcome& outcome : outcomes) {
      EXPECT_GE(outcome.identical_frames, repeats);
      EXPECT_EQ(outcome.paths[FramePath::kReused], outcome.identical_frames)
          << describeConfig(outcome.config) << " took " << outcome.paths.summary();
    }
  }
}

TEST(StressSkips, DeclaredSceneryIsQueriedEveryFrame) {
  for (bool filters : {false, true}) {
    for (const SequenceOutcome& outcome :
         runSequence("declared scenery", noSkips, smallWorld(filters), true))
      EXPECT_EQ(outcome.scenery_frames, outcome.frames) << describeConfig(outcome.config);
  }
}

TEST(StressSkips, BoxesThatCollideWithNothingAreLeftOut) {
  for (const SequenceOutcome& outcome : runSequence("filters", noSkips, smallWorld(true), false))
    EXPECT_GT(outcome.filtered_frames, 0) << describeConfig(outcome.config);
}

TEST(StressSkips, EverySkipTogether) {
  for (bool filters : {false, true}) {
    const auto outcomes =
        runSequence("every skip", everySkip, filters ? restingWorld() : smallWorld(false), true);
    expectPathTaken(outcomes, FramePath::kReused, 1, "every skip");
    for (const SequenceOutcome& outcome : outcomes)
      EXPECT_GE(outcome.scenery_frames, outcome.frames - outcome.paths[FramePath::kReused])
          << describeConfig(outcome.config);
  }
}

TEST(StressSkips, EverySkipWithFixedSkin) {
  const auto outcomes =
      runSequence("every skip, fixed skin", everySkipWithFixedSkin, smallWorld(true), true);
  expectPathTaken(outcomes, FramePath::kReused, 1, "every skip, fixed skin");
  expectPathTaken(outcomes, FramePath::kSkin, 10, "every skip, fixed skin");
}

}  // namespace
}  // namespace sap_broadphase::stress
