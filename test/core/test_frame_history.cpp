// The frame history's contract (frame_history.h): how a frame relates to the last one, which
// boxes moved and by how much, that compare() and load() leave a copy equal to the frame, that
// a frame is the last one only once remember()ed, and that load() checks records with
// validate()'s words and forgets on a refusal.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/frame_history.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::randomBoxes;

// Records of inBoxes, as a BoxArray message holds them (min x, y, z, max x, y, z per box).
struct Records {
  std::vector<double> bounds;
  std::vector<uint32_t> ids;
  InterleavedBoxes view() const {
    InterleavedBoxes boxes;
    boxes.count = ids.size();
    boxes.bounds = bounds.data();
    boxes.ids = ids.data();
    return boxes;
  }
};

Records recordsOf(const BoxSet& inBoxes) {
  Records records;
  records.ids = inBoxes.ids;
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) records.bounds.push_back(inBoxes.lo[axis][i]);
    for (int axis = 0; axis < 3; ++axis) records.bounds.push_back(inBoxes.hi[axis][i]);
  }
  return records;
}

// Bit for bit equal box sets (so that 0.0 and -0.0 differ).
::testing::AssertionResult sameBits(const BoxSet& inExpected, const BoxSet& inActual) {
  if (inExpected.ids != inActual.ids) return ::testing::AssertionFailure() << "ids differ";
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<double>* arrays[2][2] = {{&inExpected.lo[axis], &inActual.lo[axis]},
                                               {&inExpected.hi[axis], &inActual.hi[axis]}};
    for (const auto& pair : arrays) {
      if (pair[0]->size() != pair[1]->size())
        return ::testing::AssertionFailure() << "axis " << axis << ": sizes differ";
      for (std::size_t i = 0; i < pair[0]->size(); ++i)
        if (std::signbit((*pair[0])[i]) != std::signbit((*pair[1])[i]) ||
            !((*pair[0])[i] == (*pair[1])[i]))
          return ::testing::AssertionFailure() << "axis " << axis << " box " << i << " differs";
    }
  }
  if (inExpected.groups != inActual.groups || inExpected.masks != inActual.masks)
    return ::testing::AssertionFailure() << "groups or masks differ";
  return ::testing::AssertionSuccess();
}

const std::vector<int> kThreadCounts = {1, 2, 3};

TEST(FrameHistory, FirstFrameThenIdenticalThenMoved) {
  for (int threads : kThreadCounts) {
    SCOPED_TRACE(threads);
    FrameHistory history;
    const BoxSet frame = randomBoxes(3000, 100.0, 2.0, 5);
    EXPECT_EQ(history.compare(frame, threads).relation, FrameRelation::kFirst);
    history.remember(frame);
    const FrameDelta& same = history.compare(frame, threads);
    EXPECT_EQ(same.relation, FrameRelation::kIdentical);
    EXPECT_EQ(same.moved_boxes, 0u);
    EXPECT_EQ(same.max_displacement, 0.0);
    ASSERT_NE(same.unchanged, nullptr);
    EXPECT_EQ(same.unchanged->size(), frame.size());
    history.remember(frame);

    // Boxes 7 and 2999 (the last block's last box) move; box 1500 moves farthest.
    BoxSet moved = frame;
    moved.lo[0][7] += 0.25;
    moved.hi[2][2999] -= 0.125;
    moved.lo[1][1500] -= 0.5;
    moved.hi[1][1500] -= 0.5;
    const FrameDelta& delta = history.compare(moved, threads);
    EXPECT_EQ(delta.relation, FrameRelation::kSameIds);
    EXPECT_EQ(delta.moved_boxes, 3u);
    EXPECT_DOUBLE_EQ(delta.max_displacement, 0.5);
    EXPECT_FALSE(delta.filters_changed);
    for (std::size_t i = 0; i < frame.size(); ++i)
      EXPECT_EQ((*delta.unchanged)[i], i == 7 || i == 1500 || i == 2999 ? 0 : 1) << "box " << i;
    history.remember(moved);
    EXPECT_EQ(history.compare(moved, threads).relation, FrameRelation::kIdentical);
  }
}

TEST(FrameHistory, SignOfZeroAndInfinitiesCountAsChanges) {
  BoxSet frame;
  const double low[3] = {0.0, 0.0, 0.0}, high[3] = {1.0, 1.0, 1.0};
  frame.add(1, low, high);
  frame.add(2, low, high);
  FrameHistory history;
  history.compare(frame, 1);
  history.remember(frame);

  BoxSet negative_zero = frame;
  negative_zero.lo[0][0] = -0.0;  // equal as a number, another bit pattern: a change of size 0
  const FrameDelta& zero = history.compare(negative_zero, 1);
  EXPECT_EQ(zero.relation, FrameRelation::kSameIds);
  EXPECT_EQ(zero.moved_boxes, 1u);
  EXPECT_EQ(zero.max_displacement, 0.0);
  history.remember(negative_zero);

  BoxSet unbounded = negative_zero;
  unbounded.hi[1][1] = std::numeric_limits<double>::infinity();
  const FrameDelta& infinite = history.compare(unbounded, 1);
  EXPECT_EQ(infinite.moved_boxes, 1u);
  EXPECT_TRUE(std::isinf(infinite.max_displacement));  // no finite skin covers it
}

TEST(FrameHistory, OtherIdsSizeOrFiltersAreOtherFrames) {
  const BoxSet frame = randomBoxes(700, 50.0, 2.0, 9);
  FrameHistory history;
  history.compare(frame, 2);
  history.remember(frame);

  BoxSet renamed = frame;
  renamed.ids[600] = 100000;
  EXPECT_EQ(history.compare(renamed, 2).relation, FrameRelation::kOtherIds);
  history.remember(renamed);  // the copy is the renamed frame now
  EXPECT_EQ(history.compare(renamed, 2).relation, FrameRelation::kIdentical);
  history.remember(renamed);

  BoxSet fewer = renamed;
  for (auto* array :
       {&fewer.lo[0], &fewer.lo[1], &fewer.lo[2], &fewer.hi[0], &fewer.hi[1], &fewer.hi[2]})
    array->pop_back();
  fewer.ids.pop_back();
  EXPECT_EQ(history.compare(fewer, 2).relation, FrameRelation::kOtherIds);
  history.remember(fewer);

  BoxSet filtered = fewer;
  filtered.groups.assign(filtered.size(), kDefaultGroup);
  EXPECT_EQ(history.compare(filtered, 2).relation, FrameRelation::kOtherIds);
  history.remember(filtered);

  BoxSet regrouped = filtered;
  regrouped.groups[3] = 0x4;
  const FrameDelta& delta = history.compare(regrouped, 2);
  EXPECT_EQ(delta.relation, FrameRelation::kSameIds);
  EXPECT_TRUE(delta.filters_changed);
  EXPECT_EQ(delta.moved_boxes, 1u);
  EXPECT_EQ((*delta.unchanged)[3], 0);
}

TEST(FrameHistory, AFrameIsTheLastOnlyOnceRemembered) {
  const BoxSet frame = randomBoxes(1200, 50.0, 2.0, 3);
  FrameHistory history;
  history.compare(frame, 2);
  history.remember(frame);
  BoxSet moved = frame;
  moved.lo[2][5] -= 1.0;
  history.compare(moved, 2);  // the frame is not remembered (as when update() throws)
  EXPECT_EQ(history.compare(moved, 2).relation, FrameRelation::kFirst);
  history.remember(moved);
  EXPECT_EQ(history.compare(moved, 2).relation, FrameRelation::kIdentical);
  history.forget();
  EXPECT_EQ(history.compare(moved, 2).relation, FrameRelation::kFirst);
}

TEST(FrameHistory, LoadedRecordsEqualTheFrameAndCompareAsBoxSets) {
  for (int threads : kThreadCounts) {
    SCOPED_TRACE(threads);
    const BoxSet first = randomBoxes(2100, 80.0, 3.0, 17);
    BoxSet second = first;
    second.lo[0][0] -= 2.0;
    second.hi[1][2099] += 1.0;
    FrameHistory records_history, set_history;
    std::optional<ValidationError> problem;
    const Records first_records = recordsOf(first);
    EXPECT_EQ(records_history.load(first_records.view(), threads, problem).relation,
              FrameRelation::kFirst);
    ASSERT_FALSE(problem) << problem->message();
    EXPECT_TRUE(sameBits(first, records_history.loaded()));
    records_history.remember(records_history.loaded());
    set_history.compare(first, threads);
    set_history.remember(first);

    const Records second_records = recordsOf(second);
    const FrameDelta loaded = records_history.load(second_records.view(), threads, problem);
    ASSERT_FALSE(problem) << problem->message();
    EXPECT_TRUE(sameBits(second, records_history.loaded()));
    const FrameDelta compared = set_history.compare(second, threads);
    EXPECT_EQ(loaded.relation, FrameRelation::kSameIds);
    EXPECT_EQ(loaded.relation, compared.relation);
    EXPECT_EQ(loaded.moved_boxes, 2u);
    EXPECT_EQ(loaded.moved_boxes, compared.moved_boxes);
    EXPECT_EQ(loaded.max_displacement, compared.max_displacement);
    EXPECT_DOUBLE_EQ(loaded.max_displacement, 2.0);
  }
}

TEST(FrameHistory, LoadRefusesWithValidatesWordsAndForgets) {
  const BoxSet frame = randomBoxes(900, 40.0, 2.0, 21);
  FrameHistory history;
  std::optional<ValidationError> problem;
  const Records good = recordsOf(frame);
  history.load(good.view(), 2, problem);
  ASSERT_FALSE(problem);
  history.remember(history.loaded());

  // Same ids: a box min > max and a later NaN; the lowest bad box is named as validate() does.
  BoxSet bad = frame;
  bad.lo[1][700] = bad.hi[1][700] + 1.0;
  bad.hi[2][800] = std::nan("");
  Records bad_records = recordsOf(bad);
  history.load(bad_records.view(), 2, problem);
  ASSERT_TRUE(problem);
  const auto expected = validate(bad);
  ASSERT_TRUE(expected);
  EXPECT_EQ(problem->message(), expected->message());
  EXPECT_EQ(problem->index, 700u);
  // Refused: the next frame is a first frame, even the good one again.
  EXPECT_EQ(history.load(good.view(), 2, problem).relation, FrameRelation::kFirst);
  EXPECT_FALSE(problem);

  // A repeated id in a frame of the same size: other ids, named by validate().
  history.remember(history.loaded());
  Records repeated = good;
  repeated.ids[10] = repeated.ids[3];
  history.load(repeated.view(), 1, problem);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->problem, BoxProblem::kDuplicateId);
  EXPECT_EQ(problem->index, 10u);
  EXPECT_EQ(problem->earlier, 3u);
}

}  // namespace
}  // namespace sap_broadphase
