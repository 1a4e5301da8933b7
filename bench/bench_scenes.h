// The scenes the experiments use: the engine's generators with the paper's parameters, and one
// adversarial box set of the harness's own (exactly touching and nearly touching cubes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/scenes.h"

namespace sap_bench {

/// §6 uniform scene: n boxes at density d.
sap_broadphase::SceneConfig uniformScene(std::size_t inCount, double inDensity, uint64_t inSeed);
/// §7 ball cluster over inFrames frames.
sap_broadphase::SceneConfig ballScene(std::size_t inCount, int inFrames, uint64_t inSeed);
/// §7 plane cluster: side^2 boxes crossing u = 0 (inAxis: 0 = x, 1 = y) at mid-run.
sap_broadphase::SceneConfig planeScene(std::size_t inSide, int inAxis, int inFrames,
                                       uint64_t inSeed);

/// The ball cluster's most intense frames: the paper's frames 75..150 of 500, scaled.
int ballIntenseBegin(int inFrames);
int ballIntenseEnd(int inFrames);
/// The plane cluster's crossing: the paper's frames 225..275 of 500, scaled.
int planeCrossBegin(int inFrames);
int planeCrossEnd(int inFrames);

/// A cubic lattice of about inCount unit cubes; neighbours along x and z touch exactly
/// (closed intervals: a pair), neighbours along y miss by a gap of 1e-9 (no pair) — far below
/// a float32 key's resolution, so a keys-only test reports every such near miss.
sap_broadphase::BoxSet touchingLattice(std::size_t inCount);

/// Consecutive frames of a scene from a given frame on, or one fixed box set repeated.
class FrameFeed {
 public:
  /// Frames inFirstFrame, inFirstFrame + 1, ... of the scene.
  FrameFeed(const sap_broadphase::SceneConfig& inScene, int inFirstFrame);
  /// The same boxes every frame.
  explicit FrameFeed(sap_broadphase::BoxSet inFixed);
  /// The current frame's boxes.
  const sap_broadphase::BoxSet& boxes() const;
  /// Moves to the next frame.
  void step();

 private:
  std::unique_ptr<sap_broadphase::SceneSimulator> simulator_;
  sap_broadphase::BoxSet fixed_;
};

/// A named workload of the peer and accuracy experiments.
struct BenchCase {
  std::string name;   ///< e.g. "uniform d=0.05 n=2^17"
  std::string scene;  ///< "uniform", "ball", "plane", "lattice"
  std::size_t n = 0;
  double density = 0;  ///< uniform only
  std::function<FrameFeed()> makeFeed;
};

/// Uniform frames 0, 1, ... at density inDensity.
BenchCase uniformCase(std::size_t inCount, double inDensity, uint64_t inSeed);
/// Ball-cluster frames from the start of the intense window of an inFrames run.
BenchCase ballCase(std::size_t inCount, int inFrames, uint64_t inSeed);
/// Plane-cluster frames (u = y) from the start of the crossing of an inFrames run.
BenchCase planeCase(std::size_t inSide, int inFrames, uint64_t inSeed);
/// The touching lattice, the same every frame.
BenchCase latticeCase(std::size_t inCount);

}  // namespace sap_bench
