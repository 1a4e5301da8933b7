// Stable LSD radix index sort (paper §4.1) and the partitioned parallel sort of Algorithm 2.
//
// Items are packed as (key << 32 | index) so every pass moves one 64-bit word and the index
// travels with its key. Keys are 32-bit, sorted with 11-bit digits (3 passes at most); a pass
// whose digit is the same for every item is skipped. Equal keys keep index order, which puts a
// box's low endpoint (index i) before any high endpoint (index i + n) at the same coordinate:
// closed-interval semantics.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/runner/buffers.h"

namespace sap_broadphase {

/// Packs a key and an index into one sortable word.
inline uint64_t packKeyIndex(uint32_t inKey, uint32_t inIndex) {
  return (uint64_t{inKey} << 32) | inIndex;
}

/// Sorts packed items by key (upper 32 bits), stably. ioScratch must hold inCount items.
/// Returns the buffer holding the result: ioItems or ioScratch. From 2^19 items it
/// runs on the threads of the caller's scope (passThreads(); serial inside a unit of a pass),
/// with the same result on any count.
uint64_t* radixSortPacked(uint64_t* ioItems, uint64_t* ioScratch, std::size_t inCount);

/// Stable sequential index sort: outIndex[k] is the index of the k-th smallest key.
void radixIndexSort(const uint32_t* inKeys, uint32_t inCount, uint32_t* outIndex);

/// Most partitions of Algorithm 2 (partition numbers are stored in 8 bits, 0xFF reserved).
constexpr int kMaxSortPartitions = 255;

/// Partition bounds B of one axis, carried from frame to frame (temporal coherence).
struct AxisBounds {
  std::vector<uint32_t> bounds;  ///< m-1 ascending keys: partition p holds keys in [b_{p-1}, b_p)
  bool from_previous_frame = false;  ///< false: next sort initialises B from the span
};

/// Algorithm 2: splits the keys into m partitions by B, radix-sorts each partition in parallel,
/// then updates B from the sorted order and measures the dispersion D of eq. (1).
class PartitionedSorter {
 public:
  /// Sorts inKeys[0..inCount) into outIndex using inPartitions partitions on the
  /// threads of the runner's scope (passThreads()); reads and updates ioBounds. Returns D for this
  /// sort. Uses buffers of its own.
  double sort(const uint32_t* inKeys, uint32_t inCount, int inPartitions, AxisBounds& ioBounds,
              uint32_t* outIndex);
  /// The same on caller-owned buffers: ioPacked holds packKeyIndex(key_k, k) for k in
  /// [0, inCount), ioScratch room for inCount words; both are overwritten.
  double sortPacked(uint64_t* ioPacked, uint64_t* ioScratch, uint32_t inCount, int inPartitions,
                    AxisBounds& ioBounds, uint32_t* outIndex);

 private:
  void initialiseBoundsFromSpan(const uint64_t* inPacked, uint32_t inCount, int inPartitions,
                                AxisBounds& ioBounds);
  void scatterIntoPartitions(const uint64_t* inPacked, uint64_t* outScattered, uint32_t inCount,
                             const AxisBounds& inBounds);
  void sortPartitionsAndExtract(uint64_t* ioItems, uint64_t* ioScratch, uint32_t inCount,
                                uint32_t* outIndex);
  double dispersion(uint32_t inCount) const;

  Buffer<uint64_t> owned_packed_;  // sort()'s buffers; sortPacked() uses the caller's
  Buffer<uint64_t> owned_scratch_;
  Buffer<uint8_t> partition_of_;              // partition of each key, found once
  std::vector<uint8_t> prefix_table_;         // partition by the key's top 16 bits
  std::vector<uint32_t> counts_;              // [unit][partition]
  std::vector<std::size_t> partition_begin_;  // m + 1 offsets
  std::vector<uint32_t> partition_size_;
  std::vector<uint32_t> bound_samples_;  // next frame's B, read off the sorted partitions
};

}  // namespace sap_broadphase
