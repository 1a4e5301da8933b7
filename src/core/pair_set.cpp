#include "sap_broadphase/core/pair_set.h"

#include <array>

namespace sap_broadphase {
namespace {

constexpr int kDigitBits = 16;
constexpr uint32_t kDigitValues = 1u << kDigitBits;

inline uint64_t pairKey(const IdPair& inPair) {
  return (uint64_t{inPair.a} << 32) | inPair.b;
}

}  // namespace

void sortPairsCanonical(PairList& ioPairs, PairList& ioScratch) {
  const std::size_t count = ioPairs.size();
  if (count < 2) return;
  ioScratch.resize(count);
  // LSD radix sort on the 64-bit key a<<32|b with 16-bit digits; passes whose digit never
  // varies (ids below 2^16, say) are skipped.
  std::vector<uint32_t> histogram(kDigitValues);
  PairList* source = &ioPairs;
  PairList* target = &ioScratch;
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
  if (source != &ioPairs) ioPairs.swap(ioScratch);
}

void sortPairsCanonical(PairList& ioPairs) {
  PairList scratch;
  sortPairsCanonical(ioPairs, scratch);
}

}  // namespace sap_broadphase
