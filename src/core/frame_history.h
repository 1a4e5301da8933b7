// The frame history: the engine's one copy of the last frame, and what changed since.
//
// Temporal coherence (the paper's partition bounds B, §4.2) is kept by the sweep itself; what
// the history adds is the knowledge of which boxes moved and how far, which lets a frame skip
// work: an identical frame returns the last pairs, resting boxes can be indexed instead of
// swept, and the measured motion chooses the skin of the kept candidates (skin_list.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sap_broadphase/core/box_set.h"

namespace sap_broadphase {

/// How a frame relates to the last one.
enum class FrameRelation : uint8_t {
  kFirst,      ///< no last frame (the first, or after reset())
  kOtherIds,   ///< ids, their order, or the presence of groups/masks differ
  kSameIds,    ///< same ids in the same order; some bounds, groups or masks changed
  kIdentical,  ///< bit for bit the last frame (-0.0 after 0.0 counts as a change)
};

/// What changed since the last frame.
struct FrameDelta {
  FrameRelation relation = FrameRelation::kFirst;
  std::size_t moved_boxes = 0;    ///< same ids: boxes whose bounds, group or mask changed
  double max_displacement = 0.0;  ///< same ids: largest change of one bound of one box
  bool filters_changed = false;   ///< same ids: some box's group or mask changed
  /// Same ids: per box, 1 when bit for bit unchanged; empty otherwise.
  const std::vector<uint8_t>* unchanged = nullptr;

  bool sameIds() const {
    return relation == FrameRelation::kSameIds || relation == FrameRelation::kIdentical;
  }
};

class FrameHistory {
 public:
  /// Compares inBoxes with the last frame (nothing is remembered yet).
  const FrameDelta& compare(const BoxSet& inBoxes, int inThreads);
  /// Makes inBoxes the last frame; after compare(inBoxes), only the changed boxes are copied.
  void remember(const BoxSet& inBoxes);
  /// Forgets the last frame: the next one is a first frame.
  void forget();
  /// Gives back the capacity the copy does not use (after a burst of larger frames).
  void shrinkToFit();

 private:
  void compareBoxByBox(const BoxSet& inBoxes, int inThreads);
  void rememberChanges(const BoxSet& inBoxes);

  BoxSet last_;
  bool valid_ = false;
  std::vector<uint8_t> unchanged_;
  FrameDelta delta_;
};

}  // namespace sap_broadphase
