// The paper's test scenes (§6, §7), deterministic from a seed on every platform.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sap_broadphase/core/box_set.h"

namespace sap_broadphase {

enum class SceneKind : uint8_t {
  kUniform,       ///< §6: boxes of varying edges, constant velocities, bouncing off the world
  kBallCluster,   ///< §7 Fig. 5: boxes in a ball head for its centre, pack, then spread
  kPlaneCluster,  ///< §7 Fig. 6: grid in two axes, all crossing the plane u = 0 mid-run
};

/// Parses "uniform", "ball" or "plane"; returns false on anything else.
bool parseSceneKind(const std::string& inName, SceneKind& outKind);

struct SceneConfig {
  SceneKind kind = SceneKind::kUniform;
  std::size_t n = 1000;   ///< boxes (plane: rounded down to a square grid side^2)
  double density = 0.05;  ///< uniform: sum of box volumes / world volume
  uint64_t seed = 1;
  int plane_axis = 0;   ///< plane: the axis u that all boxes cross at mid-run
  int frames = 500;     ///< ball and plane: run length the motion is timed for
  double speed = 0.05;  ///< uniform: mean distance per frame, in mean box edges
};

/// A running scene: boxes() is frame frame(); step() advances one frame.
class SceneSimulator {
 public:
  explicit SceneSimulator(const SceneConfig& inConfig);
  /// The current frame's boxes (ids 0..n-1).
  const BoxSet& boxes() const { return boxes_; }
  /// Index of the current frame (0 after construction).
  int frame() const { return frame_; }
  /// Advances the motion by one frame.
  void step();
  /// Advances to frame inFrame (>= frame()).
  void advanceTo(int inFrame);

 private:
  void writeBoxes();

  SceneConfig config_;
  int frame_ = 0;
  double world_half_ = 1.0;          // world cube is [-world_half_, world_half_]^3
  std::vector<double> center_[3];    // uniform: current centre; ball/plane: start centre
  std::vector<double> velocity_[3];  // uniform: per frame
  std::vector<double> half_extent_[3];
  BoxSet boxes_;
};

/// Frame inFrame of the scene described by inConfig.
BoxSet makeSceneFrame(const SceneConfig& inConfig, int inFrame);

}  // namespace sap_broadphase
