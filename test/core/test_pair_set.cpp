// Pairs as they leave the engine (pair_set.h): canonical order, the chunked per-thread lists,
// and every sort and merge (dense ids: counting sort, sparse ids: radix sort, one thread or
// many) against std::sort.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "core/frame/pair_sort.h"
#include "core/runner/work_units.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::TestRandom;

// inCount distinct pairs with a < b (at most half of all pairs of ids below inLargestId), ids
// below inLargestId, in random order.
PairList randomPairs(std::size_t inCount, uint32_t inLargestId, uint64_t inSeed) {
  const double all_pairs = 0.5 * inLargestId * (inLargestId - 1.0);
  inCount = static_cast<std::size_t>(std::min<double>(static_cast<double>(inCount), all_pairs / 2));
  TestRandom random(inSeed);
  PairList pairs;
  while (pairs.size() < inCount) {
    while (pairs.size() < inCount) {
      const uint32_t x = static_cast<uint32_t>(random.below(inLargestId));
      const uint32_t y = static_cast<uint32_t>(random.below(inLargestId));
      if (x != y) pairs.push_back(makeIdPair(x, y));
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  }
  for (std::size_t k = pairs.size(); k > 1; --k) std::swap(pairs[k - 1], pairs[random.below(k)]);
  return pairs;
}

PairList sortedCopy(PairList inPairs) {
  std::sort(inPairs.begin(), inPairs.end());
  return inPairs;
}

// inPairs dealt round-robin into inParts chunked lists.
std::vector<PairChunks> dealt(const PairList& inPairs, std::size_t inParts) {
  std::vector<PairChunks> parts(inParts);
  for (std::size_t k = 0; k < inPairs.size(); ++k) parts[k % inParts].push_back(inPairs[k]);
  return parts;
}

TEST(PairSet, MakeIdPairPutsTheSmallerIdFirst) {
  EXPECT_EQ(makeIdPair(9, 4), (IdPair{4, 9}));
  EXPECT_EQ(makeIdPair(4, 9), (IdPair{4, 9}));
  EXPECT_TRUE(IdPair({1, 7}) < IdPair({2, 3}));
  EXPECT_TRUE(IdPair({2, 3}) < IdPair({2, 4}));
  EXPECT_FALSE(IdPair({2, 4}) < IdPair({2, 4}));
}

TEST(PairSet, IsCanonicalNeedsOrderUniquenessAndALessThanB) {
  EXPECT_TRUE(isCanonical({}));
  EXPECT_TRUE(isCanonical({{0, 1}, {0, 5}, {3, 4}}));
  EXPECT_FALSE(isCanonical({{0, 5}, {0, 1}}));          // out of order
  EXPECT_FALSE(isCanonical({{0, 1}, {0, 1}}));          // twice
  EXPECT_FALSE(isCanonical({{2, 2}}));                  // a == b
  EXPECT_FALSE(isCanonical({{0, 1}, {5, 3}}));          // a > b
  EXPECT_FALSE(isCanonical({{1, 2}, {0, 3}, {4, 5}}));  // a decreases
}

TEST(PairSet, ChunksKeepInsertionOrderAcrossChunksAndClearKeepsNothing) {
  PairChunks chunks;
  EXPECT_EQ(chunks.size(), 0u);
  const std::size_t count = 2 * PairChunks::kChunkPairs + 3;  // three chunks, the last short
  for (uint32_t k = 0; k < count; ++k) chunks.push_back(IdPair{k, k + 1});
  EXPECT_EQ(chunks.size(), count);
  uint32_t expected = 0;
  chunks.forEach([&](const IdPair& inPair) {
    EXPECT_EQ(inPair, (IdPair{expected, expected + 1}));
    ++expected;
  });
  EXPECT_EQ(expected, count);
  chunks.clear();
  EXPECT_EQ(chunks.size(), 0u);
  std::size_t visited = 0;
  chunks.forEach([&](const IdPair&) { ++visited; });
  EXPECT_EQ(visited, 0u);
  chunks.push_back(IdPair{5, 6});  // reuses the first chunk
  EXPECT_EQ(chunks.size(), 1u);
}

TEST(PairSet, MovedChunksKeepTheirPairsAndTheSourceHoldsNone) {
  PairChunks chunks;
  const std::size_t count = PairChunks::kChunkPairs + 5;  // two chunks
  for (uint32_t k = 0; k < count; ++k) chunks.push_back(IdPair{k, k + 2});
  PairChunks moved(std::move(chunks));
  EXPECT_EQ(moved.size(), count);
  EXPECT_EQ(chunks.size(), 0u);  // NOLINT: a moved-from list is empty and usable
  chunks.push_back(IdPair{1, 2});
  EXPECT_EQ(chunks.size(), 1u);
  PairChunks assigned;
  assigned.push_back(IdPair{7, 8});
  assigned = std::move(moved);  // frees the one chunk it held, takes the two
  EXPECT_EQ(assigned.size(), count);
  uint32_t expected = 0;
  assigned.forEach([&](const IdPair& inPair) {
    EXPECT_EQ(inPair, (IdPair{expected, expected + 2}));
    ++expected;
  });
  EXPECT_EQ(expected, count);
  std::vector<PairChunks> parts(2);
  parts[0] = std::move(assigned);
  parts.resize(40);  // moves the lists into new storage
  EXPECT_EQ(parts[0].size(), count);
}

TEST(PairSet, ResizingAPairListKeepsOrDiscardsAsAsked) {
  PairList pairs = {{1, 2}, {3, 4}};
  pairs.resize(100000);  // grows past the capacity: the first pairs stay
  ASSERT_EQ(pairs.size(), 100000u);
  EXPECT_EQ(pairs[0], (IdPair{1, 2}));
  EXPECT_EQ(pairs[1], (IdPair{3, 4}));
  EXPECT_EQ(pairs[99999], (IdPair{0, 0}));  // new elements value-initialised
  resizeDiscarding(pairs, 300000);
  EXPECT_EQ(pairs.size(), 300000u);
  EXPECT_GE(pairs.capacity(), 300000u);
  resizeDiscarding(pairs, 10);  // shrinking keeps the storage
  EXPECT_EQ(pairs.size(), 10u);
  EXPECT_GE(pairs.capacity(), 300000u);
}

TEST(PairSet, HugePageBuffersAreAlignedWritableAndFreed) {
  using Allocator = BufferAllocator<uint64_t>;
  const std::size_t count = (Allocator::kHugePageBytes + 12345) / sizeof(uint64_t);
  for (int round = 0; round < 3; ++round) {  // allocated and freed again: no leak, no reuse bug
    uint64_t* memory = Allocator().allocate(count);
    ASSERT_NE(memory, nullptr);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(memory) % Allocator::kHugePageBytes, 0u);
    for (std::size_t k = 0; k < count; ++k) memory[k] = k;
    EXPECT_EQ(memory[count - 1], count - 1);
    Allocator().deallocate(memory, count);
  }
  Buffer<uint64_t> buffer;
  resizeDiscarding(buffer, count);
  buffer.back() = 7;
  EXPECT_EQ(buffer.back(), 7u);
}

// Blocks from BufferCache at every edge of its size classes: each holds what was asked for (an
// overrun corrupts the heap: the asserts build checks the class's size, the sanitizers the
// writes), is aligned for a cache-line record, and comes back to the next buffer of its class.
TEST(PairSet, CachedBuffersHoldWhatWasAskedForAtEveryClassEdge) {
  using Allocator = BufferAllocator<unsigned char>;
  std::vector<std::size_t> sizes = {BufferCache::kSmallestBytes - 1, BufferCache::kLargestBytes,
                                    BufferCache::kLargestBytes + 1};
  for (std::size_t edge = BufferCache::kSmallestBytes; edge <= BufferCache::kLargestBytes;
       edge *= 2) {
    for (std::size_t offset : {std::size_t{0}, std::size_t{1}, std::size_t{64}})
      sizes.insert(sizes.end(), {edge - offset, edge + offset});
  }
  for (int round = 0; round < 2; ++round) {  // the second round takes the kept blocks
    for (std::size_t bytes : sizes) {
      unsigned char* memory = Allocator().allocate(bytes);
      ASSERT_NE(memory, nullptr) << bytes;
      if (BufferCache::serves(bytes)) {
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(memory) % BufferCache::kAlignment, 0u) << bytes;
      }
      std::memset(memory, 0xA5, bytes);
      EXPECT_EQ(memory[bytes - 1], 0xA5) << bytes;
      Allocator().deallocate(memory, bytes);
    }
  }
}

TEST(PairSet, SortMatchesStdSortForDenseAndSparseIds) {
  PairSortScratch scratch;  // reused across calls, as the engine does
  for (uint32_t largest_id : {50u, 5000u, 4000000000u}) {  // dense, dense, sparse (radix)
    for (std::size_t count : {0u, 1u, 2u, 17u, 1000u, 70000u}) {
      SCOPED_TRACE(::testing::Message() << "ids < " << largest_id << ", " << count << " pairs");
      const PairList pairs = randomPairs(count, largest_id, count * 31 + largest_id);
      PairList sorted = pairs;
      sortPairsCanonical(sorted, scratch);
      EXPECT_EQ(sorted, sortedCopy(pairs));
      EXPECT_TRUE(isCanonical(sorted));
    }
  }
}

TEST(PairSet, SortOrdersLongRunsOfOneIdByTheOther) {
  // One box against many: a run of equal a longer than the insertion-sorted limit.
  PairList pairs;
  for (uint32_t b = 1000; b > 1; --b) pairs.push_back({1, b});
  for (uint32_t b = 3; b < 40; b += 3) pairs.push_back({0, b});
  PairList sorted = pairs;
  PairSortScratch scratch;
  sortPairsCanonical(sorted, scratch);
  EXPECT_EQ(sorted, sortedCopy(pairs));
}

TEST(PairSet, MergeOfPartsEqualsSortForEveryThreadCount) {
  for (uint32_t largest_id : {3000u, 3000000000u}) {
    // Above the size from which several threads merge, and below it.
    for (std::size_t count : {500u, 90000u}) {
      const PairList pairs = randomPairs(count, largest_id, count + largest_id);
      const PairList expected = sortedCopy(pairs);
      for (std::size_t parts : {1u, 2u, 5u}) {
        const std::vector<PairChunks> chunks = dealt(pairs, parts);
        for (int threads : {1, 2, 3}) {
          SCOPED_TRACE(::testing::Message() << "ids < " << largest_id << ", " << count << " pairs, "
                                            << parts << " parts, " << threads << " threads");
          PairSortScratch scratch;
          PairList merged = {{7, 8}};  // replaced, not appended to
          const ThreadsScope scope(threads);
          sortPairsCanonical(chunks, merged, scratch);
          EXPECT_EQ(merged, expected);
          std::size_t left = 0;  // the parts are left as they were
          for (const PairChunks& part : chunks) left += part.size();
          EXPECT_EQ(left, count);
        }
      }
    }
  }
}

}  // namespace
}  // namespace sap_broadphase
