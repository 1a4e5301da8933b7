#include "core/strategies/static_index.h"

#include "core/assert.h"
#include "core/runner/buffers.h"
#include "core/sweep/axis_spread.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/sweep/radix_sort.h"

#include "core/runner/work_units.h"
#include "core/tuning.h"

namespace sap_broadphase {

namespace {

// Bits of one axis's cell index in Slot::low_cells; three axes fit in 63 bits.
constexpr int kCellBits = 21;
constexpr uint32_t kMaxCellsOnAxis = uint32_t{1} << kCellBits;

// Cells wanted on one axis before the total cap: span / (tuning::kCellInExtents * mean extent).
uint32_t wantedCells(const AxisSpread& inSpread) {
  const double span = inSpread.highest - inSpread.lowest;
  if (inSpread.finite_boxes == 0 || !(span > 0.0) || !std::isfinite(span)) return 1;
  const double mean_extent = inSpread.extent_sum / static_cast<double>(inSpread.finite_boxes);
  if (!(mean_extent > 0.0)) return kMaxCellsOnAxis;  // points: the total cap decides
  const double wanted = span / (tuning::kCellInExtents * mean_extent);
  if (!(wanted > 1.0)) return 1;
  if (wanted >= kMaxCellsOnAxis) return kMaxCellsOnAxis;
  return static_cast<uint32_t>(std::ceil(wanted));
}

uint64_t cellsOf(const uint32_t inDims[3]) {
  return uint64_t{inDims[0]} * inDims[1] * inDims[2];
}

}  // namespace

/// The query box as the scan loops read it.
struct StaticIndex::QueryBox {
  double lo[3];
  double hi[3];
  uint32_t group;
  uint32_t mask;
  uint32_t id;
  PairOrder order;

  IdPair pairWith(uint32_t inIndexedId) const {
    return order == PairOrder::kQueryFirst ? IdPair{id, inIndexedId} : makeIdPair(id, inIndexedId);
  }
};

namespace {

template <typename Slot, typename QueryBox>
bool overlapsAndAllowed(const Slot& inSlot, const QueryBox& inBox) {
  for (int axis = 0; axis < 3; ++axis)
    if (inSlot.lo[axis] > inBox.hi[axis] || inBox.lo[axis] > inSlot.hi[axis]) return false;
  return groupsMayPair(inSlot.group, inSlot.mask, inBox.group, inBox.mask);
}

}  // namespace

void StaticIndex::build(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexes) {
  chooseGrid(inBoxes, inIndexes);
  placeBoxes(inBoxes, inIndexes);
  fillCells();
  buildIdLookup();
  SAP_ASSERT(holdsEveryBoxOnce(inBoxes, inIndexes), "the static index lost or repeated a box");
}

// Every box of inIndexes has one slot (its id once among the slots' ids), and every grid slot
// is listed in its home cell, the cell of its low corner.
bool StaticIndex::holdsEveryBoxOnce(const BoxColumns& inBoxes,
                                    const std::vector<uint32_t>& inIndexes) const {
  if (slots_.size() != inIndexes.size() || live_count_ != inIndexes.size()) return false;
  std::vector<uint32_t> ids;
  for (uint32_t i : inIndexes) ids.push_back(inBoxes.ids[i]);
  std::sort(ids.begin(), ids.end());
  if (ids != sorted_ids_ || std::adjacent_find(ids.begin(), ids.end()) != ids.end()) return false;
  for (std::size_t s = 0; s < grid_count_; ++s) {
    uint64_t cell = 0;
    for (int axis = 2; axis >= 0; --axis)
      cell = cell * dims_[axis] + cellOf(axis, slots_[s].lo[axis]);
    const auto first = cell_slots_.begin() + static_cast<std::ptrdiff_t>(cell_begin_[cell]);
    const auto last = cell_slots_.begin() + static_cast<std::ptrdiff_t>(cell_begin_[cell + 1]);
    if (std::find(first, last, static_cast<uint32_t>(s)) == last) return false;
  }
  return true;
}

void StaticIndex::chooseGrid(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexes) {
  AxisSpread spreads[3];
  for (int axis = 0; axis < 3; ++axis) {
    spreads[axis] = measureAxisSpread(inBoxes, axis, &inIndexes);
    dims_[axis] = wantedCells(spreads[axis]);
  }
  // Halving the finest axis keeps cells as close to cubes (in extents) as the cap allows.
  const double cap = std::max(1.0, tuning::kCellsPerBox * static_cast<double>(inIndexes.size()));
  while (static_cast<double>(cellsOf(dims_)) > cap) {
    uint32_t& finest = *std::max_element(dims_, dims_ + 3);
    finest = (finest + 1) / 2;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const double span = spreads[axis].highest - spreads[axis].lowest;
    origin_[axis] = dims_[axis] > 1 ? spreads[axis].lowest : 0.0;
    scale_[axis] = dims_[axis] > 1 ? dims_[axis] / span : 0.0;
    if (!std::isfinite(scale_[axis])) {  // a subnormal span: not worth cells
      dims_[axis] = 1;
      origin_[axis] = scale_[axis] = 0.0;
    }
    last_cell_[axis] = static_cast<double>(dims_[axis] - 1);
  }
}

void StaticIndex::placeBoxes(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexes) {
  const std::size_t count = inIndexes.size();
  constexpr uint64_t kLarge = std::numeric_limits<uint64_t>::max();
  // Each box's home cell (the cell of its low corner), or kLarge.
  Buffer<uint64_t> home(count);
  runOverItems(WorkUnits{count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) {
      const uint32_t i = inIndexes[k];
      uint64_t covered = 1;
      uint32_t low[3];
      for (int axis = 0; axis < 3; ++axis) {
        low[axis] = cellOf(axis, inBoxes.lo[axis][i]);
        covered *= cellOf(axis, inBoxes.hi[axis][i]) - low[axis] + 1;
      }
      home[k] = covered > tuning::kMaxCellsPerBox
                    ? kLarge
                    : (uint64_t{low[2]} * dims_[1] + low[1]) * dims_[0] + low[0];
    }
  });
  // Counting sort by home cell: boxes of one cell sit together in slots_ (cache locality).
  const uint64_t cells = cellsOf(dims_);
  std::vector<std::size_t> next_slot(cells + 1, 0);
  for (std::size_t k = 0; k < count; ++k)
    if (home[k] != kLarge) ++next_slot[home[k] + 1];
  for (uint64_t cell = 0; cell < cells; ++cell) next_slot[cell + 1] += next_slot[cell];
  grid_count_ = next_slot[cells];
  std::size_t next_large = grid_count_;
  std::vector<uint32_t> slot_of(count);
  for (std::size_t k = 0; k < count; ++k)
    slot_of[k] = static_cast<uint32_t>(home[k] == kLarge ? next_large++ : next_slot[home[k]]++);

  slots_.resize(count);
  slot_ids_.resize(count);
  struct Filters {
    uint32_t any_group = 0;
    uint32_t any_mask = 0;
  };
  const Filters filters = reduceOverItems(
      WorkUnits{count}, Filters{},
      [&](std::size_t inBegin, std::size_t inEnd) {
        Filters unit;
        for (std::size_t k = inBegin; k < inEnd; ++k) {
          const uint32_t i = inIndexes[k];
          Slot& slot = slots_[slot_of[k]];
          slot.low_cells = 0;
          for (int axis = 0; axis < 3; ++axis) {
            slot.lo[axis] = inBoxes.lo[axis][i];
            slot.hi[axis] = inBoxes.hi[axis][i];
            slot.low_cells |= uint64_t{cellOf(axis, slot.lo[axis])} << (kCellBits * axis);
          }
          slot.group = inBoxes.group(i);
          slot.mask = inBoxes.mask(i);
          slot_ids_[slot_of[k]] = inBoxes.ids[i];
          unit.any_group |= slot.group;
          unit.any_mask |= slot.mask;
        }
        return unit;
      },
      [](Filters& ioAll, const Filters& inUnit) {
        ioAll.any_group |= inUnit.any_group;
        ioAll.any_mask |= inUnit.any_mask;
      });
  any_group_ = filters.any_group;
  any_mask_ = filters.any_mask;
  removed_.assign(count, 0);
  live_count_ = count;
}

void StaticIndex::fillCells() {
  const uint64_t cells = cellsOf(dims_);
  // Calls inVisit(cell) for every cell that grid slot inSlot covers.
  auto forEachCell = [this](const Slot& inSlot, auto&& inVisit) {
    uint32_t low[3], high[3];
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = cellOf(axis, inSlot.lo[axis]);
      high[axis] = cellOf(axis, inSlot.hi[axis]);
    }
    for (uint32_t z = low[2]; z <= high[2]; ++z)
      for (uint32_t y = low[1]; y <= high[1]; ++y) {
        const uint64_t row = (uint64_t{z} * dims_[1] + y) * dims_[0];
        for (uint32_t x = low[0]; x <= high[0]; ++x) inVisit(row + x);
      }
  };
  cell_begin_.assign(cells + 1, 0);
  for (std::size_t s = 0; s < grid_count_; ++s)
    forEachCell(slots_[s], [this](uint64_t inCell) { ++cell_begin_[inCell + 1]; });
  for (uint64_t cell = 0; cell < cells; ++cell) cell_begin_[cell + 1] += cell_begin_[cell];
  cell_slots_.resize(cell_begin_[cells]);
  std::vector<std::size_t> cursor(cell_begin_.begin(), cell_begin_.end() - 1);
  for (std::size_t s = 0; s < grid_count_; ++s)
    forEachCell(slots_[s],
                [&](uint64_t inCell) { cell_slots_[cursor[inCell]++] = static_cast<uint32_t>(s); });
}

void StaticIndex::buildIdLookup() {
  const auto count = static_cast<uint32_t>(slot_ids_.size());
  sorted_id_slots_.resize(count);
  radixIndexSort(slot_ids_.data(), count, sorted_id_slots_.data());
  sorted_ids_.resize(count);
  for (uint32_t k = 0; k < count; ++k) sorted_ids_[k] = slot_ids_[sorted_id_slots_[k]];
}

std::size_t StaticIndex::memoryBytes() const {
  return slots_.capacity() * sizeof(Slot) +
         (slot_ids_.capacity() + cell_slots_.capacity() + sorted_ids_.capacity() +
          sorted_id_slots_.capacity()) *
             sizeof(uint32_t) +
         cell_begin_.capacity() * sizeof(std::size_t) + removed_.capacity();
}

bool StaticIndex::remove(uint32_t inId) {
  const auto found = std::lower_bound(sorted_ids_.begin(), sorted_ids_.end(), inId);
  if (found == sorted_ids_.end() || *found != inId) return false;
  const uint32_t slot = sorted_id_slots_[found - sorted_ids_.begin()];
  if (removed_[slot]) return false;
  removed_[slot] = 1;
  slots_[slot].group = 0;  // the filter now rejects it on every path
  slots_[slot].mask = 0;
  --live_count_;
  return true;
}

void StaticIndex::query(const BoxColumns& inQueries, std::size_t inQuery, PairList& outPairs,
                        PairOrder inOrder) const {
  QueryBox box;
  box.order = inOrder;
  for (int axis = 0; axis < 3; ++axis) {
    box.lo[axis] = inQueries.lo[axis][inQuery];
    box.hi[axis] = inQueries.hi[axis][inQuery];
  }
  box.group = inQueries.group(inQuery);
  box.mask = inQueries.mask(inQuery);
  box.id = inQueries.ids[inQuery];
  if ((box.group & any_mask_) == 0 || (box.mask & any_group_) == 0) return;
  scanCells(box, outPairs);
  scanSlots(box, grid_count_, slots_.size(), outPairs);
}

uint64_t StaticIndex::cellRange(const double inLow[3], const double inHigh[3], uint32_t outLow[3],
                                uint32_t outHigh[3]) const {
  uint64_t cells = 1;
  for (int axis = 0; axis < 3; ++axis) {
    outLow[axis] = cellOf(axis, inLow[axis]);
    outHigh[axis] = cellOf(axis, inHigh[axis]);
    cells *= outHigh[axis] - outLow[axis] + 1;
  }
  return cells;
}

void StaticIndex::scanCells(const QueryBox& inBox, PairList& outPairs) const {
  if (grid_count_ == 0) return;
  uint32_t low[3], high[3];
  const uint64_t visited = cellRange(inBox.lo, inBox.hi, low, high);
  // A cell visit costs an offset read plus its list; once that exceeds one test per binned
  // box, testing each binned box once is cheaper (and needs no duplicate rule).
  const double per_cell =
      1.0 + static_cast<double>(cell_slots_.size()) / static_cast<double>(cellsOf(dims_));
  if (static_cast<double>(visited) * per_cell >= static_cast<double>(grid_count_)) {
    scanSlots(inBox, 0, grid_count_, outPairs);
    return;
  }
  // Reference-point rule: a pair is reported only in the cell holding, on every axis,
  // max(query low, indexed low), i.e. max of their low cells (cellOf is monotone). Where this
  // cell is the query's low cell on an axis, any indexed box listed here qualifies on that axis
  // (its low cell is at most this one); elsewhere its low cell must be exactly this one.
  constexpr uint64_t kAxisBits = (uint64_t{1} << kCellBits) - 1;
  for (uint32_t z = low[2]; z <= high[2]; ++z) {
    const uint64_t need_z = z > low[2] ? kAxisBits << (2 * kCellBits) : 0;
    for (uint32_t y = low[1]; y <= high[1]; ++y) {
      const uint64_t need_yz = need_z | (y > low[1] ? kAxisBits << kCellBits : 0);
      const uint64_t row = (uint64_t{z} * dims_[1] + y) * dims_[0];
      for (uint32_t x = low[0]; x <= high[0]; ++x) {
        const uint64_t need = need_yz | (x > low[0] ? kAxisBits : 0);
        const uint64_t here =
            (uint64_t{z} << (2 * kCellBits)) | (uint64_t{y} << kCellBits) | uint64_t{x};
        const uint64_t expected = here & need;
        for (std::size_t e = cell_begin_[row + x]; e < cell_begin_[row + x + 1]; ++e) {
          const uint32_t s = cell_slots_[e];
          const Slot& slot = slots_[s];
          if ((slot.low_cells & need) != expected) continue;
          if (overlapsAndAllowed(slot, inBox)) outPairs.push_back(inBox.pairWith(slot_ids_[s]));
        }
      }
    }
  }
}

void StaticIndex::scanSlots(const QueryBox& inBox, std::size_t inBegin, std::size_t inEnd,
                            PairList& outPairs) const {
  for (std::size_t s = inBegin; s < inEnd; ++s)
    if (overlapsAndAllowed(slots_[s], inBox)) outPairs.push_back(inBox.pairWith(slot_ids_[s]));
}

// Queries of a frame land in cells far apart in a large index, so each one waits for its
// cells' offsets, their slot lists and the slots themselves, one miss after the other. The
// three are fetched ahead in stages, for the query tuning::kSceneryPrefetchAhead[stage] positions
// later: offsets first, the slot lists once the offsets are in, the slots once the lists are in.
void StaticIndex::prefetchQuery(const BoxColumns& inQueries, std::size_t inQuery,
                                int inStage) const {
  if (grid_count_ == 0) return;
  const double box_low[3] = {inQueries.lo[0][inQuery], inQueries.lo[1][inQuery],
                             inQueries.lo[2][inQuery]};
  const double box_high[3] = {inQueries.hi[0][inQuery], inQueries.hi[1][inQuery],
                              inQueries.hi[2][inQuery]};
  uint32_t low[3], high[3];
  if (cellRange(box_low, box_high, low, high) > tuning::kSceneryMostCellsPrefetched)
    return;  // a large box
  for (uint32_t z = low[2]; z <= high[2]; ++z) {
    for (uint32_t y = low[1]; y <= high[1]; ++y) {
      const std::size_t row = (std::size_t{z} * dims_[1] + y) * dims_[0];
      if (inStage == 0) {
        __builtin_prefetch(&cell_begin_[row + low[0]]);
        continue;
      }
      const std::size_t begin = cell_begin_[row + low[0]];
      const std::size_t end = cell_begin_[row + high[0] + 1];
      if (inStage == 1) {
        if (begin < end) __builtin_prefetch(&cell_slots_[begin]);
        continue;
      }
      for (std::size_t e = begin; e < std::min(end, begin + tuning::kSceneryMostCellsPrefetched);
           ++e)
        __builtin_prefetch(&slots_[cell_slots_[e]]);
    }
  }
}

void StaticIndex::queryRange(const BoxColumns& inQueries,
                             const std::vector<uint32_t>& inQueryIndexes, std::size_t inBegin,
                             std::size_t inEnd, PairOrder inOrder, PairList& outPairs) const {
  for (std::size_t k = inBegin; k < inEnd; ++k) {
    for (int stage = 0; stage < 3; ++stage) {
      if (k + tuning::kSceneryPrefetchAhead[stage] < inEnd)
        prefetchQuery(inQueries, inQueryIndexes[k + tuning::kSceneryPrefetchAhead[stage]], stage);
    }
    query(inQueries, inQueryIndexes[k], outPairs, inOrder);
  }
}

void StaticIndex::queryAll(const BoxColumns& inQueries, const std::vector<uint32_t>& inQueryIndexes,
                           PairList& outPairs, PairOrder inOrder) const {
  // Units of queries, each unit's pairs in its own part, the parts joined in unit order: the
  // sequential order for any thread count (a frame of one unit queries inline).
  const WorkUnits units{inQueryIndexes.size()};
  if (units.count() <= 1) {
    queryRange(inQueries, inQueryIndexes, 0, units.items, inOrder, outPairs);
    return;
  }
  std::vector<PairList> parts(units.count());
  runUnits(units.count(), [&](std::size_t inUnit) {
    queryRange(inQueries, inQueryIndexes, units.begin(inUnit), units.end(inUnit), inOrder,
               parts[inUnit]);
  });
  std::size_t total = outPairs.size();
  for (const PairList& part : parts) total += part.size();
  outPairs.reserve(total);
  for (const PairList& part : parts) outPairs.insert(outPairs.end(), part.begin(), part.end());
}

}  // namespace sap_broadphase
