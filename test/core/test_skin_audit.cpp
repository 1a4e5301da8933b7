// The measured check of the automatic skin (SkinAudit), fed frames of made-up costs: when it
// lets the skin be chosen, when it starts a probation, and how the probations grow.
#include <gtest/gtest.h>

#include "core/strategies/skin_audit.h"
#include "core/tuning.h"

namespace sap_broadphase {
namespace {

constexpr std::size_t kBoxes = 10000;

FrameDelta deltaOf(FrameRelation inRelation) {
  FrameDelta delta;
  delta.relation = inRelation;
  return delta;
}

FramePlan planOf(FramePath inPath, double inSweepSkin) {
  FramePlan plan;
  plan.path = inPath;
  plan.sweep_skin = inSweepSkin;
  return plan;
}

void recordPlain(SkinAudit& ioAudit, double inMilliseconds) {
  ioAudit.record(planOf(FramePath::kSmallFrame, 0.0), deltaOf(FrameRelation::kSameIds), kBoxes,
                 inMilliseconds);
}

// A window of frames answered with a skin: a grown sweep (not weighed after plain frames: the
// skin's entry), then a window of kept-candidate passes.
void recordSkinWindow(SkinAudit& ioAudit, double inMilliseconds) {
  const FrameDelta moved = deltaOf(FrameRelation::kSameIds);
  ioAudit.record(planOf(FramePath::kSmallFrame, 0.5), moved, kBoxes, inMilliseconds);
  for (int frame = 0; frame < tuning::kSkinAuditFrames; ++frame)
    ioAudit.record(planOf(FramePath::kSkin, 0.0), moved, kBoxes, inMilliseconds);
}

TEST(SkinAudit, WaitsForAPlainFrameOfTheSameIds) {
  SkinAudit audit;
  EXPECT_FALSE(audit.allowsSkin());
  // A first frame and a frame of new ids load their boxes: not a plain frame's cost.
  audit.record(planOf(FramePath::kSmallFrame, 0.0), deltaOf(FrameRelation::kFirst), kBoxes, 1.0);
  audit.record(planOf(FramePath::kParallel, 0.0), deltaOf(FrameRelation::kOtherIds), kBoxes, 1.0);
  audit.record(planOf(FramePath::kReused, 0.0), deltaOf(FrameRelation::kIdentical), kBoxes, 0.1);
  EXPECT_FALSE(audit.allowsSkin());
  recordPlain(audit, 1.0);
  EXPECT_TRUE(audit.allowsSkin());
}

TEST(SkinAudit, KeepsASkinWhoseFramesCostLess) {
  SkinAudit audit;
  recordPlain(audit, 1.0);
  for (int window = 0; window < 5; ++window) {
    recordSkinWindow(audit, 0.6);
    EXPECT_TRUE(audit.allowsSkin()) << "window " << window;
    EXPECT_EQ(audit.nextProbation(), tuning::kSkinAuditFirstProbation);
  }
}

TEST(SkinAudit, ProbationAfterDearerSkinFramesGrowsUpToTheLongest) {
  SkinAudit audit;
  recordPlain(audit, 1.0);
  int expected = tuning::kSkinAuditFirstProbation;
  for (int failure = 0; failure < 8; ++failure) {
    recordSkinWindow(audit, 1.5);
    ASSERT_FALSE(audit.allowsSkin()) << "failure " << failure;
    EXPECT_EQ(audit.probationLeft(), expected) << "failure " << failure;
    for (int frame = 0; frame < expected; ++frame) {
      EXPECT_FALSE(audit.allowsSkin()) << "failure " << failure << " frame " << frame;
      recordPlain(audit, 1.0);
    }
    EXPECT_TRUE(audit.allowsSkin()) << "failure " << failure;
    expected = std::min(2 * expected, tuning::kSkinAuditLongestProbation);
  }
  EXPECT_EQ(expected, tuning::kSkinAuditLongestProbation);
  // A skin that pays again resets the next probation to the first.
  recordSkinWindow(audit, 0.5);
  EXPECT_TRUE(audit.allowsSkin());
  EXPECT_EQ(audit.nextProbation(), tuning::kSkinAuditFirstProbation);
}

TEST(SkinAudit, TheGrownSweepThatStartsASkinIsNotWeighed) {
  SkinAudit audit;
  recordPlain(audit, 1.0);
  const FrameDelta moved = deltaOf(FrameRelation::kSameIds);
  // An entry sweep of 30 plain frames, then passes at half a plain frame: the skin pays.
  audit.record(planOf(FramePath::kSmallFrame, 0.5), moved, kBoxes, 30.0);
  for (int frame = 0; frame < tuning::kSkinAuditFrames; ++frame)
    audit.record(planOf(FramePath::kSkin, 0.0), moved, kBoxes, 0.5);
  EXPECT_TRUE(audit.allowsSkin());
  // A frame of new ids ends the skin (its candidates are forgotten): the next grown sweep is
  // an entry again.
  audit.record(planOf(FramePath::kSmallFrame, 0.0), deltaOf(FrameRelation::kOtherIds), kBoxes, 1.0);
  audit.record(planOf(FramePath::kSmallFrame, 0.5), moved, kBoxes, 30.0);
  for (int frame = 0; frame < tuning::kSkinAuditFrames; ++frame)
    audit.record(planOf(FramePath::kSkin, 0.0), moved, kBoxes, 0.5);
  EXPECT_TRUE(audit.allowsSkin());
  // A grown sweep while the skin lives (its candidates ran out) is part of its cost.
  for (int frame = 0; frame < tuning::kSkinAuditFrames; ++frame)
    audit.record(planOf(FramePath::kSmallFrame, 0.5), moved, kBoxes, 1.5);
  EXPECT_FALSE(audit.allowsSkin());
}

TEST(SkinAudit, WeighsCostsPerBox) {
  SkinAudit audit;
  recordPlain(audit, 1.0);  // 100 ns a box
  // Twice the boxes at 1.6 ms: 80 ns a box, cheaper than plain a box.
  const FrameDelta moved = deltaOf(FrameRelation::kSameIds);
  for (int frame = 0; frame < tuning::kSkinAuditFrames; ++frame)
    audit.record(planOf(FramePath::kSkin, 0.0), moved, 2 * kBoxes, 1.6);
  EXPECT_TRUE(audit.allowsSkin());
}

TEST(SkinAudit, PlainFramesDuringAProbationRefreshTheirCost) {
  SkinAudit audit;
  recordPlain(audit, 1.0);
  recordSkinWindow(audit, 1.2);
  ASSERT_FALSE(audit.allowsSkin());
  // The scene grew denser: plain frames now cost 2 ms, and the same skin frames pay.
  for (int frame = 0; frame < tuning::kSkinAuditFirstProbation; ++frame) recordPlain(audit, 2.0);
  ASSERT_TRUE(audit.allowsSkin());
  recordSkinWindow(audit, 1.2);
  EXPECT_TRUE(audit.allowsSkin());
}

}  // namespace
}  // namespace sap_broadphase
