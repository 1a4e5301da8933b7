#include "wire_checks.h"

#include <exception>
#include <fstream>
#include <sstream>
#include <vector>

#include <ros/serialization.h>
#include <visualization_msgs/MarkerArray.h>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/ComputePairs.h"
#include "sap_broadphase/QueryBoxes.h"
#include "wire_layout.h"

namespace sap_broadphase::fuzz {

namespace {

/// A definition of src/ros/adapters_msgs (the types the node has no C++ class for).
std::string adapterDefinition(const char* inFile) {
  std::ifstream file(std::string(SAP_ADAPTERS_MSGS_DIR) + "/" + inFile);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

template <typename Message>
WireLayout layoutOf() {
  return WireLayout(ros::message_traits::DataType<Message>::value(),
                    ros::message_traits::Definition<Message>::value());
}

/// Deserializes bytes the layout accepted: no exception, every byte read.
template <typename Message>
std::string deserializeAccepted(const uint8_t* inData, std::size_t inSize, Message& outMessage) {
  try {
    ros::serialization::IStream stream(const_cast<uint8_t*>(inData), static_cast<uint32_t>(inSize));
    ros::serialization::deserialize(stream, outMessage);
    if (stream.getLength() != 0)
      return "accepted bytes left " + std::to_string(stream.getLength()) + " unread";
  } catch (const std::exception& exception) {
    return std::string("accepted bytes throw in roscpp: ") + exception.what();
  }
  return "";
}

std::string boxArrayWithin(const BoxArray& inBoxes, std::size_t inSize) {
  const std::size_t bytes = inBoxes.header.frame_id.size() + 4 * inBoxes.ids.size() +
                            8 * inBoxes.bounds.size() + 4 * inBoxes.groups.size() +
                            4 * inBoxes.masks.size();
  return bytes <= inSize
             ? ""
             : "a BoxArray of " + std::to_string(bytes) + " bytes from " + std::to_string(inSize);
}

std::string checkAccepted(int inType, const uint8_t* inData, std::size_t inSize) {
  if (inType == 0) {
    BoxArray boxes;
    std::string problem = deserializeAccepted(inData, inSize, boxes);
    return problem.empty() ? boxArrayWithin(boxes, inSize) : problem;
  }
  if (inType == 1) {
    visualization_msgs::MarkerArray markers;
    std::string problem = deserializeAccepted(inData, inSize, markers);
    if (!problem.empty()) return problem;
    std::size_t bytes = 154 * markers.markers.size();  // a marker's fewest bytes on the wire
    for (const auto& marker : markers.markers)
      bytes += 24 * marker.points.size() + 16 * marker.colors.size();
    return bytes <= inSize ? ""
                           : "markers of at least " + std::to_string(bytes) + " bytes from " +
                                 std::to_string(inSize);
  }
  if (inType == 5) {
    ComputePairs::Request request;
    std::string problem = deserializeAccepted(inData, inSize, request);
    return problem.empty() ? boxArrayWithin(request.boxes, inSize) : problem;
  }
  if (inType == 6) {
    QueryBoxes::Request request;
    std::string problem = deserializeAccepted(inData, inSize, request);
    return problem.empty() ? boxArrayWithin(request.boxes, inSize) : problem;
  }
  return "";  // vision_msgs and jsk: the node's decoders read what the layout accepted
}

}  // namespace

std::string checkWireInput(const uint8_t* inData, std::size_t inSize) {
  static const std::vector<WireLayout> kLayouts = {
      layoutOf<BoxArray>(),
      layoutOf<visualization_msgs::MarkerArray>(),
      WireLayout("vision_msgs/BoundingBox3DArray",
                 adapterDefinition("vision_msgs__BoundingBox3DArray.msg")),
      WireLayout("vision_msgs/Detection3DArray",
                 adapterDefinition("vision_msgs__Detection3DArray.msg")),
      WireLayout("jsk_recognition_msgs/BoundingBoxArray",
                 adapterDefinition("jsk_recognition_msgs__BoundingBoxArray.msg")),
      layoutOf<ComputePairs::Request>(),
      layoutOf<QueryBoxes::Request>(),
  };
  if (inSize == 0) return "";
  const int type = inData[0] % static_cast<int>(kLayouts.size());
  const WireLayout& layout = kLayouts[type];
  // A copy of exactly the message's bytes: ASan sees any read past them.
  const std::vector<uint8_t> bytes(inData + 1, inData + inSize);
  const auto refusal = layout.check(bytes.data(), bytes.size());
  if (refusal) {
    if (refusal->rfind(layout.typeName() + ": ", 0) != 0)
      return "a refusal that does not name the type: " + *refusal;
    return "";
  }
  const std::string problem = checkAccepted(type, bytes.data(), bytes.size());
  return problem.empty() ? "" : layout.typeName() + ": " + problem;
}

}  // namespace sap_broadphase::fuzz
