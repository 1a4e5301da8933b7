// Static boxes: a frame split into boxes kept in a StaticIndex and the moving rest.
//
// A box goes into the index when its bounds, group and mask are bit-for-bit those of the
// previous frame (same ids in the same order) and its group/mask class cannot pair with itself
// nor with the other indexed classes: then no pair lies inside the index, and a frame's pairs
// are the sweep of the moving boxes plus the moving x indexed pairs the index answers. The
// index is kept while its boxes stay put (a box that moves leaves it) and rebuilt when a
// quarter of it has left or enough new boxes came to rest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/static_index.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

class StaticSplit {
 public:
  /// Fewest indexed boxes worth an index.
  static constexpr std::size_t kMinIndexedBoxes = 4096;

  /// Updates the index from inUnchanged (per box of inBoxes, 1 when bit for bit as in the
  /// last frame, same ids in the same order: the frame history's delta). True when this
  /// frame uses it: then sweep moving() and add crossPairs().
  bool prepare(const BoxSet& inBoxes, const std::vector<uint8_t>& inUnchanged, int inThreads);
  /// The boxes not in the index, as a box set of their own.
  const BoxSet& moving() const { return moving_; }
  /// Appends every pair between a moving box and an indexed box.
  void crossPairs(const BoxSet& inBoxes, int inThreads, PairList& ioPairs) const;
  /// Boxes answering from the index this frame.
  std::size_t indexedBoxes() const { return active_ ? index_.size() : 0; }
  /// Drops the index.
  void clear();

 private:
  struct FilterClass {
    uint32_t group;
    uint32_t mask;
    std::size_t boxes;
  };
  bool chooseClasses(const BoxSet& inBoxes, const std::vector<uint8_t>& inUnchanged);
  bool inChosenClass(const BoxSet& inBoxes, std::size_t inBox) const;
  bool rebuild(const BoxSet& inBoxes, const std::vector<uint8_t>& inUnchanged, int inThreads);
  void collectMoving(const BoxSet& inBoxes);

  StaticIndex index_;
  bool active_ = false;
  std::vector<uint8_t> indexed_;  // per box: answering from the index
  std::size_t built_size_ = 0;    // boxes indexed at the last build
  std::size_t left_ = 0;          // of those, how many moved since
  std::vector<FilterClass> chosen_classes_;
  std::vector<uint32_t> members_;         // scratch: boxes to index
  std::vector<uint32_t> moving_indexes_;  // boxes not indexed, by position in the frame
  BoxSet moving_;
};

}  // namespace sap_broadphase
