#include "core/sweep/radix_sort.h"
#include "core/runner/buffers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/assert.h"
#include "core/runner/work_units.h"
#include "core/sweep/sort_keys.h"
#include "core/tuning.h"

namespace sap_broadphase {
namespace {

constexpr int kDigitBits = 11;
constexpr uint32_t kDigitValues = 1u << kDigitBits;
constexpr int kPasses = 3;  // 11 + 11 + 10 bits cover a 32-bit key

inline uint32_t digitOf(uint64_t inItem, int inPass) {
  return static_cast<uint32_t>(inItem >> (32 + inPass * kDigitBits)) & (kDigitValues - 1);
}

// Index of the partition holding inKey: the number of bounds <= inKey. Branch-free binary
// search (the compiler emits conditional moves), since keys land in partitions at random.
inline uint8_t partitionOf(uint32_t inKey, const uint32_t* inBounds, int inBoundCount) {
  if (inBoundCount == 0) return 0;
  const uint32_t* base = inBounds;
  int remaining = inBoundCount;
  while (remaining > 1) {
    const int half = remaining / 2;
    base = (base[half] <= inKey) ? base + half : base;
    remaining -= half;
  }
  return static_cast<uint8_t>((base - inBounds) + (*base <= inKey));
}

// Most keys share their top 16 bits with no bound: a table indexed by those bits names their
// partition outright, and only keys in a prefix that a bound splits need the search.
constexpr int kPrefixShift = 16;
constexpr uint8_t kSplitPrefix = 0xFF;
static_assert(kMaxSortPartitions - 1 < kSplitPrefix,
              "partition numbers are stored in 8 bits, with kSplitPrefix reserved");

// Fills entries [inFirstPrefix, inEndPrefix) of the table (the caller sized it).
void fillPrefixTable(const uint32_t* inBounds, int inBoundCount, uint32_t inFirstPrefix,
                     uint32_t inEndPrefix, uint8_t* outTable) {
  // Bounds <= the first key of inFirstPrefix, then kept up to date prefix by prefix.
  int below_first = static_cast<int>(
      std::upper_bound(inBounds, inBounds + inBoundCount, inFirstPrefix << kPrefixShift) -
      inBounds);
  for (uint32_t prefix = inFirstPrefix; prefix < inEndPrefix; ++prefix) {
    const uint32_t first = prefix << kPrefixShift;
    const uint32_t last = first | ((1u << kPrefixShift) - 1);
    while (below_first < inBoundCount && inBounds[below_first] <= first) ++below_first;
    const bool split = below_first < inBoundCount && inBounds[below_first] <= last;
    outTable[prefix] = split ? kSplitPrefix : static_cast<uint8_t>(below_first);
  }
}

constexpr uint32_t kPrefixCount = uint32_t{1} << (32 - kPrefixShift);

inline uint8_t lookupPartition(uint32_t inKey, const uint8_t* inTable, const uint32_t* inBounds,
                               int inBoundCount) {
  const uint8_t partition = inTable[inKey >> kPrefixShift];
  return partition != kSplitPrefix ? partition : partitionOf(inKey, inBounds, inBoundCount);
}

}  // namespace

namespace {

using DigitCounts = std::array<uint32_t, kDigitValues>;

// Fewest items sorted in parallel. The parallel sort reads the items twice more than the serial
// one (counting passes 2 and 3) and hands out up to seven passes, each a wait for the slowest
// unit; below this the serial sort takes a few tenths of a millisecond and, on the loaded 2-core
// VM, the parallel one was slower at 2^17 and 2^18 items (sap_bench has no quiet figure yet).
constexpr std::size_t kParallelSortMinItems = std::size_t{1} << 19;

// The serial sort: one pass counts every digit, then one scatter a digit that varies.
uint64_t* radixSortPackedSerial(uint64_t* ioItems, uint64_t* ioScratch, std::size_t inCount) {
  std::array<DigitCounts, kPasses> histograms;  // 24 KiB, on the stack
  for (auto& histogram : histograms) histogram.fill(0);
  for (std::size_t k = 0; k < inCount; ++k)
    for (int pass = 0; pass < kPasses; ++pass) ++histograms[pass][digitOf(ioItems[k], pass)];

  uint64_t* source = ioItems;
  uint64_t* target = ioScratch;
  for (int pass = 0; pass < kPasses; ++pass) {
    DigitCounts& histogram = histograms[pass];
    // A digit equal for every item would copy the data without reordering it: skip the pass.
    if (histogram[digitOf(source[0], pass)] == inCount) continue;
    uint32_t offset = 0;
    for (uint32_t& bucket : histogram) {
      const uint32_t bucket_size = bucket;
      bucket = offset;
      offset += bucket_size;
    }
    for (std::size_t k = 0; k < inCount; ++k) {
      const uint64_t item = source[k];
      target[histogram[digitOf(item, pass)]++] = item;
    }
    std::swap(source, target);
  }
  return source;
}

// The parallel sort's per-unit counters, [unit][pass] (then [unit] the unit's next slot of each
// digit while it scatters). One set per calling thread, kept between sorts so that a frame's
// sort allocates nothing; workers reach the caller's set through a reference.
std::vector<DigitCounts>& parallelSortCounters() {
  thread_local std::vector<DigitCounts> counters;
  return counters;
}

// The same sort on the scope's threads (passThreads()). The items are cut into units (contiguous
// slices, kUnitsPerThread a thread, none under kUnitBoxes items); each pass counts a unit's
// digits, gives each (digit, unit) its first slot (digits in order, and within a digit the units
// in order: the slots one pass over the items in order would give) and scatters each unit into
// its slots. So the result is the stable order whatever the thread count; each pass after the
// first reads the items once more than the serial sort does, to count them.
uint64_t* radixSortPackedParallel(uint64_t* ioItems, uint64_t* ioScratch, std::size_t inCount) {
  const int units_wanted = unitsForThreads(passThreads());
  const std::size_t slice = (inCount + units_wanted - 1) / units_wanted;
  const WorkUnits units{inCount, std::max(kUnitBoxes, slice)};
  const std::size_t unit_count = units.count();
  std::vector<DigitCounts>& counters = parallelSortCounters();
  if (counters.size() < unit_count * kPasses) counters.resize(unit_count * kPasses);
  auto countsOf = [&](std::size_t inUnit, int inPass) -> DigitCounts& {
    return counters[inUnit * kPasses + inPass];
  };
  // Every digit of every pass, counted once on the unsorted items: their totals decide which
  // passes are skipped, and the first pass run uses its counts as they are.
  runUnits(unit_count, [&](std::size_t inUnit) {
    for (int pass = 0; pass < kPasses; ++pass) countsOf(inUnit, pass).fill(0);
    for (std::size_t k = units.begin(inUnit); k < units.end(inUnit); ++k)
      for (int pass = 0; pass < kPasses; ++pass)
        ++countsOf(inUnit, pass)[digitOf(ioItems[k], pass)];
  });
  uint64_t* source = ioItems;
  uint64_t* target = ioScratch;
  bool counted = true;  // the units' counts of this pass are of source's current order
  for (int pass = 0; pass < kPasses; ++pass) {
    const uint32_t shared_digit = digitOf(source[0], pass);
    uint32_t with_shared_digit = 0;
    for (std::size_t unit = 0; unit < unit_count; ++unit)
      with_shared_digit += countsOf(unit, pass)[shared_digit];
    // A digit equal for every item would copy the data without reordering it: skip the pass.
    if (with_shared_digit == inCount) continue;
    if (!counted) {
      runUnits(unit_count, [&](std::size_t inUnit) {
        DigitCounts& counts = countsOf(inUnit, pass);
        counts.fill(0);
        for (std::size_t k = units.begin(inUnit); k < units.end(inUnit); ++k)
          ++counts[digitOf(source[k], pass)];
      });
    }
    // Each (digit, unit)'s first slot: the items of all smaller digits, then of the digit in
    // earlier units. Serial: a few thousand counters a unit, cheaper than handing out a pass.
    uint32_t slot = 0;
    for (uint32_t digit = 0; digit < kDigitValues; ++digit) {
      for (std::size_t unit = 0; unit < unit_count; ++unit) {
        uint32_t& count = countsOf(unit, pass)[digit];
        const uint32_t items = count;
        count = slot;  // from now on the unit's next slot for the digit
        slot += items;
      }
    }
    SAP_ASSERT(slot == inCount, "the digit counts do not cover every item once");
    runUnits(unit_count, [&](std::size_t inUnit) {
      DigitCounts& next_slot = countsOf(inUnit, pass);
      for (std::size_t k = units.begin(inUnit); k < units.end(inUnit); ++k) {
        const uint64_t item = source[k];
        target[next_slot[digitOf(item, pass)]++] = item;
      }
    });
    std::swap(source, target);
    counted = false;
  }
  return source;
}

}  // namespace

uint64_t* radixSortPacked(uint64_t* ioItems, uint64_t* ioScratch, std::size_t inCount) {
  if (inCount < tuning::kSmallIndexSort) {
    // Items are unique (distinct indexes), so sorting whole words is a stable sort by key
    // provided equal keys arrive in index order, which every caller guarantees.
    std::sort(ioItems, ioItems + inCount);
    return ioItems;
  }
  // Several units on several threads, unless already inside a unit (Algorithm 2 sorts its
  // partitions one a unit): a nested pass would run inline and only pay the extra counting.
  const int threads = passThreads();
  if (threads > 1 && inCount >= kParallelSortMinItems && !detail::runningAUnit())
    return radixSortPackedParallel(ioItems, ioScratch, inCount);
  return radixSortPackedSerial(ioItems, ioScratch, inCount);
}

void radixIndexSort(const uint32_t* inKeys, uint32_t inCount, uint32_t* outIndex) {
  std::vector<uint64_t> items(inCount), scratch(inCount);
  for (uint32_t i = 0; i < inCount; ++i) items[i] = packKeyIndex(inKeys[i], i);
  const uint64_t* sorted =
      inCount ? radixSortPacked(items.data(), scratch.data(), inCount) : nullptr;
  for (uint32_t k = 0; k < inCount; ++k) outIndex[k] = static_cast<uint32_t>(sorted[k]);
}

double PartitionedSorter::sort(const uint32_t* inKeys, uint32_t inCount, int inPartitions,
                               AxisBounds& ioBounds, uint32_t* outIndex) {
  resizeDiscarding(owned_packed_, inCount);
  resizeDiscarding(owned_scratch_, inCount);
  for (uint32_t k = 0; k < inCount; ++k) owned_packed_[k] = packKeyIndex(inKeys[k], k);
  return sortPacked(owned_packed_.data(), owned_scratch_.data(), inCount, inPartitions, ioBounds,
                    outIndex);
}

double PartitionedSorter::sortPacked(uint64_t* ioPacked, uint64_t* ioScratch, uint32_t inCount,
                                     int inPartitions, AxisBounds& ioBounds, uint32_t* outIndex) {
  if (inCount == 0) return 0.0;
  const int partitions = std::clamp(inPartitions, 1, kMaxSortPartitions);
  if (!ioBounds.from_previous_frame ||
      ioBounds.bounds.size() != static_cast<std::size_t>(partitions - 1))
    initialiseBoundsFromSpan(ioPacked, inCount, partitions, ioBounds);
  SAP_ASSERT(std::is_sorted(ioBounds.bounds.begin(), ioBounds.bounds.end()),
             "partition bounds B out of order");
  scatterIntoPartitions(ioPacked, ioScratch, inCount, ioBounds);
  SAP_ASSERT(partition_begin_.back() == inCount,
             "the partitions do not cover every rank exactly once");
  sortPartitionsAndExtract(ioScratch, ioPacked, inCount, outIndex);
  // Algorithm 2, lines 6-7: next frame's bounds are this frame's keys at ranks p * floor(2n/m).
  std::copy(bound_samples_.begin(), bound_samples_.end(), ioBounds.bounds.begin());
  ioBounds.from_previous_frame = true;
  return dispersion(inCount);
}

// First frame (or after an axis swap): b_p = min + p * span / m over the finite coordinates.
void PartitionedSorter::initialiseBoundsFromSpan(const uint64_t* inPacked, uint32_t inCount,
                                                 int inPartitions, AxisBounds& ioBounds) {
  struct Span {
    float lowest = std::numeric_limits<float>::infinity();
    float highest = -std::numeric_limits<float>::infinity();
  };
  const auto [lowest, highest] = reduceOverItems(
      WorkUnits{inCount}, Span{},
      [&](std::size_t inBegin, std::size_t inEnd) {
        Span unit;
        for (std::size_t k = inBegin; k < inEnd; ++k) {
          const float value = keyToFloat(static_cast<uint32_t>(inPacked[k] >> 32));
          if (std::isfinite(value)) {
            unit.lowest = std::min(unit.lowest, value);
            unit.highest = std::max(unit.highest, value);
          }
        }
        return unit;
      },
      [](Span& ioTotal, const Span& inUnit) {
        ioTotal.lowest = std::min(ioTotal.lowest, inUnit.lowest);
        ioTotal.highest = std::max(ioTotal.highest, inUnit.highest);
      });
  ioBounds.bounds.resize(inPartitions - 1);
  const bool have_span = lowest <= highest;
  for (int p = 1; p < inPartitions; ++p) {
    const double fraction = static_cast<double>(p) / inPartitions;
    ioBounds.bounds[p - 1] =
        have_span ? floatToKey(static_cast<float>(lowest + fraction * (double(highest) - lowest)))
                  : static_cast<uint32_t>(fraction * 4294967295.0);
  }
  ioBounds.from_previous_frame = false;
}

// Algorithm 2, lines 1-3: each unit (a contiguous slice of the items; more units than threads,
// claimed dynamically) is counted, then placed, so every partition receives its items in index
// order (the sort stays stable).
void PartitionedSorter::scatterIntoPartitions(const uint64_t* inPacked, uint64_t* outScattered,
                                              uint32_t inCount, const AxisBounds& inBounds) {
  const int partitions = static_cast<int>(inBounds.bounds.size()) + 1;
  const int bound_count = partitions - 1;
  SAP_ASSERT(partitions >= 1 && partitions <= kMaxSortPartitions,
             "more sort partitions than partition_of_'s 8 bits number");
  const uint32_t* bounds = inBounds.bounds.data();
  const int units = unitsForThreads(passThreads());
  // Each unit's counters sit a cache line past the previous unit's: counters that shared a
  // line would bounce between the cores on every item.
  const std::size_t stride =
      static_cast<std::size_t>(partitions) + kCacheLineBytes / sizeof(uint32_t);
  counts_.assign(static_cast<std::size_t>(units) * stride, 0);
  resizeDiscarding(partition_of_, inCount);
  prefix_table_.resize(kPrefixCount);
  partition_begin_.assign(partitions + 1, 0);
  partition_size_.assign(partitions, 0);
  auto share = [](uint64_t inTotal, int inUnit, int inUnits) {
    return static_cast<uint32_t>(inTotal * inUnit / inUnits);
  };
  uint8_t* partition_of = partition_of_.data();
  // The prefix table, a share a unit (65536 entries, a serial part otherwise).
  runUnits(units, [&](std::size_t inUnit) {
    const int unit = static_cast<int>(inUnit);
    fillPrefixTable(bounds, bound_count, share(kPrefixCount, unit, units),
                    share(kPrefixCount, unit + 1, units), prefix_table_.data());
  });
  runUnits(units, [&](std::size_t inUnit) {
    const int unit = static_cast<int>(inUnit);
    uint32_t* unit_counts = &counts_[static_cast<std::size_t>(unit) * stride];
    const uint32_t end = share(inCount, unit + 1, units);
    for (uint32_t k = share(inCount, unit, units); k < end; ++k) {
      const uint32_t key = static_cast<uint32_t>(inPacked[k] >> 32);
      partition_of[k] = lookupPartition(key, prefix_table_.data(), bounds, bound_count);
      ++unit_counts[partition_of[k]];
    }
  });
  std::size_t offset = 0;
  for (int p = 0; p < partitions; ++p) {
    partition_begin_[p] = offset;
    for (int unit = 0; unit < units; ++unit) {
      uint32_t& slot = counts_[static_cast<std::size_t>(unit) * stride + p];
      const uint32_t size = slot;
      slot = static_cast<uint32_t>(offset);
      offset += size;
    }
    partition_size_[p] = static_cast<uint32_t>(offset - partition_begin_[p]);
  }
  partition_begin_[partitions] = offset;
  runUnits(units, [&](std::size_t inUnit) {
    const int unit = static_cast<int>(inUnit);
    uint32_t* unit_counts = &counts_[static_cast<std::size_t>(unit) * stride];
    const uint32_t end = share(inCount, unit + 1, units);
    for (uint32_t k = share(inCount, unit, units); k < end; ++k)
      outScattered[unit_counts[partition_of[k]]++] = inPacked[k];
  });
}

// Algorithm 2, lines 4-5: the partitions are independent and handed out dynamically. Keys at
// the sorted positions p * floor(count / m) are kept as next frame's bounds.
void PartitionedSorter::sortPartitionsAndExtract(uint64_t* ioItems, uint64_t* ioScratch,
                                                 uint32_t inCount, uint32_t* outIndex) {
  const int partitions = static_cast<int>(partition_size_.size());
  const std::size_t sample_step = inCount / partitions;
  bound_samples_.assign(partitions - 1, 0);
  runUnits(partitions, [&](std::size_t inPartition) {
    const std::size_t begin = partition_begin_[inPartition];
    const std::size_t size = partition_size_[inPartition];
    if (size == 0) return;
    const uint64_t* sorted = radixSortPacked(&ioItems[begin], &ioScratch[begin], size);
    for (std::size_t k = 0; k < size; ++k) outIndex[begin + k] = static_cast<uint32_t>(sorted[k]);
    for (std::size_t sample = 1; sample < static_cast<std::size_t>(partitions); ++sample) {
      const std::size_t position = sample * sample_step;
      if (position >= begin && position < begin + size)
        bound_samples_[sample - 1] = static_cast<uint32_t>(sorted[position - begin] >> 32);
    }
  });
}

// Eq. (1): D = sum_p |x_p - mu| / (2n), with mu the ideal partition size.
double PartitionedSorter::dispersion(uint32_t inCount) const {
  const double ideal = static_cast<double>(inCount) / partition_size_.size();
  double deviation = 0.0;
  for (uint32_t size : partition_size_) deviation += std::abs(size - ideal);
  return deviation / inCount;
}

}  // namespace sap_broadphase
