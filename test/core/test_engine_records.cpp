// Frames given as records (BoxSpan, a BoxArray's layout): the engine loads and checks
// them itself. The pairs, the frame history and the refusals must be those of the same frame
// given as a checked BoxSet.
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

TEST(RecordFrames, SamePairsAsBoxSetFramesOnEveryPathAndThreadCount) {
  for (SceneKind kind : {SceneKind::kUniform, SceneKind::kBallCluster, SceneKind::kPlaneCluster}) {
    for (int threads : {1, 2, 3}) {
      BroadphaseConfig config = engineConfig(Method::kAuto, threads, 0, 1);
      config.parallel_min_boxes = 500;  // a sweep on every thread count, not a small frame
      // A fixed skin on two threads (kept candidates, grown sweeps), none otherwise (plain
      // sweeps): the automatic skin's choice depends on costs each engine measures apart.
      config.skin = threads == 2 ? 0.5 : 0.0;
      Broadphase from_sets(config), from_records(config);
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

}  // namespace
}  // namespace sap_broadphase
