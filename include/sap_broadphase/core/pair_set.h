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

/// Buffers reused by sortPairsCanonical between calls.
struct PairSortScratch {
  PairList pairs;
  std::vector<uint32_t> offsets;
};

/// Sorts pairs by (a, b): the canonical order used wherever pairs leave the process.
/// Dense ids (largest a below a few times the pair count): a counting sort on a, then each
/// a's short list sorted by b. Sparse ids: an LSD radix sort on the 64-bit key a<<32|b.
void sortPairsCanonical(PairList& ioPairs, PairSortScratch& ioScratch);
/// Convenience overload with temporary buffers.
void sortPairsCanonical(PairList& ioPairs);
/// Merges the disjoint lists inParts into outPairs in canonical order, without first copying
/// them into one list when ids are dense. inParts is left unchanged.
void sortPairsCanonical(const std::vector<PairList>& inParts, PairList& outPairs,
                        PairSortScratch& ioScratch);

}  // namespace sap_broadphase
