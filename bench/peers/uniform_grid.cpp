// The uniform grid baseline.
#include "uniform_grid.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace sap_bench {

using sap_broadphase::BoxSet;
using sap_broadphase::PairList;

namespace {

constexpr int64_t kMaxCellsPerBox = 64;
constexpr int kCellBits = 21;  // per axis in a packed cell
constexpr int64_t kMaxCellIndex = (int64_t{1} << kCellBits) - 1;

bool overlap(const BoxSet& inBoxes, uint32_t a, uint32_t b) {
  return sap_broadphase::boxesOverlap(inBoxes, a, b) &&
         (!inBoxes.hasFilters() || sap_broadphase::filtersAllow(inBoxes, a, b));
}

}  // namespace

UniformGrid::UniformGrid(int inThreads, double inCellScale)
    : threads_(std::max(1, inThreads)), cell_scale_(inCellScale) {}

void UniformGrid::chooseCells(const BoxSet& inBoxes) {
  const std::size_t n = inBoxes.size();
  for (int axis = 0; axis < 3; ++axis) {
    double low = inBoxes.lo(axis, 0), high = inBoxes.hi(axis, 0), edges = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      low = std::min(low, inBoxes.lo(axis, i));
      high = std::max(high, inBoxes.hi(axis, i));
      edges += inBoxes.hi(axis, i) - inBoxes.lo(axis, i);
    }
    double cell = cell_scale_ * edges / static_cast<double>(n);
    // Never more cells per axis than the packing holds; never a zero-sized cell.
    cell = std::max(cell, (high - low) / static_cast<double>(kMaxCellIndex - 1));
    if (!(cell > 0.0)) cell = 1.0;
    origin_[axis] = low;
    inverse_cell_[axis] = 1.0 / cell;
  }
}

void UniformGrid::cellRange(const BoxSet& inBoxes, uint32_t inBox, int64_t outLo[3],
                            int64_t outHi[3]) const {
  for (int axis = 0; axis < 3; ++axis) {
    // floor() of a monotone map: the intersection's low corner always lands in a cell that
    // both boxes' ranges contain, which makes the owner-cell rule exact.
    const double scale = inverse_cell_[axis];
    outLo[axis] =
        static_cast<int64_t>(std::floor((inBoxes.lo(axis, inBox) - origin_[axis]) * scale));
    outHi[axis] =
        static_cast<int64_t>(std::floor((inBoxes.hi(axis, inBox) - origin_[axis]) * scale));
    outLo[axis] = std::clamp<int64_t>(outLo[axis], 0, kMaxCellIndex);
    outHi[axis] = std::clamp<int64_t>(outHi[axis], 0, kMaxCellIndex);
  }
}

uint64_t UniformGrid::packCell(int64_t inX, int64_t inY, int64_t inZ) const {
  return (static_cast<uint64_t>(inX) << (2 * kCellBits)) |
         (static_cast<uint64_t>(inY) << kCellBits) | static_cast<uint64_t>(inZ);
}

std::size_t UniformGrid::bucketOf(uint64_t inCell) const {
  return static_cast<std::size_t>((inCell * 0x9E3779B97F4A7C15ull) >> 20) & bucket_mask_;
}

void UniformGrid::fillBuckets(const BoxSet& inBoxes) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  big_.clear();
  is_big_.assign(n, 0);
  std::size_t total = 0;
  for (uint32_t i = 0; i < n; ++i) {
    int64_t lo[3], hi[3];
    cellRange(inBoxes, i, lo, hi);
    const int64_t cells = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    if (cells > kMaxCellsPerBox) {
      big_.push_back(i);
      is_big_[i] = 1;
    } else {
      total += static_cast<std::size_t>(cells);
    }
  }
  std::size_t buckets = 1024;
  while (buckets < total) buckets *= 2;
  bucket_mask_ = buckets - 1;
  bucket_start_.assign(buckets + 1, 0);
  std::vector<Entry> unsorted;
  unsorted.reserve(total);
  for (uint32_t i = 0; i < n; ++i) {
    if (is_big_[i]) continue;
    int64_t lo[3], hi[3];
    cellRange(inBoxes, i, lo, hi);
    for (int64_t x = lo[0]; x <= hi[0]; ++x) {
      for (int64_t y = lo[1]; y <= hi[1]; ++y) {
        for (int64_t z = lo[2]; z <= hi[2]; ++z) {
          const uint64_t cell = packCell(x, y, z);
          unsorted.push_back({cell, i});
          ++bucket_start_[bucketOf(cell) + 1];
        }
      }
    }
  }
  for (std::size_t b = 0; b < buckets; ++b) bucket_start_[b + 1] += bucket_start_[b];
  entries_.resize(total);
  std::vector<uint32_t> cursor(bucket_start_.begin(), bucket_start_.end() - 1);
  for (const Entry& entry : unsorted) entries_[cursor[bucketOf(entry.cell)]++] = entry;
}

void UniformGrid::pairBuckets(const BoxSet& inBoxes) {
  const int64_t buckets = static_cast<int64_t>(bucket_mask_ + 1);
#pragma omp parallel num_threads(threads_)
  {
    PairList& out = thread_pairs_[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 256)
    for (int64_t b = 0; b < buckets; ++b) {
      Entry* first = entries_.data() + bucket_start_[b];
      Entry* last = entries_.data() + bucket_start_[b + 1];
      if (last - first < 2) continue;
      // Group by cell, then sweep along x inside each cell.
      std::sort(first, last, [&](const Entry& x, const Entry& y) {
        return x.cell != y.cell ? x.cell < y.cell : inBoxes.lo(0, x.box) < inBoxes.lo(0, y.box);
      });
      for (Entry* i = first; i != last; ++i) {
        for (Entry* j = i + 1; j != last && j->cell == i->cell; ++j) {
          if (inBoxes.lo(0, j->box) > inBoxes.hi(0, i->box)) break;
          const uint32_t a = i->box, c = j->box;
          if (!overlap(inBoxes, a, c)) continue;
          int64_t owner[3];
          for (int axis = 0; axis < 3; ++axis) {
            const double corner = std::max(inBoxes.lo(axis, a), inBoxes.lo(axis, c));
            owner[axis] = std::clamp<int64_t>(
                static_cast<int64_t>(std::floor((corner - origin_[axis]) * inverse_cell_[axis])), 0,
                kMaxCellIndex);
          }
          if (packCell(owner[0], owner[1], owner[2]) != i->cell) continue;
          out.push_back(sap_broadphase::makeIdPair(inBoxes.ids[a], inBoxes.ids[c]));
        }
      }
    }
  }
}

void UniformGrid::pairBigBoxes(const BoxSet& inBoxes) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  for (std::size_t k = 0; k < big_.size(); ++k) {
    const uint32_t a = big_[k];
    for (uint32_t b = 0; b < n; ++b) {
      // A big-big pair is reported by the one earlier in big_.
      if (b == a || (is_big_[b] && b < a) || !overlap(inBoxes, a, b)) continue;
      pairs_.push_back(sap_broadphase::makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
    }
  }
}

const PairList& UniformGrid::pairs(const BoxSet& inBoxes) {
  pairs_.clear();
  if (inBoxes.size() < 2) return pairs_;
  chooseCells(inBoxes);
  fillBuckets(inBoxes);
  thread_pairs_.resize(threads_);
  for (PairList& list : thread_pairs_) list.clear();
  pairBuckets(inBoxes);
  for (const PairList& list : thread_pairs_) pairs_.insert(pairs_.end(), list.begin(), list.end());
  pairBigBoxes(inBoxes);
  return pairs_;
}

}  // namespace sap_bench
