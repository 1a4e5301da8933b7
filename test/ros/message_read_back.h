// Messages read back into engine types, for the tests and the fuzzers only: the node itself
// takes a BoxArray through checkBoxArrayShape and boxArrayRecords (the engine validates as it
// loads) and never reads a PairArray. Needs the message headers and the core, not roscpp, so
// that scripts/fuzz.sh links it into fuzz_box_array without a ROS runtime.
#pragma once

#include <optional>
#include <string>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {
namespace test {

/// Converts a BoxArray into outBoxes (replaced; capacity reused) and validates it fully: shape,
/// NaN, min > max, duplicate ids. Empty `ids` number the boxes 0..n-1. Returns the reason of a
/// refusal naming the box, e.g. "box 3 (id 17): min_y (3) > max_y (2)", or nothing.
std::optional<std::string> boxArrayToBoxSet(const BoxArray& inMsg, BoxSet& outBoxes);

/// Reads the pairs of a PairArray back into outPairs (replaced), each with a < b (makeIdPair,
/// the one rule for a pair's order). Returns false when the array has an odd length.
bool pairArrayToPairList(const PairArray& inMsg, PairList& outPairs);

}  // namespace test
}  // namespace sap_broadphase
