#include "sap_broadphase/core/brute_force.h"

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

}  // namespace sap_broadphase
