// The world of a frame: the latest frame of every source (topic x publisher), merged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <geometry_msgs/Transform.h>
#include <ros/time.h>
#include <std_msgs/Header.h>

#include "sap_broadphase/BoxArray.h"

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/memory_policy.h"

namespace sap_broadphase {

/// One input of the world: a topic of ~sources, one publisher (caller id) on it and the
/// header.frame_id of its frames. The frame id tells robots apart where the caller id cannot:
/// `rosbag play` publishes every recorded topic under its own caller id, and the nodelets of
/// one manager share the manager's.
struct SourceKey {
  std::string topic;
  std::string publisher;
  std::string frame_id;
  bool operator<(const SourceKey& inOther) const {
    if (topic != inOther.topic) return topic < inOther.topic;
    if (publisher != inOther.publisher) return publisher < inOther.publisher;
    return frame_id < inOther.frame_id;
  }
};

/// "'boxes' from /robot_a" (and " in 'robot_a/base'" with a frame id): how logs and refusals
/// name a source.
std::string sourceName(const SourceKey& inKey);

/// Name of the latched scenery in refusals.
constexpr const char* kStaticSourceName = "'static_boxes'";

/// Moves every box of ioBoxes by inTransform (rotation, then translation) and replaces it with
/// the axis-aligned box of its 8 moved corners, each bound rounded one ulp outwards: the result
/// contains the exactly moved box, so no overlapping pair is lost to the transform (pairs of
/// rotated boxes are a superset of the exact ones). A bound that is not finite after the move
/// becomes -inf / +inf.
void transformBoxes(const geometry_msgs::Transform& inTransform, BoxSet& ioBoxes);

/// A source frame kept as published that failed its checks (NaN, min > max, a repeated id).
struct RefusedFrame {
  std_msgs::Header header;  ///< the frame's
  std::size_t boxes = 0;    ///< its box count
  std::string reason;       ///< "'boxes' from /a: box 3 (id 17): min_y (3) > max_y (2)"
};

/// What one merge left out, and why (one refusal per source left out).
struct WorldAssembly {
  std_msgs::Header header;         ///< newest stamp of the merged sources, their frame id
  std::size_t sources_merged = 0;  ///< sources in the world
  /// Sources left out, each with its frame's header and box count: "id 7 of 'boxes' from /b is
  /// also in 'boxes' from /a"
  std::vector<RefusedFrame> refusals;
  std::vector<RefusedFrame> refused_frames;  ///< kept frames that failed their checks here
  std::size_t frames_accepted = 0;  ///< kept frames that passed their checks here, first time
};

/// The world of a frame: a BoxSet, or the one source's frame as published, which the engine
/// reads where it lies (Broadphase::update of its records) and checks itself.
struct World {
  const BoxSet* boxes = nullptr;      ///< the merged boxes, or null
  const BoxArray* message = nullptr;  ///< else the one source's frame (shape checked), or null
  SourceKey source;                   ///< with a message: whose it is
  std::size_t size() const {
    return boxes ? boxes->size() : message ? message->bounds.size() / 6 : 0;
  }
};

/// The latest frame of every source, kept until replaced or timed out, and their union.
class SourceSet {
 public:
  /// Keeps inBoxes (swapped in, so ioBoxes gets the old buffer back for the next conversion) as
  /// the latest frame of inKey, received at inReceived.
  void store(const SourceKey& inKey, BoxSet& ioBoxes, const std_msgs::Header& inHeader,
             const ros::Time& inReceived);
  /// Keeps inMessage, a frame whose shape is checked and which needs no transform, as the
  /// latest frame of inKey, unconverted: its boxes are checked and copied only where the
  /// world needs them as a BoxSet (several sources, markers); alone, the engine reads them.
  void storeMessage(const SourceKey& inKey, const BoxArrayConstPtr& inMessage,
                    const ros::Time& inReceived);
  /// The engine accepted inKey's kept frame: it becomes the one a refusal falls back on.
  /// True the first time for this frame.
  bool accept(const SourceKey& inKey);
  /// The engine refused inKey's kept frame: the source falls back on its last accepted frame,
  /// or leaves the world when it has none (as a frame refused at conversion never joins).
  void refuse(const SourceKey& inKey);
  /// A source dropped by expire(): its key and how many frames it delivered in its life.
  struct Expired {
    SourceKey key;
    uint64_t frames;
  };
  /// Drops the sources whose latest frame is older than their own time-out, inTimeoutOf(key)
  /// seconds (0 = never), at inNow; returns the sources dropped.
  std::vector<Expired> expire(const ros::Time& inNow,
                              const std::function<double(const SourceKey&)>& inTimeoutOf);
  /// The ROS clock went back to inNow (sim time restarted, a bag looped): every source counts
  /// as received now, so that each times out a full time-out after its last frame of the new
  /// clock (a receipt time in the clock's future would never time out).
  void restartClock(const ros::Time& inNow);
  /// Number of sources held.
  std::size_t size() const { return sources_.size(); }

  /// Builds the world of a frame into outWorld and returns it, or returns the one source's own
  /// boxes or, unless inNeedBoxes, its kept message when it is alone (no copy). Kept messages
  /// are converted and checked where a BoxSet is needed; one that fails is refused
  /// (outAssembly.refused_frames) and its source falls back as refuse() says. Sources are taken in
  /// the order they appeared (a source lives from its first frame until it times out); a source is
  /// left out, with a refusal naming both sides, when one of its ids is already in the world or in
  /// inStaticIds (sorted), or when its frame_id differs from the world's (inRequiredFrame when not
  /// empty, else the first source's).
  World assemble(const std::vector<uint32_t>& inStaticIds, const std::string& inRequiredFrame,
                 BoxSet& outWorld, WorldAssembly& outAssembly, bool inNeedBoxes = true);

 private:
  struct Source {
    BoxSet boxes;
    std_msgs::Header header;
    ros::Time received;
    uint64_t joined = 0;  // order in which sources appeared: the older one keeps a shared id
    uint64_t frames = 0;  // frames delivered since it appeared
    std::vector<uint32_t> sorted_ids;  // ids of the frame, sorted; built only when compared
    GiveBackWatch watch;
    BoxArrayConstPtr message;             // a frame kept as published; boxes hold it once converted
    BoxArrayConstPtr accepted;            // the last kept frame that passed its checks
    const BoxArray* converted = nullptr;  // the kept frame boxes hold, if any
    /// A frame kept as published that boxes do not hold yet.
    bool unconverted() const { return message && converted != message.get(); }
  };
  using SourceIt = std::map<SourceKey, Source>::iterator;
  /// The source's ids, sorted (cached until its next frame).
  static const std::vector<uint32_t>& sortedIds(Source& ioSource);
  /// Converts and checks the kept frame of ioSource into its boxes (once per frame); on a
  /// refusal falls back as refuse() says. False when the source has no frame left.
  static bool convertKept(const SourceKey& inKey, Source& ioSource, WorldAssembly& ioAssembly);
  /// Falls back on the last accepted frame; false when there is none.
  static bool fallBack(Source& ioSource);
  /// Why inSource cannot join the sources of inMerged, or empty.
  std::string conflict(const SourceIt& inSource, const std::vector<SourceIt>& inMerged,
                       const std::vector<uint32_t>& inStaticIds, const std::string& inWorldFrame,
                       const std::string& inWorldFrameOwner);

  std::map<SourceKey, Source> sources_;
  uint64_t next_join_ = 0;
};

/// Appends inAdd to ioWorld; groups and masks are completed with the defaults when only one
/// side has them.
void appendBoxes(const BoxSet& inAdd, BoxSet& ioWorld);

/// Releases the capacity of every array of ioBoxes beyond its size.
void shrinkBoxSet(BoxSet& ioBoxes);

}  // namespace sap_broadphase
