#include "sap_broadphase/core/pair_set.h"
#include "core/buffers.h"

#include <algorithm>

namespace sap_broadphase {
namespace {

constexpr int kDigitBits = 16;
constexpr uint32_t kDigitValues = 1u << kDigitBits;
// Lists of pairs sharing `a` up to this long are insertion-sorted.
constexpr std::size_t kInsertionSortLimit = 16;

inline uint64_t pairKey(const IdPair& inPair) {
  return (uint64_t{inPair.a} << 32) | inPair.b;
}

void sortByB(IdPair* ioBegin, IdPair* ioEnd) {
  if (static_cast<std::size_t>(ioEnd - ioBegin) > kInsertionSortLimit) {
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
                std::vector<uint32_t>& ioOffsets, PairList& outSorted) {
  resizeDiscarding(ioOffsets, std::size_t{inLargestA} + 2);
  std::fill(ioOffsets.begin(), ioOffsets.end(), 0);
  forEachPair(inPairs, [&](const IdPair& inPair) { ++ioOffsets[inPair.a + 1]; });
  for (std::size_t a = 1; a < ioOffsets.size(); ++a) ioOffsets[a] += ioOffsets[a - 1];
  resizeDiscarding(outSorted, inTotal);
  forEachPair(inPairs, [&](const IdPair& inPair) { outSorted[ioOffsets[inPair.a]++] = inPair; });
  // ioOffsets[a] now ends a's run, which starts where a - 1's ended.
  uint32_t begin = 0;
  for (std::size_t a = 0; a <= inLargestA; ++a) {
    const uint32_t end = ioOffsets[a];
    if (end - begin > 1) sortByB(&outSorted[begin], &outSorted[0] + end);
    begin = end;
  }
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
  std::vector<uint32_t>& histogram = ioScratch.offsets;
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
}

}  // namespace

void sortPairsCanonical(PairList& ioPairs, PairSortScratch& ioScratch) {
  const std::size_t count = ioPairs.size();
  if (count < 2) return;
  const uint32_t largest_a = largestA(ioPairs);
  if (denseEnough(largest_a, count)) {
    bucketSort(ioPairs, count, largest_a, ioScratch.offsets, ioScratch.pairs);
    ioPairs.swap(ioScratch.pairs);
  } else {
    radixSort(ioPairs, ioScratch);
  }
}

void sortPairsCanonical(const std::vector<PairChunks>& inParts, PairList& outPairs,
                        PairSortScratch& ioScratch) {
  std::size_t total = 0;
  for (const PairChunks& part : inParts) total += part.size();
  const uint32_t largest_a = largestA(inParts);
  if (denseEnough(largest_a, total)) {
    bucketSort(inParts, total, largest_a, ioScratch.offsets, outPairs);
    return;
  }
  resizeDiscarding(outPairs, total);
  std::size_t next = 0;
  forEachPair(inParts, [&](const IdPair& inPair) { outPairs[next++] = inPair; });
  if (total > 1) radixSort(outPairs, ioScratch);
}

void sortPairsCanonical(PairList& ioPairs) {
  PairSortScratch scratch;
  sortPairsCanonical(ioPairs, scratch);
}

void PairChunks::startChunk() {
  if (used_chunks_ == chunks_.size()) chunks_.emplace_back(new IdPair[kChunkPairs]);
  ++used_chunks_;
  fill_ = 0;
}

bool isCanonical(const PairList& inPairs) {
  for (std::size_t k = 0; k < inPairs.size(); ++k) {
    if (!(inPairs[k].a < inPairs[k].b)) return false;
    if (k > 0 && !(inPairs[k - 1] < inPairs[k])) return false;
  }
  return true;
}

}  // namespace sap_broadphase
