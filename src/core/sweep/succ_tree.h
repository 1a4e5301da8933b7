// SuccTree (paper §3): a 64-ary tree of bit vectors over the universe {0, ..., size-1}.
//
// Level 0 holds one bit per element; a bit at level d+1 is set iff its 64-bit word at level d
// is non-zero. insert/erase/next/min touch at most two root-to-leaf paths: O(log_64 n).
// Range iteration walks set bits a word at a time with count-trailing-zeros.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/assert.h"

namespace sap_broadphase {

class SuccTree {
 public:
  /// Value returned by next()/min() when there is no such element.
  static constexpr uint32_t kNone = 0xFFFFFFFFu;

  /// An empty tree over the empty universe (one zero word, so every operation is defined).
  SuccTree() { resize(0); }
  /// An empty tree over {0, ..., inSize-1}.
  explicit SuccTree(uint32_t inSize) { resize(inSize); }

  /// Re-sizes the universe and empties the tree (keeps capacity).
  void resize(uint32_t inSize);
  /// Removes every element in O(words set) (cheap when the tree is nearly empty).
  void clear();
  /// Universe size.
  uint32_t size() const { return size_; }
  /// True when no element is present.
  bool empty() const { return levels_.back()[0] == 0; }

  /// Adds inValue (no effect if present).
  void insert(uint32_t inValue);
  /// Removes inValue (no effect if absent).
  void erase(uint32_t inValue);
  /// Adds inValue if absent, removes it if present.
  void toggle(uint32_t inValue);
  /// True when inValue is present.
  bool contains(uint32_t inValue) const {
    SAP_ASSERT(inValue < size_ || (size_ == 0 && inValue == 0),
               "a SuccTree asked beyond its universe");
    return (levels_[0][inValue >> 6] >> (inValue & 63)) & 1u;
  }
  /// Smallest element, or kNone.
  uint32_t min() const { return empty() ? kNone : next(0); }
  /// Smallest element >= inValue, or kNone.
  uint32_t next(uint32_t inValue) const;

  /// Calls inVisit(r) for each element r in [inBegin, inEnd), in increasing order.
  template <typename Visit>
  void forEachInRange(uint32_t inBegin, uint32_t inEnd, Visit&& inVisit) const;

  /// this := this ⊕ inOther (symmetric difference); both must have the same size.
  void symmetricDifference(const SuccTree& inOther);
  /// this := inOther (same size; reuses storage).
  void assign(const SuccTree& inOther);

 private:
  void setBitAndAncestors(uint32_t inValue);
  void clearBitAndAncestors(uint32_t inValue);
  void refreshAncestors(uint32_t inWordIndex);

  uint32_t size_ = 0;
  std::vector<std::vector<uint64_t>> levels_;  // levels_[0] = leaves; back() has one word
};

// Walks the level-1 summary of the range (bit w set iff leaf word w has elements), then the
// set bits of each non-empty leaf word: word-at-a-time on both levels, no climbing per element.
// Ranges here span at most a few summary words (a pairing partition is 2^15 ranks).
template <typename Visit>
void SuccTree::forEachInRange(uint32_t inBegin, uint32_t inEnd, Visit&& inVisit) const {
  // Callers pass ranges of the tree's own ranks: a candidate range clipped to the sweep's
  // ranks (whole stream) or to its partition (local ranks).
  SAP_ASSERT(inEnd <= size_, "a SuccTree range reaches beyond its universe");
  if (inEnd > size_) inEnd = size_;
  if (inBegin >= inEnd) return;
  const uint64_t* leaves = levels_[0].data();
  const uint32_t first_word = inBegin >> 6;
  const uint32_t last_word = (inEnd - 1) >> 6;
  const auto visitWord = [&](uint32_t inWord) {
    uint64_t bits = leaves[inWord];
    if (inWord == first_word) bits &= ~uint64_t{0} << (inBegin & 63);
    if (inWord == last_word) bits &= ~uint64_t{0} >> (63 - ((inEnd - 1) & 63));
    while (bits) {
      const uint32_t value = (inWord << 6) | static_cast<uint32_t>(__builtin_ctzll(bits));
      SAP_ASSERT(value >= inBegin && value < inEnd, "a SuccTree range walk left its range");
      inVisit(value);
      bits &= bits - 1;
    }
  };
  if (levels_.size() == 1) {  // a single leaf word
    visitWord(0);
    return;
  }
  const uint64_t* summary = levels_[1].data();
  const uint32_t first_group = first_word >> 6;
  const uint32_t last_group = last_word >> 6;
  for (uint32_t group = first_group; group <= last_group; ++group) {
    uint64_t words = summary[group];
    if (group == first_group) words &= ~uint64_t{0} << (first_word & 63);
    if (group == last_group) words &= ~uint64_t{0} >> (63 - (last_word & 63));
    while (words) {
      visitWord((group << 6) | static_cast<uint32_t>(__builtin_ctzll(words)));
      words &= words - 1;
    }
  }
}

}  // namespace sap_broadphase
