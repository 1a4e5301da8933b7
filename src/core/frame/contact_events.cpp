#include "core/frame/contact_events.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/assert.h"

namespace sap_broadphase {

namespace {

// Pairs compared as one 64-bit key each: (a, b) order is the key's order.
inline uint64_t keyOf(const IdPair& inPair) {
  return (static_cast<uint64_t>(inPair.a) << 32) | inPair.b;
}

// In a steady frame most pairs persist: runs of equal pairs are skipped a block at a time
// (memcmp runs vectorised), the pair-by-pair merge handles the block where they differ.
constexpr std::size_t kEqualBlock = 32;

}  // namespace

void diffPairLists(const PairList& inLast, const PairList& inNow, ContactEvents& outEvents) {
  outEvents.began.clear();
  outEvents.ended.clear();
  const IdPair* last = inLast.data();
  const IdPair* now = inNow.data();
  const IdPair* const last_end = last + inLast.size();
  const IdPair* const now_end = now + inNow.size();
  while (last != last_end && now != now_end) {
    if (last_end - last >= static_cast<std::ptrdiff_t>(kEqualBlock) &&
        now_end - now >= static_cast<std::ptrdiff_t>(kEqualBlock) &&
        std::memcmp(last, now, kEqualBlock * sizeof(IdPair)) == 0) {
      last += kEqualBlock;
      now += kEqualBlock;
      continue;
    }
    const IdPair* const block_end = last + std::min<std::ptrdiff_t>(kEqualBlock, last_end - last);
    while (last != block_end && now != now_end) {
      const uint64_t last_key = keyOf(*last);
      const uint64_t now_key = keyOf(*now);
      if (last_key < now_key) {
        outEvents.ended.push_back(*last++);
      } else if (now_key < last_key) {
        outEvents.began.push_back(*now++);
      } else {
        ++last;
        ++now;
      }
    }
  }
  outEvents.ended.insert(outEvents.ended.end(), last, last_end);
  outEvents.began.insert(outEvents.began.end(), now, now_end);
}

void ContactEventTracker::startFrame() {
  all_began_.store(nullptr);
  events_.began.clear();
  events_.ended.clear();
}

void ContactEventTracker::keepLastList(PairList& ioPairs) {
  // A frame that took the list and never compared threw half-way: the list it left is no
  // frame's, so the next one reports as a first frame.
  if (frame_open_) has_last_ = false;
  last_.swap(ioPairs);
  frame_open_ = true;
}

void ContactEventTracker::compare(const PairList& inPairs) {
  SAP_ASSERT(frame_open_, "events compared without the last list kept");
  if (has_last_) {
    diffPairLists(last_, inPairs, events_);
  } else {
    events_.began.clear();
    events_.ended.clear();
    all_began_.store(&inPairs);  // copied if events() asks (a first frame's pairs all began)
  }
  has_last_ = true;
  frame_open_ = false;
}

const ContactEvents& ContactEventTracker::events() const {
  if (all_began_.load(std::memory_order_acquire) == nullptr) return events_;
  const std::lock_guard<std::mutex> lock(fill_);
  if (const PairList* all = all_began_.load()) {
    events_.began.assign(all->begin(), all->end());
    all_began_.store(nullptr, std::memory_order_release);
  }
  return events_;
}

void ContactEventTracker::restoreLastList(PairList& ioPairs) {
  if (!frame_open_) return;
  last_.swap(ioPairs);
  PairList().swap(last_);
  frame_open_ = false;
}

void ContactEventTracker::sameListAsLast() {
  SAP_ASSERT(has_last_, "a reused frame without a last list");
}

void ContactEventTracker::forget() {
  has_last_ = false;
  frame_open_ = false;
  startFrame();
}

void ContactEventTracker::releaseMemory() {
  PairList().swap(last_);
}

}  // namespace sap_broadphase
