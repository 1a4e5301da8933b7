// Passes of the skin's builds whose result is a list, run on the runner's workers: each unit
// writes its own part of the list behind the parts of the units before it, so the list is the
// same, element for element, for any thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/runner/buffers.h"
#include "core/runner/work_units.h"
#include "core/sweep/radix_sort.h"

namespace sap_broadphase {

/// The lowest and highest of some values on each axis (e.g. the low ends of some boxes), combined
/// over units in any grouping with the same result.
struct AxisRanges {
  double low[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::infinity()};
  double high[3] = {-std::numeric_limits<double>::infinity(),
                    -std::numeric_limits<double>::infinity(),
                    -std::numeric_limits<double>::infinity()};
  void add(const AxisRanges& inOther) {
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = std::min(low[axis], inOther.low[axis]);
      high[axis] = std::max(high[axis], inOther.high[axis]);
    }
  }
};

/// The items i of inUnits for which inKeep(i) holds, in increasing order, appended to ioOut:
/// each unit counts its items, then writes them behind those of the units before it (inKeep
/// runs twice an item: it should be a cheap test).
template <class Keep>
void appendItemsWhere(const WorkUnits& inUnits, Keep&& inKeep, Buffer<uint32_t>& ioOut) {
  const std::size_t units = inUnits.count();
  std::vector<std::size_t> start(units + 1, 0);
  runUnits(units, [&](std::size_t inUnit) {
    std::size_t kept = 0;
    for (std::size_t i = inUnits.begin(inUnit); i < inUnits.end(inUnit); ++i)
      kept += inKeep(i) ? 1 : 0;
    start[inUnit + 1] = kept;
  });
  start[0] = ioOut.size();
  for (std::size_t unit = 0; unit < units; ++unit) start[unit + 1] += start[unit];
  ioOut.resize(start[units]);  // a Buffer: growing it initialises nothing
  runUnits(units, [&](std::size_t inUnit) {
    uint32_t* out = ioOut.data() + start[inUnit];
    for (std::size_t i = inUnits.begin(inUnit); i < inUnits.end(inUnit); ++i)
      if (inKeep(i)) *out++ = static_cast<uint32_t>(i);
  });
}

/// ioValues[i] becomes the sum of ioValues[0..i]: each unit sums its own values, the units'
/// sums are added up in unit order, then each unit adds its offset to its running sums (whole
/// numbers: the same for any thread count).
template <class T>
void prefixSumInUnits(T* ioValues, std::size_t inCount) {
  const WorkUnits units{inCount};
  std::vector<T> offset(units.count(), T{0});
  runUnits(units.count(), [&](std::size_t inUnit) {
    T sum{0};
    for (std::size_t i = units.begin(inUnit); i < units.end(inUnit); ++i) sum += ioValues[i];
    offset[inUnit] = sum;
  });
  T running{0};
  for (T& unit_offset : offset) {
    const T sum = unit_offset;
    unit_offset = running;
    running += sum;
  }
  runUnits(units.count(), [&](std::size_t inUnit) {
    T sum = offset[inUnit];
    for (std::size_t i = units.begin(inUnit); i < units.end(inUnit); ++i) {
      sum += ioValues[i];
      ioValues[i] = sum;
    }
  });
}

/// radixIndexSort's result (outIndex[k]: the index of the k-th smallest of inKeys, equal keys
/// in index order), with the keys packed and the indexes unpacked on the workers and the packed
/// lists in buffers that nothing zeroes; the sort itself goes to the workers from
/// radixSortPacked's threshold on.
inline void indexesByKey(const uint32_t* inKeys, std::size_t inCount, uint32_t* outIndex) {
  if (inCount == 0) return;
  Buffer<uint64_t> items;
  Buffer<uint64_t> scratch;
  resizeDiscarding(items, inCount);
  resizeDiscarding(scratch, inCount);
  const WorkUnits units{inCount};
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t i = inBegin; i < inEnd; ++i)
      items[i] = packKeyIndex(inKeys[i], static_cast<uint32_t>(i));
  });
  const uint64_t* sorted = radixSortPacked(items.data(), scratch.data(), inCount);
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) outIndex[k] = static_cast<uint32_t>(sorted[k]);
  });
}

}  // namespace sap_broadphase
