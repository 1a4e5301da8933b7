// Hostile scenes for the stress suite: extreme magnitudes, subnormals, signed zeros,
// infinities, ulp lattices at large coordinates, special-value mixtures. All deterministic.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sap_broadphase/core/box_set.h"

namespace sap_broadphase::stress {

/// Boxes in clusters spread over the decades 1e-300..1e300 (both signs): each cluster's boxes
/// have extents of its own decade, so pairs form inside every decade; a few boxes span
/// [-1e300, 1e300] on one axis and meet boxes of every scale.
BoxSet magnitudeScene(std::size_t inCount, uint64_t inSeed);

/// Coordinates that are multiples of the smallest subnormal (and a few around DBL_MIN), both
/// signs: many boxes touch, many have zero extent, and all keys round to float zero or its
/// neighbours.
BoxSet subnormalScene(std::size_t inCount, uint64_t inSeed);

/// Integer lattice boxes in [-3, 3] whose zero coordinates are randomly -0.0 or +0.0, so boxes
/// touch at -0.0 vs 0.0 on every axis.
BoxSet signedZeroScene(std::size_t inCount, uint64_t inSeed);

/// Random finite boxes plus ground planes, half-spaces, slabs infinite on two axes, boxes
/// infinite on all three, and zero-extent boxes at +-infinity.
BoxSet infiniteSlabScene(std::size_t inCount, uint64_t inSeed);

/// Boxes whose corners are inBase moved by k representable doubles (k in [-inCells, inCells]),
/// extents 0 to inMaxEdge ulps: touching, 1-ulp gaps and 1-ulp overlaps everywhere. Each
/// axis uses the same base.
BoxSet ulpLatticeScene(double inBase, std::size_t inCount, int inCells, int inMaxEdge,
                       uint64_t inSeed);

/// Intervals drawn from a pool of special values (+-inf, +-1e300, +-2^53, +-2^24, +-1, DBL_MIN,
/// subnormals, +-0, their ulp neighbours), each interval a short run of the sorted pool.
BoxSet specialValueScene(std::size_t inCount, uint64_t inSeed);

/// inBoxes with inOffset added to every coordinate of axis a (rounded as doubles round).
BoxSet translated(const BoxSet& inBoxes, const double inOffset[3]);

/// Gives each box a random group and mask from a few bits, some of them zero.
void addRandomFilters(BoxSet& ioBoxes, uint64_t inSeed);

}  // namespace sap_broadphase::stress
