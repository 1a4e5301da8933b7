// The frame history's contract (frame_history.h): how a frame relates to the last one, which
// boxes moved and by how much, that load() leaves a copy equal to the frame whatever its spans,
// that a frame is the last one only once remember()ed, and that load() checks records with
// validate()'s words (naming the span) and forgets on a refusal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/frame/frame_history.h"
#include "core/runner/work_units.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::randomBoxes;

// Loads inFrame into ioHistory, which must accept it, and returns the delta (a copy).
FrameDelta loadAccepted(FrameHistory& ioHistory, const BoxFrame& inFrame, int inThreads) {
  std::optional<ValidationError> problem;
  const ThreadsScope threads(inThreads);
  const FrameDelta delta = ioHistory.load(inFrame, problem);
  EXPECT_FALSE(problem) << problem->message();
  return delta;
}

// Loads and remembers inFrame.
void loadAndRemember(FrameHistory& ioHistory, const BoxFrame& inFrame, int inThreads) {
  loadAccepted(ioHistory, inFrame, inThreads);
  ioHistory.remember();
}

// Bit for bit equal boxes (so that 0.0 and -0.0 differ): the history's copy against the frame.
::testing::AssertionResult sameBits(const BoxSet& inExpected, const BoxColumns& inActual) {
  if (inExpected.ids != inActual.ids) return ::testing::AssertionFailure() << "ids differ";
  for (std::size_t i = 0; i < inExpected.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double expected[2] = {inExpected.lo(axis, i), inExpected.hi(axis, i)};
      const double actual[2] = {inActual.lo[axis][i], inActual.hi[axis][i]};
      for (int side = 0; side < 2; ++side)
        if (std::signbit(expected[side]) != std::signbit(actual[side]) ||
            !(expected[side] == actual[side]))
          return ::testing::AssertionFailure() << "axis " << axis << " box " << i << " differs";
    }
  }
  if (inExpected.hasFilters() != inActual.hasFilters())
    return ::testing::AssertionFailure() << "only one side has groups and masks";
  for (std::size_t i = 0; i < inExpected.size(); ++i)
    if (inExpected.group(i) != inActual.group(i) || inExpected.mask(i) != inActual.mask(i))
      return ::testing::AssertionFailure() << "box " << i << ": group or mask differs";
  return ::testing::AssertionSuccess();
}

const std::vector<int> kThreadCounts = {1, 2, 3};

TEST(FrameHistory, FirstFrameThenIdenticalThenMoved) {
  for (int threads : kThreadCounts) {
    SCOPED_TRACE(threads);
    FrameHistory history;
    const BoxSet frame = randomBoxes(3000, 100.0, 2.0, 5);
    EXPECT_EQ(loadAccepted(history, frame, threads).relation, FrameRelation::kFirst);
    EXPECT_TRUE(sameBits(frame, history.loaded()));
    history.remember();
    const FrameDelta same = loadAccepted(history, frame, threads);
    EXPECT_EQ(same.relation, FrameRelation::kIdentical);
    EXPECT_EQ(same.moved_boxes, 0u);
    EXPECT_EQ(same.max_displacement, 0.0);
    ASSERT_NE(same.unchanged, nullptr);
    EXPECT_EQ(same.unchanged->size(), frame.size());
    history.remember();

    // Boxes 7 and 2999 (the last block's last box) move; box 1500 moves farthest.
    BoxSet moved = frame;
    moved.lo(0, 7) += 0.25;
    moved.hi(2, 2999) -= 0.125;
    moved.lo(1, 1500) -= 0.5;
    moved.hi(1, 1500) -= 0.5;
    const FrameDelta delta = loadAccepted(history, moved, threads);
    EXPECT_EQ(delta.relation, FrameRelation::kSameIds);
    EXPECT_EQ(delta.moved_boxes, 3u);
    EXPECT_DOUBLE_EQ(delta.max_displacement, 0.5);
    EXPECT_FALSE(delta.filters_changed);
    for (std::size_t i = 0; i < frame.size(); ++i)
      EXPECT_EQ((*delta.unchanged)[i], i == 7 || i == 1500 || i == 2999 ? 0 : 1) << "box " << i;
    EXPECT_TRUE(sameBits(moved, history.loaded()));
    history.remember();
    EXPECT_EQ(loadAccepted(history, moved, threads).relation, FrameRelation::kIdentical);
  }
}

TEST(FrameHistory, SignOfZeroAndInfinitiesCountAsChanges) {
  BoxSet frame;
  const double low[3] = {0.0, 0.0, 0.0}, high[3] = {1.0, 1.0, 1.0};
  frame.add(1, low, high);
  frame.add(2, low, high);
  FrameHistory history;
  loadAndRemember(history, frame, 1);

  BoxSet negative_zero = frame;
  negative_zero.lo(0, 0) = -0.0;  // equal as a number, another bit pattern: a change of size 0
  const FrameDelta zero = loadAccepted(history, negative_zero, 1);
  EXPECT_EQ(zero.relation, FrameRelation::kSameIds);
  EXPECT_EQ(zero.moved_boxes, 1u);
  EXPECT_EQ(zero.max_displacement, 0.0);
  EXPECT_TRUE(sameBits(negative_zero, history.loaded()));
  history.remember();

  BoxSet unbounded = negative_zero;
  unbounded.hi(1, 1) = std::numeric_limits<double>::infinity();
  const FrameDelta infinite = loadAccepted(history, unbounded, 1);
  EXPECT_EQ(infinite.moved_boxes, 1u);
  EXPECT_TRUE(std::isinf(infinite.max_displacement));  // no finite skin covers it
}

TEST(FrameHistory, OtherIdsSizeOrFiltersAreOtherFrames) {
  const BoxSet frame = randomBoxes(700, 50.0, 2.0, 9);
  FrameHistory history;
  loadAndRemember(history, frame, 2);

  BoxSet renamed = frame;
  renamed.ids[600] = 100000;
  EXPECT_EQ(loadAccepted(history, renamed, 2).relation, FrameRelation::kOtherIds);
  history.remember();  // the copy is the renamed frame now
  EXPECT_EQ(loadAccepted(history, renamed, 2).relation, FrameRelation::kIdentical);
  history.remember();

  BoxSet fewer = renamed;
  fewer.bounds.resize(fewer.bounds.size() - kBoundsPerBox);
  fewer.ids.pop_back();
  EXPECT_EQ(loadAccepted(history, fewer, 2).relation, FrameRelation::kOtherIds);
  history.remember();

  BoxSet filtered = fewer;
  filtered.groups.assign(filtered.size(), kDefaultGroup);
  EXPECT_EQ(loadAccepted(history, filtered, 2).relation, FrameRelation::kOtherIds);
  history.remember();

  BoxSet regrouped = filtered;
  regrouped.groups[3] = 0x4;
  const FrameDelta delta = loadAccepted(history, regrouped, 2);
  EXPECT_EQ(delta.relation, FrameRelation::kSameIds);
  EXPECT_TRUE(delta.filters_changed);
  EXPECT_EQ(delta.moved_boxes, 1u);
  EXPECT_EQ((*delta.unchanged)[3], 0);
  EXPECT_TRUE(sameBits(regrouped, history.loaded()));
}

TEST(FrameHistory, AFrameIsTheLastOnlyOnceRemembered) {
  const BoxSet frame = randomBoxes(1200, 50.0, 2.0, 3);
  FrameHistory history;
  loadAndRemember(history, frame, 2);
  BoxSet moved = frame;
  moved.lo(2, 5) -= 1.0;
  loadAccepted(history, moved, 2);  // not remembered (as when update() throws after the load)
  EXPECT_EQ(loadAccepted(history, moved, 2).relation, FrameRelation::kFirst);
  history.remember();
  EXPECT_EQ(loadAccepted(history, moved, 2).relation, FrameRelation::kIdentical);
  history.forget();
  EXPECT_EQ(loadAccepted(history, moved, 2).relation, FrameRelation::kFirst);
}

// A frame given as several spans (sources) loads as the same frame given as one: the same copy,
// the same delta, block seams and span seams wherever they fall.
TEST(FrameHistory, SpansLoadAsOneFrame) {
  for (int threads : kThreadCounts) {
    for (std::size_t span_boxes : {1u, 37u, 512u, 1000u}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, spans of " << span_boxes);
      BoxSet first = randomBoxes(2100, 80.0, 3.0, 17);
      test_support::addRandomFilters(first, 4);
      BoxSet second = first;
      second.lo(0, 0) -= 2.0;
      second.hi(1, 2099) += 1.0;
      second.masks[1234] ^= 0x2;
      FrameHistory whole, in_spans;
      loadAndRemember(whole, first, threads);
      loadAndRemember(in_spans, BoxFrame(test_support::cutIntoSpans(first, span_boxes)), threads);
      EXPECT_TRUE(sameBits(first, in_spans.loaded()));
      const FrameDelta expected = loadAccepted(whole, second, threads);
      const std::vector<BoxSpan> spans = test_support::cutIntoSpans(second, span_boxes);
      const FrameDelta actual = loadAccepted(in_spans, BoxFrame(spans), threads);
      EXPECT_TRUE(sameBits(second, in_spans.loaded()));
      EXPECT_EQ(actual.relation, FrameRelation::kSameIds);
      EXPECT_EQ(actual.relation, expected.relation);
      EXPECT_EQ(actual.moved_boxes, 3u);
      EXPECT_EQ(actual.moved_boxes, expected.moved_boxes);
      EXPECT_TRUE(actual.filters_changed);
      EXPECT_DOUBLE_EQ(actual.max_displacement, 2.0);
    }
  }
}

TEST(FrameHistory, LoadRefusesWithValidatesWordsAndForgets) {
  const BoxSet frame = randomBoxes(900, 40.0, 2.0, 21);
  FrameHistory history;
  std::optional<ValidationError> problem;
  loadAndRemember(history, frame, 2);
  const ThreadsScope two_threads(2);  // the refused loads below run on two threads too

  // Same ids: a box min > max and a later NaN; the lowest bad box is named as validate() does.
  BoxSet bad = frame;
  bad.lo(1, 700) = bad.hi(1, 700) + 1.0;
  bad.hi(2, 800) = std::nan("");
  const std::vector<BoxSpan> bad_spans = test_support::cutIntoSpans(bad, 300);
  history.load(BoxFrame(bad_spans), problem);
  ASSERT_TRUE(problem);
  const auto expected = validate(bad);
  ASSERT_TRUE(expected);
  EXPECT_EQ(problem->message(), expected->message());
  EXPECT_EQ(problem->index, 700u);
  EXPECT_EQ(problem->span, 2u);  // boxes 600..899
  // Refused: the next frame is a first frame, even the good one again.
  EXPECT_EQ(history.load(frame, problem).relation, FrameRelation::kFirst);
  EXPECT_FALSE(problem);

  // A repeated id in a frame of the same size: other ids, named by validate(), with both spans.
  history.remember();
  BoxSet repeated = frame;
  repeated.ids[410] = repeated.ids[3];
  const std::vector<BoxSpan> repeated_spans = test_support::cutIntoSpans(repeated, 300);
  history.load(BoxFrame(repeated_spans), problem);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->problem, BoxProblem::kDuplicateId);
  EXPECT_EQ(problem->index, 410u);
  EXPECT_EQ(problem->earlier, 3u);
  EXPECT_EQ(problem->span, 1u);
  EXPECT_EQ(problem->earlier_span, 0u);
}

// Ids of a span are its own plus its offset; numbered spans (no ids) count from the offset; an
// id beyond 32 bits is refused naming the box, on a first frame and on a frame of the same size.
TEST(FrameHistory, IdOffsetsNumberSpansAndOverflowIsRefused) {
  const double bounds[12] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3};
  BoxSpan numbered;
  numbered.count = 2;
  numbered.bounds = bounds;
  numbered.id_offset = 100;
  const uint32_t given_ids[2] = {5, 6};
  BoxSpan given = numbered;
  given.ids = given_ids;
  given.id_offset = 1000;
  FrameHistory history;
  const std::vector<BoxSpan> spans = {numbered, given};
  loadAndRemember(history, BoxFrame(spans), 1);
  EXPECT_EQ(history.loaded().ids, (std::vector<uint32_t>{100, 101, 1005, 1006}));

  std::vector<BoxSpan> overflowing = spans;
  overflowing[1].id_offset = UINT32_MAX - 5;  // 5 fits, 6 does not
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::optional<ValidationError> problem;
    history.load(BoxFrame(overflowing), problem);
    ASSERT_TRUE(problem) << "attempt " << attempt;
    EXPECT_EQ(problem->problem, BoxProblem::kIdOverflow);
    EXPECT_EQ(problem->index, 3u);
    EXPECT_EQ(problem->span, 1u);
    EXPECT_EQ(problem->id, 6u) << "the box's own id, not the sum wrapped past 32 bits";
    EXPECT_NE(problem->message().find("(id 6)"), std::string::npos) << problem->message();
    EXPECT_NE(problem->message().find("exceeds 4294967295"), std::string::npos)
        << problem->message();
    loadAndRemember(history, BoxFrame(spans), 1);  // then the same size again: the block path
  }
}

}  // namespace
}  // namespace sap_broadphase
