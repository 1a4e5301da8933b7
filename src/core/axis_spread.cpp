#include "core/axis_spread.h"

#include <algorithm>
#include <cmath>

namespace sap_broadphase {

AxisSpread measureAxisSpread(const BoxSet& inBoxes, int inAxis, int inThreads,
                             const std::vector<uint32_t>* inIndexes) {
  const double* low = inBoxes.lo[inAxis].data();
  const double* high = inBoxes.hi[inAxis].data();
  const uint32_t* indexes = inIndexes ? inIndexes->data() : nullptr;
  const std::size_t count = inIndexes ? inIndexes->size() : inBoxes.size();
  AxisSpread spread;
  double lowest = spread.lowest, highest = spread.highest, extent_sum = 0.0;
  std::size_t finite_boxes = 0;
#pragma omp parallel for num_threads(inThreads) schedule(static) reduction(min : lowest) \
    reduction(max : highest) reduction(+ : extent_sum, finite_boxes)
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = indexes ? indexes[k] : k;
    if (std::isfinite(low[i])) lowest = std::min(lowest, low[i]);
    if (std::isfinite(high[i])) highest = std::max(highest, high[i]);
    const double extent = high[i] - low[i];  // inf for infinite or overflowing intervals
    if (std::isfinite(extent)) {
      extent_sum += extent;
      ++finite_boxes;
    }
  }
  spread.lowest = lowest;
  spread.highest = highest;
  spread.extent_sum = extent_sum;
  spread.finite_boxes = finite_boxes;
  return spread;
}

}  // namespace sap_broadphase
