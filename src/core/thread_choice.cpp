#include "core/thread_choice.h"
#include "core/tuning.h"

#include <algorithm>

namespace sap_broadphase {
namespace {

bool sameSize(std::size_t inA, std::size_t inB) {
  const double a = static_cast<double>(std::max<std::size_t>(inA, 1));
  const double b = static_cast<double>(std::max<std::size_t>(inB, 1));
  return std::max(a, b) <= tuning::kSameSizeFactor * std::min(a, b);
}

}  // namespace

int ThreadChoice::preferred(ThreadedWork inWork, int inPlanned) const {
  const Learnt& learnt = learnt_[static_cast<int>(inWork)];
  if (learnt.planned != inPlanned) return inPlanned;
  const double one = learnt.ns_per_box[0], planned = learnt.ns_per_box[1];
  return one > 0.0 && (planned == 0.0 || one < planned) ? 1 : inPlanned;
}

int ThreadChoice::choose(ThreadedWork inWork, int inPlanned, std::size_t inBoxes) {
  Learnt& learnt = learnt_[static_cast<int>(inWork)];
  if (learnt.planned != inPlanned || !sameSize(learnt.boxes, inBoxes)) {
    learnt = Learnt();
    learnt.planned = inPlanned;
    learnt.boxes = inBoxes;
  }
  learnt.current = inBoxes;
  // Unmeasured counts are assumed to lose: the planned count runs until a probe measures one.
  const bool one_is_cheaper = preferred(inWork, inPlanned) == 1;
  learnt.probing = --learnt.frames_to_probe <= 0;
  if (learnt.probing) learnt.frames_to_probe = learnt.probe_interval;
  return one_is_cheaper != learnt.probing ? 1 : inPlanned;
}

void ThreadChoice::record(ThreadedWork inWork, int inThreads, double inMilliseconds) {
  Learnt& learnt = learnt_[static_cast<int>(inWork)];
  if (learnt.planned == 0) return;  // nothing chosen
  const int measured = inThreads == 1 ? 0 : 1;
  const double ns_per_box =
      inMilliseconds * 1e6 / static_cast<double>(std::max<std::size_t>(learnt.current, 1));
  double& cost = learnt.ns_per_box[measured];
  if (learnt.probing) {
    cost = ns_per_box;  // a fresh look at the other count
    const double in_use = learnt.ns_per_box[1 - measured];
    const bool clear_loss = in_use > 0.0 && ns_per_box >= tuning::kClearLoss * in_use;
    learnt.probe_interval = clear_loss
                                ? std::min(2 * learnt.probe_interval, tuning::kLongestProbeInterval)
                                : tuning::kShortestProbeInterval;
    learnt.frames_to_probe = learnt.probe_interval;
    learnt.probing = false;
  } else {
    cost = cost == 0.0
               ? ns_per_box
               : (1.0 - tuning::kRunningWeight) * cost + tuning::kRunningWeight * ns_per_box;
  }
}

void ThreadChoice::forget() {
  for (Learnt& learnt : learnt_) learnt = Learnt();
}

}  // namespace sap_broadphase
