// The oracle: every pair tested, nothing clever. Tests compare the engine against it.
#pragma once

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"  // the engine the oracle checks, for its users
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// All overlapping, filter-allowed pairs of the frame's boxes by testing every pair (O(n^2)),
/// in canonical (a, b) order. The frame is not checked (validate() it).
PairList bruteForcePairs(const BoxFrame& inFrame);

/// What Broadphase::query() answers, by testing every query box against every box of inWorld
/// (O(m n)): {query id, world id} for each overlapping, filter-allowed pair, sorted.
QueryHitList bruteForceQuery(const BoxFrame& inQueries, const BoxFrame& inWorld);

}  // namespace sap_broadphase
