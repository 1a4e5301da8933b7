#include "sap_broadphase/core/pair_set.h"

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

// Counting sort on a (ids 0..inLargestA) of the pairs of all inParts into outSorted, then
// each run of equal a sorted by b.
void bucketSort(const PairList* inParts, std::size_t inPartCount, uint32_t inLargestA,
                std::vector<uint32_t>& ioOffsets, PairList& outSorted) {
  ioOffsets.assign(std::size_t{inLargestA} + 2, 0);
  std::size_t total = 0;
  for (std::size_t part = 0; part < inPartCount; ++part) {
    total += inParts[part].size();
    for (const IdPair& pair : inParts[part]) ++ioOffsets[pair.a + 1];
  }
  for (std::size_t a = 1; a < ioOffsets.size(); ++a) ioOffsets[a] += ioOffsets[a - 1];
  outSorted.resize(total);
  for (std::size_t part = 0; part < inPartCount; ++part)
    for (const IdPair& pair : inParts[part]) outSorted[ioOffsets[pair.a]++] = pair;
  // ioOffsets[a] now ends a's run, which starts where a - 1's ended.
  uint32_t begin = 0;
  for (std::size_t a = 0; a <= inLargestA; ++a) {
    const uint32_t end = ioOffsets[a];
    if (end - begin > 1) sortByB(&outSorted[begin], &outSorted[0] + end);
    begin = end;
  }
}

uint32_t largestA(const PairList& inPairs) {
  uint32_t largest = 0;
  for (const IdPair& pair : inPairs) largest = std::max(largest, pair.a);
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
  ioScratch.pairs.resize(count);
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
    bucketSort(&ioPairs, 1, largest_a, ioScratch.offsets, ioScratch.pairs);
    ioPairs.swap(ioScratch.pairs);
  } else {
    radixSort(ioPairs, ioScratch);
  }
}

void sortPairsCanonical(const std::vector<PairList>& inParts, PairList& outPairs,
                        PairSortScratch& ioScratch) {
  std::size_t total = 0;
  uint32_t largest_a = 0;
  for (const PairList& part : inParts) {
    total += part.size();
    largest_a = std::max(largest_a, largestA(part));
  }
  if (denseEnough(largest_a, total)) {
    bucketSort(inParts.data(), inParts.size(), largest_a, ioScratch.offsets, outPairs);
    return;
  }
  outPairs.clear();
  for (const PairList& part : inParts) outPairs.insert(outPairs.end(), part.begin(), part.end());
  if (total > 1) radixSort(outPairs, ioScratch);
}

void sortPairsCanonical(PairList& ioPairs) {
  PairSortScratch scratch;
  sortPairsCanonical(ioPairs, scratch);
}

}  // namespace sap_broadphase
