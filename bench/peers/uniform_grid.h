// The naive baseline: a well-tuned uniform grid. Exact on closed intervals, each
// pair reported once (by the cell holding the low corner of the two boxes' intersection).
#pragma once

#include <cstdint>
#include <vector>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_bench {

/// Hashed uniform grid rebuilt every frame; cells of inCellScale times the mean box edge per
/// axis; boxes covering too many cells are tested against every box instead.
class UniformGrid {
 public:
  explicit UniformGrid(int inThreads = 1, double inCellScale = 1.0);
  /// Every overlapping, filter-allowed pair of inBoxes as ids (a < b), unordered.
  const sap_broadphase::PairList& pairs(const sap_broadphase::BoxSet& inBoxes);

 private:
  struct Entry {
    uint64_t cell;  ///< packed cell coordinates
    uint32_t box;
  };
  void chooseCells(const sap_broadphase::BoxSet& inBoxes);
  void fillBuckets(const sap_broadphase::BoxSet& inBoxes);
  void pairBuckets(const sap_broadphase::BoxSet& inBoxes);
  void pairBigBoxes(const sap_broadphase::BoxSet& inBoxes);
  void cellRange(const sap_broadphase::BoxSet& inBoxes, uint32_t inBox, int64_t outLo[3],
                 int64_t outHi[3]) const;
  uint64_t packCell(int64_t inX, int64_t inY, int64_t inZ) const;
  std::size_t bucketOf(uint64_t inCell) const;

  int threads_;
  double cell_scale_;
  double origin_[3] = {0, 0, 0};
  double inverse_cell_[3] = {1, 1, 1};
  std::size_t bucket_mask_ = 0;
  std::vector<uint32_t> bucket_start_;
  std::vector<Entry> entries_;
  std::vector<uint32_t> big_;  ///< boxes covering more than kMaxCellsPerBox cells
  std::vector<uint8_t> is_big_;
  std::vector<sap_broadphase::PairList> thread_pairs_;
  sap_broadphase::PairList pairs_;
};

}  // namespace sap_bench
