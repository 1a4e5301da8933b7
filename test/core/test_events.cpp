// Contact events (Broadphase::events()) against the oracle: on every frame of multi-frame runs,
// the set differences of consecutive brute-force pair lists, on every path and thread count,
// with scenery, reset() and refused frames; and the merge that finds them on its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/frame/contact_events.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::engineConfig;
using test_support::movingScene;
using test_support::PathCounts;
using test_support::samePairs;

/// Pairs of inFrom absent from inWithout: the oracle's side of an event list.
PairList difference(const PairList& inFrom, const PairList& inWithout) {
  PairList out;
  std::set_difference(inFrom.begin(), inFrom.end(), inWithout.begin(), inWithout.end(),
                      std::back_inserter(out));
  return out;
}

/// The engine's events equal the set differences between inBefore and inNow.
::testing::AssertionResult sameEvents(const PairList& inBefore, const PairList& inNow,
                                      const ContactEvents& inEvents) {
  const auto began = samePairs(difference(inNow, inBefore), inEvents.began);
  if (!began) return ::testing::AssertionFailure() << "began: " << began.message();
  const auto ended = samePairs(difference(inBefore, inNow), inEvents.ended);
  if (!ended) return ::testing::AssertionFailure() << "ended: " << ended.message();
  return ::testing::AssertionSuccess();
}

/// The oracle of a frame with scenery: every pair of the moving boxes and the scenery together,
/// less the scenery x scenery pairs (the engine never reports those).
PairList oracleWithScenery(const BoxSet& inMoving, const BoxSet& inScenery) {
  BoxSet all = inMoving;
  for (std::size_t i = 0; i < inScenery.size(); ++i) {
    const double lo[3] = {inScenery.lo(0, i), inScenery.lo(1, i), inScenery.lo(2, i)};
    const double hi[3] = {inScenery.hi(0, i), inScenery.hi(1, i), inScenery.hi(2, i)};
    all.add(inScenery.ids[i], lo, hi);
  }
  std::vector<uint32_t> scenery_ids = inScenery.ids;
  std::sort(scenery_ids.begin(), scenery_ids.end());
  const auto is_scenery = [&](uint32_t inId) {
    return std::binary_search(scenery_ids.begin(), scenery_ids.end(), inId);
  };
  PairList pairs = bruteForcePairs(all);
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](const IdPair& p) { return is_scenery(p.a) && is_scenery(p.b); }),
              pairs.end());
  return pairs;
}

/// Frame inFrame of a run: the scene's boxes, with now and then a frame repeated (reuse), a box
/// added (new ids), boxes dropped, a jump out of any skin, or fewer than two boxes.
BoxSet frameOf(const SceneSimulator& inScene, int inFrame) {
  BoxSet boxes = inScene.boxes();
  if (inFrame % 11 == 4) {
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    boxes.add(800000 + inFrame, lo, hi);
  }
  if (inFrame % 7 == 5) boxes.hi(0, 3) += 8.0;
  if (inFrame % 13 == 9) {  // every third box left out: ids change, pairs end
    BoxSet kept;
    for (std::size_t i = 0; i < boxes.size(); i += 3) {
      const double lo[3] = {boxes.lo(0, i), boxes.lo(1, i), boxes.lo(2, i)};
      const double hi[3] = {boxes.hi(0, i), boxes.hi(1, i), boxes.hi(2, i)};
      kept.add(boxes.ids[i], lo, hi);
    }
    boxes = kept;
  }
  if (inFrame == 20) boxes = BoxSet();  // no box: every pair ends
  return boxes;
}

// ---- The merge on its own ----

TEST(DiffPairLists, EqualsTheSetDifferencesOnRandomLists) {
  std::mt19937_64 random(17);
  ContactEvents events;
  for (int round = 0; round < 400; ++round) {
    // Lists sharing long runs (a steady frame), or hardly anything, of 0..3000 pairs.
    const std::size_t size = random() % 3000;
    const int change_per_mille = round % 4 == 0 ? 900 : static_cast<int>(random() % 40);
    PairList before, now;
    for (std::size_t i = 0; i < size; ++i) {
      const IdPair pair{static_cast<uint32_t>(i / 5), static_cast<uint32_t>(i + 1 + i / 5)};
      const int draw = static_cast<int>(random() % 1000);
      if (draw < change_per_mille / 2) {
        before.push_back(pair);
      } else if (draw < change_per_mille) {
        now.push_back(pair);
      } else {
        before.push_back(pair);
        now.push_back(pair);
      }
    }
    // Ids above 2^31: the 64-bit key must order them as unsigned.
    if (round % 3 == 0) now.push_back({0xFFFFFFF0u, 0xFFFFFFFFu});
    ASSERT_TRUE(isCanonical(before) && isCanonical(now));
    diffPairLists(before, now, events);
    ASSERT_TRUE(sameEvents(before, now, events)) << "round " << round;
  }
}

TEST(DiffPairLists, EmptySidesAndReusedBuffers) {
  const PairList some = {{0, 1}, {0, 2}, {5, 9}};
  ContactEvents events;
  diffPairLists({}, some, events);
  EXPECT_TRUE(sameEvents({}, some, events));
  diffPairLists(some, {}, events);
  EXPECT_TRUE(sameEvents(some, {}, events));
  diffPairLists(some, some, events);
  EXPECT_TRUE(events.began.empty() && events.ended.empty());
}

// ---- The engine over moving frames ----

/// One engine of the matrix: a configuration and the label of its failures.
struct EngineCase {
  BroadphaseConfig config;
  std::string label;
};

/// Every method, with the skin off, fixed and automatic, at thread counts 1-4; the parallel
/// sweep taken from 1000 boxes on, reuse of unchanged frames on and off.
std::vector<EngineCase> everyPathAndThreadCount() {
  std::vector<EngineCase> cases;
  for (Method method :
       {Method::kAuto, Method::kSequential, Method::kParallel, Method::kBruteForce}) {
    for (int threads = 1; threads <= 4; ++threads) {
      if (method == Method::kSequential && threads > 1) continue;
      if (method == Method::kBruteForce && threads > 1) continue;
      for (int skin = 0; skin < 3; ++skin) {
        BroadphaseConfig config = engineConfig(method, threads, threads % 3, (threads + 1) % 3);
        if (skin == 0) config.skin = 0.0;
        if (skin == 1) config.skin = 0.4;
        config.parallel_min_boxes = 1000;
        config.reuse_unchanged_frames = skin != 1;
        cases.push_back({config, test_support::describe(config)});
      }
    }
  }
  return cases;
}

TEST(EngineEvents, EqualTheOracleOnEveryFrameEveryPathAndThreadCount) {
  const std::vector<EngineCase> cases = everyPathAndThreadCount();
  PathCounts paths;
  for (SceneKind kind : {SceneKind::kUniform, SceneKind::kBallCluster, SceneKind::kPlaneCluster}) {
    for (uint64_t seed : {3u, 8u}) {
      const std::size_t boxes = kind == SceneKind::kUniform ? 2500 : 1500;
      SceneSimulator scene(movingScene(kind, seed, boxes, 0.25, 40));
      std::vector<Broadphase> engines;
      for (const EngineCase& engine_case : cases) engines.emplace_back(engine_case.config);
      PairList before;
      for (int frame = 0; frame < 26; ++frame) {
        const BoxSet boxes_now = frameOf(scene, frame);
        const PairList now = bruteForcePairs(boxes_now);
        for (std::size_t e = 0; e < engines.size(); ++e) {
          ASSERT_TRUE(samePairs(now, engines[e].update(boxes_now)));
          paths.add(engines[e].stats());
          ASSERT_TRUE(sameEvents(before, now, engines[e].events()))
              << cases[e].label << ", scene " << int(kind) << " seed " << seed << " frame " << frame
              << ", path " << framePathName(engines[e].stats().path);
        }
        before = now;
        if (frame % 6 != 2) scene.step();  // else the next frame repeats this one
      }
    }
  }
  // Each path ran, so none passes by never being taken.
  for (FramePath path :
       {FramePath::kEmpty, FramePath::kReused, FramePath::kBruteForce, FramePath::kSkin,
        FramePath::kSmallFrame, FramePath::kSequential, FramePath::kParallel})
    EXPECT_GT(paths[path], 0) << framePathName(path) << " never ran: " << paths.summary();
}

TEST(EngineEvents, FirstFrameBeginsEveryPairAndResetStartsOver) {
  SceneSimulator scene(movingScene(SceneKind::kUniform, 21, 2000, 0.3, 20));
  for (int threads = 1; threads <= 4; ++threads) {
    Broadphase engine(engineConfig(Method::kAuto, threads, 0, 1));
    EXPECT_TRUE(engine.events().began.empty() && engine.events().ended.empty());
    const PairList first = bruteForcePairs(scene.boxes());
    ASSERT_FALSE(first.empty());
    engine.update(scene.boxes());
    EXPECT_TRUE(sameEvents({}, first, engine.events())) << "first frame, threads " << threads;
    engine.update(scene.boxes());  // the same frame again: nothing changes
    EXPECT_TRUE(sameEvents(first, first, engine.events())) << "threads " << threads;
    engine.reset();
    EXPECT_TRUE(engine.events().began.empty() && engine.events().ended.empty());
    engine.update(scene.boxes());
    EXPECT_TRUE(sameEvents({}, first, engine.events())) << "after reset(), threads " << threads;
  }
}

// A first frame's events are copied from its pair list only when asked for: asked by several
// threads at once they are the same complete list for each, and a frame that nobody asked
// leaves nothing behind for the next one.
TEST(EngineEvents, FirstFrameEventsAskedConcurrentlyOrNeverAreRight) {
  SceneSimulator scene(movingScene(SceneKind::kUniform, 22, 3000, 0.3, 5));
  Broadphase engine(engineConfig(Method::kAuto, 2, 0, 1));
  const PairList first = bruteForcePairs(scene.boxes());
  ASSERT_FALSE(first.empty());
  engine.update(scene.boxes());
  std::vector<std::size_t> began(4, 0);
  std::vector<std::thread> readers;
  for (std::size_t r = 0; r < began.size(); ++r)
    readers.emplace_back([&, r] { began[r] = engine.events().began.size(); });
  for (std::thread& reader : readers) reader.join();
  for (std::size_t r = 0; r < began.size(); ++r) EXPECT_EQ(began[r], first.size()) << r;
  EXPECT_TRUE(sameEvents({}, first, engine.events()));
  engine.reset();
  engine.update(scene.boxes());  // a first frame again, its events never asked for
  scene.step();
  const PairList second = bruteForcePairs(scene.boxes());
  engine.update(scene.boxes());
  EXPECT_TRUE(sameEvents(first, second, engine.events()));
}

TEST(EngineEvents, SceneryChangesShowAtTheNextUpdate) {
  SceneSimulator scene(movingScene(SceneKind::kUniform, 5, 2400, 0.3, 40));
  // Every fourth box of the first frame becomes scenery under new ids; the rest move.
  BoxSet scenery, other_scenery;
  for (std::size_t i = 0; i < scene.boxes().size(); i += 4) {
    const BoxSet& b = scene.boxes();
    const double lo[3] = {b.lo(0, i), b.lo(1, i), b.lo(2, i)};
    const double hi[3] = {b.hi(0, i), b.hi(1, i), b.hi(2, i)};
    scenery.add(1000000 + static_cast<uint32_t>(i), lo, hi);
    const double shifted_lo[3] = {lo[0] + 0.3, lo[1], lo[2]};
    const double shifted_hi[3] = {hi[0] + 0.3, hi[1], hi[2]};
    other_scenery.add(2000000 + static_cast<uint32_t>(i), shifted_lo, shifted_hi);
  }
  for (int threads = 1; threads <= 4; ++threads) {
    for (Method method : {Method::kAuto, Method::kParallel, Method::kSequential}) {
      BroadphaseConfig config = engineConfig(method, threads, 1, 2);
      config.parallel_min_boxes = 1000;
      Broadphase engine(config);
      SceneSimulator moving(movingScene(SceneKind::kUniform, 6 + threads, 2000, 0.3, 40));
      const BoxSet none;
      const BoxSet* in_force = &none;
      PairList before;
      for (int frame = 0; frame < 16; ++frame) {
        if (frame == 3) {
          engine.setStaticBoxes(scenery);
          in_force = &scenery;
        }
        if (frame == 7) {
          engine.setStaticBoxes(other_scenery);
          in_force = &other_scenery;
        }
        if (frame == 11) {
          engine.clearStaticBoxes();
          in_force = &none;
        }
        const PairList now = oracleWithScenery(moving.boxes(), *in_force);
        ASSERT_TRUE(samePairs(now, engine.update(moving.boxes())));
        ASSERT_TRUE(sameEvents(before, now, engine.events()))
            << test_support::describe(config) << ", frame " << frame;
        before = now;
        if (frame % 5 != 1) moving.step();
      }
    }
  }
}

TEST(EngineEvents, ARefusedFrameReportsNoneAndTheNextComparesWithTheLastList) {
  SceneSimulator scene(movingScene(SceneKind::kBallCluster, 12, 2000, 0.3, 40));
  for (int threads = 1; threads <= 4; ++threads) {
    for (Method method : {Method::kAuto, Method::kParallel}) {
      BroadphaseConfig config = engineConfig(method, threads, 0, 2);
      config.parallel_min_boxes = 1000;
      Broadphase engine(config);
      engine.update(scene.boxes());
      scene.step();
      const PairList last = bruteForcePairs(scene.boxes());
      engine.update(scene.boxes());
      scene.step();
      BoxSet bad = scene.boxes();
      bad.lo(1, 17) = std::numeric_limits<double>::quiet_NaN();
      EXPECT_THROW(engine.update(bad), InvalidBoxes);
      EXPECT_TRUE(engine.events().began.empty() && engine.events().ended.empty())
          << test_support::describe(config);
      scene.step();
      const PairList now = bruteForcePairs(scene.boxes());
      ASSERT_TRUE(samePairs(now, engine.update(scene.boxes())));
      EXPECT_TRUE(sameEvents(last, now, engine.events()))
          << "after a refused frame, " << test_support::describe(config);
      // A frame that shares an id with the scenery is refused too, the same way.
      BoxSet scenery;
      const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
      scenery.add(scene.boxes().ids[0], lo, hi);
      engine.setStaticBoxes(scenery);
      EXPECT_THROW(engine.update(scene.boxes()), InvalidBoxes);
      EXPECT_TRUE(engine.events().began.empty() && engine.events().ended.empty());
      engine.clearStaticBoxes();
      scene.step();
      const PairList later = bruteForcePairs(scene.boxes());
      ASSERT_TRUE(samePairs(later, engine.update(scene.boxes())));
      EXPECT_TRUE(sameEvents(now, later, engine.events()))
          << "after a frame refused for the scenery's ids, " << test_support::describe(config);
    }
  }
}

}  // namespace
}  // namespace sap_broadphase
