// When buffers sized for a burst of large frames are given back: the engine's one rule. A process
// that runs for days must not keep the memory of one frame of 2^21 boxes; an occasional large frame
// among small ones must not make every buffer be allocated again.
#pragma once

#include <cstddef>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace sap_broadphase {

/// Consecutive small frames after which a buffer is given back.
constexpr std::size_t kGiveBackAfterSmallFrames = 64;
/// A frame counts as small when its buffer holds more than this many times what it uses.
constexpr std::size_t kGiveBackRatio = 4;
/// Buffers of at most this many boxes are kept whatever their use (about 3.4 MB of boxes).
constexpr std::size_t kGiveBackMinBoxes = 65536;

/// Watches one buffer (or a group of buffers sized together) frame after frame.
class GiveBackWatch {
 public:
  /// Records a frame of inUsed boxes held in a buffer of inCapacity boxes. True, once, when
  /// the last kGiveBackAfterSmallFrames frames were all small and the buffer is larger than
  /// kGiveBackMinBoxes: the caller gives the buffer back now. A frame that is not small
  /// starts the wait again.
  bool shouldGiveBack(std::size_t inUsed, std::size_t inCapacity) {
    const bool small = inCapacity > kGiveBackMinBoxes && inCapacity > kGiveBackRatio * inUsed;
    small_frames_ = small ? small_frames_ + 1 : 0;
    if (small_frames_ < kGiveBackAfterSmallFrames) return false;
    small_frames_ = 0;
    return true;
  }

 private:
  std::size_t small_frames_ = 0;
};

/// Gives the heap's free pages back to the system (glibc). The engine's pair lists are
/// std::vectors; once glibc has freed a large block it serves blocks of that size from the heap
/// instead of mappings of their own, and keeps them resident after they are freed, so a kept
/// engine's resident set would creep up by the lists of every frame that made large ones. Called
/// after the frames that free such lists (a grown sweep), rarely: it walks the heap.
inline void returnFreedHeapPages() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace sap_broadphase
