// Contact events: the pairs that began and ended between two consecutive canonical pair lists,
// found by one linear merge of the two, and the state that keeps the last list without copying it.
#pragma once

#include <atomic>
#include <mutex>

#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// Writes into outEvents the pairs of inNow absent from inLast (began) and those of inLast absent
/// from inNow (ended), both canonical as the inputs must be: one pass over the two lists,
/// equal stretches compared a block at a time. Reuses outEvents' buffers.
void diffPairLists(const PairList& inLast, const PairList& inNow, ContactEvents& outEvents);

/// The events of a Broadphase across frames. The last frame's list is the engine's own pair
/// list: before a frame's strategy writes that list, keepLastList() takes it by swapping buffers
/// (the strategy then writes into the buffer of the frame before, already sized), so a steady
/// frame neither copies nor allocates.
class ContactEventTracker {
 public:
  /// A frame begins: its events are none until it completes (a frame that throws reports none).
  void startFrame();
  /// Takes the last frame's list out of ioPairs (a swap); ioPairs keeps a buffer to write into.
  void keepLastList(PairList& ioPairs);
  /// The frame's list is complete: its events are the difference from the kept last list (from
  /// nothing on a first frame), and it becomes the last list. inPairs must stay unchanged until
  /// the next startFrame() or forget(): a first frame's events (every pair began) are copied
  /// from it only when events() asks for them, so that a first frame neither copies its pairs
  /// nor keeps a second list of their size for good.
  void compare(const PairList& inPairs);
  /// The frame was refused before it compared (TooManyPairs): the last list goes back into
  /// ioPairs, where the next keepLastList() takes it again, and the refused frame's list is
  /// freed. The next frame's events are then those since the last frame returned.
  void restoreLastList(PairList& ioPairs);
  /// The frame's list is the last one, untouched (a reused frame): no events.
  void sameListAsLast();
  /// The next frame is a first frame: every pair begins. The events of the last frame go too.
  void forget();
  /// Gives back the spare buffer (the list before the last one) after a burst of large frames.
  void releaseMemory();
  /// The last frame's events. Safe to call from several threads at once (between frames).
  const ContactEvents& events() const;

 private:
  PairList last_;  // between keepLastList() and compare(): the last frame's list
  // The last frame's events; on a first frame `began` is filled from all_began_ on request.
  mutable ContactEvents events_;
  mutable std::atomic<const PairList*> all_began_{nullptr};
  mutable std::mutex fill_;  // one events() fills `began`, the others wait for it
  bool has_last_ = false;    // a frame completed since construction or forget()
  bool frame_open_ = false;  // keepLastList() without its compare(): that frame threw
};

}  // namespace sap_broadphase
