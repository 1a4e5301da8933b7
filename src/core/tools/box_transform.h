// Moving boxes between frames: the axis-aligned box of a box's 8 corners moved by a rigid
// transform, rounded outwards, so that no overlapping pair is lost to the move. Pure arithmetic
// on box records: the ROS node moves source frames, query boxes and posed boxes with it, and
// turns its transforms into RigidTransform to do so.
#pragma once

#include <optional>
#include <string>

#include "sap_broadphase/core/box_set.h"

namespace sap_broadphase {

/// A rotation, then a translation.
struct RigidTransform {
  double translation[3] = {0.0, 0.0, 0.0};
  /// Quaternion x, y, z, w; its length is divided out (as tf2's rotation matrix does).
  double rotation[4] = {0.0, 0.0, 0.0, 1.0};
};

/// Why inTransform cannot move boxes: a translation or rotation component that is not finite
/// ("translation.x is inf"), or nothing. tf2 refuses NaN but takes infinities, which would
/// make every moved box span the whole axis and pair with everything.
std::optional<std::string> nonFiniteTransform(const RigidTransform& inTransform);

/// Moves every box of ioBoxes by inTransform and replaces it with the axis-aligned box of its 8
/// moved corners, each bound rounded one ulp outwards: the result contains the exactly moved
/// box, so no overlapping pair is lost to the transform (pairs of rotated boxes are a superset
/// of the exact ones). A bound that is not finite after the move becomes -inf / +inf. A box
/// that is no box (a NaN bound, min > max) stays as published, for the engine's check to name
/// it in the sender's own numbers. inTransform must be finite (SAP_ASSERT).
void transformBoxes(const RigidTransform& inTransform, BoxSet& ioBoxes);

/// transformBoxes() for a transform from anywhere: refuses a transform that is not finite,
/// leaving ioBoxes as they were, with the reason nonFiniteTransform() gives.
std::optional<std::string> moveBoxes(const RigidTransform& inTransform, BoxSet& ioBoxes);

}  // namespace sap_broadphase
