// SourcePlacement: moves boxes into ~fixed_frame with tf2. Runs on the thread that asks (the
// frame worker for source frames and the scenery, the query threads for query boxes, the
// subscriber callbacks for "can it be placed now?"); it keeps no state of its own after
// construction and reads tf2 through the buffer's own lock, so no lock of ours is needed.
#pragma once

#include <optional>
#include <string>

#include <ros/time.h>
#include <std_msgs/Header.h>
#include <tf2/buffer_core.h>

#include "sources.h"

namespace sap_broadphase {

/// Why boxes could not be placed in ~fixed_frame.
struct PlacementRefusal {
  enum class Kind {
    kUnplaceable,   ///< an empty frame_id: nothing could ever place it
    kNoTransform,   ///< tf2 has no transform (yet): a source's frame is skipped, not refused
    kBadTransform,  ///< the transform is not finite: refused, as a wrong box is
  };
  Kind kind;
  std::string reason;  ///< "no transform into 'map': ...", "the transform from 'a' ...: refused"
};

class SourcePlacement {
 public:
  /// Moves boxes into inFixedFrame with the transforms of inTransforms (tf2_ros::Buffer in the
  /// node, a tf2::BufferCore filled by hand in the tests), which must outlive the placement.
  /// An empty inFixedFrame (no ~fixed_frame) moves nothing, and inTransforms may then be null.
  SourcePlacement(std::string inFixedFrame, const tf2::BufferCore* inTransforms);

  /// The frame every source is moved into, or empty without a ~fixed_frame.
  const std::string& fixedFrame() const { return fixed_frame_; }
  /// True when boxes are moved, with a ~fixed_frame.
  bool moves() const { return !fixed_frame_.empty(); }

  /// With a ~fixed_frame, the reason a frame named inFrame cannot be placed at all (an empty
  /// frame id: tf2 would only print its own complaint, and the frame would wait for nothing).
  std::optional<std::string> unplaceableFrame(const std::string& inFrame) const;
  /// True when boxes of frame inFrame at inStamp (time 0: the latest) can be placed now,
  /// without waiting: always without a ~fixed_frame.
  bool canPlace(const std::string& inFrame, const ros::Time& inStamp) const;

  /// The one rule for boxes that arrive as a message (a source's frame, a query): read where
  /// they lie when nothing moves them; with a ~fixed_frame, copied from the message into
  /// ioFrame.records and moved there with the transform at inStamp (time 0: the latest).
  /// After it, ioFrame.span() is what the engine reads and, when moved, header.frame_id is the
  /// fixed frame. The refusal when they cannot be placed: the boxes are then as published.
  std::optional<PlacementRefusal> place(const ros::Time& inStamp, SourceFrame& ioFrame) const;

 private:
  /// Moves ioBoxes from inFrame into the fixed frame at inStamp, or says why not.
  std::optional<PlacementRefusal> move(const std::string& inFrame, const ros::Time& inStamp,
                                       BoxSet& ioBoxes) const;

  std::string fixed_frame_;
  const tf2::BufferCore* transforms_;
};

}  // namespace sap_broadphase
