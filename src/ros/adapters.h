// Input adapters: the box messages robots publish (visualization_msgs/MarkerArray, vision_msgs,
// jsk_recognition_msgs) turned into records of the node's frames, one adapter per ~sources
// entry.
//
// vision_msgs and jsk_recognition_msgs are not packaged in Debian 12, so the node has no build
// dependency on them: it subscribes with topic_tools::ShapeShifter, checks the publisher's
// type name and MD5 sum against the ROS 1 (noetic) definitions embedded here
// (src/ros/adapters_msgs/*.msg) and decodes the wire bytes with ros::serialization.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Vector3.h>
#include <std_msgs/Header.h>
#include <topic_tools/shape_shifter.h>
#include <visualization_msgs/MarkerArray.h>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/core/box_set.h"
#include "source_spec.h"
#include "sources.h"
#include "wire_layout.h"

namespace sap_broadphase {

/// What the node knows of a type: its ROS name, MD5 sum and full definition (as gencpp writes
/// it: the type's own text, then each dependency after a line of '=' and "MSG: pkg/Type").
struct InputTypeInfo {
  InputType type;
  const char* name;
  const char* md5;
  const char* definition;
};

/// The description of inType.
const InputTypeInfo& inputTypeInfo(InputType inType);
/// The type named inName (e.g. "vision_msgs/Detection3DArray"), or nothing.
std::optional<InputType> inputTypeByName(const std::string& inName);
/// "sap_broadphase/BoxArray, visualization_msgs/MarkerArray, ...": for refusals.
std::string inputTypeNames();
/// The wire layout of inType, read once from its definition: every message of a source is
/// checked against it before it is deserialized.
const WireLayout& wireLayout(InputType inType);
/// Why a publisher of type inType and MD5 sum inMd5 cannot feed a source of inExpected, or
/// nothing (the source's name goes in front).
std::optional<std::string> checkPublishedType(InputType inExpected, const std::string& inType,
                                              const std::string& inMd5);

/// A box as the messages give it: a box of `size` centred on `centre`, in the frame that `pose`
/// places in the message's frame.
struct PosedBox {
  std::string name;               ///< what the box is called in its source: "obstacles/7", ...
  geometry_msgs::Pose pose;       ///< of the box's frame in the message's frame
  geometry_msgs::Point centre;    ///< in the box's frame: a CUBE_LIST point, else the origin
  geometry_msgs::Vector3 size;    ///< full extent along the box's frame axes
  std::optional<int32_t> own_id;  ///< a CUBE marker's id (a CUBE_LIST's points have none)
};

/// The boxes of one message of a vision_msgs or jsk type, with the message's header.
struct DecodedBoxes {
  std_msgs::Header header;
  std::vector<PosedBox> boxes;
};

/// Decodes the serialized message inData (of inSize bytes) of inType (BoundingBox3DArray,
/// Detection3DArray or jsk BoundingBoxArray) into outDecoded. Boxes are named "box k",
/// "detection k" and "label L" ("label L #j" for the j-th repeat of L in the message). Returns
/// the refusal (truncated or over-long data, a box in another frame than its array), or nothing.
std::optional<std::string> decodeWireBoxes(InputType inType, const uint8_t* inData, uint32_t inSize,
                                           DecodedBoxes& outDecoded);

/// Checks a box at the edge: no NaN in pose or size, no negative size, a unit quaternion (an
/// all-zero quaternion is read as the identity, as rviz does). Returns the reason, or nothing.
std::optional<std::string> checkPosedBox(const PosedBox& inBox);

/// Names a source may give ids to: each costs about 350 bytes (the name twice, a map node) for
/// the life of the node, so a publisher inventing a new name per message cannot grow the node
/// without bound. A box whose name would pass the cap is refused, saying so.
constexpr std::size_t kMaxNamesPerSource = std::size_t{1} << 18;

/// Stable ids for the names of a source: the k-th name seen gets id_offset + k, for the life of
/// the node, whatever order later messages list them in; or, for a box with an id of its own
/// (a marker's, with `ids: marker`), id_offset + that id.
class IdTable {
 public:
  explicit IdTable(uint32_t inOffset) : offset_(inOffset) {}
  /// The id of inName (registered when new), or nothing when the offset plus the number of
  /// names would pass 2^32 - 1 or the table holds kMaxNamesPerSource names.
  std::optional<uint32_t> idOf(const std::string& inName);
  /// offset() + inOwnId for the box inName, its name registered when new; nothing, with
  /// outReason, when inOwnId is negative, the sum passes 2^32 - 1 or the table is full.
  std::optional<uint32_t> ownIdOf(const std::string& inName, int32_t inOwnId,
                                  std::string& outReason);
  /// Every (id, name) registered, in the order first seen.
  const std::vector<std::pair<uint32_t, std::string>>& entries() const { return entries_; }
  uint32_t offset() const { return offset_; }

 private:
  uint32_t offset_;
  std::map<std::string, uint32_t> ids_;
  std::vector<std::pair<uint32_t, std::string>> entries_;
};

/// Converts the messages of one ~sources entry into source frames of records. Thread-safe: one
/// mutex per source (roscpp calls one subscription's callbacks one at a time, in order, which the
/// marker state relies on).
class SourceAdapter {
 public:
  explicit SourceAdapter(const SourceSpec& inSpec);
  const SourceSpec& spec() const { return spec_; }

  /// Any message of the topic: checks its type name and MD5 sum against spec().type, decodes
  /// and converts it into outFrame (header and records replaced). Returns the refusal, or
  /// nothing; the header is the message's wherever it was read, for the refusal to name.
  std::optional<std::string> convert(const topic_tools::ShapeShifter& inMsg,
                                     const std::string& inPublisher, SourceFrame& outFrame);
  /// A MarkerArray of inPublisher: applied to the publisher's marker set (ADD/MODIFY replace a
  /// marker, DELETE removes one, DELETEALL all of them), then the whole set of CUBE and
  /// CUBE_LIST markers is converted. A refused message leaves the set as it was.
  std::optional<std::string> convertMarkers(const visualization_msgs::MarkerArray& inMsg,
                                            const std::string& inPublisher, SourceFrame& outFrame);
  /// Serialized bytes of a vision_msgs or jsk message of inType (type already checked).
  std::optional<std::string> convertWire(InputType inType, const std::vector<uint8_t>& inData,
                                         SourceFrame& outFrame);
  /// A BoxArray of a source with an id_offset, group or mask: its records (ids numbered
  /// 0..n-1 when it has none) with the spec's group and mask, and the id_offset for the engine
  /// to add (it refuses an id the offset takes past 2^32 - 1). Returns the refusal of a shape.
  std::optional<std::string> convertBoxArray(const BoxArray& inBoxes, SourceFrame& outFrame) const;

  /// Appends the (id, name) of every named box seen so far; the number of names grows only.
  void appendIdNames(std::vector<uint32_t>& ioIds, std::vector<std::string>& ioNames) const;
  /// Number of names given an id so far (grows only: a change means ~id_names is out of date).
  std::size_t nameCount() const;
  /// Forgets the marker set of inPublisher, whose source timed out: a publisher that left
  /// costs nothing after its time-out, and one that comes back starts from an empty set.
  void dropPublisher(const std::string& inPublisher);
  /// Number of publishers whose marker sets are kept.
  std::size_t publisherCount() const;

 private:
  /// One publisher's markers, by (ns, id), and the frame of the last set converted.
  struct MarkerSet {
    std::map<std::pair<std::string, int32_t>, visualization_msgs::Marker> markers;
    std_msgs::Header header;
  };
  /// Checks and converts inBoxes (in the frame of inHeader) into outFrame with ids from the
  /// table and the spec's group and mask (caller holds mutex_).
  std::optional<std::string> toRecords(const std_msgs::Header& inHeader,
                                       const std::vector<PosedBox>& inBoxes, SourceFrame& outFrame);
  /// The spec's group and mask, when given, on every box of ioBoxes.
  void applyFilters(BoxSet& ioBoxes) const;

  const SourceSpec spec_;
  mutable std::mutex mutex_;
  IdTable ids_;
  std::map<std::string, MarkerSet> marker_sets_;  // by publisher
  DecodedBoxes decoded_;                          // reused
  BoxSet one_box_;                                // a box moved by its pose, reused
};

}  // namespace sap_broadphase
