#include "sap_broadphase/core/brute_force.h"

#include <algorithm>

#include "core/frame/box_columns.h"
#include "core/frame/pair_sort.h"

namespace sap_broadphase {

PairList bruteForcePairs(const BoxColumns& inBoxes) {
  PairList pairs;
  const std::size_t n = inBoxes.size();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      if (boxesOverlap(inBoxes, a, b) && filtersAllow(inBoxes, a, b))
        pairs.push_back(makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
  sortPairsCanonical(pairs);
  return pairs;
}

PairList bruteForcePairs(const BoxFrame& inFrame) {
  return bruteForcePairs(columnsOf(inFrame));
}

QueryHitList bruteForceQuery(const BoxFrame& inQueryFrame, const BoxFrame& inWorldFrame) {
  const BoxColumns queries = columnsOf(inQueryFrame);
  const BoxColumns world = columnsOf(inWorldFrame);
  QueryHitList hits;
  for (std::size_t q = 0; q < queries.size(); ++q)
    for (std::size_t w = 0; w < world.size(); ++w)
      if (boxesOverlap(queries, q, world, w) &&
          groupsMayPair(queries.group(q), queries.mask(q), world.group(w), world.mask(w)))
        hits.push_back(QueryHit{queries.ids[q], world.ids[w]});
  std::sort(hits.begin(), hits.end());
  return hits;
}

}  // namespace sap_broadphase
