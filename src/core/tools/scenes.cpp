#include "sap_broadphase/core/scenes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/tools/random.h"

namespace sap_broadphase {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A uniformly distributed unit vector.
void randomDirection(SplitMix64& ioRandom, double outVector[3]) {
  const double z = ioRandom.between(-1.0, 1.0);
  const double angle = ioRandom.between(0.0, 2.0 * kPi);
  const double radius = std::sqrt(std::max(0.0, 1.0 - z * z));
  outVector[0] = radius * std::cos(angle);
  outVector[1] = radius * std::sin(angle);
  outVector[2] = z;
}

// Ball cluster timing, as fractions of the run: contract until kPackedAt, hold, then spread.
constexpr double kPackedAt = 0.2;
constexpr double kSpreadFrom = 0.24;
// Packed ball: boxes fill about half its volume; the start ball has 4x its radius.
constexpr double kPackedFill = 0.5;
constexpr double kStartRadiusFactor = 4.0;
// Plane cluster: cubes almost touch their grid neighbours (gap of 5% of the spacing).
constexpr double kPlaneCubeEdge = 0.95;

}  // namespace

bool parseSceneKind(const std::string& inName, SceneKind& outKind) {
  if (inName == "uniform")
    outKind = SceneKind::kUniform;
  else if (inName == "ball")
    outKind = SceneKind::kBallCluster;
  else if (inName == "plane")
    outKind = SceneKind::kPlaneCluster;
  else
    return false;
  return true;
}

SceneSimulator::SceneSimulator(const SceneConfig& inConfig) : config_(inConfig) {
  if (config_.plane_axis < 0 || config_.plane_axis > 2)
    throw std::invalid_argument("plane axis must be 0, 1 or 2");
  if (config_.kind == SceneKind::kUniform && !(config_.density > 0.0))
    throw std::invalid_argument("density must be > 0");
  if (config_.frames < 2) throw std::invalid_argument("frames must be >= 2");
  SplitMix64 random(config_.seed);
  std::size_t n = config_.n;
  std::size_t side = 0;
  if (config_.kind == SceneKind::kPlaneCluster) {
    side = static_cast<std::size_t>(std::sqrt(static_cast<double>(n)));
    while ((side + 1) * (side + 1) <= n) ++side;
    n = side * side;
  }
  for (int axis = 0; axis < 3; ++axis) {
    center_[axis].resize(n);
    velocity_[axis].assign(n, 0.0);
    half_extent_[axis].resize(n);
  }
  switch (config_.kind) {
    case SceneKind::kUniform: {
      // Mean edge 1 on each axis (uniform in [0.5, 1.5]), so the mean volume is 1 and the
      // world's volume is n / density.
      world_half_ = 0.5 * std::cbrt(static_cast<double>(n) / config_.density);
      for (std::size_t i = 0; i < n; ++i) {
        double direction[3];
        randomDirection(random, direction);
        const double speed = config_.speed * random.between(0.5, 1.5);
        for (int axis = 0; axis < 3; ++axis) {
          const double half = 0.5 * random.between(0.5, 1.5);
          half_extent_[axis][i] = half;
          const double room = std::max(0.0, world_half_ - half);
          center_[axis][i] = random.between(-room, room);
          velocity_[axis][i] = speed * direction[axis];
        }
      }
      break;
    }
    case SceneKind::kBallCluster: {
      const double packed_radius = std::cbrt(3.0 * n / (4.0 * kPi * kPackedFill));
      world_half_ = kStartRadiusFactor * packed_radius;
      for (std::size_t i = 0; i < n; ++i) {
        double direction[3];
        randomDirection(random, direction);
        const double radius = world_half_ * std::cbrt(random.unit());
        // velocity_ holds each box's final spread factor (how far out it ends), in [1, 2).
        const double spread = random.between(1.0, 2.0);
        for (int axis = 0; axis < 3; ++axis) {
          half_extent_[axis][i] = 0.5 * random.between(0.5, 1.5);
          center_[axis][i] = radius * direction[axis];
          velocity_[axis][i] = spread;
        }
      }
      break;
    }
    case SceneKind::kPlaneCluster: {
      const int u = config_.plane_axis;
      const int v = (u + 1) % 3;
      const int w = (u + 2) % 3;
      world_half_ = 0.5 * static_cast<double>(side);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t row = i / side;
        const std::size_t column = i % side;
        center_[v][i] = -world_half_ + 0.5 + static_cast<double>(row);
        center_[w][i] = -world_half_ + 0.5 + static_cast<double>(column);
        center_[u][i] = random.between(-world_half_, world_half_);
        for (int axis = 0; axis < 3; ++axis) half_extent_[axis][i] = 0.5 * kPlaneCubeEdge;
      }
      break;
    }
  }
  writeBoxes();
}

void SceneSimulator::step() {
  ++frame_;
  if (config_.kind == SceneKind::kUniform) {
    // Constant velocities; boxes pass through each other and bounce off the world's walls.
    const std::size_t n = center_[0].size();
    for (int axis = 0; axis < 3; ++axis) {
      for (std::size_t i = 0; i < n; ++i) {
        double& centre = center_[axis][i];
        double& velocity = velocity_[axis][i];
        const double limit = std::max(0.0, world_half_ - half_extent_[axis][i]);
        centre += velocity;
        if (centre > limit) {
          centre = std::max(-limit, 2.0 * limit - centre);
          velocity = -velocity;
        } else if (centre < -limit) {
          centre = std::min(limit, -2.0 * limit - centre);
          velocity = -velocity;
        }
      }
    }
  }
  writeBoxes();
}

void SceneSimulator::advanceTo(int inFrame) {
  while (frame_ < inFrame) step();
}

void SceneSimulator::writeBoxes() {
  const std::size_t n = center_[0].size();
  boxes_.clear();
  boxes_.ids.resize(n);
  boxes_.bounds.resize(kBoundsPerBox * n);
  const double progress = static_cast<double>(frame_) / config_.frames;
  for (std::size_t i = 0; i < n; ++i) {
    boxes_.ids[i] = static_cast<uint32_t>(i);
    double scale = 1.0;  // position = start centre * scale (ball), or u-coordinate factor (plane)
    if (config_.kind == SceneKind::kBallCluster) {
      const double packed = 1.0 / kStartRadiusFactor;
      if (progress < kPackedAt)
        scale = 1.0 - (1.0 - packed) * progress / kPackedAt;
      else if (progress < kSpreadFrom)
        scale = packed;
      else
        scale = packed + (velocity_[0][i] - packed) * (progress - kSpreadFrom) / (1 - kSpreadFrom);
    } else if (config_.kind == SceneKind::kPlaneCluster) {
      scale = 1.0 - 2.0 * progress;  // every box crosses u = 0 at mid-run
    }
    for (int axis = 0; axis < 3; ++axis) {
      double centre = center_[axis][i];
      if (config_.kind == SceneKind::kBallCluster ||
          (config_.kind == SceneKind::kPlaneCluster && axis == config_.plane_axis))
        centre *= scale;
      boxes_.lo(axis, i) = centre - half_extent_[axis][i];
      boxes_.hi(axis, i) = centre + half_extent_[axis][i];
    }
  }
}

BoxSet makeSceneFrame(const SceneConfig& inConfig, int inFrame) {
  SceneSimulator simulator(inConfig);
  simulator.advanceTo(inFrame);
  return simulator.boxes();
}

}  // namespace sap_broadphase
