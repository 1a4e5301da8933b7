// The oracle: every pair tested, nothing clever. Tests compare the engine against it.
#pragma once

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// All overlapping, filter-allowed pairs of inBoxes by testing every pair (O(n^2)),
/// in canonical (a, b) order.
PairList bruteForcePairs(const BoxSet& inBoxes);

}  // namespace sap_broadphase
