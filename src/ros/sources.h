// The world of a frame: the latest frame of every source (topic x publisher), one span each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <geometry_msgs/Transform.h>
#include <ros/time.h>
#include <std_msgs/Header.h>

#include "sap_broadphase/BoxArray.h"

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

struct RigidTransform;  // core/box_transform.h: how the core moves boxes

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

/// inTransform as the core moves boxes with it (core/box_transform.h).
RigidTransform rigidTransform(const geometry_msgs::Transform& inTransform);

/// The core's transformBoxes() for a ROS transform (finite: tf2 transforms are checked with
/// moveBoxes() first): the one rule of the node for a moved box, 8 corners rounded outwards.
void transformBoxes(const geometry_msgs::Transform& inTransform, BoxSet& ioBoxes);

/// One frame of a source as the node keeps it, immutable once stored: the source's latest
/// frame, its last accepted one and the spans of the world being computed share it.
struct SourceFrame {
  std_msgs::Header header;   ///< the frame's; frame_id is ~fixed_frame once moved there
  BoxArrayConstPtr message;  ///< the frame as published (shape checked), read where it lies
  BoxSet records;            ///< else the records the node wrote (an adapter, a transform)
  uint32_t id_offset = 0;    ///< added to every id by the engine (a ~sources entry's id_offset)
  /// The boxes as the engine reads them (valid while the frame is).
  BoxSpan span() const;
  std::size_t size() const { return message ? message->bounds.size() / 6 : records.size(); }
};
using SourceFramePtr = std::shared_ptr<const SourceFrame>;

/// One source of a frame's world and the frame it brings.
struct WorldMember {
  SourceKey key;
  SourceFramePtr frame;
};

/// A source that a frame's world leaves out for its frame_id, and why.
struct LeftOutSource {
  WorldMember source;
  std::string reason;  ///< "'boxes' from /b publishes in frame 'b' but 'boxes' from /a in ..."
};

/// The world of a frame: the sources that join it, in the order they appeared, and those
/// left out for their frame_id.
struct WorldAssembly {
  std::vector<WorldMember> members;
  std::string frame_id;  ///< the frame every member publishes in
  std::vector<LeftOutSource> left_out;
  /// The world's header: the newest stamp of its members, frame_id.
  std_msgs::Header header() const;
};

/// Why the engine refused inWorld (as its error inError says), in the node's words: a box of one
/// source, numbered in that source's own frame, "'boxes' from /b: box 3 (id 17): min_y (3) >
/// max_y (2)"; or an id that two sources (or a source and the scenery) share, "id 7 of 'boxes'
/// from /b is also in 'boxes' from /a: give each source its own id range ...".
std::string worldRefusal(const ValidationError& inError, const WorldAssembly& inWorld);

/// The latest frame of every source, kept until replaced or timed out, and the last frame of
/// each that the engine accepted: a frame the engine refuses leaves the one accepted before.
class SourceSet {
 public:
  /// Keeps inFrame as the latest frame of inKey, received at inReceived.
  void store(const SourceKey& inKey, SourceFramePtr inFrame, const ros::Time& inReceived);
  /// The engine accepted the latest frame of inKey. True the first time for this frame.
  bool accept(const SourceKey& inKey);
  /// The engine refused the latest frame of inKey: the source falls back on its last accepted
  /// frame, which is returned, or leaves the world (null) when it has none or that frame is
  /// the one refused.
  SourceFramePtr refuse(const SourceKey& inKey);
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

  /// The world of a frame into outWorld (replaced): every source's latest frame, in the order
  /// the sources appeared (a source lives from its first frame until it times out, and the
  /// older of two sources keeps an id both use), but for a source whose frame_id differs from
  /// the world's (inRequiredFrame when not empty, else the first source's), left out with the
  /// reason naming both frames. Boxes and ids are the engine's to check.
  void assemble(const std::string& inRequiredFrame, WorldAssembly& outWorld) const;

 private:
  struct Source {
    SourceFramePtr latest;
    SourceFramePtr accepted;  // the last frame the engine accepted, if any
    ros::Time received;
    uint64_t joined = 0;  // order in which sources appeared: the older one keeps a shared id
    uint64_t frames = 0;  // frames delivered since it appeared
  };

  std::map<SourceKey, Source> sources_;
  uint64_t next_join_ = 0;
};

/// Loads a world into the engine through inUpdate (which throws InvalidBoxes, naming the box or
/// span, for a frame it refuses) and returns the pairs, or null when no source is left. Each
/// refusal is told to inRefused (the frame refused, in the node's words of worldRefusal) and
/// takes the source that holds the problem back to its last accepted frame in ioSources, or
/// out of ioWorld without one; the world is then loaded again. The loop ends after at most two
/// refusals a source. ioSpans holds the members' spans as the engine read them last.
using WorldUpdate = std::function<const PairList&(const BoxFrame& inFrame)>;
using MemberRefusal = std::function<void(const SourceFrame& inFrame, const std::string& inReason)>;
const PairList* loadWorld(WorldAssembly& ioWorld, SourceSet& ioSources,
                          std::vector<BoxSpan>& ioSpans, const WorldUpdate& inUpdate,
                          const MemberRefusal& inRefused);

}  // namespace sap_broadphase
