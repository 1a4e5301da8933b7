// Box frames for the node tests, built as BoxSets so the oracle can check the node's answer.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {
namespace test {

/// inCount random boxes in [0, 10]^3 with edges up to inMaxEdge; ids 0..n-1 unless
/// inSparseIds, then distinct random ids spread over all of uint32.
BoxSet randomBoxes(std::size_t inCount, double inMaxEdge, bool inSparseIds, uint32_t inSeed);
/// A inSide^3 grid of unit cubes that touch their 26 neighbours on faces, edges and corners.
BoxSet touchingGrid(int inSide, uint32_t inFirstId);
/// inCount identical boxes with ids inFirstId, inFirstId + 7, ... (every pair overlaps).
BoxSet identicalBoxes(std::size_t inCount, uint32_t inFirstId);
/// Gives every box of ioBoxes random group and mask bits drawn from inBits low bits.
void randomFilters(BoxSet& ioBoxes, int inBits, uint32_t inSeed);
/// The message of inBoxes (ids written unless inOmitIds) in frame inFrameId.
BoxArray toMessage(const BoxSet& inBoxes, const char* inFrameId, bool inOmitIds = false);
/// The pairs of a PairArray as a list.
PairList toPairs(const PairArray& inMsg);

}  // namespace test
}  // namespace sap_broadphase
