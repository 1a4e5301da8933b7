// Input adapters: MarkerArray, vision_msgs and jsk_recognition_msgs boxes into records.
#include "adapters.h"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include <geometry_msgs/PoseWithCovariance.h>
#include <geometry_msgs/Transform.h>
#include <ros/serialization.h>
#include <sensor_msgs/PointCloud2.h>

#include "sap_broadphase/ros/conversions.h"
// kVisionBoundingBox3DArrayDefinition, ...: src/ros/adapters_msgs/*.msg, embedded by CMake.
#include "sap_broadphase_adapters_msgs.h"

namespace sap_broadphase {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

const InputTypeInfo kInputTypes[] = {
    {InputType::kBoxArray, "sap_broadphase/BoxArray",
     ros::message_traits::MD5Sum<BoxArray>::value(),
     ros::message_traits::Definition<BoxArray>::value()},
    {InputType::kMarkerArray, "visualization_msgs/MarkerArray",
     ros::message_traits::MD5Sum<visualization_msgs::MarkerArray>::value(),
     ros::message_traits::Definition<visualization_msgs::MarkerArray>::value()},
    // The MD5 sums of the ROS 1 definitions, as genmsg computes them (test_adapters_units checks
    // them against genmsg's computation of the embedded text).
    {InputType::kBoundingBox3DArray, "vision_msgs/BoundingBox3DArray",
     "9e1a3932308592aa1b20232d818486db", kVisionBoundingBox3DArrayDefinition},
    {InputType::kDetection3DArray, "vision_msgs/Detection3DArray",
     "05c51d9aea1fb4cfdc8effb94f197b6f", kVisionDetection3DArrayDefinition},
    {InputType::kJskBoundingBoxArray, "jsk_recognition_msgs/BoundingBoxArray",
     "c8f4a8bb1acd18ce778d183912bb472d", kJskBoundingBoxArrayDefinition},
};

std::string numberText(double inValue) {
  std::ostringstream text;
  text.precision(17);
  text << inValue;
  return text.str();
}

/// Reads a vision_msgs/BoundingBox3D (Pose center, Vector3 size).
void readBoundingBox3D(ros::serialization::IStream& ioStream, PosedBox& outBox) {
  ioStream.next(outBox.pose);
  ioStream.next(outBox.size);
}

/// A box with its own header (Detection3D, jsk BoundingBox) must be in its array's frame: the
/// node places the whole message with one transform.
std::optional<std::string> checkBoxFrame(const std::string& inBoxFrame,
                                         const std_msgs::Header& inArrayHeader,
                                         const std::string& inBoxName) {
  if (inBoxFrame.empty() || inBoxFrame == inArrayHeader.frame_id) return std::nullopt;
  return inBoxName + " is in frame '" + inBoxFrame + "' but its array in frame '" +
         inArrayHeader.frame_id + "': publish every box in the array's frame";
}

std::optional<std::string> decodeBoundingBox3DArray(ros::serialization::IStream& ioStream,
                                                    DecodedBoxes& outDecoded) {
  ioStream.next(outDecoded.header);
  uint32_t count = 0;
  ioStream.next(count);
  for (uint32_t k = 0; k < count; ++k) {
    PosedBox box;
    box.name = "box " + std::to_string(k);
    readBoundingBox3D(ioStream, box);
    outDecoded.boxes.push_back(std::move(box));
  }
  return std::nullopt;
}

std::optional<std::string> decodeDetection3DArray(ros::serialization::IStream& ioStream,
                                                  DecodedBoxes& outDecoded) {
  ioStream.next(outDecoded.header);
  uint32_t count = 0;
  ioStream.next(count);
  std_msgs::Header detection_header;
  sensor_msgs::PointCloud2 source_cloud;
  for (uint32_t k = 0; k < count; ++k) {
    PosedBox box;
    box.name = "detection " + std::to_string(k);
    ioStream.next(detection_header);
    uint32_t results = 0;
    ioStream.next(results);
    for (uint32_t r = 0; r < results; ++r) {
      // ObjectHypothesisWithPose: the class hypotheses do not change the box.
      int64_t class_id = 0;
      double score = 0.0;
      geometry_msgs::PoseWithCovariance pose;
      ioStream.next(class_id);
      ioStream.next(score);
      ioStream.next(pose);
    }
    readBoundingBox3D(ioStream, box);
    ioStream.next(source_cloud);
    if (auto reason = checkBoxFrame(detection_header.frame_id, outDecoded.header, box.name))
      return reason;
    outDecoded.boxes.push_back(std::move(box));
  }
  return std::nullopt;
}

std::optional<std::string> decodeJskBoundingBoxArray(ros::serialization::IStream& ioStream,
                                                     DecodedBoxes& outDecoded) {
  ioStream.next(outDecoded.header);
  uint32_t count = 0;
  ioStream.next(count);
  std::map<uint32_t, uint32_t> label_repeats;
  std_msgs::Header box_header;
  for (uint32_t k = 0; k < count; ++k) {
    PosedBox box;
    float value = 0.0f;
    uint32_t label = 0;
    ioStream.next(box_header);
    ioStream.next(box.pose);
    ioStream.next(box.size);
    ioStream.next(value);
    ioStream.next(label);
    // Labels name boxes; several boxes of one label (a class label, or the default 0) are told
    // apart by their order among the boxes of that label.
    const uint32_t repeat = label_repeats[label]++;
    box.name = "label " + std::to_string(label);
    if (repeat > 0) box.name += " #" + std::to_string(repeat);
    if (auto reason = checkBoxFrame(box_header.frame_id, outDecoded.header, "box " + box.name))
      return reason;
    outDecoded.boxes.push_back(std::move(box));
  }
  return std::nullopt;
}

/// The marker's boxes: a CUBE is one box of `scale` under its pose, a CUBE_LIST one such box
/// around each point. Other marker types carry no box and give none.
void appendMarkerBoxes(const visualization_msgs::Marker& inMarker, std::vector<PosedBox>& ioBoxes) {
  const std::string name = inMarker.ns + "/" + std::to_string(inMarker.id);
  if (inMarker.type == visualization_msgs::Marker::CUBE) {
    ioBoxes.push_back(
        PosedBox{name, inMarker.pose, geometry_msgs::Point(), inMarker.scale, inMarker.id});
  } else if (inMarker.type == visualization_msgs::Marker::CUBE_LIST) {
    for (std::size_t k = 0; k < inMarker.points.size(); ++k) {
      ioBoxes.push_back(PosedBox{name + "[" + std::to_string(k) + "]", inMarker.pose,
                                 inMarker.points[k], inMarker.scale, std::nullopt});
    }
  }
}

bool isBoxMarker(const visualization_msgs::Marker& inMarker) {
  return inMarker.type == visualization_msgs::Marker::CUBE ||
         inMarker.type == visualization_msgs::Marker::CUBE_LIST;
}

}  // namespace

const InputTypeInfo& inputTypeInfo(InputType inType) {
  for (const InputTypeInfo& info : kInputTypes)
    if (info.type == inType) return info;
  return kInputTypes[0];
}

std::optional<InputType> inputTypeByName(const std::string& inName) {
  for (const InputTypeInfo& info : kInputTypes)
    if (inName == info.name) return info.type;
  return std::nullopt;
}

std::string inputTypeNames() {
  std::string names;
  for (const InputTypeInfo& info : kInputTypes)
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

const WireLayout& wireLayout(InputType inType) {
  // One layout per type, built on first use (thread-safe) and kept for the life of the process.
  static const WireLayout kLayouts[] = {
      WireLayout(inputTypeInfo(InputType::kBoxArray).name,
                 inputTypeInfo(InputType::kBoxArray).definition),
      WireLayout(inputTypeInfo(InputType::kMarkerArray).name,
                 inputTypeInfo(InputType::kMarkerArray).definition),
      WireLayout(inputTypeInfo(InputType::kBoundingBox3DArray).name,
                 inputTypeInfo(InputType::kBoundingBox3DArray).definition),
      WireLayout(inputTypeInfo(InputType::kDetection3DArray).name,
                 inputTypeInfo(InputType::kDetection3DArray).definition),
      WireLayout(inputTypeInfo(InputType::kJskBoundingBoxArray).name,
                 inputTypeInfo(InputType::kJskBoundingBoxArray).definition),
  };
  for (const WireLayout& layout : kLayouts)
    if (layout.typeName() == inputTypeInfo(inType).name) return layout;
  return kLayouts[0];
}

std::optional<std::string> checkPublishedType(InputType inExpected, const std::string& inType,
                                              const std::string& inMd5) {
  const InputTypeInfo& expected = inputTypeInfo(inExpected);
  if (inType != expected.name) {
    return "a " + inType + " message, but the entry's type is " + expected.name +
           ": set the type the topic carries (" + inputTypeNames() + ")";
  }
  if (inMd5 != expected.md5) {
    return std::string(expected.name) + " with MD5 sum " + inMd5 + ", not " + expected.md5 +
           " (the ROS 1 definition the node decodes): another version of the message";
  }
  return std::nullopt;
}

std::optional<std::string> decodeWireBoxes(InputType inType, const uint8_t* inData, uint32_t inSize,
                                           DecodedBoxes& outDecoded) {
  outDecoded.header = std_msgs::Header();
  outDecoded.boxes.clear();
  // Every length prefix against the bytes that follow it, before the readers below allocate.
  if (auto reason = wireLayout(inType).check(inData, inSize)) return reason;
  // IStream only reads, but takes a non-const pointer.
  ros::serialization::IStream stream(const_cast<uint8_t*>(inData), inSize);
  std::optional<std::string> reason;
  try {
    switch (inType) {
      case InputType::kBoundingBox3DArray:
        reason = decodeBoundingBox3DArray(stream, outDecoded);
        break;
      case InputType::kDetection3DArray:
        reason = decodeDetection3DArray(stream, outDecoded);
        break;
      case InputType::kJskBoundingBoxArray:
        reason = decodeJskBoundingBoxArray(stream, outDecoded);
        break;
      default:
        return std::string(inputTypeInfo(inType).name) + " has no wire decoder";
    }
  } catch (const ros::serialization::StreamOverrunException&) {
    return std::string(inputTypeInfo(inType).name) + ": the message ends early (" +
           std::to_string(inSize) + " bytes): not the layout its MD5 sum promises";
  }
  if (!reason && stream.getLength() != 0) {
    return std::string(inputTypeInfo(inType).name) + ": " + std::to_string(stream.getLength()) +
           " bytes left after the last field: not the layout its MD5 sum promises";
  }
  return reason;
}

std::optional<std::string> checkPosedBox(const PosedBox& inBox) {
  const std::string who = "box '" + inBox.name + "'";
  const geometry_msgs::Point& p = inBox.pose.position;
  const geometry_msgs::Quaternion& q = inBox.pose.orientation;
  const geometry_msgs::Vector3& s = inBox.size;
  const geometry_msgs::Point& c = inBox.centre;
  if (std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z)) return who + ": position is NaN";
  if (std::isnan(c.x) || std::isnan(c.y) || std::isnan(c.z)) return who + ": point is NaN";
  if (std::isnan(s.x) || std::isnan(s.y) || std::isnan(s.z)) return who + ": size is NaN";
  if (s.x < 0 || s.y < 0 || s.z < 0) {
    return who + ": negative size (" + numberText(s.x) + ", " + numberText(s.y) + ", " +
           numberText(s.z) + ")";
  }
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.w))
    return who + ": orientation is not finite";
  const double norm2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  // rviz's tolerance for markers; an all-zero quaternion (an unset pose) means no rotation.
  if (norm2 != 0.0 && std::fabs(norm2 - 1.0) > 1e-2) {
    return who + ": orientation (" + numberText(q.x) + ", " + numberText(q.y) + ", " +
           numberText(q.z) + ", " + numberText(q.w) + ") is not a unit quaternion (norm " +
           numberText(std::sqrt(norm2)) + ")";
  }
  return std::nullopt;
}

std::optional<uint32_t> IdTable::idOf(const std::string& inName) {
  auto found = ids_.find(inName);
  if (found != ids_.end()) return found->second;
  const uint64_t id = uint64_t{offset_} + entries_.size();
  if (id > std::numeric_limits<uint32_t>::max() || entries_.size() >= kMaxNamesPerSource)
    return std::nullopt;
  ids_.emplace(inName, static_cast<uint32_t>(id));
  entries_.emplace_back(static_cast<uint32_t>(id), inName);
  return static_cast<uint32_t>(id);
}

std::optional<uint32_t> IdTable::ownIdOf(const std::string& inName, int32_t inOwnId,
                                         std::string& outReason) {
  auto found = ids_.find(inName);
  if (found != ids_.end()) return found->second;  // a name's id never changes
  const int64_t id = int64_t{offset_} + inOwnId;
  if (inOwnId < 0 || id > int64_t{std::numeric_limits<uint32_t>::max()}) {
    outReason = "id " + std::to_string(inOwnId) + " plus id_offset " + std::to_string(offset_) +
                " is no id from 0 to 2^32 - 1 (ids: marker takes ids >= 0)";
    return std::nullopt;
  }
  if (entries_.size() >= kMaxNamesPerSource) {
    outReason = "no id left: the source has named " + std::to_string(entries_.size()) +
                " boxes (at most " + std::to_string(kMaxNamesPerSource) + ")";
    return std::nullopt;
  }
  ids_.emplace(inName, static_cast<uint32_t>(id));
  entries_.emplace_back(static_cast<uint32_t>(id), inName);
  return static_cast<uint32_t>(id);
}

SourceAdapter::SourceAdapter(const SourceSpec& inSpec) : spec_(inSpec), ids_(inSpec.id_offset) {
  const double origin[3] = {0.0, 0.0, 0.0};
  one_box_.add(0, origin, origin);
}

std::optional<std::string> SourceAdapter::convert(const topic_tools::ShapeShifter& inMsg,
                                                  const std::string& inPublisher,
                                                  SourceFrame& outFrame) {
  // The node names the source (topic and publisher) in front of these refusals.
  if (auto reason = checkPublishedType(spec_.type, inMsg.getDataType(), inMsg.getMD5Sum()))
    return reason;
  const InputTypeInfo& expected = inputTypeInfo(spec_.type);
  std::vector<uint8_t> bytes(inMsg.size());
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  inMsg.write(out);
  // roscpp believes length prefixes: the bytes are checked against the layout first, so that
  // what is allocated below is bounded by the message's size on the wire.
  if (auto reason = wireLayout(spec_.type).check(bytes.data(), bytes.size())) return reason;
  try {
    ros::serialization::IStream in(bytes.data(), static_cast<uint32_t>(bytes.size()));
    if (spec_.type == InputType::kMarkerArray) {
      visualization_msgs::MarkerArray markers;
      ros::serialization::deserialize(in, markers);
      return convertMarkers(markers, inPublisher, outFrame);
    }
    if (spec_.type == InputType::kBoxArray) {
      BoxArray boxes;
      ros::serialization::deserialize(in, boxes);
      return convertBoxArray(boxes, outFrame);
    }
  } catch (const ros::Exception& exception) {  // bytes shorter than the type's layout
    return std::string(expected.name) + " that cannot be read: " + exception.what();
  }
  return convertWire(spec_.type, bytes, outFrame);
}

std::optional<std::string> SourceAdapter::convertWire(InputType inType,
                                                      const std::vector<uint8_t>& inData,
                                                      SourceFrame& outFrame) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto reason =
      decodeWireBoxes(inType, inData.data(), static_cast<uint32_t>(inData.size()), decoded_);
  outFrame.header = decoded_.header;  // what a refusal names, when the header was read
  if (reason) return reason;
  return toRecords(decoded_.header, decoded_.boxes, outFrame);
}

std::optional<std::string> SourceAdapter::convertMarkers(
    const visualization_msgs::MarkerArray& inMsg, const std::string& inPublisher,
    SourceFrame& outFrame) {
  std::lock_guard<std::mutex> lock(mutex_);
  // A refusal names the frame and stamp of the message's first marker.
  if (!inMsg.markers.empty()) outFrame.header = inMsg.markers.front().header;
  // Applied to a copy: a refused message leaves the publisher's markers as they were.
  MarkerSet next = marker_sets_[inPublisher];
  bool stamped = false;
  for (const visualization_msgs::Marker& marker : inMsg.markers) {
    const auto key = std::make_pair(marker.ns, marker.id);
    switch (marker.action) {
      case visualization_msgs::Marker::ADD:  // = MODIFY
        if (isBoxMarker(marker)) {
          next.markers[key] = marker;
          if (!stamped || marker.header.stamp > next.header.stamp)
            next.header.stamp = marker.header.stamp;
          stamped = true;
        } else {
          next.markers.erase(key);  // replaced by a marker that is no box
        }
        break;
      case visualization_msgs::Marker::DELETE:
        next.markers.erase(key);
        break;
      case visualization_msgs::Marker::DELETEALL:
        next.markers.clear();
        break;
      default:
        return "marker '" + marker.ns + "/" + std::to_string(marker.id) + "': unknown action " +
               std::to_string(marker.action);
    }
  }
  std::vector<PosedBox> boxes;
  std::string owner;  // the first marker, whose frame the others must share
  for (const auto& [key, marker] : next.markers) {
    if (owner.empty()) {
      owner = "marker '" + key.first + "/" + std::to_string(key.second) + "'";
      next.header.frame_id = marker.header.frame_id;
    } else if (marker.header.frame_id != next.header.frame_id) {
      return "marker '" + key.first + "/" + std::to_string(key.second) + "' is in frame '" +
             marker.header.frame_id + "' but " + owner + " in frame '" + next.header.frame_id +
             "': publish a source's markers in one frame";
    }
    appendMarkerBoxes(marker, boxes);
  }
  if (auto reason = toRecords(next.header, boxes, outFrame)) return reason;
  marker_sets_[inPublisher] = std::move(next);
  return std::nullopt;
}

std::optional<std::string> SourceAdapter::toRecords(const std_msgs::Header& inHeader,
                                                    const std::vector<PosedBox>& inBoxes,
                                                    SourceFrame& outFrame) {
  outFrame.header = inHeader;
  for (const PosedBox& box : inBoxes)
    if (auto reason = checkPosedBox(box)) return reason;
  BoxSet& records = outFrame.records;
  records.clear();
  records.reserve(inBoxes.size());
  for (const PosedBox& box : inBoxes) {
    std::optional<uint32_t> id;
    if (spec_.marker_ids) {
      std::string reason =
          "a CUBE_LIST's points have no id of their own (ids: marker takes "
          "CUBE markers only)";
      if (box.own_id) id = ids_.ownIdOf(box.name, *box.own_id, reason);
      if (!id) return "box '" + box.name + "': " + reason;
    } else if (!(id = ids_.idOf(box.name))) {
      return "box '" + box.name + "': no id left: the source has named " +
             std::to_string(ids_.entries().size()) + " boxes (at most " +
             std::to_string(kMaxNamesPerSource) + ", and id_offset " +
             std::to_string(spec_.id_offset) + " plus the names must stay below 2^32)";
    }
    records.ids.push_back(*id);
    // The box in its own frame; a point's box is widened by an ulp each way so the rounding of
    // point +- size / 2 never shrinks it.
    const double centre[3] = {box.centre.x, box.centre.y, box.centre.z};
    const double half[3] = {box.size.x / 2, box.size.y / 2, box.size.z / 2};
    for (int axis = 0; axis < 3; ++axis) {
      double lo = centre[axis] - half[axis], hi = centre[axis] + half[axis];
      if (centre[axis] != 0.0) {
        lo = std::nextafter(lo, -kInfinity);
        hi = std::nextafter(hi, kInfinity);
      }
      one_box_.lo(axis, 0) = lo;
      one_box_.hi(axis, 0) = hi;
    }
    geometry_msgs::Transform pose;
    pose.translation.x = box.pose.position.x;
    pose.translation.y = box.pose.position.y;
    pose.translation.z = box.pose.position.z;
    pose.rotation = box.pose.orientation;
    const geometry_msgs::Quaternion& q = pose.rotation;
    if (q.x == 0 && q.y == 0 && q.z == 0 && q.w == 0) pose.rotation.w = 1.0;
    // The one rule of the node for a moved box: the axis-aligned box of its 8 corners, rounded
    // outwards (the tf2 sources use it too).
    transformBoxes(pose, one_box_);
    records.bounds.insert(records.bounds.end(), one_box_.bounds.begin(), one_box_.bounds.end());
  }
  applyFilters(records);
  return std::nullopt;
}

void SourceAdapter::applyFilters(BoxSet& ioBoxes) const {
  if (spec_.group) ioBoxes.groups.assign(ioBoxes.size(), *spec_.group);
  if (spec_.mask) ioBoxes.masks.assign(ioBoxes.size(), *spec_.mask);
}

std::optional<std::string> SourceAdapter::convertBoxArray(const BoxArray& inBoxes,
                                                          SourceFrame& outFrame) const {
  outFrame.header = inBoxes.header;
  if (auto reason = checkBoxArrayShape(inBoxes)) return reason;
  copyBoxArray(inBoxes, outFrame.records);
  outFrame.id_offset = spec_.id_offset;
  applyFilters(outFrame.records);
  return std::nullopt;
}

void SourceAdapter::appendIdNames(std::vector<uint32_t>& ioIds,
                                  std::vector<std::string>& ioNames) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [id, name] : ids_.entries()) {
    ioIds.push_back(id);
    ioNames.push_back(spec_.topic + ": " + name);
  }
}

std::size_t SourceAdapter::nameCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ids_.entries().size();
}

void SourceAdapter::dropPublisher(const std::string& inPublisher) {
  std::lock_guard<std::mutex> lock(mutex_);
  marker_sets_.erase(inPublisher);
}

std::size_t SourceAdapter::publisherCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return marker_sets_.size();
}

}  // namespace sap_broadphase
