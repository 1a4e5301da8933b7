// Slabs along the unused third axis, which split the pairing phase's active list.
#pragma once

#include <cstdint>

#include "core/assert.h"
#include "core/sweep/axis_spread.h"
#include "sap_broadphase/core/config.h"

namespace sap_broadphase {

/// Most slabs: the configuration's bound on third_axis_slabs (config.h).
constexpr int kMaxSlabs = kMaxThirdAxisSlabs;

/// Slabs of the unused (third) axis. Our extension of Algorithm 4: the secondary-axis active
/// list is split into one SuccTree per slab, so a range query only meets candidates that are
/// also near on the third axis. A box joins the trees of every slab its interval touches; a
/// pair is reported only in the slab holding the larger of the two low ends, hence once.
/// With one slab this is exactly the paper's active list.
struct SlabGrid {
  int count = 1;        ///< number of slabs (1 = the paper's single active list)
  double origin = 0.0;  ///< third-axis coordinate where slab 0 starts
  double width = 1.0;   ///< slab width
  /// Slab of coordinate inValue: monotone in inValue, clamped to [0, count).
  int slabOf(double inValue) const {
    const double position = (inValue - origin) / width;
    if (!(position > 0.0)) return 0;  // also -inf
    if (position >= count - 1) return count - 1;
    SAP_ASSERT(position >= 0.0 && position < count - 1, "a slab position outside the grid");
    return static_cast<int>(position);
  }
};

/// Chooses slabs for the third axis inAxis: about two mean box extents wide over the span of
/// the finite coordinates, at most kMaxSlabs, one slab when boxes are few or the span is
/// degenerate (empty, infinite). inRequested > 0 forces that many slabs (1 = the paper).
/// ioSpread is the spread of the boxes (measured on the scope's threads if not yet).
SlabGrid chooseSlabGrid(FrameSpread& ioSpread, int inAxis, int inRequested);

}  // namespace sap_broadphase
