// Messages read back into engine types (tests and fuzzers).
#include "message_read_back.h"

#include <cstddef>

#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {
namespace test {

std::optional<std::string> boxArrayToBoxSet(const BoxArray& inMsg, BoxSet& outBoxes) {
  if (auto shapeError = checkBoxArrayShape(inMsg)) return shapeError;
  copyBoxArray(inMsg, outBoxes);
  if (auto error = validate(outBoxes)) return error->message();
  return std::nullopt;
}

bool pairArrayToPairList(const PairArray& inMsg, PairList& outPairs) {
  if (inMsg.pairs.size() % 2 != 0) return false;
  outPairs.resize(inMsg.pairs.size() / 2);
  for (std::size_t i = 0; i < outPairs.size(); ++i)
    outPairs[i] = makeIdPair(inMsg.pairs[2 * i], inMsg.pairs[2 * i + 1]);
  return true;
}

}  // namespace test
}  // namespace sap_broadphase
