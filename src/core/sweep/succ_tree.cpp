#include "core/sweep/succ_tree.h"

#include <algorithm>

#include "core/assert.h"

namespace sap_broadphase {
namespace {

constexpr uint32_t kWordBits = 64;

uint32_t wordsFor(uint32_t inBits) {
  return std::max<uint32_t>(1, (inBits + 63) / kWordBits);
}

// Bits strictly above position inBit of a word.
uint64_t bitsAbove(uint32_t inBit) {
  return inBit >= 63 ? 0 : (~uint64_t{0} << (inBit + 1));
}

}  // namespace

void SuccTree::resize(uint32_t inSize) {
  size_ = inSize;
  uint32_t words = wordsFor(inSize);
  std::size_t level = 0;
  while (true) {
    if (levels_.size() <= level) levels_.emplace_back();
    levels_[level].assign(words, 0);
    ++level;
    if (words == 1) break;
    words = wordsFor(words);
  }
  levels_.resize(level);
  SAP_ASSERT(levels_.back().size() == 1 && levels_[0].size() * kWordBits >= inSize,
             "a SuccTree's levels do not end in one root word over the whole universe");
}

void SuccTree::clear() {
  for (std::vector<uint64_t>& level : levels_) std::fill(level.begin(), level.end(), 0);
}

void SuccTree::setBitAndAncestors(uint32_t inValue) {
  uint32_t position = inValue;
  for (std::vector<uint64_t>& level : levels_) {
    uint64_t& word = level[position >> 6];
    const bool was_empty = word == 0;
    word |= uint64_t{1} << (position & 63);
    if (!was_empty) return;  // ancestors already mark this word as non-empty
    position >>= 6;
  }
}

void SuccTree::clearBitAndAncestors(uint32_t inValue) {
  uint32_t position = inValue;
  for (std::vector<uint64_t>& level : levels_) {
    uint64_t& word = level[position >> 6];
    word &= ~(uint64_t{1} << (position & 63));
    if (word != 0) return;  // the word still has elements: ancestors stay set
    position >>= 6;
  }
}

void SuccTree::insert(uint32_t inValue) {
  SAP_ASSERT(inValue < size_, "SuccTree::insert beyond the universe");
  setBitAndAncestors(inValue);
  SAP_ASSERT(contains(inValue) && !empty(), "SuccTree::insert left the value out");
}

void SuccTree::erase(uint32_t inValue) {
  SAP_ASSERT(inValue < size_, "SuccTree::erase beyond the universe");
  if (contains(inValue)) clearBitAndAncestors(inValue);
  SAP_ASSERT(!contains(inValue), "SuccTree::erase left the value in");
}

void SuccTree::toggle(uint32_t inValue) {
  SAP_ASSERT(inValue < size_, "SuccTree::toggle beyond the universe");
  if (contains(inValue))
    clearBitAndAncestors(inValue);
  else
    setBitAndAncestors(inValue);
}

uint32_t SuccTree::next(uint32_t inValue) const {
  if (inValue >= size_) return kNone;
  // Search the leaf word first, then climb until a level has a set bit to the right.
  uint32_t position = inValue;
  uint64_t bits = levels_[0][position >> 6] & (~uint64_t{0} << (position & 63));
  std::size_t level = 0;
  while (bits == 0) {
    if (++level == levels_.size()) return kNone;
    position >>= 6;  // the word index below is the bit position at this level
    bits = levels_[level][position >> 6] & bitsAbove(position & 63);
  }
  // Descend along the least set bits to the leaf.
  position = (position & ~uint32_t{63}) | static_cast<uint32_t>(__builtin_ctzll(bits));
  while (level > 0) {
    --level;
    position = (position << 6) | static_cast<uint32_t>(__builtin_ctzll(levels_[level][position]));
  }
  // A set summary bit always leads down to a set leaf bit (the levels agree).
  SAP_ASSERT(position < size_ && position >= inValue && contains(position),
             "SuccTree::next found no element below a set summary bit");
  return position < size_ ? position : kNone;
}

void SuccTree::refreshAncestors(uint32_t inWordIndex) {
  uint32_t child = inWordIndex;
  for (std::size_t level = 1; level < levels_.size(); ++level) {
    const bool child_non_empty = levels_[level - 1][child] != 0;
    uint64_t& word = levels_[level][child >> 6];
    const uint64_t bit = uint64_t{1} << (child & 63);
    if (((word & bit) != 0) == child_non_empty) return;  // already consistent above
    const bool word_was_empty = word == 0;
    word ^= bit;
    if (!word_was_empty && word != 0) return;  // this word's own emptiness did not change
    child >>= 6;
  }
}

void SuccTree::symmetricDifference(const SuccTree& inOther) {
  SAP_ASSERT(size_ == inOther.size_, "symmetric difference of SuccTrees over other universes");
  const std::vector<uint64_t>& other_leaves = inOther.levels_[0];
  std::vector<uint64_t>& leaves = levels_[0];
  if (levels_.size() == 1) {
    leaves[0] ^= other_leaves[0];
    return;
  }
  // Visit only the other tree's non-empty leaf words, found through its level-1 bits.
  const std::vector<uint64_t>& other_level1 = inOther.levels_[1];
  for (uint32_t group = 0; group < other_level1.size(); ++group) {
    uint64_t non_empty = other_level1[group];
    while (non_empty) {
      const uint32_t word_index = (group << 6) | static_cast<uint32_t>(__builtin_ctzll(non_empty));
      non_empty &= non_empty - 1;
      leaves[word_index] ^= other_leaves[word_index];
      refreshAncestors(word_index);
    }
  }
}

void SuccTree::assign(const SuccTree& inOther) {
  size_ = inOther.size_;
  levels_.resize(inOther.levels_.size());
  for (std::size_t level = 0; level < levels_.size(); ++level)
    levels_[level].assign(inOther.levels_[level].begin(), inOther.levels_[level].end());
}

}  // namespace sap_broadphase
