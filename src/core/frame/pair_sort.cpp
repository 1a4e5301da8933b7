#include "core/frame/pair_sort.h"

#include "core/assert.h"
#include "core/runner/buffers.h"
#include "core/runner/work_units.h"
#include "core/tuning.h"

#include <algorithm>

namespace sap_broadphase {
namespace {

constexpr int kDigitBits = 16;
constexpr uint32_t kDigitValues = 1u << kDigitBits;

inline uint64_t pairKey(const IdPair& inPair) {
  return (uint64_t{inPair.a} << 32) | inPair.b;
}

void sortByB(IdPair* ioBegin, IdPair* ioEnd) {
  if (static_cast<std::size_t>(ioEnd - ioBegin) > tuning::kPairInsertionSortLimit) {
    std::sort(ioBegin, ioEnd);
    return;
  }
  for (IdPair* next = ioBegin + 1; next < ioEnd; ++next) {
    const IdPair moving = *next;
    IdPair* slot = next;
    for (; slot > ioBegin && slot[-1].b > moving.b; --slot) *slot = slot[-1];
    *slot = moving;
  }
}

// Calls inVisit(pair) for every pair of a PairList or of every PairChunks of a vector.
template <typename Visit>
void forEachPair(const PairList& inPairs, Visit&& inVisit) {
  for (const IdPair& pair : inPairs) inVisit(pair);
}
template <typename Visit>
void forEachPair(const std::vector<PairChunks>& inParts, Visit&& inVisit) {
  for (const PairChunks& part : inParts) part.forEach(inVisit);
}

// Counting sort on a (ids 0..inLargestA) of the inTotal pairs of inPairs into outSorted, then
// each run of equal a sorted by b.
template <typename Pairs>
void bucketSort(const Pairs& inPairs, std::size_t inTotal, uint32_t inLargestA,
                Buffer<uint32_t>& ioOffsets, PairList& outSorted) {
  resizeDiscarding(ioOffsets, std::size_t{inLargestA} + 2);
  std::fill(ioOffsets.begin(), ioOffsets.end(), 0);
  forEachPair(inPairs, [&](const IdPair& inPair) { ++ioOffsets[inPair.a + 1]; });
  for (std::size_t a = 1; a < ioOffsets.size(); ++a) ioOffsets[a] += ioOffsets[a - 1];
  resizeDiscarding(outSorted, inTotal);
  forEachPair(inPairs, [&](const IdPair& inPair) { outSorted[ioOffsets[inPair.a]++] = inPair; });
  // ioOffsets[a] now ends a's run, which starts where a - 1's ended.
  SAP_ASSERT(ioOffsets[inLargestA] == inTotal, "the counting sort placed other than every pair");
  uint32_t begin = 0;
  for (std::size_t a = 0; a <= inLargestA; ++a) {
    const uint32_t end = ioOffsets[a];
    if (end - begin > 1) sortByB(&outSorted[begin], &outSorted[0] + end);
    begin = end;
  }
}

// bucketSort of the per-thread parts on the scope's threads: each part counted and placed by
// one thread, the offsets' prefix sum split into ranges of a, the runs of equal a sorted by b in
// chunks, all handed out dynamically. ioOffsets holds one row of counts per part; after placing,
// the last part's row ends each run of a. Same result as bucketSort: the layout is part 0's
// pairs of a, then part 1's, ..., and every run is then sorted by b.
void bucketSortParts(const std::vector<PairChunks>& inParts, std::size_t inTotal,
                     uint32_t inLargestA, Buffer<uint32_t>& ioOffsets, PairList& outSorted) {
  const std::size_t parts = inParts.size();
  const std::size_t row = std::size_t{inLargestA} + 1;
  resizeDiscarding(ioOffsets, parts * row);
  resizeDiscarding(outSorted, inTotal);
  uint32_t* offsets = ioOffsets.data();
  IdPair* sorted = outSorted.data();
  // The values of a are cut into more ranges than threads, and every step's parts or ranges are
  // claimed dynamically (work_units.h).
  const int ranges = unitsForThreads(passThreads());
  std::vector<uint32_t> range_base(ranges + 1, 0);  // pairs before each range of a
  auto rangeBegin = [&](std::size_t inRange) { return row * inRange / ranges; };
  runUnits(parts, [&](std::size_t inPart) {
    uint32_t* counts = offsets + inPart * row;
    std::fill(counts, counts + row, 0u);
    inParts[inPart].forEach([&](const IdPair& inPair) { ++counts[inPair.a]; });
  });
  runUnits(ranges, [&](std::size_t inRange) {
    uint32_t in_range = 0;
    for (std::size_t part = 0; part < parts; ++part)
      for (std::size_t a = rangeBegin(inRange); a < rangeBegin(inRange + 1); ++a)
        in_range += offsets[part * row + a];
    range_base[inRange + 1] = in_range;
  });
  for (int range = 0; range < ranges; ++range) range_base[range + 1] += range_base[range];
  SAP_ASSERT(range_base[ranges] == inTotal, "the ranges of a miss some pairs");
  runUnits(ranges, [&](std::size_t inRange) {
    uint32_t next = range_base[inRange];
    for (std::size_t a = rangeBegin(inRange); a < rangeBegin(inRange + 1); ++a) {
      for (std::size_t part = 0; part < parts; ++part) {
        uint32_t& slot = offsets[part * row + a];
        const uint32_t count = slot;
        slot = next;
        next += count;
      }
    }
  });
  runUnits(parts, [&](std::size_t inPart) {
    uint32_t* next_slot = offsets + inPart * row;
    inParts[inPart].forEach([&](const IdPair& inPair) { sorted[next_slot[inPair.a]++] = inPair; });
  });
  const uint32_t* run_end = offsets + (parts - 1) * row;
  constexpr std::size_t kRunChunk = tuning::kPairRunChunk;
  runUnits((row + kRunChunk - 1) / kRunChunk, [&](std::size_t inChunk) {
    const std::size_t first = inChunk * kRunChunk;
    const std::size_t last = std::min(row, first + kRunChunk);
    uint32_t begin = first == 0 ? 0 : run_end[first - 1];
    for (std::size_t a = first; a < last; ++a) {
      const uint32_t end = run_end[a];
      if (end - begin > 1) sortByB(sorted + begin, sorted + end);
      begin = end;
    }
  });
}

template <typename Pairs>
uint32_t largestA(const Pairs& inPairs) {
  uint32_t largest = 0;
  forEachPair(inPairs, [&](const IdPair& inPair) { largest = std::max(largest, inPair.a); });
  return largest;
}

bool denseEnough(uint32_t inLargestA, std::size_t inCount) {
  return inLargestA < 4 * inCount + 65536;
}

// LSD radix sort on the 64-bit key with 16-bit digits; passes whose digit never varies are
// skipped.
void radixSort(PairList& ioPairs, PairSortScratch& ioScratch) {
  const std::size_t count = ioPairs.size();
  Buffer<uint32_t>& histogram = ioScratch.offsets;
  histogram.resize(kDigitValues);
  resizeDiscarding(ioScratch.pairs, count);
  PairList* source = &ioPairs;
  PairList* target = &ioScratch.pairs;
  for (int shift = 0; shift < 64; shift += kDigitBits) {
    std::fill(histogram.begin(), histogram.end(), 0);
    for (const IdPair& pair : *source) ++histogram[(pairKey(pair) >> shift) & (kDigitValues - 1)];
    if (histogram[(pairKey((*source)[0]) >> shift) & (kDigitValues - 1)] == count) continue;
    uint32_t offset = 0;
    for (uint32_t& bucket : histogram) {
      const uint32_t size = bucket;
      bucket = offset;
      offset += size;
    }
    for (const IdPair& pair : *source)
      (*target)[histogram[(pairKey(pair) >> shift) & (kDigitValues - 1)]++] = pair;
    std::swap(source, target);
  }
  if (source != &ioPairs) ioPairs.swap(ioScratch.pairs);
  SAP_ASSERT(ioPairs.size() == count, "the radix sort lost pairs");
}

// The result of every sort below: pairs ordered by (a, b), each with a < b. (Unique too when
// the pairs came from the engine, which finds each pair once: update() asserts that.)
[[maybe_unused]] bool inCanonicalOrder(const PairList& inPairs) {
  return std::is_sorted(inPairs.begin(), inPairs.end()) &&
         std::all_of(inPairs.begin(), inPairs.end(),
                     [](const IdPair& inPair) { return inPair.a < inPair.b; });
}

}  // namespace

void sortPairsByAThenB(PairList& ioPairs, PairSortScratch& ioScratch) {
  const std::size_t count = ioPairs.size();
  if (count < 2) return;
  const uint32_t largest_a = largestA(ioPairs);
  if (denseEnough(largest_a, count)) {
    bucketSort(ioPairs, count, largest_a, ioScratch.offsets, ioScratch.pairs);
    ioPairs.swap(ioScratch.pairs);
  } else {
    radixSort(ioPairs, ioScratch);
  }
  SAP_ASSERT(std::is_sorted(ioPairs.begin(), ioPairs.end()), "sorted pairs out of (a, b) order");
}

void sortPairsCanonical(PairList& ioPairs, PairSortScratch& ioScratch) {
  sortPairsByAThenB(ioPairs, ioScratch);
  SAP_ASSERT(inCanonicalOrder(ioPairs), "sorted pairs out of canonical (a, b) order");
}

void sortPairsCanonical(const std::vector<PairChunks>& inParts, PairList& outPairs,
                        PairSortScratch& ioScratch) {
  std::size_t total = 0;
  for (const PairChunks& part : inParts) total += part.size();
  const int threads =
      static_cast<int>(std::min<std::size_t>(std::max(1, passThreads()), inParts.size()));
  // The largest a of each part, then of all: the same for any thread count.
  std::vector<uint32_t> largest_of_part(inParts.size(), 0);
  runUnits(inParts.size(), [&](std::size_t inPart) {
    uint32_t largest = 0;
    inParts[inPart].forEach([&](const IdPair& inPair) { largest = std::max(largest, inPair.a); });
    largest_of_part[inPart] = largest;
  });
  uint32_t largest_a = 0;
  for (uint32_t largest : largest_of_part) largest_a = std::max(largest_a, largest);
  if (denseEnough(largest_a, total)) {
    if (threads > 1 && total >= tuning::kParallelMergePairs) {
      const NarrowedScope part_threads(threads);  // no more threads than parts
      bucketSortParts(inParts, total, largest_a, ioScratch.offsets, outPairs);
    } else {
      bucketSort(inParts, total, largest_a, ioScratch.offsets, outPairs);
    }
  } else {
    resizeDiscarding(outPairs, total);
    std::size_t next = 0;
    forEachPair(inParts, [&](const IdPair& inPair) { outPairs[next++] = inPair; });
    if (total > 1) radixSort(outPairs, ioScratch);
  }
  SAP_ASSERT(outPairs.size() == total, "the merge lost or added pairs");
  SAP_ASSERT(inCanonicalOrder(outPairs), "merged pairs out of canonical (a, b) order");
}

void sortPairsCanonical(PairList& ioPairs) {
  PairSortScratch scratch;
  sortPairsCanonical(ioPairs, scratch);
}

void PairBudget::count(std::size_t inPairs) {
  if (found_.fetch_add(inPairs, std::memory_order_relaxed) + inPairs > limit_)
    throw TooManyPairs(limit_);
}

void PairChunks::startChunk() {
  // The chunk before is full: its pairs count against the frame's budget before another one
  // is taken.
  if (budget_ && used_chunks_ > 0) budget_->count(kChunkPairs);
  if (used_chunks_ == chunks_.size()) {
    chunks_.reserve(chunks_.size() + 1);  // so that a throw below leaks no chunk
    chunks_.push_back(BufferAllocator<IdPair>().allocate(kChunkPairs));
  }
  ++used_chunks_;
  fill_ = 0;
}

void PairChunks::releaseChunks() {
  for (IdPair* chunk : chunks_) BufferAllocator<IdPair>().deallocate(chunk, kChunkPairs);
  chunks_.clear();
  used_chunks_ = 0;
  fill_ = kChunkPairs;
}

}  // namespace sap_broadphase
