// The frame history: the engine's one copy of the last frame, and what changed since.
//
// Temporal coherence (the paper's partition bounds B, §4.2) is kept by the sweep itself; what
// the history adds is the knowledge of which boxes moved and how far, which lets a frame skip
// work: an identical frame returns the last pairs, and the measured motion chooses the skin of
// the kept candidates (skin_list.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
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

/// What one pass of the history over a frame of the last frame's size found.
struct FramePass {
  std::size_t moved_boxes = 0;
  bool other_ids = false;  ///< some id differs from the last frame's
  bool unusable = false;   ///< some box has a NaN bound or min > max (records only)
  bool filters_changed = false;
  double max_displacement = 0.0;
};

class FrameHistory {
 public:
  /// Compares inBoxes with the last frame. Where ids, their count and the presence of groups
  /// and masks agree, the same pass over the boxes (each thread its slice) also copies the
  /// changed boxes: the copy then holds inBoxes, but counts as the last frame only after
  /// remember(), so a frame that throws in between leaves a first frame behind.
  const FrameDelta& compare(const BoxSet& inBoxes, int inThreads);
  /// compare() for a frame given as records, checked on the way: the history's copy is made
  /// from inBoxes directly (read block by block into a cache-resident scratch while compared)
  /// and is the frame the engine then runs on, loaded(); the caller's memory is read once.
  /// On a NaN bound, min > max or a repeated id, outProblem names the lowest bad box as
  /// validate() does and the history is forgotten (the next frame is a first frame). Frames
  /// without groups and masks only: the engine drops boxes that pair with nothing first.
  const FrameDelta& load(const InterleavedBoxes& inBoxes, int inThreads,
                         std::optional<ValidationError>& outProblem);
  /// The frame load() made, until the next compare(), load() or forget().
  const BoxSet& loaded() const { return last_; }
  /// The last frame remember() made, still there after forget() (which only stops the next
  /// frame from being compared with it), until the next compare() or load() starts replacing
  /// it. Box queries read the world here (frame_query.h).
  const BoxSet& remembered() const { return last_; }
  /// Makes inBoxes, the frame given to compare() or load(), the last frame (copied in parallel
  /// unless compare() copied it already).
  void remember(const BoxSet& inBoxes);
  /// Forgets the last frame: the next one is a first frame.
  void forget();
  /// Gives back the capacity the copy does not use (after a burst of larger frames).
  void shrinkToFit();

 private:
  // The delta of a frame of the last frame's size, from the one pass that compared and copied
  // it (frame_history.cpp).
  void describeSameSize(const FramePass& inPass);
  void copyWholeFrame(const BoxSet& inBoxes, int inThreads);

  BoxSet last_;
  bool valid_ = false;   // last_ is the last frame
  bool copied_ = false;  // compare() made last_ equal to its frame; remember() need not copy
  int threads_ = 1;      // compare()'s, for remember()
  std::vector<uint8_t> unchanged_;
  FrameDelta delta_;
};

}  // namespace sap_broadphase
