// Scene parameters of the experiments.
#include "bench_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "bench_table.h"

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::SceneConfig;
using sap_broadphase::SceneKind;

SceneConfig uniformScene(std::size_t inCount, double inDensity, uint64_t inSeed) {
  SceneConfig config;
  config.kind = SceneKind::kUniform;
  config.n = inCount;
  config.density = inDensity;
  config.seed = inSeed;
  return config;
}

SceneConfig ballScene(std::size_t inCount, int inFrames, uint64_t inSeed) {
  SceneConfig config;
  config.kind = SceneKind::kBallCluster;
  config.n = inCount;
  config.frames = inFrames;
  config.seed = inSeed;
  return config;
}

SceneConfig planeScene(std::size_t inSide, int inAxis, int inFrames, uint64_t inSeed) {
  SceneConfig config;
  config.kind = SceneKind::kPlaneCluster;
  config.n = inSide * inSide;
  config.plane_axis = inAxis;
  config.frames = inFrames;
  config.seed = inSeed;
  return config;
}

int ballIntenseBegin(int inFrames) {
  return inFrames * 75 / 500;
}
int ballIntenseEnd(int inFrames) {
  return inFrames * 150 / 500;
}
int planeCrossBegin(int inFrames) {
  return inFrames * 225 / 500;
}
int planeCrossEnd(int inFrames) {
  return inFrames * 275 / 500;
}

BoxSet touchingLattice(std::size_t inCount) {
  const int side = std::max(2, static_cast<int>(std::cbrt(static_cast<double>(inCount))));
  const double gap = 1e-9;
  BoxSet boxes;
  boxes.reserve(static_cast<std::size_t>(side) * side * side);
  uint32_t id = 0;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      for (int k = 0; k < side; ++k) {
        const double lo[3] = {1.0 * i, (1.0 + gap) * j, 1.0 * k};
        const double hi[3] = {lo[0] + 1.0, lo[1] + 1.0, lo[2] + 1.0};
        boxes.add(id++, lo, hi);
      }
    }
  }
  return boxes;
}

FrameFeed::FrameFeed(const SceneConfig& inScene, int inFirstFrame)
    : simulator_(std::make_unique<sap_broadphase::SceneSimulator>(inScene)) {
  simulator_->advanceTo(inFirstFrame);
}

FrameFeed::FrameFeed(BoxSet inFixed) : fixed_(std::move(inFixed)) {}

const BoxSet& FrameFeed::boxes() const {
  return simulator_ ? simulator_->boxes() : fixed_;
}

void FrameFeed::step() {
  if (simulator_) simulator_->step();
}

BenchCase uniformCase(std::size_t inCount, double inDensity, uint64_t inSeed) {
  const SceneConfig scene = uniformScene(inCount, inDensity, inSeed);
  char density[16];
  std::snprintf(density, sizeof(density), "%.2f", inDensity);
  return {"uniform d=" + std::string(density) + " n=" + fmtSize(inCount), "uniform", inCount,
          inDensity, [scene] { return FrameFeed(scene, 0); }};
}

BenchCase ballCase(std::size_t inCount, int inFrames, uint64_t inSeed) {
  const SceneConfig scene = ballScene(inCount, inFrames, inSeed);
  const int first = ballIntenseBegin(inFrames);
  return {"ball n=" + fmtSize(inCount) + " f" + std::to_string(first), "ball", inCount, 0.0,
          [scene, first] { return FrameFeed(scene, first); }};
}

BenchCase planeCase(std::size_t inSide, int inFrames, uint64_t inSeed) {
  const SceneConfig scene = planeScene(inSide, 1, inFrames, inSeed);
  const int first = planeCrossBegin(inFrames);
  return {"plane u=y " + std::to_string(inSide) + "^2 f" + std::to_string(first), "plane",
          inSide * inSide, 0.0, [scene, first] { return FrameFeed(scene, first); }};
}

BenchCase latticeCase(std::size_t inCount) {
  BoxSet boxes = touchingLattice(inCount);
  const std::size_t n = boxes.size();
  auto shared = std::make_shared<BoxSet>(std::move(boxes));
  return {"lattice n=" + std::to_string(n), "lattice", n, 0.0,
          [shared] { return FrameFeed(*shared); }};
}

}  // namespace sap_bench
