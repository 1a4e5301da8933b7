// Missed and extra pairs of a result against the oracle's.
#pragma once

#include <cstddef>

#include "sap_broadphase/core/pair_set.h"

namespace sap_bench {

/// How a pair list differs from the true one.
struct PairDiff {
  std::size_t truth = 0;   ///< pairs in the oracle's list
  std::size_t missed = 0;  ///< in the oracle's list, not in the result
  std::size_t extra = 0;   ///< in the result, not in the oracle's list
};

/// Compares two lists, both sorted in canonical (a, b) order without duplicates.
PairDiff comparePairs(const sap_broadphase::PairList& inResult,
                      const sap_broadphase::PairList& inTruth);

}  // namespace sap_bench
