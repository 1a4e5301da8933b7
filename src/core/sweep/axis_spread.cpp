#include "core/sweep/axis_spread.h"

#include <algorithm>
#include <cmath>

#include "core/runner/work_units.h"

namespace sap_broadphase {

AxisSpread measureAxisSpread(const BoxColumns& inBoxes, int inAxis,
                             const std::vector<uint32_t>* inIndexes) {
  const double* low = inBoxes.lo[inAxis].data();
  const double* high = inBoxes.hi[inAxis].data();
  const uint32_t* indexes = inIndexes ? inIndexes->data() : nullptr;
  const std::size_t count = inIndexes ? inIndexes->size() : inBoxes.size();
  // Per-unit partial sums folded in unit order: the same spread for any thread count.
  AxisSpread spread = reduceOverItems(
      WorkUnits{count}, AxisSpread{},
      [&](std::size_t inBegin, std::size_t inEnd) {
        AxisSpread unit;
        for (std::size_t k = inBegin; k < inEnd; ++k) {
          const std::size_t i = indexes ? indexes[k] : k;
          if (std::isfinite(low[i])) unit.lowest = std::min(unit.lowest, low[i]);
          if (std::isfinite(high[i])) unit.highest = std::max(unit.highest, high[i]);
          const double extent = high[i] - low[i];  // inf for infinite or overflowing intervals
          if (std::isfinite(extent)) {
            unit.extent_sum += extent;
            ++unit.finite_boxes;
          }
        }
        return unit;
      },
      [](AxisSpread& ioTotal, const AxisSpread& inUnit) {
        ioTotal.lowest = std::min(ioTotal.lowest, inUnit.lowest);
        ioTotal.highest = std::max(ioTotal.highest, inUnit.highest);
        ioTotal.extent_sum += inUnit.extent_sum;
        ioTotal.finite_boxes += inUnit.finite_boxes;
      });
  return spread;
}

}  // namespace sap_broadphase
