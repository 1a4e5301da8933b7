// Pairs of box ids as they leave the engine: each pair once, a < b, sorted by (a, b).
#pragma once

#include <cstddef>
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

/// True when inPairs are in canonical order: a < b in every pair, sorted by (a, b), none twice
/// (what Broadphase::update() returns).
bool isCanonical(const PairList& inPairs);

}  // namespace sap_broadphase
