// The plan on its own: which work each combination of configuration, delta, size and costs
// gets, and the automatic skin's cost model.
#include <gtest/gtest.h>

#include <cmath>

#include "core/frame/frame_plan.h"
#include "core/tuning.h"

namespace sap_broadphase {
namespace {

// Costs of a uniform scene as a 2-thread sweep measures them: 300 ns a box to sort, 40 ns a
// box or candidate to pair, 4 candidates a box at skin 0, boxes about one unit wide.
SkinCosts uniformCosts() {
  SkinCosts costs;
  costs.sweep_ns_per_box = 300.0;
  costs.pairing_ns_per_item = 40.0;
  costs.reference_boxes = 100000;
  costs.reference_candidates = 400000.0;
  costs.reference_skin = 0.0;
  costs.pass_ns_per_box = 3.0;
  costs.pass_ns_per_candidate = 4.0;
  for (double& extent : costs.mean_extent) extent = 1.0;
  for (double& span : costs.span) span = 46.4;  // 400000 candidates at skin 0
  return costs;
}

PlanInputs coherentFrame(const BroadphaseConfig& inConfig) {
  PlanInputs inputs;
  inputs.config = &inConfig;
  inputs.delta.relation = FrameRelation::kSameIds;
  inputs.delta.moved_boxes = 100000;
  inputs.delta.max_displacement = 0.01;
  inputs.boxes = 100000;
  inputs.threads = tuning::kKernelMostThreads + 2;  // a machine where the sweep answers
  inputs.last_pairs_valid = true;
  inputs.motion = 0.01;
  inputs.costs = uniformCosts();
  return inputs;
}

TEST(FramePlan, FewerThanTwoBoxesIsEmpty) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  inputs.boxes = 1;
  EXPECT_EQ(planFrame(inputs).path, FramePath::kEmpty);
}

TEST(FramePlan, BruteForceMethodIsHonoured) {
  BroadphaseConfig config;
  config.method = Method::kBruteForce;
  EXPECT_EQ(planFrame(coherentFrame(config)).path, FramePath::kBruteForce);
}

TEST(FramePlan, IdenticalFrameReusesOnlyWhenAllowedAndHeld) {
  BroadphaseConfig config;
  config.reuse_unchanged_frames = true;
  PlanInputs inputs = coherentFrame(config);
  inputs.delta.relation = FrameRelation::kIdentical;
  EXPECT_EQ(planFrame(inputs).path, FramePath::kReused);
  inputs.last_pairs_valid = false;
  EXPECT_NE(planFrame(inputs).path, FramePath::kReused);
  inputs.last_pairs_valid = true;
  config.reuse_unchanged_frames = false;
  EXPECT_NE(planFrame(inputs).path, FramePath::kReused);
}

TEST(FramePlan, FirstFrameIsAPlainSweepEvenWithAutomaticSkin) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  inputs.delta = FrameDelta();
  const FramePlan plan = planFrame(inputs);
  EXPECT_EQ(plan.path, FramePath::kParallel);
  EXPECT_EQ(plan.sweep_skin, 0.0);
  EXPECT_EQ(plan.skin_choice, SkinChoice::kFirstFrame);
}

TEST(FramePlan, OtherIdsGiveAPlainSweep) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  inputs.delta.relation = FrameRelation::kOtherIds;
  const FramePlan plan = planFrame(inputs);
  EXPECT_EQ(plan.sweep_skin, 0.0);
  EXPECT_EQ(plan.skin_choice, SkinChoice::kIdsChanged);
}

TEST(FramePlan, SlowMotionChoosesASkinAndKeptCandidatesAnswerWhileCovered) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  const FramePlan sweep = planFrame(inputs);
  EXPECT_EQ(sweep.path, FramePath::kParallel);
  EXPECT_EQ(sweep.skin_choice, SkinChoice::kChosen);
  EXPECT_GE(sweep.sweep_skin, 2 * inputs.motion);
  EXPECT_EQ(sweep.threads, inputs.threads);
  inputs.kept_candidates = true;
  inputs.kept_covers = true;
  inputs.kept_skin = sweep.sweep_skin;
  const FramePlan pass = planFrame(inputs);
  EXPECT_EQ(pass.path, FramePath::kSkin);
  EXPECT_EQ(pass.skin, sweep.sweep_skin);
  EXPECT_EQ(pass.skin_choice, SkinChoice::kKept);
  inputs.kept_covers = false;
  EXPECT_EQ(planFrame(inputs).path, FramePath::kParallel);
}

TEST(FramePlan, KeptCandidatesAreConsideredOnlyWhereNoEarlierRuleDecides) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  EXPECT_FALSE(planConsidersKeptCandidates(inputs)) << "no kept list";
  inputs.kept_candidates = true;
  EXPECT_TRUE(planConsidersKeptCandidates(inputs));
  PlanInputs changed = inputs;
  changed.delta.relation = FrameRelation::kOtherIds;
  EXPECT_FALSE(planConsidersKeptCandidates(changed)) << "other ids";
  changed = inputs;
  changed.delta.filters_changed = true;
  EXPECT_FALSE(planConsidersKeptCandidates(changed)) << "filters changed";
  changed = inputs;
  changed.delta.relation = FrameRelation::kIdentical;
  EXPECT_FALSE(planConsidersKeptCandidates(changed)) << "the last pairs are reused";
  changed.last_pairs_valid = false;
  EXPECT_TRUE(planConsidersKeptCandidates(changed)) << "identical, but no last pairs to reuse";
  changed = inputs;
  changed.boxes = 1;
  EXPECT_FALSE(planConsidersKeptCandidates(changed)) << "one box";
  BroadphaseConfig skin_off;
  skin_off.skin = 0.0;
  changed = inputs;
  changed.config = &skin_off;
  EXPECT_FALSE(planConsidersKeptCandidates(changed)) << "skin off";
  BroadphaseConfig brute;
  brute.method = Method::kBruteForce;
  changed.config = &brute;
  EXPECT_FALSE(planConsidersKeptCandidates(changed)) << "brute force";
}

TEST(FramePlan, FastMotionTurnsTheSkinOff) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  inputs.motion = 0.5;  // half a box edge a frame
  const FramePlan plan = planFrame(inputs);
  EXPECT_EQ(plan.sweep_skin, 0.0);
  EXPECT_EQ(plan.skin_choice, SkinChoice::kTooFast);
  inputs.motion = HUGE_VAL;  // a box jumped to infinity
  EXPECT_EQ(planFrame(inputs).skin_choice, SkinChoice::kTooFast);
}

TEST(FramePlan, SmallFramesAndUnmeasuredCostsTakeNoSkin) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  inputs.boxes = tuning::kMinSkinBoxes - 1;
  EXPECT_EQ(planFrame(inputs).skin_choice, SkinChoice::kNotWorthIt);
  inputs = coherentFrame(config);
  inputs.costs.reference_boxes = 0;
  EXPECT_EQ(planFrame(inputs).skin_choice, SkinChoice::kNotWorthIt);
  inputs = coherentFrame(config);
  inputs.motion = 0.0;
  EXPECT_EQ(planFrame(inputs).skin_choice, SkinChoice::kNotWorthIt);
}

// A probation of the skin audit (skin_audit.h): the automatic skin is neither chosen nor
// answered from kept candidates; a fixed skin is the user's and stays.
TEST(FramePlan, AuditProbationTurnsTheAutomaticSkinOffOnly) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);
  ASSERT_GT(planFrame(inputs).sweep_skin, 0.0);
  inputs.skin_audit_allows = false;
  FramePlan plan = planFrame(inputs);
  EXPECT_EQ(plan.sweep_skin, 0.0);
  EXPECT_EQ(plan.skin_choice, SkinChoice::kNotWorthIt);
  inputs.kept_candidates = inputs.kept_covers = true;
  EXPECT_FALSE(planConsidersKeptCandidates(inputs));
  EXPECT_NE(planFrame(inputs).path, FramePath::kSkin);
  config.skin = 0.3;
  EXPECT_TRUE(planConsidersKeptCandidates(inputs));
  plan = planFrame(inputs);
  EXPECT_EQ(plan.path, FramePath::kSkin);
  EXPECT_EQ(plan.skin_choice, SkinChoice::kFixed);
}

TEST(FramePlan, FixedSkinAndSkinOffAreObeyed) {
  BroadphaseConfig config;
  config.skin = 0.3;
  PlanInputs inputs = coherentFrame(config);
  inputs.motion = 5.0;
  FramePlan plan = planFrame(inputs);
  EXPECT_EQ(plan.sweep_skin, 0.3);
  EXPECT_EQ(plan.skin_choice, SkinChoice::kFixed);
  config.skin = 0.0;
  inputs.kept_candidates = inputs.kept_covers = true;
  plan = planFrame(inputs);
  EXPECT_EQ(plan.path, FramePath::kParallel);
  EXPECT_EQ(plan.sweep_skin, 0.0);
  EXPECT_EQ(plan.skin_choice, SkinChoice::kOff);
}

TEST(FramePlan, SweepPathFollowsMethodSizeAndThreads) {
  BroadphaseConfig config;
  config.parallel_min_boxes = 1000;
  EXPECT_EQ(sweepPath(config, 999, 2), FramePath::kSequential);
  EXPECT_EQ(sweepPath(config, 1000, 2), FramePath::kParallel);
  EXPECT_EQ(sweepPath(config, 1000000, 1), FramePath::kSequential);
  config.method = Method::kParallel;
  EXPECT_EQ(sweepPath(config, 10, 2), FramePath::kParallel);
  config.method = Method::kSequential;
  EXPECT_EQ(sweepPath(config, 1000000, 8), FramePath::kSequential);
  PlanInputs inputs = coherentFrame(config);
  inputs.motion = 1.0;  // no skin: a plain sequential sweep on one thread
  EXPECT_EQ(planFrame(inputs).threads, 1);
}

// The small-frame kernel answers frames below the cut-off on any thread count (on one thread),
// and every frame of Method::kAuto on up to tuning::kKernelMostThreads threads (on all of
// them); with more threads a large frame is swept in parallel, and a fixed skin or another
// method keeps the sweep. The frame's threads are decided once, by frameThreads.
TEST(FramePlan, TheKernelAnswersSmallFramesAndEveryFrameOnFewThreads) {
  BroadphaseConfig config;
  PlanInputs inputs = coherentFrame(config);  // 100000 boxes
  inputs.delta.relation = FrameRelation::kFirst;
  for (int threads = 1; threads <= tuning::kKernelMostThreads; ++threads) {
    inputs.threads = frameThreads(config, inputs.boxes, threads);
    EXPECT_EQ(inputs.threads, threads);
    const FramePlan plan = planFrame(inputs);
    EXPECT_EQ(plan.path, FramePath::kSmallFrame) << threads;
    EXPECT_EQ(plan.threads, threads);
  }
  const int many = tuning::kKernelMostThreads + 1;
  inputs.threads = frameThreads(config, inputs.boxes, many);
  EXPECT_EQ(inputs.threads, many);
  EXPECT_EQ(planFrame(inputs).path, FramePath::kParallel);
  EXPECT_EQ(planFrame(inputs).threads, many);
  inputs.boxes = config.parallel_min_boxes - 1;
  for (int threads : {2, many}) {
    inputs.threads = frameThreads(config, inputs.boxes, threads);
    EXPECT_EQ(inputs.threads, 1) << threads;
    EXPECT_EQ(planFrame(inputs).path, FramePath::kSmallFrame);
  }
  inputs.boxes = 100000;
  inputs.threads = 1;
  config.method = Method::kSequential;
  EXPECT_EQ(frameThreads(config, inputs.boxes - 90000, 2), 2) << "only kAuto's small frames";
  EXPECT_EQ(planFrame(inputs).path, FramePath::kSequential);
  config.method = Method::kAuto;
  config.skin = 0.5;
  EXPECT_EQ(planFrame(inputs).path, FramePath::kSequential);
  EXPECT_EQ(planFrame(inputs).sweep_skin, 0.5);
}

TEST(FramePlan, SkinGrowsWithMotionWhileItPays) {
  const SkinCosts costs = uniformCosts();
  SkinChoice choice;
  const double slow = chooseSkin(0.001, 100000, costs, choice);
  EXPECT_EQ(choice, SkinChoice::kChosen);
  const double faster = chooseSkin(0.01, 100000, costs, choice);
  EXPECT_EQ(choice, SkinChoice::kChosen);
  EXPECT_LT(slow, faster);
}

// The grown sweep's own work (growing the boxes, keeping the candidates) is charged to the
// skin: when it costs more than the passes save, no skin is chosen.
TEST(FramePlan, DearKeepingTurnsTheSkinOff) {
  SkinCosts costs = uniformCosts();
  SkinChoice choice;
  costs.grow_ns_per_box = 1.0;
  costs.keep_ns_per_candidate = 1.0;
  EXPECT_GT(chooseSkin(0.01, 100000, costs, choice), 0.0);
  EXPECT_EQ(choice, SkinChoice::kChosen);
  costs.grow_ns_per_box = 1e6;  // one grown sweep dearer than thousands of plain ones
  EXPECT_EQ(chooseSkin(0.01, 100000, costs, choice), 0.0);
  EXPECT_EQ(choice, SkinChoice::kTooFast);
}

}  // namespace
}  // namespace sap_broadphase
