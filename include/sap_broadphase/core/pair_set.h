// Pairs of box ids as they leave the engine: each pair once, a < b, sorted by (a, b); the
// hits of a box query and the contact events of a frame, made of them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
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

/// One answer of Broadphase::query(): the query box with id `query` overlaps the world box
/// with id `world`.
struct QueryHit {
  uint32_t query;
  uint32_t world;
  friend bool operator==(const QueryHit& x, const QueryHit& y) {
    return x.query == y.query && x.world == y.world;
  }
  friend bool operator<(const QueryHit& x, const QueryHit& y) {
    return x.query < y.query || (x.query == y.query && x.world < y.world);
  }
};

/// The answers of one Broadphase::query(), sorted by (query, world), none twice.
using QueryHitList = std::vector<QueryHit>;

/// A frame with more pairs than BroadphaseConfig::max_pairs, refused by Broadphase::update()
/// (a std::length_error, as a query with too many hits; Python's ValueError). Thrown once the
/// pairs found pass the bound: the frame's pairs are not all found, and the engine is as after
/// reset(), its pair buffers given back.
class TooManyPairs : public std::length_error {
 public:
  explicit TooManyPairs(std::size_t inLimit)
      : std::length_error("frame refused: more than " + std::to_string(inLimit) +
                          " pairs (max_pairs); the pairs found so far were dropped: raise "
                          "max_pairs if the memory allows (8 bytes a pair in each copy)"),
        limit_(inLimit) {}
  /// The bound passed (max_pairs).
  std::size_t limit() const { return limit_; }

 private:
  std::size_t limit_;
};

/// The pairs that began and the pairs that ended at the last update(), each sorted as a PairList.
struct ContactEvents {
  PairList began;
  PairList ended;
};

}  // namespace sap_broadphase
