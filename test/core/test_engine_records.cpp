// Frames given as records (BoxSpan, a BoxArray's layout), in one span or several (one per
// source): the engine loads and checks them itself. The pairs, the frame history and the
// refusals must be those of the same frame given as one BoxSet, and the oracle's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::engineConfig;
using test_support::movingScene;

// A frame laid out as a BoxArray message holds it.
struct Records {
  std::vector<double> bounds;
  std::vector<uint32_t> ids, groups, masks;

  explicit Records(const BoxSet& inBoxes) {
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) bounds.push_back(inBoxes.lo(axis, i));
      for (int axis = 0; axis < 3; ++axis) bounds.push_back(inBoxes.hi(axis, i));
    }
    ids = inBoxes.ids;
    groups = inBoxes.groups;
    masks = inBoxes.masks;
  }
  BoxSpan view(bool inWithIds = true) const {
    BoxSpan records;
    records.count = bounds.size() / 6;
    records.bounds = bounds.data();
    records.ids = inWithIds ? ids.data() : nullptr;
    records.groups = groups.empty() ? nullptr : groups.data();
    records.masks = masks.empty() ? nullptr : masks.data();
    return records;
  }
  double& bound(std::size_t inBox, int inCoordinate) { return bounds[6 * inBox + inCoordinate]; }
};

// What the frame sequence does to the boxes at frame inFrame: now and then identical to the
// last frame, a box added (other ids), a box jumping, two boxes swapped (same count, other
// ids), a bound moved from 0.0 to -0.0.
BoxSet frameOf(SceneSimulator& ioScene, int inFrame, const BoxSet& inLast) {
  if (inFrame % 11 == 4 && inLast.size() > 0) return inLast;
  BoxSet boxes = ioScene.boxes();
  ioScene.step();
  if (inFrame % 9 == 5) {
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    boxes.add(700000 + inFrame, lo, hi);
  }
  if (inFrame % 7 == 3) boxes.hi(1, 17) += 5.0;
  if (inFrame % 13 == 6) std::swap(boxes.ids[3], boxes.ids[40]);
  if (inFrame % 10 == 8) {  // box 5 starts at z = 0.0 on one such frame, -0.0 on the next
    boxes.hi(2, 5) = std::max(boxes.hi(2, 5), 0.0);
    boxes.lo(2, 5) = inFrame % 20 == 8 ? 0.0 : -0.0;
  }
  return boxes;
}

TEST(RecordFrames, SpansGiveTheSamePairsAsOneSetOnEveryPathAndThreadCount) {
  for (SceneKind kind : {SceneKind::kUniform, SceneKind::kBallCluster, SceneKind::kPlaneCluster}) {
    for (int threads : {1, 2, 3}) {
      BroadphaseConfig config = engineConfig(Method::kAuto, threads, 0, 1);
      config.parallel_min_boxes = 500;  // a sweep on every thread count, not a small frame
      // A fixed skin on two threads (kept candidates, grown sweeps), none otherwise (plain
      // sweeps): the automatic skin's choice depends on costs each engine measures apart.
      config.skin = threads == 2 ? 0.5 : 0.0;
      Broadphase from_sets(config), from_records(config), from_spans(config);
      SceneSimulator scene(movingScene(kind, 31 + threads, 2500, 0.25, 60));
      BoxSet boxes;
      for (int frame = 0; frame < 45; ++frame) {
        boxes = frameOf(scene, frame, boxes);
        const Records records(boxes);
        const PairList expected = bruteForcePairs(boxes);
        const std::string where = "scene " + std::to_string(int(kind)) + " threads " +
                                  std::to_string(threads) + " frame " + std::to_string(frame);
        ASSERT_EQ(from_sets.update(boxes), expected) << where;
        ASSERT_EQ(from_records.update(records.view()), expected)
            << where << " path " << framePathName(from_records.stats().path);
        // The history sees the same frame: the same motion, hence the same plan.
        EXPECT_EQ(from_records.stats().moved_boxes, from_sets.stats().moved_boxes) << where;
        EXPECT_EQ(from_records.stats().path, from_sets.stats().path) << where;
        // Several sources: spans of 1000 boxes, seams moving as boxes are added.
        const std::vector<BoxSpan> spans = test_support::cutIntoSpans(boxes, 1000);
        ASSERT_EQ(from_spans.update(BoxFrame(spans)), expected)
            << where << " path " << framePathName(from_spans.stats().path);
        EXPECT_EQ(from_spans.stats().moved_boxes, from_sets.stats().moved_boxes) << where;
      }
    }
  }
}

TEST(RecordFrames, WithoutIdsBoxesAreNumberedInOrder) {
  const BoxSet boxes = test_support::randomBoxes(3000, 20.0, 1.5, 77);  // ids 0..n-1
  Broadphase engine(engineConfig(Method::kAuto, 2, 0, 1));
  const Records records(boxes);
  EXPECT_EQ(engine.update(records.view(false)), bruteForcePairs(boxes));
  EXPECT_EQ(engine.update(records.view(false)), bruteForcePairs(boxes));
}

TEST(RecordFrames, FiltersAreHonouredAndMayBeHalfGiven) {
  BoxSet boxes = test_support::randomBoxes(2000, 15.0, 1.5, 78);
  test_support::addRandomFilters(boxes, 79);
  for (std::size_t i = 0; i < boxes.size(); i += 23) boxes.groups[i] = 0;  // pairs with nothing
  Broadphase engine(engineConfig(Method::kAuto, 2, 0, 1));
  Records records(boxes);
  for (int frame = 0; frame < 3; ++frame)
    EXPECT_EQ(engine.update(records.view()), bruteForcePairs(boxes)) << "frame " << frame;
  // Groups alone: the masks are the default.
  records.masks.clear();
  boxes.masks.assign(boxes.size(), kDefaultMask);
  EXPECT_EQ(engine.update(records.view()), bruteForcePairs(boxes));
}

TEST(RecordFrames, InfinitiesAndSignedZerosAreBoxes) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  BoxSet boxes;
  const double lo0[3] = {-kInf, -0.0, 0}, hi0[3] = {kInf, 0.0, 1};
  const double lo1[3] = {0.0, 0.0, 1}, hi1[3] = {1, 1, kInf};
  const double lo2[3] = {2, -kInf, -kInf}, hi2[3] = {3, -0.0, 0};
  boxes.add(5, lo0, hi0);
  boxes.add(9, lo1, hi1);
  boxes.add(2, lo2, hi2);
  Broadphase engine;
  EXPECT_EQ(engine.update(Records(boxes).view()), bruteForcePairs(boxes));
  boxes.lo(0, 1) = -0.0;  // a change of size 0 is still a change
  EXPECT_EQ(engine.update(Records(boxes).view()), bruteForcePairs(boxes));
  EXPECT_EQ(engine.stats().moved_boxes, 1u);
}

// The refusal names the lowest bad box in validate()'s words, on a first frame and on a
// frame compared with the last one, and the engine goes on exactly afterwards.
void expectRefusedAsValidateWould(Broadphase& ioEngine, const BoxSet& inBad,
                                  const std::string& inWhere) {
  const auto expected = validate(inBad);
  ASSERT_TRUE(expected) << inWhere;
  try {
    ioEngine.update(Records(inBad).view());
    ADD_FAILURE() << inWhere << ": not refused";
  } catch (const InvalidBoxes& refusal) {
    EXPECT_EQ(refusal.error().message(), expected->message()) << inWhere;
    EXPECT_EQ(refusal.error().problem, expected->problem) << inWhere;
    EXPECT_STREQ(refusal.what(), expected->message().c_str()) << inWhere;
  }
}

TEST(RecordFrames, BadBoxesAreRefusedAsValidateNamesThem) {
  const BoxSet good = test_support::randomBoxes(4000, 20.0, 1.5, 80);
  struct Case {
    const char* name;
    void (*spoil)(BoxSet&);
  };
  const Case cases[] = {
      {"NaN", [](BoxSet& b) { b.hi(2, 1234) = std::nan(""); }},
      {"min > max", [](BoxSet& b) { b.lo(1, 2345) = b.hi(1, 2345) + 1.0; }},
      {"two bad boxes",
       [](BoxSet& b) {
         b.lo(0, 3000) = b.hi(0, 3000) + 1.0;
         b.lo(2, 700) = std::nan("");
       }},
      {"repeated id", [](BoxSet& b) { b.ids[3500] = b.ids[12]; }},
      {"repeated id before a bad box",
       [](BoxSet& b) {
         b.ids[100] = b.ids[99];
         b.lo(0, 200) = std::nan("");
       }},
  };
  for (const Case& bad_case : cases) {
    BoxSet bad = good;
    bad_case.spoil(bad);
    for (int threads : {1, 2}) {
      Broadphase engine(engineConfig(Method::kAuto, threads, 0, 1));
      const std::string where = std::string(bad_case.name) + ", threads " + std::to_string(threads);
      expectRefusedAsValidateWould(engine, bad, where + ", first frame");
      ASSERT_EQ(engine.update(Records(good).view()), bruteForcePairs(good)) << where;
      ASSERT_EQ(engine.update(Records(good).view()), bruteForcePairs(good)) << where;
      expectRefusedAsValidateWould(engine, bad, where + ", after a frame of the same ids");
      // After a refusal the next frame starts afresh, and is exact.
      ASSERT_EQ(engine.update(Records(good).view()), bruteForcePairs(good)) << where;
    }
  }
}

TEST(RecordFrames, FilteredBadBoxesAreRefusedToo) {
  BoxSet bad = test_support::randomBoxes(1000, 10.0, 1.5, 81);
  test_support::addRandomFilters(bad, 82);
  bad.lo(0, 10) = std::nan("");
  Broadphase engine;
  expectRefusedAsValidateWould(engine, bad, "filtered");
}

// Spans numbered by their offsets (a source without ids, as numpy arrays come) pair as the
// same boxes with those ids; query() reads spans too.
TEST(RecordFrames, NumberedSpansWithOffsetsAndQueries) {
  const BoxSet left = test_support::randomBoxes(700, 20.0, 1.5, 3);  // ids 0..699
  const BoxSet right = test_support::randomBoxes(900, 20.0, 1.5, 4);
  BoxSpan left_span = left.span(), right_span = right.span();
  left_span.ids = right_span.ids = nullptr;
  right_span.id_offset = 1000;
  const std::vector<BoxSpan> spans = {left_span, right_span};
  BoxSet joined = left;
  for (std::size_t i = 0; i < right.size(); ++i) {
    const double lo[3] = {right.lo(0, i), right.lo(1, i), right.lo(2, i)};
    const double hi[3] = {right.hi(0, i), right.hi(1, i), right.hi(2, i)};
    joined.add(static_cast<uint32_t>(1000 + i), lo, hi);
  }
  Broadphase engine(engineConfig(Method::kAuto, 2, 0, 1));
  EXPECT_EQ(engine.update(BoxFrame(spans)), bruteForcePairs(joined));
  const BoxSet queries = test_support::randomBoxes(40, 20.0, 3.0, 5);
  const std::vector<BoxSpan> query_spans = test_support::cutIntoSpans(queries, 15);
  EXPECT_EQ(engine.query(BoxFrame(query_spans)), bruteForceQuery(queries, joined));
}

// A frame's id that a scenery box has is refused naming the box, its span and the scenery; the
// engine goes on with the next frame. A bad scenery is refused and the old one stays.
TEST(RecordFrames, IdsOfTheSceneryAndBadSceneryAreRefused) {
  BoxSet scenery, moving;
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  for (uint32_t id = 100; id < 110; ++id) scenery.add(id, lo, hi);
  for (uint32_t id = 0; id < 20; ++id) moving.add(id, lo, hi);
  for (int threads : {1, 2}) {
    Broadphase engine(engineConfig(Method::kAuto, threads, 0, 1));
    engine.setStaticBoxes(scenery);
    const PairList good = engine.update(moving);
    EXPECT_EQ(good.size(), 20u * 19u / 2u + 20u * 10u);
    BoxSet clashing = moving;
    clashing.ids[15] = 104;
    const std::vector<BoxSpan> spans = test_support::cutIntoSpans(clashing, 10);
    try {
      engine.update(BoxFrame(spans));
      ADD_FAILURE() << "an id of the scenery was accepted";
    } catch (const InvalidBoxes& refusal) {
      EXPECT_EQ(refusal.error().problem, BoxProblem::kDuplicateId);
      EXPECT_EQ(refusal.error().index, 15u);
      EXPECT_EQ(refusal.error().id, 104u);
      EXPECT_EQ(refusal.error().span, 1u);
      EXPECT_EQ(refusal.error().earlier_span, ValidationError::kScenery);
    }
    EXPECT_EQ(engine.update(moving), good);

    BoxSet bad_scenery = scenery;
    bad_scenery.hi(0, 2) = std::nan("");
    EXPECT_THROW(engine.setStaticBoxes(bad_scenery), InvalidBoxes);
    EXPECT_EQ(engine.staticBoxCount(), scenery.size());
    EXPECT_EQ(engine.update(moving), good);
  }
}

// Boxes with group 0 or mask 0 stay in the frame the engine loads and pair with nothing, on
// every path (a frame that alternates between having such boxes and not).
TEST(RecordFrames, BoxesThatPairWithNothingStayAndPairWithNothing) {
  for (int threads : {1, 2}) {
    Broadphase engine(engineConfig(Method::kAuto, threads, 0, 1));
    BoxSet boxes = test_support::randomBoxes(3000, 30.0, 2.0, 8);
    test_support::addRandomFilters(boxes, 9);
    for (int frame = 0; frame < 6; ++frame) {
      for (std::size_t i = frame; i < boxes.size(); i += 7) boxes.groups[i] = frame % 2 ? 0 : 1;
      boxes.lo(0, 11) += 0.01;
      boxes.hi(0, 11) += 0.01;
      ASSERT_EQ(engine.update(boxes), bruteForcePairs(boxes)) << "frame " << frame;
      std::size_t excluded = 0;
      for (std::size_t i = 0; i < boxes.size(); ++i)
        excluded += boxes.group(i) == 0 || boxes.mask(i) == 0;
      EXPECT_EQ(engine.stats().boxes_filtered_out, excluded);
    }
  }
}

}  // namespace
}  // namespace sap_broadphase
