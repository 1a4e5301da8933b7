// An exact index of boxes that do not move, the declared scenery: a uniform 3-D grid in CSR
// form.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/frame/box_columns.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// Exact index of boxes that stay put over many frames: answers "which indexed boxes overlap
/// this box" for closed float64 boxes (touching overlaps, -0.0 == 0.0, ±inf allowed, input
/// already validated: no NaN, min <= max).
///
/// Boxes are binned into a uniform grid over all three axes (an axis whose boxes have no
/// finite spread gets one cell), stored in CSR form: per-cell offsets into one list of box
/// slots. A box that would cover more than a few dozen cells (huge or infinite) is kept in a
/// separate list that every query tests. A pair met in several cells is reported only in the
/// cell holding the larger of the two low ends on every axis, so once; the final test is the
/// exact float64 closed test on all three axes plus the group/mask filter both ways.
/// Queries are const and may run concurrently; build() and remove() may not.
class StaticIndex {
 public:
  /// Indexes boxes inIndexes (distinct positions in inBoxes) of inBoxes on the threads of the
  /// runner's scope (passThreads()); keeps its own copy of their bounds, ids, groups and masks (the
  /// BoxColumns may change afterwards). Replaces any earlier content.
  void build(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexes);
  /// Number of indexed boxes not removed.
  std::size_t size() const { return live_count_; }
  /// How a pair is written: makeIdPair(query id, indexed id), as the engine's pairs are, or
  /// {query id, indexed id} as they are, for box queries whose ids name another set
  /// (Broadphase::query).
  enum class PairOrder : uint8_t { kCanonical, kQueryFirst };
  /// Appends to outPairs (in inOrder) every indexed box that overlaps box inQuery of inQueries
  /// and passes the group/mask filter both ways; each pair once. Allocates nothing beyond
  /// outPairs' growth. In canonical order, query ids are expected to differ from indexed ids
  /// (a box queried against itself would give the pair (id, id)).
  void query(const BoxColumns& inQueries, std::size_t inQuery, PairList& outPairs,
             PairOrder inOrder = PairOrder::kCanonical) const;
  /// All pairs between boxes inQueryIndexes of inQueries and the index, on the threads of the
  /// runner's scope, appended to outPairs (any order; the caller sorts canonically). The order
  /// is the sequential one, whatever the thread count.
  void queryAll(const BoxColumns& inQueries, const std::vector<uint32_t>& inQueryIndexes,
                PairList& outPairs, PairOrder inOrder = PairOrder::kCanonical) const;
  /// Marks the indexed box with id inId as removed (it no longer answers queries); false if
  /// no such box is indexed or it was already removed.
  bool remove(uint32_t inId);

  /// Grid cells per axis chosen by the last build() (for tests and statistics).
  uint32_t cellsOnAxis(int inAxis) const { return dims_[inAxis]; }
  /// Indexed boxes kept in the large list (tested against every query).
  std::size_t largeCount() const { return slots_.size() - grid_count_; }
  /// Bytes held by the index (about 90 bytes an indexed box on the uniform scene).
  std::size_t memoryBytes() const;

 private:
  /// One indexed box, one cache line: what the exact test and the filter read.
  struct alignas(64) Slot {
    double lo[3];
    double hi[3];
    uint32_t group;      ///< 0 once removed, so the filter rejects it
    uint32_t mask;       ///< 0 once removed
    uint64_t low_cells;  ///< cell of lo[] on each axis, kCellBits bits an axis (x lowest)
  };
  struct QueryBox;

  /// Cell of coordinate inValue on axis inAxis: monotone in inValue, clamped to the grid.
  uint32_t cellOf(int inAxis, double inValue) const {
    if (dims_[inAxis] == 1) return 0;
    const double position = (inValue - origin_[inAxis]) * scale_[inAxis];
    if (!(position > 0.0)) return 0;                               // also -inf
    if (position >= last_cell_[inAxis]) return dims_[inAxis] - 1;  // also +inf
    return static_cast<uint32_t>(position);
  }
  void chooseGrid(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexes);
  void placeBoxes(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexes);
  void fillCells();
  void buildIdLookup();
  bool holdsEveryBoxOnce(const BoxColumns& inBoxes, const std::vector<uint32_t>& inIndexes) const;
  /// The cells a box covers on each axis (outLow..outHigh), and how many they are.
  uint64_t cellRange(const double inLow[3], const double inHigh[3], uint32_t outLow[3],
                     uint32_t outHigh[3]) const;
  void scanCells(const QueryBox& inBox, PairList& outPairs) const;
  void prefetchQuery(const BoxColumns& inQueries, std::size_t inQuery, int inStage) const;
  void queryRange(const BoxColumns& inQueries, const std::vector<uint32_t>& inQueryIndexes,
                  std::size_t inBegin, std::size_t inEnd, PairOrder inOrder,
                  PairList& outPairs) const;
  void scanSlots(const QueryBox& inBox, std::size_t inBegin, std::size_t inEnd,
                 PairList& outPairs) const;

  // Grid geometry: cell k on axis a covers [origin + k / scale, origin + (k+1) / scale).
  double origin_[3] = {0.0, 0.0, 0.0};
  double scale_[3] = {0.0, 0.0, 0.0};      // cells per unit length
  double last_cell_[3] = {0.0, 0.0, 0.0};  // dims - 1, as a double
  uint32_t dims_[3] = {1, 1, 1};

  std::vector<Slot> slots_;              // grid boxes [0, grid_count_) by low cell, then large
  std::vector<uint32_t> slot_ids_;       // id of each slot
  std::size_t grid_count_ = 0;           // slots binned into cells
  std::vector<std::size_t> cell_begin_;  // CSR offsets into cell_slots_, one per cell + 1
  std::vector<uint32_t> cell_slots_;     // slots of each cell, ascending
  std::vector<uint32_t> sorted_ids_;     // ids ascending, for remove()
  std::vector<uint32_t> sorted_id_slots_;
  std::vector<uint8_t> removed_;  // per slot
  uint32_t any_group_ = 0;        // OR of all indexed groups: a query no mask of which meets
  uint32_t any_mask_ = 0;         // these cannot pair with anything
  std::size_t live_count_ = 0;
};

}  // namespace sap_broadphase
