// Messages <-> engine types.
#include "sap_broadphase/ros/conversions.h"

#include <cstddef>
#include <cstring>
#include <numeric>
#include <type_traits>

namespace sap_broadphase {

namespace {

/// "1 box", "2 boxes": inCount and the noun that agrees with it.
std::string countOf(std::size_t inCount, const char* inOne, const char* inMany) {
  return std::to_string(inCount) + " " + (inCount == 1 ? inOne : inMany);
}

// Says what the sender can change: the two lengths that disagree and the two valid choices.
std::string lengthError(const char* inField, std::size_t inLength, std::size_t inBoxes) {
  return std::string(inField) + " has " + countOf(inLength, "entry", "entries") +
         " but bounds holds " + countOf(inBoxes, "box", "boxes") + " (" +
         countOf(6 * inBoxes, "value", "values") + "): give one " + inField +
         " entry per box, or none";
}

}  // namespace

std::optional<std::string> checkBoxArrayShape(const BoxArray& inMsg) {
  if (inMsg.bounds.size() % 6 != 0) {
    return "bounds has " + std::to_string(inMsg.bounds.size()) +
           " values, expected 6 per box (min_x min_y min_z max_x max_y max_z)";
  }
  const std::size_t count = inMsg.bounds.size() / 6;
  if (!inMsg.ids.empty() && inMsg.ids.size() != count)
    return lengthError("ids", inMsg.ids.size(), count);
  if (!inMsg.groups.empty() && inMsg.groups.size() != count)
    return lengthError("groups", inMsg.groups.size(), count);
  if (!inMsg.masks.empty() && inMsg.masks.size() != count)
    return lengthError("masks", inMsg.masks.size(), count);
  return std::nullopt;
}

BoxSpan boxArrayRecords(const BoxArray& inMsg) {
  BoxSpan records;
  records.count = inMsg.bounds.size() / 6;
  records.bounds = inMsg.bounds.data();
  records.ids = inMsg.ids.empty() ? nullptr : inMsg.ids.data();
  records.groups = inMsg.groups.empty() ? nullptr : inMsg.groups.data();
  records.masks = inMsg.masks.empty() ? nullptr : inMsg.masks.data();
  return records;
}

void copyBoxArray(const BoxArray& inMsg, BoxSet& outBoxes) {
  outBoxes.ids.resize(inMsg.bounds.size() / 6);
  if (inMsg.ids.empty())
    std::iota(outBoxes.ids.begin(), outBoxes.ids.end(), 0u);
  else
    outBoxes.ids.assign(inMsg.ids.begin(), inMsg.ids.end());
  outBoxes.bounds.assign(inMsg.bounds.begin(), inMsg.bounds.end());
  outBoxes.groups.assign(inMsg.groups.begin(), inMsg.groups.end());
  outBoxes.masks.assign(inMsg.masks.begin(), inMsg.masks.end());
}

void pairListToPairArray(const PairList& inPairs, const std_msgs::Header& inHeader,
                         PairArray& outMsg) {
  outMsg.header = inHeader;
  // IdPair is two uint32 (a, b) without padding, the message's layout: one block copy of the
  // engine's buffer (millions of pairs at 2^20 boxes).
  static_assert(sizeof(IdPair) == 2 * sizeof(uint32_t) && std::is_standard_layout_v<IdPair> &&
                    offsetof(IdPair, a) == 0 && offsetof(IdPair, b) == sizeof(uint32_t),
                "IdPair must be laid out as two consecutive uint32");
  outMsg.pairs.resize(2 * inPairs.size());
  if (!inPairs.empty())
    std::memcpy(outMsg.pairs.data(), inPairs.data(), inPairs.size() * sizeof(IdPair));
}

void boxSetToBoxArray(const BoxSet& inBoxes, const std_msgs::Header& inHeader, BoxArray& outMsg) {
  outMsg.header = inHeader;
  outMsg.ids.assign(inBoxes.ids.begin(), inBoxes.ids.end());
  outMsg.bounds.assign(inBoxes.bounds.begin(), inBoxes.bounds.end());  // the same records
  outMsg.groups.assign(inBoxes.groups.begin(), inBoxes.groups.end());
  outMsg.masks.assign(inBoxes.masks.begin(), inBoxes.masks.end());
}

}  // namespace sap_broadphase
