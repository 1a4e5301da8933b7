// Merging two sorted pair lists.
#include "pair_diff.h"

namespace sap_bench {

PairDiff comparePairs(const sap_broadphase::PairList& inResult,
                      const sap_broadphase::PairList& inTruth) {
  PairDiff diff;
  diff.truth = inTruth.size();
  std::size_t r = 0, t = 0;
  while (r < inResult.size() && t < inTruth.size()) {
    if (inResult[r] == inTruth[t]) {
      ++r, ++t;
    } else if (inResult[r] < inTruth[t]) {
      ++diff.extra, ++r;
    } else {
      ++diff.missed, ++t;
    }
  }
  diff.extra += inResult.size() - r;
  diff.missed += inTruth.size() - t;
  return diff;
}

}  // namespace sap_bench
