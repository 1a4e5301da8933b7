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

// Counting sort on a (ids 0..inLargestA), then each run of equal a sorted by b.
void bucketSort(PairList& ioPairs, PairSortScratch& ioScratch, uint32_t inLargestA) {
  std::vector<uint32_t>& offsets = ioScratch.offsets;
  offsets.assign(std::size_t{inLargestA} + 2, 0);
  for (const IdPair& pair : ioPairs) ++offsets[pair.a + 1];
  for (std::size_t a = 1; a < offsets.size(); ++a) offsets[a] += offsets[a - 1];
  PairList& sorted = ioScratch.pairs;
  sorted.resize(ioPairs.size());
  for (const IdPair& pair : ioPairs) sorted[offsets[pair.a]++] = pair;
  // offsets[a] now ends a's run, which starts where a - 1's ended.
  uint32_t begin = 0;
  for (std::size_t a = 0; a <= inLargestA; ++a) {
    const uint32_t end = offsets[a];
    if (end - begin > 1) sortByB(&sorted[begin], &sorted[0] + end);
    begin = end;
  }
  ioPairs.swap(sorted);
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
  uint32_t largest_a = 0;
  for (const IdPair& pair : ioPairs) largest_a = std::max(largest_a, pair.a);
  if (largest_a < 4 * count + 65536)
    bucketSort(ioPairs, ioScratch, largest_a);
  else
    radixSort(ioPairs, ioScratch);
}

void sortPairsCanonical(PairList& ioPairs) {
  PairSortScratch scratch;
  sortPairsCanonical(ioPairs, scratch);
}

}  // namespace sap_broadphase
