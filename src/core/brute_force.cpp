#include "sap_broadphase/core/brute_force.h"

#include <algorithm>
#include "core/pair_sort.h"

namespace sap_broadphase {

PairList bruteForcePairs(const BoxSet& inBoxes) {
  PairList pairs;
  const std::size_t n = inBoxes.size();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      if (boxesOverlap(inBoxes, a, b) && filtersAllow(inBoxes, a, b))
        pairs.push_back(makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
  sortPairsCanonical(pairs);
  return pairs;
}

QueryHitList bruteForceQuery(const BoxSet& inQueries, const BoxSet& inWorld) {
  QueryHitList hits;
  for (std::size_t q = 0; q < inQueries.size(); ++q)
    for (std::size_t w = 0; w < inWorld.size(); ++w)
      if (boxesOverlap(inQueries, q, inWorld, w) &&
          groupsMayPair(inQueries.group(q), inQueries.mask(q), inWorld.group(w), inWorld.mask(w)))
        hits.push_back(QueryHit{inQueries.ids[q], inWorld.ids[w]});
  std::sort(hits.begin(), hits.end());
  return hits;
}

}  // namespace sap_broadphase
