// Pairs of box ids as they leave the engine.
#pragma once

#include <cstdint>
#include <vector>

namespace sap_broadphase {

/// An unordered pair of box ids, stored with a < b.
struct IdPair {
  uint32_t a;
  uint32_t b;
  friend bool operator==(const IdPair& x, const IdPair& y) { return x.a == y.a && x.b == y.b; }
  friend bool operator<(const IdPair& x, const IdPair& y) {
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  }
};

using PairList = std::vector<IdPair>;

/// Makes a < b in the pair (swaps when needed).
inline IdPair makeIdPair(uint32_t x, uint32_t y) {
  return x < y ? IdPair{x, y} : IdPair{y, x};
}

/// Sorts pairs by (a, b) with a stable LSD radix sort on the 64-bit key a<<32|b: the canonical
/// order used wherever pairs leave the process. ioScratch is reused between calls.
void sortPairsCanonical(PairList& ioPairs, PairList& ioScratch);
/// Convenience overload with a temporary scratch buffer.
void sortPairsCanonical(PairList& ioPairs);

}  // namespace sap_broadphase
