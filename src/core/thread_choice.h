// Whether a frame's work runs on every core or on one, when the user left that to the engine
// (BroadphaseConfig::threads = 0 with Method::kAuto): measured, not assumed.
//
// The paper's parallel phases pay from a few thousand boxes on an idle machine, and the plan's
// fixed rule (parallel_min_boxes, the small-frame crossover) is measured there. On a machine
// whose other cores are busy, or with OMP_WAIT_POLICY=passive, where a sleeping worker is often
// woken onto a busy core and runs after the master rather than beside it, a second thread can
// cost a frame more than it brings, and no rule fixed in advance knows the machine's load. So
// the engine measures both: a frame's work runs on the planned threads, and now and then (a
// probe) on the other count; the count whose recent frames cost less per box is used until a
// probe says otherwise. A probe that loses clearly doubles the time to the next one (up to
// tuning::kLongestProbeInterval frames), so on a machine where the choice is clear probes cost a
// fraction of a per cent; a close one keeps probing often. Pairs do not depend on the thread
// count (the oracle tests at every count), only the time does.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/tuning.h"

namespace sap_broadphase {

/// The work a thread count is learnt for: each has its own costs per box.
enum class ThreadedWork : uint8_t { kSweep, kGrownSweep, kKeptCandidates };

class ThreadChoice {
 public:
  /// The threads for a frame of inWork on inBoxes boxes that the plan gave inPlanned (> 1)
  /// threads: inPlanned, or 1.
  int choose(ThreadedWork inWork, int inPlanned, std::size_t inBoxes);
  /// The count inWork runs on between probes, as learnt so far (inPlanned until a probe of one
  /// thread has won): the frame's passes outside its work (the history's) follow it.
  int preferred(ThreadedWork inWork, int inPlanned) const;
  /// What that frame's work cost: inMilliseconds on inThreads threads (what choose() said).
  void record(ThreadedWork inWork, int inThreads, double inMilliseconds);
  /// Forgets what was measured.
  void forget();

 private:
  struct Learnt {
    double ns_per_box[2] = {0.0, 0.0};  // [0]: one thread, [1]: the planned count; 0: unknown
    int planned = 0;                    // the planned count the costs are for
    std::size_t boxes = 0;              // frame size they are for (costs change with caches)
    int frames_to_probe = tuning::kShortestProbeInterval;
    int probe_interval = tuning::kShortestProbeInterval;
    bool probing = false;     // the frame being measured is a probe
    std::size_t current = 0;  // boxes of the frame being measured
  };
  Learnt learnt_[3];
};

}  // namespace sap_broadphase
