// Input adapters without a roscore: the embedded definitions against genmsg, the wire decoders
// of vision_msgs and jsk_recognition_msgs, MarkerArray state, validation, ~sources entries.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <geometry_msgs/PoseWithCovariance.h>
#include <ros/serialization.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>

#include "adapters.h"
#include "adapters_sources.h"
#include "node_params.h"

namespace sap_broadphase {
namespace {

/// Serializes values one after the other, as a publisher of the type would.
class WireWriter {
 public:
  template <class T>
  void put(const T& inValue) {
    const uint32_t length = ros::serialization::serializationLength(inValue);
    const std::size_t at = bytes.size();
    bytes.resize(at + length);
    ros::serialization::OStream stream(bytes.data() + at, length);
    ros::serialization::serialize(stream, inValue);
  }
  std::vector<uint8_t> bytes;
};

std_msgs::Header header(const char* inFrame, uint32_t inSeconds = 7) {
  std_msgs::Header h;
  h.frame_id = inFrame;
  h.stamp = ros::Time(inSeconds, 5);
  return h;
}

geometry_msgs::Pose pose(double inX, double inY, double inZ, const tf2::Quaternion& inRotation) {
  geometry_msgs::Pose p;
  p.position.x = inX;
  p.position.y = inY;
  p.position.z = inZ;
  p.orientation.x = inRotation.x();
  p.orientation.y = inRotation.y();
  p.orientation.z = inRotation.z();
  p.orientation.w = inRotation.w();
  return p;
}

geometry_msgs::Vector3 vector(double inX, double inY, double inZ) {
  geometry_msgs::Vector3 v;
  v.x = inX;
  v.y = inY;
  v.z = inZ;
  return v;
}

/// An oriented box as the tests draw it, and the exact AABB of its corners.
struct OrientedBox {
  geometry_msgs::Pose pose;
  geometry_msgs::Vector3 size;
  std::array<double, 6> aabb() const {
    const tf2::Matrix3x3 r(tf2::Quaternion(pose.orientation.x, pose.orientation.y,
                                           pose.orientation.z, pose.orientation.w));
    std::array<double, 6> out{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (int corner = 0; corner < 8; ++corner) {
      const double local[3] = {(corner & 1 ? 0.5 : -0.5) * size.x,
                               (corner & 2 ? 0.5 : -0.5) * size.y,
                               (corner & 4 ? 0.5 : -0.5) * size.z};
      const double position[3] = {pose.position.x, pose.position.y, pose.position.z};
      for (int axis = 0; axis < 3; ++axis) {
        const double v =
            position[axis] + r[axis][0] * local[0] + r[axis][1] * local[1] + r[axis][2] * local[2];
        out[axis] = std::min(out[axis], v);
        out[3 + axis] = std::max(out[3 + axis], v);
      }
    }
    return out;
  }
};

std::vector<OrientedBox> randomOrientedBoxes(std::size_t inCount, uint32_t inSeed) {
  std::mt19937 random(inSeed);
  std::uniform_real_distribution<double> where(-20.0, 20.0), edge(0.0, 3.0), angle(-M_PI, M_PI);
  std::vector<OrientedBox> boxes;
  for (std::size_t k = 0; k < inCount; ++k) {
    tf2::Quaternion rotation;
    if (k % 2 == 0)
      rotation.setRPY(angle(random), angle(random), angle(random));
    else
      rotation.setRPY(0, 0, 0);  // every other box axis-aligned
    OrientedBox box{pose(where(random), where(random), where(random), rotation),
                    vector(edge(random), edge(random), edge(random))};
    boxes.push_back(box);
  }
  return boxes;
}

/// The adapter's box k contains the exact corners and is no more than a few ulps larger.
void expectBoundsAround(const SourceFrame& inFrame, std::size_t inBox,
                        const std::array<double, 6>& inExact) {
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = inFrame.records.lo(axis, inBox), hi = inFrame.records.hi(axis, inBox);
    EXPECT_LE(lo, inExact[axis]) << "box " << inBox << " axis " << axis;
    EXPECT_GE(hi, inExact[3 + axis]) << "box " << inBox << " axis " << axis;
    EXPECT_NEAR(lo, inExact[axis], 1e-12) << "box " << inBox << " axis " << axis;
    EXPECT_NEAR(hi, inExact[3 + axis], 1e-12) << "box " << inBox << " axis " << axis;
  }
}

std::vector<uint8_t> boundingBox3DArray(const std_msgs::Header& inHeader,
                                        const std::vector<OrientedBox>& inBoxes) {
  WireWriter wire;
  wire.put(inHeader);
  wire.put(static_cast<uint32_t>(inBoxes.size()));
  for (const OrientedBox& box : inBoxes) {
    wire.put(box.pose);
    wire.put(box.size);
  }
  return wire.bytes;
}

std::vector<uint8_t> detection3DArray(const std_msgs::Header& inHeader,
                                      const std::vector<OrientedBox>& inBoxes,
                                      const char* inDetectionFrame) {
  WireWriter wire;
  wire.put(inHeader);
  wire.put(static_cast<uint32_t>(inBoxes.size()));
  for (std::size_t k = 0; k < inBoxes.size(); ++k) {
    wire.put(header(inDetectionFrame));
    wire.put(static_cast<uint32_t>(k % 3));  // results: 0, 1 or 2 hypotheses
    for (std::size_t r = 0; r < k % 3; ++r) {
      wire.put(static_cast<int64_t>(40 + r));
      wire.put(0.5);
      wire.put(geometry_msgs::PoseWithCovariance());
    }
    wire.put(inBoxes[k].pose);
    wire.put(inBoxes[k].size);
    sensor_msgs::PointCloud2 cloud;  // a cloud with data, to be skipped
    cloud.header = inHeader;
    cloud.width = 3;
    cloud.height = 1;
    cloud.fields.resize(1);
    cloud.fields[0].name = "x";
    cloud.point_step = 4;
    cloud.data.assign(12, static_cast<uint8_t>(k));
    wire.put(cloud);
  }
  return wire.bytes;
}

std::vector<uint8_t> jskBoundingBoxArray(const std_msgs::Header& inHeader,
                                         const std::vector<OrientedBox>& inBoxes,
                                         const std::vector<uint32_t>& inLabels) {
  WireWriter wire;
  wire.put(inHeader);
  wire.put(static_cast<uint32_t>(inBoxes.size()));
  for (std::size_t k = 0; k < inBoxes.size(); ++k) {
    wire.put(inHeader);
    wire.put(inBoxes[k].pose);
    wire.put(inBoxes[k].size);
    wire.put(0.75f);
    wire.put(inLabels[k]);
  }
  return wire.bytes;
}

/// A ShapeShifter holding inBytes as a message of inType with inMd5, as a subscriber gets it.
topic_tools::ShapeShifter shapeShifter(const std::string& inType, const std::string& inMd5,
                                       std::vector<uint8_t> inBytes) {
  topic_tools::ShapeShifter msg;
  msg.morph(inMd5, inType, "", "0");
  ros::serialization::IStream stream(inBytes.data(), static_cast<uint32_t>(inBytes.size()));
  msg.read(stream);
  return msg;
}

std::string md5FromGenmsg(const std::string& inType, const std::string& inDefinition) {
  const std::string path = testing::TempDir() + "adapters_definition.msg";
  std::ofstream(path) << inDefinition;
  const std::string command =
      "/usr/bin/python3 " SAP_TEST_ROS_DIR "/msg_md5.py " + inType + " " + path;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "popen failed";
  char line[128] = {};
  const bool read = std::fgets(line, sizeof line, pipe) != nullptr;
  pclose(pipe);
  std::remove(path.c_str());
  std::string md5 = read ? line : "";
  while (!md5.empty() && (md5.back() == '\n' || md5.back() == '\r')) md5.pop_back();
  return md5;
}

TEST(AdapterTypes, EmbeddedDefinitionsHaveTheMd5GenmsgComputes) {
  for (InputType type : {InputType::kBoundingBox3DArray, InputType::kDetection3DArray,
                         InputType::kJskBoundingBoxArray}) {
    const InputTypeInfo& info = inputTypeInfo(type);
    EXPECT_EQ(md5FromGenmsg(info.name, info.definition), info.md5) << info.name;
  }
}

TEST(AdapterTypes, NamesAreFoundAndUnknownOnesAreNot) {
  EXPECT_EQ(inputTypeByName("visualization_msgs/MarkerArray"), InputType::kMarkerArray);
  EXPECT_EQ(inputTypeByName("jsk_recognition_msgs/BoundingBoxArray"),
            InputType::kJskBoundingBoxArray);
  EXPECT_FALSE(inputTypeByName("vision_msgs/Detection3D"));
  EXPECT_EQ(std::string(inputTypeInfo(InputType::kBoxArray).md5),
            ros::message_traits::md5sum<BoxArray>());
}

TEST(WireDecoders, BoundingBox3DArrayRotatedAndAxisAlignedContainTheirCorners) {
  const std::vector<OrientedBox> boxes = randomOrientedBoxes(40, 11);
  SourceAdapter adapter(SourceSpec{"boxes", InputType::kBoundingBox3DArray, 100, {}, {}, {}});
  SourceFrame out;
  ASSERT_FALSE(adapter.convertWire(InputType::kBoundingBox3DArray,
                                   boundingBox3DArray(header("map"), boxes), out));
  EXPECT_EQ(out.header.frame_id, "map");
  EXPECT_EQ(out.header.stamp, ros::Time(7, 5));
  ASSERT_EQ(out.records.bounds.size(), 6 * boxes.size());
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    EXPECT_EQ(out.records.ids[k], 100 + k);
    expectBoundsAround(out, k, boxes[k].aabb());
  }
}

TEST(WireDecoders, Detection3DArraySkipsHypothesesAndCloud) {
  const std::vector<OrientedBox> boxes = randomOrientedBoxes(9, 12);
  SourceAdapter adapter(SourceSpec{"detections", InputType::kDetection3DArray, 0, 4u, 6u, {}});
  SourceFrame out;
  ASSERT_FALSE(adapter.convertWire(InputType::kDetection3DArray,
                                   detection3DArray(header("cam"), boxes, "cam"), out));
  ASSERT_EQ(out.records.bounds.size(), 6 * boxes.size());
  for (std::size_t k = 0; k < boxes.size(); ++k) expectBoundsAround(out, k, boxes[k].aabb());
  EXPECT_EQ(out.records.groups, std::vector<uint32_t>(boxes.size(), 4u));
  EXPECT_EQ(out.records.masks, std::vector<uint32_t>(boxes.size(), 6u));
  std::vector<uint32_t> ids;
  std::vector<std::string> names;
  adapter.appendIdNames(ids, names);
  ASSERT_EQ(names.size(), boxes.size());
  EXPECT_EQ(names[3], "detections: detection 3");
}

TEST(WireDecoders, Detection3DInAnotherFrameIsRefused) {
  SourceAdapter adapter(SourceSpec{"detections", InputType::kDetection3DArray, 0, {}, {}, {}});
  SourceFrame out;
  const auto reason =
      adapter.convertWire(InputType::kDetection3DArray,
                          detection3DArray(header("cam"), randomOrientedBoxes(2, 1), "lidar"), out);
  ASSERT_TRUE(reason);
  EXPECT_NE(reason->find("detection 0 is in frame 'lidar'"), std::string::npos) << *reason;
  EXPECT_EQ(out.header.frame_id, "cam") << "the refusal names the array's frame";
}

TEST(WireDecoders, JskLabelsNameBoxesStably) {
  const std::vector<OrientedBox> boxes = randomOrientedBoxes(4, 13);
  SourceAdapter adapter(SourceSpec{"jsk", InputType::kJskBoundingBoxArray, 500, {}, {}, {}});
  SourceFrame first, second;
  ASSERT_FALSE(adapter.convertWire(InputType::kJskBoundingBoxArray,
                                   jskBoundingBoxArray(header("map"), boxes, {9, 3, 9, 0}), first));
  EXPECT_EQ(first.records.ids, (std::vector<uint32_t>{500, 501, 502, 503}));
  for (std::size_t k = 0; k < boxes.size(); ++k) expectBoundsAround(first, k, boxes[k].aabb());
  // The same labels in another order keep their ids; a new label gets the next one.
  ASSERT_FALSE(adapter.convertWire(
      InputType::kJskBoundingBoxArray,
      jskBoundingBoxArray(header("map"), {boxes[0], boxes[1], boxes[2]}, {0, 7, 3}), second));
  EXPECT_EQ(second.records.ids, (std::vector<uint32_t>{503, 504, 501}));
  std::vector<uint32_t> ids;
  std::vector<std::string> names;
  adapter.appendIdNames(ids, names);
  EXPECT_EQ(ids, (std::vector<uint32_t>{500, 501, 502, 503, 504}));
  EXPECT_EQ(names, (std::vector<std::string>{"jsk: label 9", "jsk: label 3", "jsk: label 9 #1",
                                             "jsk: label 0", "jsk: label 7"}));
}

TEST(WireDecoders, TruncatedAndOverlongMessagesAreRefused) {
  std::vector<uint8_t> bytes = boundingBox3DArray(header("map"), randomOrientedBoxes(3, 2));
  DecodedBoxes decoded;
  ASSERT_FALSE(decodeWireBoxes(InputType::kBoundingBox3DArray, bytes.data(),
                               static_cast<uint32_t>(bytes.size()), decoded));
  EXPECT_EQ(decoded.boxes.size(), 3u);
  const auto truncated = decodeWireBoxes(InputType::kBoundingBox3DArray, bytes.data(),
                                         static_cast<uint32_t>(bytes.size() - 8), decoded);
  ASSERT_TRUE(truncated);
  EXPECT_NE(truncated->find("boxes: claims 3 elements"), std::string::npos) << *truncated;
  bytes.push_back(0);
  const auto overlong = decodeWireBoxes(InputType::kBoundingBox3DArray, bytes.data(),
                                        static_cast<uint32_t>(bytes.size()), decoded);
  ASSERT_TRUE(overlong);
  EXPECT_NE(overlong->find("1 bytes left"), std::string::npos) << *overlong;
}

/// Bytes of a BoxArray in frame inFrame whose bounds prefix claims inClaimed values, followed by
/// inFollowing of them.
std::vector<uint8_t> boxArrayClaiming(uint32_t inClaimed, uint32_t inFollowing) {
  BoxArray message;
  message.header = header("map");
  message.bounds.assign(inFollowing, 1.0);
  WireWriter wire;
  wire.put(message);
  const std::size_t prefix_at = wire.bytes.size() - 8 * inFollowing - 4 - 4 - 4;
  std::memcpy(wire.bytes.data() + prefix_at, &inClaimed, sizeof inClaimed);
  return wire.bytes;
}

TEST(WireLayouts, EveryPrefixCheckedAgainstTheBytesLeft) {
  const WireLayout& layout = wireLayout(InputType::kBoxArray);
  EXPECT_FALSE(layout.check(boxArrayClaiming(6, 6).data(), boxArrayClaiming(6, 6).size()));
  const std::vector<uint8_t> lying = boxArrayClaiming(1u << 27, 6);
  const auto refusal = layout.check(lying.data(), lying.size());
  ASSERT_TRUE(refusal);
  EXPECT_EQ(*refusal,
            "sap_broadphase/BoxArray: bounds: claims 134217728 elements of at least 8 bytes, 56 "
            "bytes left");
  std::vector<uint8_t> trailing = boxArrayClaiming(6, 6);
  trailing.push_back(0);
  EXPECT_EQ(*layout.check(trailing.data(), trailing.size()),
            "sap_broadphase/BoxArray: 1 bytes left after the last field: not the layout its MD5 "
            "sum promises");
  // A string longer than the bytes: the frame id of the header.
  std::vector<uint8_t> long_frame = boxArrayClaiming(6, 6);
  const uint32_t claimed = 1000;
  std::memcpy(long_frame.data() + 12, &claimed, sizeof claimed);
  EXPECT_NE(layout.check(long_frame.data(), long_frame.size())
                ->find("header.frame_id: a string of 1000 bytes"),
            std::string::npos);
  // Any cut of a valid message is refused, never read past its end.
  const std::vector<uint8_t> whole = boxArrayClaiming(12, 12);
  for (std::size_t size = 0; size < whole.size(); ++size)
    EXPECT_TRUE(layout.check(whole.data(), size)) << size;
}

TEST(WireLayouts, NestedArraysOfEveryTypeAreBounded) {
  // 10^9 markers in 4 bytes; a point cloud of 2^32 - 1 bytes inside a detection.
  const uint32_t billion = 1000000000;
  std::vector<uint8_t> markers(4);
  std::memcpy(markers.data(), &billion, 4);
  EXPECT_EQ(*wireLayout(InputType::kMarkerArray).check(markers.data(), markers.size()),
            "visualization_msgs/MarkerArray: markers: claims 1000000000 elements of at least "
            "154 bytes, 0 bytes left");
  for (InputType type : {InputType::kBoundingBox3DArray, InputType::kDetection3DArray,
                         InputType::kJskBoundingBoxArray}) {
    std::vector<uint8_t> bytes = boundingBox3DArray(header("map"), {});
    std::memcpy(bytes.data() + bytes.size() - 4, &billion, 4);
    const auto refusal = wireLayout(type).check(bytes.data(), bytes.size());
    ASSERT_TRUE(refusal);
    EXPECT_NE(refusal->find("claims 1000000000 elements"), std::string::npos) << *refusal;
    DecodedBoxes decoded;
    EXPECT_TRUE(decodeWireBoxes(type, bytes.data(), static_cast<uint32_t>(bytes.size()), decoded));
  }
}

TEST(ShapeShifterCheck, TheTypeNameAndMd5MustMatch) {
  const std::vector<OrientedBox> boxes = randomOrientedBoxes(2, 3);
  const std::vector<uint8_t> bytes = boundingBox3DArray(header("map"), boxes);
  SourceAdapter adapter(SourceSpec{"boxes", InputType::kBoundingBox3DArray, 0, {}, {}, {}});
  SourceFrame out;
  const InputTypeInfo& info = inputTypeInfo(InputType::kBoundingBox3DArray);
  EXPECT_FALSE(adapter.convert(shapeShifter(info.name, info.md5, bytes), "/robot", out));
  EXPECT_EQ(out.records.bounds.size(), 12u);

  // vision_msgs 2 names the centre `origin`... any other definition has another MD5 sum.
  const auto other_md5 = adapter.convert(
      shapeShifter(info.name, "0123456789abcdef0123456789abcdef", bytes), "/robot", out);
  ASSERT_TRUE(other_md5);
  EXPECT_NE(
      other_md5->find("MD5 sum 0123456789abcdef0123456789abcdef, not " + std::string(info.md5)),
      std::string::npos)
      << *other_md5;
  const auto other_type =
      adapter.convert(shapeShifter("vision_msgs/Detection3DArray",
                                   inputTypeInfo(InputType::kDetection3DArray).md5, bytes),
                      "/robot", out);
  ASSERT_TRUE(other_type);
  EXPECT_NE(other_type->find("a vision_msgs/Detection3DArray message, but the entry's type is "
                             "vision_msgs/BoundingBox3DArray"),
            std::string::npos)
      << *other_type;
}

TEST(ShapeShifterCheck, MarkerArrayAndBoxArrayAreInstantiated) {
  visualization_msgs::MarkerArray markers;
  markers.markers.resize(1);
  markers.markers[0].header = header("map");
  markers.markers[0].ns = "walls";
  markers.markers[0].id = 4;
  markers.markers[0].type = visualization_msgs::Marker::CUBE;
  markers.markers[0].pose.orientation.w = 1.0;
  markers.markers[0].scale = vector(2, 2, 2);
  WireWriter wire;
  wire.put(markers);
  SourceAdapter adapter(SourceSpec{"markers", InputType::kMarkerArray, 0, {}, {}, {}});
  SourceFrame out;
  const InputTypeInfo& info = inputTypeInfo(InputType::kMarkerArray);
  ASSERT_FALSE(adapter.convert(shapeShifter(info.name, info.md5, wire.bytes), "/robot", out));
  ASSERT_EQ(out.records.bounds.size(), 6u);
  EXPECT_NEAR(out.records.bounds[0], -1.0, 1e-12);
  EXPECT_NEAR(out.records.bounds[5], 1.0, 1e-12);
  std::vector<uint8_t> truncated = wire.bytes;
  truncated.resize(truncated.size() - 10);
  const auto unreadable =
      adapter.convert(shapeShifter(info.name, info.md5, truncated), "/robot", out);
  ASSERT_TRUE(unreadable);
  EXPECT_NE(unreadable->find("visualization_msgs/MarkerArray: markers: claims 1 elements"),
            std::string::npos)
      << *unreadable;

  BoxArray boxes;
  boxes.header = header("map");
  boxes.bounds = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3};
  WireWriter box_wire;
  box_wire.put(boxes);
  SourceAdapter offset(SourceSpec{"boxes", InputType::kBoxArray, 10, {}, 3u, {}});
  const InputTypeInfo& box_info = inputTypeInfo(InputType::kBoxArray);
  ASSERT_FALSE(
      offset.convert(shapeShifter(box_info.name, box_info.md5, box_wire.bytes), "/robot", out));
  // Numbered 0..n-1; the engine adds the id_offset as it reads the span.
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(out.span().idOf(0), 10u);
  EXPECT_EQ(out.span().idOf(1), 11u);
  EXPECT_EQ(out.records.masks, (std::vector<uint32_t>{3, 3}));
  EXPECT_TRUE(out.records.groups.empty());
}

visualization_msgs::Marker cube(const char* inNs, int32_t inId, double inX, const char* inFrame) {
  visualization_msgs::Marker marker;
  marker.header = header(inFrame);
  marker.ns = inNs;
  marker.id = inId;
  marker.type = visualization_msgs::Marker::CUBE;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.position.x = inX;
  marker.pose.orientation.w = 1.0;
  marker.scale = vector(1, 2, 4);
  return marker;
}

visualization_msgs::Marker action(int32_t inAction, const char* inNs = "", int32_t inId = 0) {
  visualization_msgs::Marker marker;
  marker.action = inAction;
  marker.ns = inNs;
  marker.id = inId;
  return marker;
}

TEST(MarkerAdapter, CubeListPointsAreCubesUnderThePose) {
  visualization_msgs::Marker list = cube("list", 1, 10.0, "map");
  list.type = visualization_msgs::Marker::CUBE_LIST;
  tf2::Quaternion quarter;
  quarter.setRPY(0, 0, M_PI / 2);  // x -> y
  list.pose = pose(10.0, 0.0, 0.0, quarter);
  list.points.resize(2);
  list.points[1].x = 3.0;
  visualization_msgs::MarkerArray msg;
  msg.markers = {list};
  SourceAdapter adapter(SourceSpec{"m", InputType::kMarkerArray, 0, {}, {}, {}});
  SourceFrame out;
  ASSERT_FALSE(adapter.convertMarkers(msg, "/a", out));
  ASSERT_EQ(out.records.bounds.size(), 12u);
  // Point (3, 0, 0), scale (1, 2, 4), turned a quarter about z, then moved by (10, 0, 0).
  expectBoundsAround(out, 0, {9.0, -0.5, -2.0, 11.0, 0.5, 2.0});
  expectBoundsAround(out, 1, {9.0, 2.5, -2.0, 11.0, 3.5, 2.0});
  std::vector<uint32_t> ids;
  std::vector<std::string> names;
  adapter.appendIdNames(ids, names);
  EXPECT_EQ(names, (std::vector<std::string>{"m: list/1[0]", "m: list/1[1]"}));
}

TEST(MarkerAdapter, IdsMarkerGivesTheMarkersOwnIdPlusTheOffset) {
  XmlRpc::XmlRpcValue list;
  ASSERT_EQ(parseYamlParameter("[{topic: m, type: visualization_msgs/MarkerArray, id_offset: 1000, "
                               "ids: marker}]",
                               list),
            "");
  std::vector<SourceSpec> specs;
  ASSERT_EQ(parseSourceSpecs(list, specs), "");
  ASSERT_TRUE(specs[0].marker_ids);
  EXPECT_EQ(describeSourceSpec(specs[0]),
            "m (visualization_msgs/MarkerArray, id_offset 1000, ids marker)");
  SourceAdapter adapter(specs[0]);
  SourceFrame out;
  visualization_msgs::MarkerArray msg;
  msg.markers = {cube("a", 7, 0.0, "map"), cube("a", 3, 5.0, "map")};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r1", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{1003, 1007}));  // the set in (ns, id) order
  std::vector<uint32_t> ids;
  std::vector<std::string> names;
  adapter.appendIdNames(ids, names);
  EXPECT_EQ(ids, (std::vector<uint32_t>{1003, 1007}));
  EXPECT_EQ(names, (std::vector<std::string>{"m: a/3", "m: a/7"}));

  // What has no representation is refused, naming the box and why; the set stays as it was.
  msg.markers = {cube("a", -1, 0.0, "map")};
  const auto negative = adapter.convertMarkers(msg, "/r1", out);
  ASSERT_TRUE(negative);
  EXPECT_NE(negative->find("box 'a/-1': id -1 plus id_offset 1000 is no id"), std::string::npos)
      << *negative;
  visualization_msgs::Marker points = cube("b", 1, 0.0, "map");
  points.type = visualization_msgs::Marker::CUBE_LIST;
  points.points.resize(1);
  msg.markers = {points};
  const auto listed = SourceAdapter(specs[0]).convertMarkers(msg, "/r1", out);
  ASSERT_TRUE(listed);
  EXPECT_NE(listed->find("CUBE_LIST's points have no id of their own"), std::string::npos)
      << *listed;

  XmlRpc::XmlRpcValue boxes;
  ASSERT_EQ(parseYamlParameter("[{topic: b, ids: marker}]", boxes), "");
  EXPECT_EQ(parseSourceSpecs(boxes, specs),
            "~sources[0].ids 'marker' needs type visualization_msgs/MarkerArray");
}

TEST(MarkerAdapter, DeleteAndDeleteAllChangeThePublishersSet) {
  SourceAdapter adapter(SourceSpec{"m", InputType::kMarkerArray, 1000, {}, {}, {}});
  SourceFrame out;
  visualization_msgs::MarkerArray msg;
  msg.markers = {cube("a", 1, 0.0, "map"), cube("a", 2, 5.0, "map"), cube("b", 1, 9.0, "map")};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r1", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{1000, 1001, 1002}));

  // The set is kept: a message with one changed marker still gives all three.
  msg.markers = {cube("a", 2, 6.0, "map")};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r1", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{1000, 1001, 1002}));
  EXPECT_NEAR(out.records.bounds[6], 5.5, 1e-12);

  msg.markers = {action(visualization_msgs::Marker::DELETE, "a", 1)};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r1", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{1001, 1002}));

  // Another publisher has its own set.
  msg.markers = {cube("a", 1, 0.0, "map")};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r2", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{1000}));

  // DELETEALL, then an ADD in the same message: only the ADD is left.
  msg.markers = {action(visualization_msgs::Marker::DELETEALL), cube("c", 0, 1.0, "map")};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r1", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{1003}));
  msg.markers = {action(visualization_msgs::Marker::DELETEALL)};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r1", out));
  EXPECT_TRUE(out.records.ids.empty());
  EXPECT_EQ(out.header.frame_id, "map");  // an emptied set stays in its frame
}

TEST(MarkerAdapter, OtherMarkerTypesGiveNoBoxAndReplaceACube) {
  SourceAdapter adapter(SourceSpec{"m", InputType::kMarkerArray, 0, {}, {}, {}});
  SourceFrame out;
  visualization_msgs::MarkerArray msg;
  visualization_msgs::Marker sphere = cube("s", 1, 0.0, "map");
  sphere.type = visualization_msgs::Marker::SPHERE;
  msg.markers = {cube("s", 1, 0.0, "map"), cube("t", 1, 0.0, "map")};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r", out));
  EXPECT_EQ(out.records.ids.size(), 2u);
  msg.markers = {sphere};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{1}));
}

TEST(MarkerAdapter, ARefusedMessageLeavesTheSetAsItWas) {
  SourceAdapter adapter(SourceSpec{"m", InputType::kMarkerArray, 0, {}, {}, {}});
  SourceFrame out;
  visualization_msgs::MarkerArray msg;
  msg.markers = {cube("a", 1, 0.0, "map")};
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r", out));
  msg.markers = {action(visualization_msgs::Marker::DELETE, "a", 1), cube("a", 2, 0.0, "odom"),
                 cube("a", 3, 0.0, "map")};
  const auto frames = adapter.convertMarkers(msg, "/r", out);
  ASSERT_TRUE(frames);
  EXPECT_NE(frames->find("marker 'a/3' is in frame 'map' but marker 'a/2' in frame 'odom'"),
            std::string::npos)
      << *frames;
  msg.markers = {cube("b", 1, 0.0, "map")};
  msg.markers[0].scale.y = -1.0;
  const auto negative = adapter.convertMarkers(msg, "/r", out);
  ASSERT_TRUE(negative);
  EXPECT_NE(negative->find("box 'b/1': negative size (1, -1, 4)"), std::string::npos) << *negative;
  EXPECT_EQ(out.header.frame_id, "map") << "the refusal names the marker's frame";
  msg.markers.clear();
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r", out));
  EXPECT_EQ(out.records.ids, (std::vector<uint32_t>{0}));  // a/1 still there
}

TEST(MarkerAdapter, DepartedPublishersAreForgotten) {
  // Publishers coming and going: each leaves its marker set until its source times out.
  SourceAdapter adapter(SourceSpec{"m", InputType::kMarkerArray, 0, {}, {}, {}});
  SourceFrame out;
  visualization_msgs::MarkerArray msg;
  msg.markers = {cube("a", 1, 0.0, "map")};
  for (int k = 0; k < 50; ++k)
    ASSERT_FALSE(adapter.convertMarkers(msg, "/robot_" + std::to_string(k), out));
  EXPECT_EQ(adapter.publisherCount(), 50u);
  for (int k = 0; k < 50; ++k) adapter.dropPublisher("/robot_" + std::to_string(k));
  EXPECT_EQ(adapter.publisherCount(), 0u);
  // Back after its time-out, a publisher starts from an empty set: its old cube is gone.
  msg.markers.clear();
  ASSERT_FALSE(adapter.convertMarkers(msg, "/robot_0", out));
  EXPECT_TRUE(out.records.ids.empty());
}

TEST(MarkerAdapter, NamesPastTheCapAreRefusedSayingSo) {
  SourceAdapter adapter(SourceSpec{"m", InputType::kMarkerArray, 0, {}, {}, {}});
  SourceFrame out;
  visualization_msgs::MarkerArray msg;
  msg.markers = {cube("a", 0, 0.0, "map")};
  msg.markers[0].type = visualization_msgs::Marker::CUBE_LIST;
  msg.markers[0].points.resize(kMaxNamesPerSource);  // one name per point: the cap, exactly
  ASSERT_FALSE(adapter.convertMarkers(msg, "/r", out));
  EXPECT_EQ(adapter.nameCount(), kMaxNamesPerSource);
  msg.markers = {cube("b", 1, 0.0, "map")};
  const auto refusal = adapter.convertMarkers(msg, "/r2", out);
  ASSERT_TRUE(refusal);
  EXPECT_NE(refusal->find("box 'b/1': no id left: the source has named 262144 boxes (at most "
                          "262144"),
            std::string::npos)
      << *refusal;
  EXPECT_EQ(adapter.nameCount(), kMaxNamesPerSource);
}

TEST(Validation, NaNNegativeSizeAndBadQuaternionsNameTheBox) {
  PosedBox box{"obstacles/7", pose(0, 0, 0, tf2::Quaternion(0, 0, 0, 1)), geometry_msgs::Point(),
               vector(1, 1, 1), std::nullopt};
  EXPECT_FALSE(checkPosedBox(box));
  PosedBox zero = box;
  zero.pose.orientation.w = 0.0;  // an unset orientation: the identity, as in rviz
  EXPECT_FALSE(checkPosedBox(zero));
  PosedBox nan_position = box;
  nan_position.pose.position.y = NAN;
  EXPECT_EQ(checkPosedBox(nan_position).value_or(""), "box 'obstacles/7': position is NaN");
  PosedBox nan_size = box;
  nan_size.size.z = NAN;
  EXPECT_EQ(checkPosedBox(nan_size).value_or(""), "box 'obstacles/7': size is NaN");
  PosedBox long_quaternion = box;
  long_quaternion.pose.orientation.w = 2.0;
  EXPECT_EQ(checkPosedBox(long_quaternion).value_or(""),
            "box 'obstacles/7': orientation (0, 0, 0, 2) is not a unit quaternion (norm 2)");
  PosedBox infinite_size = box;
  infinite_size.size.x = INFINITY;  // an unbounded box is allowed, as in BoxArray
  EXPECT_FALSE(checkPosedBox(infinite_size));
}

TEST(Overrides, IdOffsetOverflowIsRefusedByTheEngine) {
  SourceAdapter adapter(SourceSpec{"b", InputType::kBoxArray, 4294967290u, {}, {}, {}});
  BoxArray boxes;
  boxes.bounds.assign(12, 0.0);
  boxes.ids = {1, 5};
  SourceFrame frame;
  ASSERT_FALSE(adapter.convertBoxArray(boxes, frame));
  EXPECT_FALSE(validate(BoxFrame(frame.span())));
  EXPECT_EQ(frame.span().idOf(1), 4294967295u);
  boxes.ids = {1, 6};
  ASSERT_FALSE(adapter.convertBoxArray(boxes, frame));
  const auto error = validate(BoxFrame(frame.span()));
  ASSERT_TRUE(error);
  EXPECT_EQ(error->index, 1u);
  EXPECT_EQ(error->problem, BoxProblem::kIdOverflow) << error->message();
  // A shape the records cannot take is the adapter's to refuse.
  boxes.ids = {1};
  EXPECT_EQ(adapter.convertBoxArray(boxes, frame).value_or("").rfind("ids has 1 entry but", 0), 0u);
}

XmlRpc::XmlRpcValue entry(const std::string& inTopic) {
  XmlRpc::XmlRpcValue value;
  value["topic"] = inTopic;
  return value;
}

TEST(SourceSpecs, TopicsAndDictsAreRead) {
  XmlRpc::XmlRpcValue list;
  list[0] = std::string("boxes");
  list[1] = entry("markers");
  list[1]["type"] = std::string("visualization_msgs/MarkerArray");
  list[1]["id_offset"] = 1000;
  list[1]["timeout"] = 0.5;
  list[2] = entry("jsk");
  list[2]["type"] = std::string("jsk_recognition_msgs/BoundingBoxArray");
  list[2]["mask"] = 4294967295.0;  // YAML reads 0xFFFFFFFF as a double: past int32
  list[2]["group"] = std::string("0x2");
  std::vector<SourceSpec> specs;
  ASSERT_EQ(parseSourceSpecs(list, specs), "");
  ASSERT_EQ(specs.size(), 3u);
  EXPECT_TRUE(specs[0].takesBoxArrayAsIs());
  EXPECT_EQ(specs[1].type, InputType::kMarkerArray);
  EXPECT_EQ(specs[1].id_offset, 1000u);
  EXPECT_EQ(specs[1].timeout, 0.5);
  EXPECT_EQ(specs[2].mask, 4294967295u);
  EXPECT_EQ(specs[2].group, 2u);
  EXPECT_EQ(describeSourceSpec(specs[0]), "boxes");
  EXPECT_EQ(describeSourceSpec(specs[1]),
            "markers (visualization_msgs/MarkerArray, id_offset 1000, timeout 0.5 s)");
  EXPECT_EQ(describeSourceSpec(specs[2]),
            "jsk (jsk_recognition_msgs/BoundingBoxArray, group 0x2, mask 0xFFFFFFFF)");
}

// roscpp hands `rosrun sap_broadphase node _sources:="[...]"` over as this string.
TEST(SourceSpecs, TheCommandLinesYamlStringIsRead) {
  XmlRpc::XmlRpcValue value;
  ASSERT_EQ(parseYamlParameter("[boxes, {topic: obstacles, type: visualization_msgs/MarkerArray, "
                               "id_offset: 1000, mask: '0xFFFFFFFD', timeout: 0.5}]",
                               value),
            "");
  std::vector<SourceSpec> specs;
  ASSERT_EQ(parseSourceSpecs(value, specs), "");
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(describeSourceSpec(specs[0]), "boxes");
  EXPECT_EQ(describeSourceSpec(specs[1]),
            "obstacles (visualization_msgs/MarkerArray, id_offset 1000, mask 0xFFFFFFFD, "
            "timeout 0.5 s)");
  EXPECT_EQ(
      parseYamlParameter("[boxes, {topic: a", value).rfind("'[boxes, {topic: a' is not YAML (", 0),
      0u);
  // An alias inside the node it names nests without end: refused, not a stack overflow (the
  // sources fuzzer's find, kept in fuzz/regressions/sources/).
  EXPECT_NE(parseYamlParameter("&x [boxes, *x]", value).find("nests deeper than 16 levels"),
            std::string::npos);
  EXPECT_NE(parseYamlParameter("a: &x [1, 2, b: *x]", value).find("nests deeper than"),
            std::string::npos);
}

TEST(SourceSpecs, ProblemsNameTheEntryAndKey) {
  std::vector<SourceSpec> specs;
  XmlRpc::XmlRpcValue empty;
  empty.setSize(0);
  EXPECT_NE(parseSourceSpecs(empty, specs).find("non-empty list"), std::string::npos);

  XmlRpc::XmlRpcValue unknown_type;
  unknown_type[0] = entry("a");
  unknown_type[0]["type"] = std::string("vision_msgs/Detection2DArray");
  EXPECT_EQ(parseSourceSpecs(unknown_type, specs)
                .rfind("~sources[0].type 'vision_msgs/Detection2DArray' is none of ", 0),
            0u);
  XmlRpc::XmlRpcValue unknown_key;
  unknown_key[0] = entry("a");
  unknown_key[0]["offset"] = 3;
  EXPECT_EQ(parseSourceSpecs(unknown_key, specs),
            "~sources[0] has an unknown key 'offset' (keys: topic, type, id_offset, group, mask, "
            "timeout, ids)");
  XmlRpc::XmlRpcValue negative;
  negative[0] = entry("a");
  negative[0]["id_offset"] = -1;
  EXPECT_EQ(parseSourceSpecs(negative, specs),
            "~sources[0].id_offset must be a whole number from 0 to 4294967295 (past 2147483647 "
            "as a float or as text, e.g. 4294967293.0 or '0xFFFFFFFD')");
  XmlRpc::XmlRpcValue bad_text;
  bad_text[0] = entry("a");
  bad_text[0]["mask"] = std::string("0x1FFFFFFFF");
  EXPECT_NE(parseSourceSpecs(bad_text, specs).find("~sources[0].mask must be"), std::string::npos);
  XmlRpc::XmlRpcValue twice;
  twice[0] = std::string("a");
  twice[1] = entry("a");
  EXPECT_EQ(parseSourceSpecs(twice, specs), "~sources lists 'a' twice");
  XmlRpc::XmlRpcValue no_topic;
  no_topic[0]["type"] = std::string("visualization_msgs/MarkerArray");
  EXPECT_EQ(parseSourceSpecs(no_topic, specs), "~sources[0].topic must be a topic name (a string)");
  XmlRpc::XmlRpcValue bad_timeout;
  bad_timeout[0] = entry("a");
  bad_timeout[0]["timeout"] = -0.5;
  EXPECT_EQ(parseSourceSpecs(bad_timeout, specs),
            "~sources[0].timeout must be a number of seconds >= 0 (0 = never)");
  EXPECT_TRUE(specs.empty());  // never replaced by a refused list
}

// Topics are compared as the node subscribes to them, resolved in its namespace: one topic
// spelled two ways, or the scenery topic as a source, is refused naming both spellings.
TEST(SourceSpecs, TopicsAreComparedAsResolvedNames) {
  const auto in_ns = [](const std::string& inTopic) {
    return inTopic.front() == '/' ? inTopic : "/ns/" + inTopic;
  };
  const auto specs_of = [](std::vector<std::string> inTopics) {
    std::vector<SourceSpec> specs(inTopics.size());
    for (std::size_t k = 0; k < specs.size(); ++k) specs[k].topic = inTopics[k];
    return specs;
  };
  EXPECT_EQ(checkResolvedSourceTopics(specs_of({"boxes", "/ns/boxes"}), in_ns),
            "~sources lists 'boxes' and '/ns/boxes', one topic twice (/ns/boxes)");
  EXPECT_EQ(checkResolvedSourceTopics(specs_of({"/ns/markers", "a", "markers"}), in_ns),
            "~sources lists '/ns/markers' and 'markers', one topic twice (/ns/markers)");
  EXPECT_EQ(checkResolvedSourceTopics(specs_of({"a", "/ns/static_boxes"}), in_ns),
            "~sources lists '/ns/static_boxes', which is the scenery topic static_boxes "
            "(/ns/static_boxes): the scenery is read as static_boxes only");
  EXPECT_EQ(checkResolvedSourceTopics(specs_of({"boxes", "/boxes", "/other/boxes"}), in_ns), "");
}

}  // namespace
}  // namespace sap_broadphase
