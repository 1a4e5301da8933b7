// The C interface that ab_compare.cpp loads from each library build (built into it by
// ab_build.sh): one engine per handle, driven through the public API only, so that the same
// file builds against any commit of the engine.
#include "sap_broadphase/core/broadphase.h"

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::FrameReport;
using sap_broadphase::Method;

namespace {

// The flow's own time (FrameReport::ms_plan) and the skin's (ms_skin), in builds that report
// them: the same file builds against commits from before those fields.
template <typename Report>
auto flowMs(const Report& inReport, int) -> decltype(inReport.ms_plan + inReport.ms_skin) {
  return inReport.ms_plan + inReport.ms_skin;
}
template <typename Report>
double flowMs(const Report&, long) {
  return 0.0;
}

}  // namespace

extern "C" {

/// inMethod: 0 auto, 1 parallel, 2 sequential. inSkinOff: 1 = skin 0 (every frame swept),
/// 0 = the default (automatic skin).
__attribute__((visibility("default"))) void* abMakeEngine(int inThreads, int inMethod,
                                                          int inSkinOff) {
  BroadphaseConfig config;
  config.threads = inThreads;
  config.method = inMethod == 1   ? Method::kParallel
                  : inMethod == 2 ? Method::kSequential
                                  : Method::kAuto;
  if (inSkinOff) config.skin = 0.0;
  return new Broadphase(config);
}

__attribute__((visibility("default"))) void abFreeEngine(void* inEngine) {
  delete static_cast<Broadphase*>(inEngine);
}

/// One frame; outTimes receives keys, sort, candidates, pairing, output, the other reported
/// phases (history, static, and where reported skin and the flow's own), total (ms). Returns
/// the pair count.
__attribute__((visibility("default"))) std::size_t abUpdate(void* ioEngine, const void* inBoxes,
                                                            double* outTimes) {
  Broadphase& engine = *static_cast<Broadphase*>(ioEngine);
  const std::size_t pairs = engine.update(*static_cast<const BoxSet*>(inBoxes)).size();
  const FrameReport& report = engine.stats();
  const double phases[] = {
      report.ms_keys,    report.ms_sort,   report.ms_candidates,
      report.ms_pairing, report.ms_output, report.ms_history + report.ms_static + flowMs(report, 0),
      report.ms_total};
  for (int k = 0; k < 7; ++k) outTimes[k] = phases[k];
  return pairs;
}

}  // extern "C"
