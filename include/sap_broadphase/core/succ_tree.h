// SuccTree (paper §3): a 64-ary tree of bit vectors over the universe {0, ..., size-1}.
//
// Level 0 holds one bit per element; a bit at level d+1 is set iff its 64-bit word at level d
// is non-zero. insert/erase/next/min touch at most two root-to-leaf paths: O(log_64 n).
// Range iteration walks set bits a word at a time with count-trailing-zeros.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

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

template <typename Visit>
void SuccTree::forEachInRange(uint32_t inBegin, uint32_t inEnd, Visit&& inVisit) const {
  if (inBegin >= inEnd) return;
  const std::vector<uint64_t>& leaves = levels_[0];
  uint32_t cursor = next(inBegin);
  while (cursor < inEnd) {
    const uint32_t word_index = cursor >> 6;
    uint64_t bits = leaves[word_index] & (~uint64_t{0} << (cursor & 63));
    const uint32_t word_base = word_index << 6;
    if (inEnd - word_base < 64) bits &= (uint64_t{1} << (inEnd - word_base)) - 1;
    while (bits) {
      inVisit(word_base + static_cast<uint32_t>(__builtin_ctzll(bits)));
      bits &= bits - 1;
    }
    const uint32_t following = word_base + 64;
    if (following >= inEnd || following >= size_) return;
    // Reuse the leaf word after this one directly when it has bits; climb only when empty.
    cursor = leaves[word_index + 1] ? following : next(following);
  }
}

}  // namespace sap_broadphase
