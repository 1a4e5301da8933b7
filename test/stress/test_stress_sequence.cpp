// Temporal state across wildly different frames: one engine per configuration sees every
// stress scene in turn, frames grow and shrink (0, 1, 5000 boxes), and partition bounds from a
// frame at 1e300 meet a frame of subnormals. Every frame must still match the oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "stress_scenes.h"
#include "stress_support.h"
#include "test_support.h"

namespace sap_broadphase::stress {
namespace {

using test_support::randomBoxes;

std::vector<std::pair<std::string, BoxSet>> frameSequence() {
  std::vector<std::pair<std::string, BoxSet>> frames;
  frames.emplace_back("uniform", randomBoxes(5000, 100.0, 3.0, 91));
  frames.emplace_back("empty", BoxSet());
  frames.emplace_back("ulp lattice 1e300", ulpLatticeScene(1e300, 5000, 12, 2, 92));
  frames.emplace_back("subnormals", subnormalScene(5000, 93));
  BoxSet single;
  addBox(single, 4, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
  frames.emplace_back("one box", single);
  frames.emplace_back("infinite slabs", infiniteSlabScene(5000, 94));
  frames.emplace_back("magnitudes", magnitudeScene(5000, 95));
  frames.emplace_back("special values", specialValueScene(5000, 96));
  frames.emplace_back("uniform again", randomBoxes(5000, 100.0, 3.0, 91));
  return frames;
}

TEST(StressSequence, OneEngineSeesEveryScene) {
  const auto frames = frameSequence();
  std::vector<PairList> oracles;
  for (const auto& frame : frames) oracles.push_back(bruteForcePairs(frame.second));
  for (const BroadphaseConfig& config : stressConfigs(Coverage::kPairwise)) {
    Broadphase engine(config);
    for (std::size_t f = 0; f < frames.size(); ++f) {
      EXPECT_TRUE(samePairList(oracles[f], engine.update(frames[f].second)))
          << "frame " << f << " (" << frames[f].first << "), " << describeConfig(config);
    }
  }
}

// A scene drifting far away frame by frame: partition bounds are always one frame stale.
TEST(StressSequence, DriftTowardsLargeCoordinates) {
  const BoxSet base = randomBoxes(4500, 50.0, 2.0, 97);
  BroadphaseConfig config;
  config.method = Method::kParallel;
  config.threads = 3;
  Broadphase engine(config);
  for (int frame = 0; frame < 12; ++frame) {
    const double shift = frame == 0 ? 0.0 : std::ldexp(1.0, 5 * frame);  // up to 2^55
    const double offset[3] = {shift, -shift, shift * 0.5};
    const BoxSet moved = translated(base, offset);
    EXPECT_TRUE(samePairList(bruteForcePairs(moved), engine.update(moved)))
        << "frame " << frame << " shifted by " << shift;
  }
}

}  // namespace
}  // namespace sap_broadphase::stress
