// The bound on a frame's pairs (BroadphaseConfig::max_pairs): a frame with more pairs is
// refused with TooManyPairs on every path, the pairing threads stop within a chunk each past
// the bound, and the engine answers the next frame as the oracle does.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/frame/pair_sort.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"

namespace sap_broadphase {
namespace {

// inCount unit cubes at one place: inCount (inCount - 1) / 2 pairs.
BoxSet pile(std::size_t inCount, uint32_t inFirstId = 0) {
  BoxSet boxes;
  const double lo[3] = {0.0, 0.0, 0.0};
  const double hi[3] = {1.0, 1.0, 1.0};
  for (std::size_t i = 0; i < inCount; ++i) boxes.add(inFirstId + static_cast<uint32_t>(i), lo, hi);
  return boxes;
}

// inCount unit cubes in a row, each touching the next: inCount - 1 pairs.
BoxSet row(std::size_t inCount) {
  BoxSet boxes;
  for (std::size_t i = 0; i < inCount; ++i) {
    const double lo[3] = {static_cast<double>(i), 0.0, 0.0};
    const double hi[3] = {static_cast<double>(i) + 1.0, 1.0, 1.0};
    boxes.add(static_cast<uint32_t>(i), lo, hi);
  }
  return boxes;
}

TEST(PairBound, ChunksStopWithinAChunkPastTheBudget) {
  PairBudget budget(10000);
  PairChunks pairs;
  pairs.setBudget(&budget);
  std::size_t pushed = 0;
  try {
    for (; pushed < (std::size_t{1} << 20); ++pushed) pairs.push_back(IdPair{0, 1});
    ADD_FAILURE() << "2^20 pairs held past a budget of 10000";
  } catch (const TooManyPairs& refusal) {
    EXPECT_EQ(refusal.limit(), 10000u);
    EXPECT_LE(pairs.size(), 10000u + PairChunks::kChunkPairs);
  }
  // Exactly the budget in full chunks passes.
  PairBudget exact(2 * PairChunks::kChunkPairs);
  PairChunks within;
  within.setBudget(&exact);
  for (std::size_t i = 0; i < 3 * PairChunks::kChunkPairs; ++i) within.push_back(IdPair{0, 1});
  EXPECT_EQ(within.size(), 3 * PairChunks::kChunkPairs);  // the third chunk is not full
}

// Every method and thread count: 1500 boxes at one place (1 124 250 pairs) past a bound of
// 50 000 are refused naming it; the engine then answers frames as the oracle does, and a frame
// with exactly the bound's pairs passes.
TEST(PairBound, EveryPathRefusesAFramePastTheBoundAndGoesOn) {
  const BoxSet crowd = pile(1500);
  const BoxSet small = row(100);
  const PairList small_pairs = bruteForcePairs(small);
  for (const Method method : kMethods) {
    for (const int threads : {1, 2, 3}) {
      for (const bool skin : {false, true}) {
        SCOPED_TRACE(std::string(methodName(method)) + " threads " + std::to_string(threads) +
                     (skin ? " skin 0.5" : " no skin"));
        BroadphaseConfig config;
        config.method = method;
        config.threads = threads;
        config.max_pairs = 50000;
        config.parallel_min_boxes = 256;  // auto sweeps the crowd in parallel on 3 threads
        config.skin = skin ? std::optional<double>(0.5) : std::optional<double>(0.0);
        Broadphase engine(config);
        EXPECT_EQ(engine.update(small), small_pairs);
        try {
          engine.update(crowd);
          ADD_FAILURE() << "a frame of 1124250 pairs passed max_pairs 50000";
        } catch (const TooManyPairs& refusal) {
          EXPECT_EQ(refusal.limit(), 50000u);
          EXPECT_NE(std::string(refusal.what()).find("more than 50000 pairs (max_pairs)"),
                    std::string::npos)
              << refusal.what();
        }
        // The refused frame reported no events; the next one compares with the last list
        // returned (the small frame's), which it equals.
        EXPECT_TRUE(engine.events().began.empty() && engine.events().ended.empty());
        EXPECT_EQ(engine.update(small), small_pairs);
        EXPECT_TRUE(engine.events().began.empty() && engine.events().ended.empty());
        // The refused frame left no world for queries: the small frame is it now.
        EXPECT_EQ(engine.query(pile(1, 7)).size(), 2u);  // boxes 0 and 1 touch the cube at 0
        // At the bound exactly: accepted.
        config.max_pairs = 1124250;
        Broadphase at_bound(config);
        EXPECT_EQ(at_bound.update(crowd).size(), 1124250u);
      }
    }
  }
}

// The pairs with the declared scenery count too: 40 frame boxes over 40 scenery boxes at one
// place have 780 pairs among them and 1600 with the scenery.
TEST(PairBound, PairsWithTheSceneryCount) {
  BroadphaseConfig config;
  config.max_pairs = 2000;
  Broadphase engine(config);
  engine.setStaticBoxes(pile(40, 1000));
  EXPECT_THROW(engine.update(pile(40)), TooManyPairs);
  config.max_pairs = 2380;
  Broadphase at_bound(config);
  at_bound.setStaticBoxes(pile(40, 1000));
  EXPECT_EQ(at_bound.update(pile(40)).size(), 2380u);
  // Without the scenery the refused engine answers the frame.
  engine.clearStaticBoxes();
  EXPECT_EQ(engine.update(pile(40)).size(), 780u);
}

TEST(PairBound, TheBoundIsAConfigurationField) {
  BroadphaseConfig config;
  EXPECT_EQ(config.max_pairs, kDefaultMaxPairs);
  config.max_pairs = 0;
  EXPECT_THROW(Broadphase{config}, std::invalid_argument);
  const ConfigField* field = findConfigField("max_pairs");
  ASSERT_NE(field, nullptr);
  EXPECT_EQ(std::string(field->default_text), std::to_string(kDefaultMaxPairs));
}

}  // namespace
}  // namespace sap_broadphase
