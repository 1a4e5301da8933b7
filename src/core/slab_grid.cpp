#include "core/slab_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace sap_broadphase {
namespace {

// Below this many boxes one active list is as fast as any split.
constexpr std::size_t kMinBoxesForSlabs = 2048;
// Slab width in mean box extents: wider slabs mean more candidates per query, narrower ones
// mean boxes sit in more trees.
constexpr double kSlabWidthInExtents = 2.0;

}  // namespace

SlabGrid chooseSlabGrid(const BoxSet& inBoxes, int inAxis, int inRequested, int inThreads) {
  SlabGrid grid;
  const std::size_t n = inBoxes.size();
  if (inRequested == 1 || n < 2 || (inRequested <= 0 && n < kMinBoxesForSlabs)) return grid;
  const double* low = inBoxes.lo[inAxis].data();
  const double* high = inBoxes.hi[inAxis].data();
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -std::numeric_limits<double>::infinity();
  double extent_sum = 0.0;
  std::size_t finite_boxes = 0;
#pragma omp parallel for num_threads(inThreads) reduction(min : lowest) reduction(max : highest) \
    reduction(+ : extent_sum, finite_boxes)
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(low[i])) lowest = std::min(lowest, low[i]);
    if (std::isfinite(high[i])) highest = std::max(highest, high[i]);
    const double extent = high[i] - low[i];
    if (std::isfinite(extent)) {
      extent_sum += extent;
      ++finite_boxes;
    }
  }
  const double span = highest - lowest;
  if (!(span > 0.0) || !std::isfinite(span) || finite_boxes == 0) return grid;
  int count = inRequested;
  if (count <= 0) {
    const double width = kSlabWidthInExtents * extent_sum / finite_boxes;
    if (!(width > 0.0)) return grid;
    count = static_cast<int>(std::min<double>(kMaxSlabs, std::ceil(span / width)));
  }
  count = std::clamp(count, 1, kMaxSlabs);
  assert(count <= kMaxSlabs);  // RankedSlabs holds slab numbers in 8 bits
  grid.count = count;
  grid.origin = lowest;
  grid.width = span / count;
  if (!(grid.width > 0.0)) return SlabGrid();
  return grid;
}

}  // namespace sap_broadphase
