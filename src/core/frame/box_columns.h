// The engine's working layout of a frame: boxes as a structure of arrays, one array per bound,
// as the sweep, the skin and the small-frame kernel stream them. The frame history fills it
// from a BoxFrame, the one copy a frame gets (frame_history.h); the rest of the engine reads it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/runner/buffers.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// Box i is [lo[0][i], hi[0][i]] x [lo[1][i], hi[1][i]] x [lo[2][i], hi[2][i]]; `groups` and
/// `masks` are either empty (the defaults) or one per box. The bounds, 48 of a box's 52 bytes,
/// are buffers (buffers.h): sizing them does not zero memory that the copy then overwrites, and
/// a first frame's copy is the first to touch their pages, each thread its own slice.
struct BoxColumns {
  std::vector<uint32_t> ids;
  Buffer<double> lo[3];
  Buffer<double> hi[3];
  std::vector<uint32_t> groups;
  std::vector<uint32_t> masks;

  std::size_t size() const { return ids.size(); }
  /// Removes all boxes, keeping capacity.
  void clear();
  /// Reserves room for inCount boxes.
  void reserve(std::size_t inCount);
  /// Sizes every array for inCount boxes, groups and masks only when inFiltered, for a caller
  /// that then writes every bound: the bounds are left unset (not zeroed, not kept when an
  /// array grows).
  void resize(std::size_t inCount, bool inFiltered);
  /// Appends one box with the default group and mask.
  void add(uint32_t inId, const double inMin[3], const double inMax[3]);
  /// Appends one box with an explicit group and mask (fills defaults for earlier boxes).
  void add(uint32_t inId, const double inMin[3], const double inMax[3], uint32_t inGroup,
           uint32_t inMask);
  uint32_t group(std::size_t i) const { return groups.empty() ? kDefaultGroup : groups[i]; }
  uint32_t mask(std::size_t i) const { return masks.empty() ? kDefaultMask : masks[i]; }
  bool hasFilters() const { return !groups.empty() || !masks.empty(); }
};

/// Copies every box of inFrame into outBoxes (replaced, capacity reused), unchecked, on the
/// threads of the runner's scope (passThreads()): for the engine's parts tested or measured on
/// their own, and for query boxes. Ids beyond 32 bits wrap (check the frame first).
void copyFrame(const BoxFrame& inFrame, BoxColumns& outBoxes);
/// The same, returned.
BoxColumns columnsOf(const BoxFrame& inFrame);

/// The check validate() and the engine's load make, on boxes already in columns: the problem
/// of the lowest box index, named as validate() says, with inFrame's spans to name it.
std::optional<ValidationError> checkColumns(const BoxColumns& inBoxes, const BoxFrame& inFrame);

/// The oracle on columns: every pair tested (brute_force.h; the engine's smallest frames).
std::vector<IdPair> bruteForcePairs(const BoxColumns& inBoxes);

inline bool boxesOverlap(const BoxColumns& inBoxesA, std::size_t a, const BoxColumns& inBoxesB,
                         std::size_t b) {
  for (int axis = 0; axis < 3; ++axis) {
    if (inBoxesA.lo[axis][a] > inBoxesB.hi[axis][b] || inBoxesB.lo[axis][b] > inBoxesA.hi[axis][a])
      return false;
  }
  return true;
}

inline bool boxesOverlap(const BoxColumns& inBoxes, std::size_t a, std::size_t b) {
  return boxesOverlap(inBoxes, a, inBoxes, b);
}

inline bool filtersAllow(const BoxColumns& inBoxes, std::size_t a, std::size_t b) {
  return groupsMayPair(inBoxes.group(a), inBoxes.mask(a), inBoxes.group(b), inBoxes.mask(b));
}

}  // namespace sap_broadphase
