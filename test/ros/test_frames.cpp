// Box frames for the node tests.
#include "test_frames.h"

#include <random>
#include <unordered_set>

#include "message_read_back.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {
namespace test {

BoxSet randomBoxes(std::size_t inCount, double inMaxEdge, bool inSparseIds, uint32_t inSeed) {
  std::mt19937 random(inSeed);
  std::uniform_real_distribution<double> position(0.0, 10.0), edge(0.0, inMaxEdge);
  std::uniform_int_distribution<uint32_t> any_id;
  std::unordered_set<uint32_t> used;
  BoxSet boxes;
  for (std::size_t i = 0; i < inCount; ++i) {
    uint32_t id = static_cast<uint32_t>(i);
    if (inSparseIds) {
      do id = any_id(random);
      while (!used.insert(id).second);
    }
    double lo[3], hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = position(random);
      hi[axis] = lo[axis] + edge(random);
    }
    boxes.add(id, lo, hi);
  }
  return boxes;
}

BoxSet touchingGrid(int inSide, uint32_t inFirstId) {
  BoxSet boxes;
  uint32_t id = inFirstId;
  for (int x = 0; x < inSide; ++x) {
    for (int y = 0; y < inSide; ++y) {
      for (int z = 0; z < inSide; ++z) {
        const double lo[3] = {double(x), double(y), double(z)};
        const double hi[3] = {x + 1.0, y + 1.0, z + 1.0};
        boxes.add(id++, lo, hi);
      }
    }
  }
  return boxes;
}

BoxSet identicalBoxes(std::size_t inCount, uint32_t inFirstId) {
  BoxSet boxes;
  const double lo[3] = {-1.5, 2.0, 0.25}, hi[3] = {-0.5, 2.0, 4.0};  // flat in y
  for (std::size_t i = 0; i < inCount; ++i)
    boxes.add(inFirstId + 7 * static_cast<uint32_t>(i), lo, hi);
  return boxes;
}

void randomFilters(BoxSet& ioBoxes, int inBits, uint32_t inSeed) {
  std::mt19937 random(inSeed);
  std::uniform_int_distribution<uint32_t> bits(0, (1u << inBits) - 1);
  ioBoxes.groups.resize(ioBoxes.size());
  ioBoxes.masks.resize(ioBoxes.size());
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    ioBoxes.groups[i] = bits(random);
    ioBoxes.masks[i] = bits(random);
  }
}

BoxArray toMessage(const BoxSet& inBoxes, const char* inFrameId, bool inOmitIds) {
  std_msgs::Header header;
  header.frame_id = inFrameId;
  BoxArray msg;
  boxSetToBoxArray(inBoxes, header, msg);
  if (inOmitIds) msg.ids.clear();
  return msg;
}

PairList toPairs(const PairArray& inMsg) {
  PairList pairs;
  pairArrayToPairList(inMsg, pairs);
  return pairs;
}

}  // namespace test
}  // namespace sap_broadphase
