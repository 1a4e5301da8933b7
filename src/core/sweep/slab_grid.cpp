#include "core/sweep/slab_grid.h"

#include "core/assert.h"
#include "core/sweep/axis_spread.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/tuning.h"

namespace sap_broadphase {

SlabGrid chooseSlabGrid(FrameSpread& ioSpread, int inAxis, int inRequested) {
  SlabGrid grid;
  const std::size_t n = ioSpread.boxes().size();
  if (inRequested == 1 || n < 2 || (inRequested <= 0 && n < tuning::kMinBoxesForSlabs)) return grid;
  const AxisSpread& spread = ioSpread.axis(inAxis);
  const double span = spread.span();
  if (!(span > 0.0) || !std::isfinite(span) || spread.finite_boxes == 0) return grid;
  int count = inRequested;
  if (count <= 0) {
    const double width = tuning::kSlabWidthInExtents * spread.meanExtent();
    if (!(width > 0.0)) return grid;
    count = static_cast<int>(std::min<double>(kMaxSlabs, std::ceil(span / width)));
  }
  count = std::clamp(count, 1, kMaxSlabs);
  SAP_ASSERT(count >= 1 && count <= kMaxSlabs, "more slabs than RankedSlabs' 8 bits number");
  grid.count = count;
  grid.origin = spread.lowest;
  grid.width = span / count;
  if (!(grid.width > 0.0)) return SlabGrid();
  // The last slab reaches the highest finite bound: every box falls in the grid.
  SAP_ASSERT(grid.slabOf(spread.lowest) == 0 && grid.slabOf(spread.lowest + span) == count - 1,
             "the slabs do not span the boxes' third-axis bounds");
  return grid;
}

}  // namespace sap_broadphase
