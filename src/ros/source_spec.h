// A ~sources entry: a topic, the message type published on it, and what the node adds to its
// boxes (src/ros/adapters_sources.cpp reads it, src/ros/adapters.cpp converts its messages).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace sap_broadphase {

/// The message types a ~sources entry can name.
enum class InputType {
  kBoxArray,             ///< sap_broadphase/BoxArray: axis-aligned bounds, ids, groups, masks
  kMarkerArray,          ///< visualization_msgs/MarkerArray: CUBE and CUBE_LIST markers
  kBoundingBox3DArray,   ///< vision_msgs/BoundingBox3DArray: centre pose and size
  kDetection3DArray,     ///< vision_msgs/Detection3DArray: the bbox of each detection
  kJskBoundingBoxArray,  ///< jsk_recognition_msgs/BoundingBoxArray: pose, dimensions, label
};

/// A ~sources entry: a topic name alone, or {topic, type, id_offset, group, mask, timeout}.
struct SourceSpec {
  std::string topic;
  InputType type = InputType::kBoxArray;
  uint32_t id_offset = 0;         ///< added to every id the adapter gives
  std::optional<uint32_t> group;  ///< collision group bits of every box (else the message's)
  std::optional<uint32_t> mask;   ///< groups every box collides with (else the message's)
  std::optional<double> timeout;  ///< seconds of silence before the source drops out (else
                                  ///< ~source_timeout); 0 = never
  bool marker_ids = false;  ///< `ids: marker`: a MarkerArray CUBE's id is id_offset + marker.id
                            ///< (else names are numbered as first seen)
  /// True when the node can take the topic's BoxArray messages as they are (no copy): a
  /// BoxArray source with no id_offset, group or mask.
  bool takesBoxArrayAsIs() const {
    return type == InputType::kBoxArray && id_offset == 0 && !group && !mask;
  }
};

}  // namespace sap_broadphase
