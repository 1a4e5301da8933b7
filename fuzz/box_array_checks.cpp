#include "box_array_checks.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <ros/serialization.h>

#include "fuzz_checks.h"
#include "message_read_back.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase::fuzz {
namespace {

// Largest serialized message this check deserializes: roscpp itself refuses messages above
// 1e9 bytes; fuzz inputs are far smaller, but a length prefix inside may claim 4 G entries.
constexpr std::size_t kMaxClaimedBytes = std::size_t{1} << 26;

bool sameBits(double inA, double inB) {
  return std::memcmp(&inA, &inB, sizeof inA) == 0;
}

// The element counts claimed by the four array length prefixes, checked against the bytes
// left, so that a claim of 4 G doubles is refused before resize() (roscpp would throw
// std::bad_alloc, or allocate and then throw StreamOverrunException).
bool claimsFit(const uint8_t* inData, std::size_t inSize) {
  std::size_t offset = 0;
  auto read32 = [&](uint32_t& outValue) {
    if (offset + 4 > inSize) return false;
    std::memcpy(&outValue, inData + offset, 4);  // ROS serialization is little-endian
    offset += 4;
    return true;
  };
  uint32_t value = 0;
  // header: seq, stamp (2 x uint32), frame_id (length + bytes)
  for (int k = 0; k < 3; ++k)
    if (!read32(value)) return false;
  if (!read32(value) || value > inSize - offset) return false;
  offset += value;
  const std::size_t element_bytes[4] = {4, 8, 4, 4};  // ids, bounds, groups, masks
  for (std::size_t bytes : element_bytes) {
    if (!read32(value)) return false;
    const std::size_t claimed = std::size_t{value} * bytes;
    if (claimed > kMaxClaimedBytes || claimed > inSize - offset) return false;
    offset += claimed;
  }
  return true;
}

// The engine reading the message's records itself: it refuses what the conversion refuses,
// in the same words, and otherwise finds the pairs of the converted boxes. Twice: after a
// clean frame of the same size and numbering, so the bad boxes meet the check made while the
// records are compared with the last frame, not only the first frame's full check.
std::string checkRecords(const BoxArray& inMsg, const std::optional<std::string>& inRefusal,
                         const BoxSet& inConverted) {
  const std::size_t count = inMsg.bounds.size() / 6;
  if (count > kMaxEngineBoxes) return "";
  BoxArray clean = inMsg;
  for (std::size_t i = 0; i < count; ++i) {
    double* record = clean.bounds.data() + 6 * i;
    for (int coordinate = 0; coordinate < 6; ++coordinate)
      if (std::isnan(record[coordinate])) record[coordinate] = 0.0;
    for (int axis = 0; axis < 3; ++axis)
      if (record[axis] > record[3 + axis]) std::swap(record[axis], record[3 + axis]);
  }
  clean.ids.clear();  // numbered 0..n-1: unique
  Broadphase engine(BroadphaseConfig{});
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) engine.update(boxArrayRecords(clean));
    try {
      const PairList& pairs = engine.update(boxArrayRecords(inMsg));
      if (inRefusal) return "the engine accepted records the conversion refuses";
      Broadphase reference(BroadphaseConfig{});
      if (pairs != reference.update(inConverted)) return "records gave other pairs than the BoxSet";
    } catch (const InvalidBoxes& refusal) {
      if (!inRefusal) return "the engine refused records the conversion accepts";
      if (refusal.error().message() != *inRefusal)
        return "the engine's refusal is worded otherwise";
    }
  }
  return "";
}

std::string checkConverted(const BoxArray& inMsg) {
  const auto shape = checkBoxArrayShape(inMsg);
  BoxSet boxes;
  const auto refusal = test::boxArrayToBoxSet(inMsg, boxes);
  if (shape && !refusal) return "shape error '" + *shape + "' but the conversion accepted";
  if (shape && *refusal != *shape) return "conversion gave a different reason than the shape";
  if (!shape) {
    const std::string records = checkRecords(inMsg, refusal, boxes);
    if (!records.empty()) return records;
  }
  if (refusal) {
    if (refusal->empty()) return "refusal without a reason";
    if (!shape && !validate(boxes)) return "conversion refused what validate() accepts";
    return "";
  }
  if (validate(boxes)) return "conversion accepted what validate() refuses";
  const std::size_t count = inMsg.bounds.size() / 6;
  if (boxes.size() != count) return "box count changed";
  for (std::size_t i = 0; i < count; ++i) {
    if (boxes.ids[i] != (inMsg.ids.empty() ? i : inMsg.ids[i])) return "id changed";
    for (int axis = 0; axis < 3; ++axis)
      if (!sameBits(boxes.lo(axis, i), inMsg.bounds[6 * i + axis]) ||
          !sameBits(boxes.hi(axis, i), inMsg.bounds[6 * i + 3 + axis]))
        return "bound changed in the conversion";
  }
  BoxArray back;
  boxSetToBoxArray(boxes, inMsg.header, back);
  BoxSet again;
  if (auto error = test::boxArrayToBoxSet(back, again)) return "boxSetToBoxArray output refused";
  if (again.ids != boxes.ids || again.groups != boxes.groups || again.masks != boxes.masks)
    return "ids or filters changed in the message round trip";
  if (boxes.size() > kMaxEngineBoxes) return "";
  const std::string engine = checkEngine(boxes, static_cast<uint32_t>(count));
  if (!engine.empty()) return engine;
  Broadphase oracle_engine(BroadphaseConfig{});
  PairArray pairs_msg;
  pairListToPairArray(oracle_engine.update(boxes), inMsg.header, pairs_msg);
  PairList pairs;
  if (!test::pairArrayToPairList(pairs_msg, pairs) || pairs != oracle_engine.update(boxes))
    return "pairs changed in the PairArray round trip";
  return "";
}

}  // namespace

std::string checkBoxArrayBytes(const uint8_t* inData, std::size_t inSize) {
  if (!claimsFit(inData, inSize)) return "";
  BoxArray msg;
  try {
    // ros::serialization::IStream does not write; the cast only satisfies its signature.
    ros::serialization::IStream stream(const_cast<uint8_t*>(inData), static_cast<uint32_t>(inSize));
    ros::serialization::deserialize(stream, msg);
  } catch (const std::exception&) {
    return "";  // roscpp's MessageDeserializer catches and logs the same exceptions
  }
  return checkConverted(msg);
}

std::string checkBoxArrayFromBoxSetBytes(const uint8_t* inData, std::size_t inSize) {
  uint32_t variant = 0;
  const BoxSet boxes = decodeBoxSet(inData, inSize, variant);
  BoxArray msg;
  msg.header.frame_id = "fuzz";
  msg.header.seq = variant;
  if (variant & 0x1) msg.ids = boxes.ids;
  msg.groups = boxes.groups;
  msg.masks = boxes.masks;
  msg.bounds = boxes.bounds;  // the same records, a short one included
  const std::size_t count = boxes.bounds.size() / kBoundsPerBox;
  if (variant & 0x2) msg.bounds.resize(msg.bounds.size() - std::min<std::size_t>(1, count));
  return checkConverted(msg);
}

std::string checkBoxArrayInput(const uint8_t* inData, std::size_t inSize) {
  if (inSize == 0) return "";
  return (inData[0] & 1) ? checkBoxArrayFromBoxSetBytes(inData + 1, inSize - 1)
                         : checkBoxArrayBytes(inData + 1, inSize - 1);
}

}  // namespace sap_broadphase::fuzz
