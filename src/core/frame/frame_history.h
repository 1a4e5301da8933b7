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

#include "core/frame/box_columns.h"

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
  bool unusable = false;   ///< some box has a NaN bound, min > max or an id beyond 32 bits
  bool filters_changed = false;
  double max_displacement = 0.0;
};

class FrameHistory {
 public:
  /// Loads inFrame: the history's copy is made from the caller's records directly (read block
  /// by block into a cache-resident scratch while compared with the last frame, and checked on
  /// the way) and is the frame the engine then runs on, loaded(); the caller's memory is read
  /// once. This is the one place a frame is copied and checked. On a NaN bound, min > max, a
  /// repeated id or an id beyond 32 bits, outProblem names the lowest bad box as validate()
  /// does and the history is forgotten (the next frame is a first frame). The copy counts as
  /// the last frame only after remember(), so a frame that throws in between leaves a first
  /// frame behind.
  const FrameDelta& load(const BoxFrame& inFrame, std::optional<ValidationError>& outProblem);
  /// The frame load() made, until the next load() or forget().
  const BoxColumns& loaded() const { return last_; }
  /// The last frame remember() made, still there after forget() (which only stops the next
  /// frame from being compared with it), until the next load() starts replacing it. Box
  /// queries read the world here (frame_query.h).
  const BoxColumns& remembered() const { return last_; }
  /// Makes the loaded frame the last frame, the one the next load() is compared with.
  void remember();
  /// Forgets the last frame: the next one is a first frame.
  void forget();
  /// Gives back the capacity the copy does not use (after a burst of larger frames).
  void shrinkToFit();
  /// Bytes held (capacities): the copy and the per-box change flags.
  std::size_t bytesHeld() const;

 private:
  // The delta of a frame of the last frame's size, from the one pass that compared and copied
  // it (frame_history.cpp).
  void describeSameSize(const FramePass& inPass);

  BoxColumns last_;
  bool valid_ = false;                         // last_ is the last frame
  std::vector<std::size_t> span_first_boxes_;  // the frame being loaded: where each span starts
  std::vector<uint8_t> unchanged_;
  FrameDelta delta_;
};

}  // namespace sap_broadphase
