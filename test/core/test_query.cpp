// Box queries (Broadphase::query) against the brute-force query oracle: random and lattice
// worlds, infinities and -0.0, groups and masks, declared scenery, frame sequences on every
// path, thread counts, both ways of answering (scans and the frame's index), refusals, and
// queries from other threads between frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/frame/pair_sort.h"
#include "core/runner/work_units.h"
#include "core/strategies/frame_query.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::addRandomFilters;
using test_support::engineConfig;
using test_support::latticeBoxes;
using test_support::movingScene;
using test_support::randomBoxes;
using test_support::TestRandom;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr uint32_t kSceneryIds = 1000000;  // scenery ids start here, above every frame's ids

::testing::AssertionResult sameHits(const QueryHitList& inExpected, const QueryHitList& inActual) {
  if (inExpected == inActual) return ::testing::AssertionSuccess();
  std::ostringstream text;
  text << "expected " << inExpected.size() << " hits, got " << inActual.size();
  for (std::size_t k = 0; k < std::max(inExpected.size(), inActual.size()); ++k) {
    const bool has_expected = k < inExpected.size(), has_actual = k < inActual.size();
    if (has_expected && has_actual && inExpected[k] == inActual[k]) continue;
    text << "; first difference at hit " << k << ": expected ";
    if (has_expected)
      text << "(" << inExpected[k].query << ", " << inExpected[k].world << ")";
    else
      text << "nothing";
    text << ", got ";
    if (has_actual)
      text << "(" << inActual[k].query << ", " << inActual[k].world << ")";
    else
      text << "nothing";
    break;
  }
  return ::testing::AssertionFailure() << text.str();
}

// The world a query sees: the frame's boxes and the scenery's, in one set for the oracle.
BoxSet joined(const BoxSet& inFrame, const BoxSet& inScenery) {
  BoxSet world;
  for (const BoxSet* part : {&inFrame, &inScenery}) {
    for (std::size_t i = 0; i < part->size(); ++i) {
      const double lo[3] = {part->lo(0, i), part->lo(1, i), part->lo(2, i)};
      const double hi[3] = {part->hi(0, i), part->hi(1, i), part->hi(2, i)};
      world.add(part->ids[i], lo, hi, part->group(i), part->mask(i));
    }
  }
  return world;
}

// inBoxes renumbered from inFirstId on.
BoxSet renumbered(BoxSet inBoxes, uint32_t inFirstId) {
  for (std::size_t i = 0; i < inBoxes.size(); ++i)
    inBoxes.ids[i] = inFirstId + static_cast<uint32_t>(i);
  return inBoxes;
}

// Query boxes about the world's size: some inside it, some larger, a few infinite or flat.
BoxSet queryBoxes(std::size_t inCount, double inWorld, uint64_t inSeed) {
  TestRandom random(inSeed);
  BoxSet queries;
  for (std::size_t q = 0; q < inCount; ++q) {
    double lo[3], hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = random.between(-0.1 * inWorld, inWorld);
      hi[axis] = lo[axis] + random.between(0.0, 0.15 * inWorld);
    }
    if (random.chance(0.05)) lo[random.below(3)] = -kInf;
    if (random.chance(0.05)) hi[random.below(3)] = kInf;
    if (random.chance(0.05)) {
      const int axis = static_cast<int>(random.below(3));
      hi[axis] = lo[axis];
    }
    queries.add(static_cast<uint32_t>(q), lo, hi);
  }
  return queries;
}

// Every query of inQueries asked of inEngine, one box at a time and all at once, against the
// oracle on inWorld.
void expectQueriesMatch(const Broadphase& inEngine, const BoxSet& inQueries, const BoxSet& inWorld,
                        const std::string& inLabel) {
  const QueryHitList expected = bruteForceQuery(inQueries, inWorld);
  EXPECT_TRUE(sameHits(expected, inEngine.query(inQueries))) << inLabel << ", all at once";
}

TEST(Query, RandomWorldsWithSceneryFiltersAndThreadCounts) {
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    const bool lattice = seed % 2 == 0;
    BoxSet frame = lattice ? latticeBoxes(1500, 40, 4, seed) : randomBoxes(1500, 100.0, 6.0, seed);
    BoxSet scenery = renumbered(
        lattice ? latticeBoxes(400, 40, 6, seed + 100) : randomBoxes(400, 100.0, 9.0, seed + 100),
        kSceneryIds);
    BoxSet queries = lattice ? latticeBoxes(70, 40, 10, seed + 200) : queryBoxes(70, 100.0, seed);
    if (seed % 3 == 0) {
      addRandomFilters(frame, seed);
      addRandomFilters(scenery, seed + 1);
      addRandomFilters(queries, seed + 2);
    }
    const bool with_scenery = seed % 4 != 1;
    const BoxSet world = joined(frame, with_scenery ? scenery : BoxSet());
    for (int threads : {1, 2, 3, 4}) {
      Broadphase engine(engineConfig(Method::kAuto, threads, 0, 1));
      if (with_scenery) engine.setStaticBoxes(scenery);
      engine.update(frame);
      const std::string label =
          "seed " + std::to_string(seed) + ", threads " + std::to_string(threads);
      // One box at a time first (the frame is scanned), then the whole batch (indexed).
      for (std::size_t q = 0; q < 5; ++q) {
        BoxSet one;
        const double lo[3] = {queries.lo(0, q), queries.lo(1, q), queries.lo(2, q)};
        const double hi[3] = {queries.hi(0, q), queries.hi(1, q), queries.hi(2, q)};
        one.add(queries.ids[q], lo, hi, queries.group(q), queries.mask(q));
        expectQueriesMatch(engine, one, world, label + ", query " + std::to_string(q));
      }
      expectQueriesMatch(engine, queries, world, label);
    }
  }
}

// The frame's two ways of answering, side by side: scans for the first queries of a frame,
// the index once scans have cost as much as it would.
TEST(Query, ScansAndTheFrameIndexGiveTheOracleAnswers) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    BoxSet frame = randomBoxes(3000, 100.0, 5.0, seed);
    if (seed % 2 == 0) addRandomFilters(frame, seed);
    const BoxColumns frame_columns = columnsOf(frame);
    FrameQuery frame_query;
    frame_query.setFrame(frame_columns);
    const ThreadsScope two_threads(2);
    for (int round = 0; round < 6; ++round) {
      BoxSet queries = queryBoxes(20, 100.0, seed * 10 + round);
      if (seed % 2 == 0) addRandomFilters(queries, seed + round);
      const bool was_indexed = frame_query.indexed();
      PairList hits;
      frame_query.query(columnsOf(queries), hits);
      PairSortScratch scratch;
      sortPairsByAThenB(hits, scratch);
      QueryHitList answer;
      for (const IdPair& hit : hits) answer.push_back({hit.a, hit.b});
      EXPECT_TRUE(sameHits(bruteForceQuery(queries, frame), answer))
          << "seed " << seed << ", round " << round << (was_indexed ? ", indexed" : ", scanned");
    }
    EXPECT_TRUE(frame_query.indexed()) << "120 query boxes in a frame build its index";
    frame_query.setFrame(frame_columns);
    EXPECT_FALSE(frame_query.indexed()) << "a new frame forgets the last frame's index";
  }
}

TEST(Query, InfinitiesNegativeZeroAndTouchingFaces) {
  BoxSet frame;
  const double z_lo[3] = {-0.0, -0.0, -0.0}, z_hi[3] = {1, 1, 1};
  frame.add(10, z_lo, z_hi);  // starts at -0.0
  const double far_lo[3] = {5, 5, 5}, far_hi[3] = {kInf, kInf, kInf};
  frame.add(11, far_lo, far_hi);  // reaches +inf
  const double all_lo[3] = {-kInf, -kInf, -kInf}, all_hi[3] = {-kInf, kInf, kInf};
  frame.add(12, all_lo, all_hi);  // a plane at x = -inf
  const double point[3] = {2, 2, 2};
  frame.add(13, point, point);  // a point
  BoxSet queries;
  const double q0_lo[3] = {-1, -1, -1}, q0_hi[3] = {0.0, 0.0, 0.0};
  queries.add(0, q0_lo, q0_hi);  // touches box 10 at 0.0 == -0.0
  const double q1_lo[3] = {1e308, 1e308, 1e308}, q1_hi[3] = {kInf, kInf, kInf};
  queries.add(1, q1_lo, q1_hi);  // far out: only box 11
  const double q2_lo[3] = {-kInf, 0, 0}, q2_hi[3] = {-kInf, 0, 0};
  queries.add(2, q2_lo, q2_hi);  // at x = -inf: only the plane
  queries.add(3, point, point);  // the point touches the point
  const double q4_lo[3] = {1, 1, 1}, q4_hi[3] = {2, 2, 2};
  queries.add(4, q4_lo, q4_hi);  // touches box 10's far corner and the point
  const QueryHitList expected = {{0, 10}, {1, 11}, {2, 12}, {3, 13}, {4, 10}, {4, 13}};
  // The oracle agrees with the hits written out by hand, and the engine with both, on every
  // thread count, scanned and indexed, and with the frame as scenery instead.
  ASSERT_TRUE(sameHits(expected, bruteForceQuery(queries, frame)));
  for (int threads : {1, 2, 3, 4}) {
    Broadphase engine(engineConfig(Method::kAuto, threads, 0, 1));
    engine.update(frame);
    for (int round = 0; round < 12; ++round)
      EXPECT_TRUE(sameHits(expected, engine.query(queries))) << "round " << round;
    Broadphase scenery_only(engineConfig(Method::kAuto, threads, 0, 1));
    scenery_only.setStaticBoxes(frame);
    EXPECT_TRUE(sameHits(expected, scenery_only.query(queries))) << "as scenery";
  }
}

TEST(Query, GroupsAndMasksApplyBothWaysAndGroupZeroMeetsNothing) {
  BoxSet frame;
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  frame.add(1, lo, hi, 0x1, 0xFFFFFFFF);  // group 1, meets all
  frame.add(2, lo, hi, 0x2, 0x2);         // group 2, meets only group 2
  frame.add(3, lo, hi, 0x4, 0x1);         // group 4, meets only group 1
  frame.add(4, lo, hi, 0x0, 0xFFFFFFFF);  // group 0: dropped by update(), meets nothing
  BoxSet queries;
  queries.add(0, lo, hi, 0x1, 0xFFFFFFFF);  // meets 1 and 3 (2 refuses group 1)
  queries.add(1, lo, hi, 0x2, 0x2);         // meets only 2
  queries.add(2, lo, hi, 0x1, 0x0);         // mask 0: nothing
  queries.add(3, lo, hi, 0x4, 0x4);         // 3 refuses group 4; 1's group 1 not in mask 4
  const QueryHitList expected = {{0, 1}, {0, 3}, {1, 2}};
  ASSERT_TRUE(sameHits(expected, bruteForceQuery(queries, frame)));
  Broadphase engine;
  engine.update(frame);
  EXPECT_TRUE(sameHits(expected, engine.query(queries)));
  Broadphase scenery_only;
  scenery_only.setStaticBoxes(frame);
  EXPECT_TRUE(sameHits(expected, scenery_only.query(queries)));
}

// Frames of the paper's scenes on every path the engine takes (sweeps, kept candidates,
// reused frames, small frames; frames reused or not), queried after each frame.
TEST(Query, AfterEveryFrameOfMovingScenes) {
  for (SceneKind kind : {SceneKind::kUniform, SceneKind::kBallCluster, SceneKind::kPlaneCluster}) {
    for (bool reuse_unchanged : {false, true}) {
      BroadphaseConfig config = engineConfig(Method::kAuto, 2, 0, 1);
      config.parallel_min_boxes = 500;
      config.reuse_unchanged_frames = reuse_unchanged;
      Broadphase engine(config);
      SceneSimulator scene(movingScene(kind, 7, 2000, 0.25, 30));
      for (int frame = 0; frame < 24; ++frame) {
        const BoxSet boxes = scene.boxes();
        engine.update(boxes);
        if (frame % 6 != 4) scene.step();  // now and then the same frame twice (reused)
        // The world's extent, for query boxes that land in it.
        double low = kInf, high = -kInf;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
          low = std::min(low, boxes.lo(0, i));
          high = std::max(high, boxes.hi(0, i));
        }
        BoxSet queries = queryBoxes(frame % 3 == 0 ? 60 : 3, 1.0, 31 * frame + 1);
        for (int axis = 0; axis < 3; ++axis) {
          for (std::size_t q = 0; q < queries.size(); ++q) {
            queries.lo(axis, q) = low + (high - low) * queries.lo(axis, q);
            queries.hi(axis, q) = low + (high - low) * queries.hi(axis, q);
          }
        }
        expectQueriesMatch(engine, queries, boxes,
                           "scene " + std::to_string(static_cast<int>(kind)) + ", frame " +
                               std::to_string(frame) + ", path " +
                               framePathName(engine.stats().path));
      }
    }
  }
}

TEST(Query, QueryIdsNameTheQueryBoxesAndMayEqualWorldIds) {
  const BoxSet frame = randomBoxes(500, 50.0, 5.0, 3);
  BoxSet queries = queryBoxes(30, 50.0, 4);
  // Sparse, unordered ids, some equal to world ids: the answer is sorted by query id.
  for (std::size_t q = 0; q < queries.size(); ++q)
    queries.ids[q] = static_cast<uint32_t>((q * 7919) % 1000);
  Broadphase engine;
  engine.update(frame);
  const QueryHitList answer = engine.query(queries);
  EXPECT_TRUE(sameHits(bruteForceQuery(queries, frame), answer));
  EXPECT_TRUE(std::is_sorted(answer.begin(), answer.end()));
}

TEST(Query, RecordsAreQueryIndexes) {
  const BoxSet frame = randomBoxes(800, 50.0, 5.0, 5);
  const BoxSet queries = queryBoxes(25, 50.0, 6);
  std::vector<double> bounds;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    for (int axis = 0; axis < 3; ++axis) bounds.push_back(queries.lo(axis, q));
    for (int axis = 0; axis < 3; ++axis) bounds.push_back(queries.hi(axis, q));
  }
  BoxSpan records;
  records.count = queries.size();
  records.bounds = bounds.data();
  Broadphase engine;
  engine.update(frame);
  EXPECT_TRUE(sameHits(bruteForceQuery(queries, frame), engine.query(records)));
}

TEST(Query, BadQueryBoxesAreRefusedWithValidatesWordsAndChangeNothing) {
  const BoxSet frame = randomBoxes(300, 20.0, 3.0, 8);
  const BoxSet good = queryBoxes(10, 20.0, 9);
  Broadphase engine;
  engine.update(frame);
  const QueryHitList before = engine.query(good);
  for (int problem = 0; problem < 3; ++problem) {
    BoxSet bad = good;
    if (problem == 0) bad.hi(1, 4) = std::nan("");
    if (problem == 1) bad.lo(2, 6) = bad.hi(2, 6) + 1.0;
    if (problem == 2) bad.ids[7] = bad.ids[2];
    const std::optional<ValidationError> expected = validate(bad);
    ASSERT_TRUE(expected.has_value());
    try {
      engine.query(bad);
      ADD_FAILURE() << "query box problem " << problem << " was not refused";
    } catch (const InvalidBoxes& refusal) {
      EXPECT_EQ(expected->message(), refusal.what());
      EXPECT_EQ(expected->index, refusal.error().index);
    }
  }
  EXPECT_TRUE(sameHits(before, engine.query(good)));
  const PairList pairs = engine.update(frame);
  EXPECT_TRUE(test_support::samePairs(bruteForcePairs(frame), pairs));
}

// Boxes [i, i + 0.5] in x, none touching another; a query box [-1, inCount] meets them all.
BoxSet disjointRow(std::size_t inCount) {
  BoxSet boxes;
  for (std::size_t i = 0; i < inCount; ++i) {
    const double lo[3] = {static_cast<double>(i), 0.0, 0.0};
    const double hi[3] = {i + 0.5, 1.0, 1.0};
    boxes.add(static_cast<uint32_t>(i), lo, hi);
  }
  return boxes;
}

BoxSet queriesOverRow(std::size_t inQueries, std::size_t inRow) {
  BoxSet queries;
  for (std::size_t q = 0; q < inQueries; ++q) {
    const double lo[3] = {-1.0, 0.0, 0.0};
    const double hi[3] = {static_cast<double>(inRow), 1.0, 1.0};
    queries.add(static_cast<uint32_t>(q), lo, hi);
  }
  return queries;
}

TEST(Query, MoreHitsThanTheBoundAreRefusedOnScansAndIndexes) {
  // Scanned: few query boxes (the first scans of a frame), each meeting the whole frame.
  const std::size_t row = kMaxQueryHits / 40 + 1;
  const BoxSet frame = disjointRow(row);
  const BoxColumns frame_columns = columnsOf(frame);
  FrameQuery frame_query;
  frame_query.setFrame(frame_columns);
  const ThreadsScope two_threads(2);
  PairList hits;
  EXPECT_THROW(frame_query.query(columnsOf(queriesOverRow(40, row)), hits), std::length_error);
  EXPECT_FALSE(frame_query.indexed()) << "40 query boxes are scanned";

  // Indexed (many query boxes), through the engine: refused naming the bound, then the engine
  // answers as before.
  const std::size_t side = 4097;  // 4097^2 hits, past 2^24
  BroadphaseConfig config;
  config.threads = 2;
  Broadphase engine(config);
  const BoxSet world = disjointRow(side);
  EXPECT_TRUE(engine.update(world).empty());
  try {
    engine.query(queriesOverRow(side, side));
    ADD_FAILURE() << side * side << " hits were answered, past kMaxQueryHits";
  } catch (const std::length_error& refusal) {
    EXPECT_NE(std::string(refusal.what()).find(std::to_string(kMaxQueryHits)), std::string::npos)
        << refusal.what();
  }
  const BoxSet one = queriesOverRow(1, side);
  EXPECT_TRUE(sameHits(bruteForceQuery(one, world), engine.query(one)));
}

TEST(Query, TheWorldIsTheLastFrameThatReturned) {
  const BoxSet frame = randomBoxes(400, 20.0, 3.0, 10);
  const BoxSet scenery = renumbered(randomBoxes(100, 20.0, 3.0, 11), kSceneryIds);
  const BoxSet queries = queryBoxes(8, 20.0, 12);
  Broadphase engine;
  engine.setStaticBoxes(scenery);
  EXPECT_TRUE(sameHits(bruteForceQuery(queries, scenery), engine.query(queries)))
      << "before the first frame: the scenery alone";
  engine.update(frame);
  const QueryHitList with_frame = bruteForceQuery(queries, joined(frame, scenery));
  EXPECT_TRUE(sameHits(with_frame, engine.query(queries)));
  engine.reset();
  EXPECT_TRUE(sameHits(with_frame, engine.query(queries))) << "reset() keeps the world";
  // A frame of records refused half-way: the world is the scenery alone until the next frame.
  std::vector<double> bounds(6 * frame.size(), 1.0);
  bounds[6 * 200 + 0] = 2.0;  // min_x > max_x of box 200
  BoxSpan records;
  records.count = frame.size();
  records.bounds = bounds.data();
  EXPECT_THROW(engine.update(records), InvalidBoxes);
  EXPECT_TRUE(sameHits(bruteForceQuery(queries, scenery), engine.query(queries)))
      << "after a refused frame";
  engine.clearStaticBoxes();
  engine.update(frame);
  EXPECT_TRUE(sameHits(bruteForceQuery(queries, frame), engine.query(queries)))
      << "without scenery";
}

// A burst of one large frame, then small frames until the engine gives its buffers back (the
// frame's query index among them): every frame's queries still match the oracle.
TEST(Query, AfterMemoryIsGivenBack) {
  Broadphase engine(engineConfig(Method::kAuto, 2, 0, 1));
  const BoxSet burst = randomBoxes(70000, 400.0, 4.0, 30);
  engine.update(burst);
  const BoxSet burst_queries = queryBoxes(60, 400.0, 31);
  expectQueriesMatch(engine, burst_queries, burst, "the burst");
  for (int frame = 0; frame < 70; ++frame) {
    const BoxSet boxes = randomBoxes(500, 40.0, 4.0, 100 + frame);
    engine.update(boxes);
    expectQueriesMatch(engine, queryBoxes(60, 40.0, 200 + frame), boxes,
                       "small frame " + std::to_string(frame));
  }
}

// Between frames, queries run on other threads, several at once, while the thread that calls
// update() waits for them (the documented contract: queries never overlap update()).
TEST(Query, QueriesFromOtherThreadsBetweenFrames) {
  SceneSimulator scene(movingScene(SceneKind::kUniform, 21, 6000, 0.2, 10));
  BroadphaseConfig config = engineConfig(Method::kAuto, 2, 0, 1);
  Broadphase engine(config);
  for (int frame = 0; frame < 5; ++frame) {
    const BoxSet boxes = scene.boxes();
    engine.update(boxes);
    scene.step();
    std::vector<QueryHitList> expected(4), answers(4);
    std::vector<BoxSet> queries(4);
    for (int k = 0; k < 4; ++k) {
      queries[k] = renumbered(randomBoxes(k == 3 ? 80 : 2 + k, 1.0, 0.3, 100 * frame + k), 0);
      for (int axis = 0; axis < 3; ++axis) {
        for (std::size_t q = 0; q < queries[k].size(); ++q) {
          queries[k].lo(axis, q) = 2.0 * queries[k].lo(axis, q) - 1.0;
          queries[k].hi(axis, q) = 2.0 * queries[k].hi(axis, q) - 1.0;
        }
      }
      expected[k] = bruteForceQuery(queries[k], boxes);
    }
    std::vector<std::thread> askers;
    for (int k = 0; k < 4; ++k)
      askers.emplace_back([&, k] { answers[k] = engine.query(queries[k]); });
    for (std::thread& asker : askers) asker.join();
    for (int k = 0; k < 4; ++k)
      EXPECT_TRUE(sameHits(expected[k], answers[k])) << "frame " << frame << ", asker " << k;
  }
}

}  // namespace
}  // namespace sap_broadphase
