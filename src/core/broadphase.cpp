// The per-frame flow (docs/ARCHITECTURE.md walks through it step by step):
//
//   boxes -> drop boxes that pair with nothing -> frame history: delta since the last frame
//         -> resting boxes into their index (optional) -> plan -> one strategy:
//            reuse | kept candidates | sweep (grown by a skin or plain) | brute force
//         -> declared scenery queried -> pairs in canonical order -> remember the frame,
//            learn the costs, give back memory a burst of large frames left behind
#include "sap_broadphase/core/broadphase.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/axis_spread.h"
#include "core/frame_history.h"
#include "core/frame_plan.h"
#include "core/phase_timer.h"
#include "core/skin_list.h"
#include "core/slab_grid.h"
#include "core/small_frame.h"
#include "core/static_index.h"
#include "core/static_split.h"
#include "core/sweep_and_prune.h"
#include "core/tuning.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/memory_policy.h"

namespace sap_broadphase {

namespace {

// Mean finite box extent and the span of the finite bounds on each axis (the skin cost
// model's picture of the frame).
void measureExtents(const BoxSet& inBoxes, int inThreads, SkinCosts& ioCosts) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisSpread spread = measureAxisSpread(inBoxes, axis, inThreads);
    ioCosts.mean_extent[axis] = spread.meanExtent();
    ioCosts.span[axis] = spread.span();
  }
}

double smoothed(double inAverage, double inSample) {
  return inAverage > 0.0 ? inAverage + tuning::kCostSmoothing * (inSample - inAverage) : inSample;
}

}  // namespace

struct Broadphase::Impl {
  explicit Impl(const BroadphaseConfig& inConfig) : config(inConfig), sweep(inConfig) {}

  BroadphaseConfig config;
  FrameReport report;
  FrameHistory history;
  SweepAndPrune sweep;
  SkinList kept;                    // kept candidates of the last grown sweep (skin_list.h)
  SmallFrameWorkspace small_frame;  // buffers of the small-frame path
  double kept_skin = 0.0;
  StaticSplit resting;              // boxes guessed static (index_static_boxes)
  StaticIndex scenery;              // boxes declared static (setStaticBoxes)
  std::vector<uint32_t> every_box;  // 0..n-1: the scenery's queries
  BoxSet collidable;                // the frame without boxes that can pair with nothing
  PairList pairs;
  PairSortScratch pair_scratch;
  bool pairs_valid = false;  // pairs hold the last frame's whole answer
  SkinCosts costs;
  // This frame's share of the kept-candidate work, for learnCosts: growing the boxes, keeping
  // the grown sweep's candidates, every pass tried, and the last pass (the one that answered).
  struct KeptWorkTimes {
    double ms_grow = 0.0;
    double ms_keep = 0.0;
    double ms_passes = 0.0;
    double ms_last_pass = 0.0;
  } kept_times;
  double recent_motion[tuning::kMotionWindow] = {};
  int motion_slot = 0;
  GiveBackWatch give_back;

  const BoxSet& dropBoxesThatPairWithNothing(const BoxSet& inBoxes);
  const BoxSet& setAsideRestingBoxes(const BoxSet& inBoxes, const FrameDelta& inDelta,
                                     int inThreads);
  PlanInputs planInputs(const BoxSet& inBoxes, const BoxSet& inSwept, const FrameDelta& inDelta,
                        int inThreads);
  bool execute(const FramePlan& inPlan, const BoxSet& inBoxes, const BoxSet& inSwept);
  bool testKeptCandidates(const BoxSet& inSwept, int inThreads);
  void sweepGrown(const BoxSet& inSwept, const FramePlan& inPlan);
  void addRestingPairs(const BoxSet& inBoxes, int inThreads);
  void addSceneryPairs(const BoxSet& inBoxes, int inThreads);
  void learnCosts(const FramePlan& inPlan, const BoxSet& inSwept, std::size_t inSweepPairs);
  void learnPassCosts(double inMilliseconds, double inBoxes);
  void rememberMotion(const FrameDelta& inDelta);
  double recentMotion() const;
  void giveBackMemoryAfterBursts(std::size_t inBoxes);
};

// A box with group 0 or mask 0 passes no filter: it is left out before anything else. The
// copy is made only when such boxes exist.
const BoxSet& Broadphase::Impl::dropBoxesThatPairWithNothing(const BoxSet& inBoxes) {
  if (!inBoxes.hasFilters()) return inBoxes;
  std::size_t excluded = 0;
  for (std::size_t i = 0; i < inBoxes.size(); ++i)
    excluded += inBoxes.group(i) == 0 || inBoxes.mask(i) == 0;
  report.boxes_filtered_out = excluded;
  if (excluded == 0) return inBoxes;
  collidable.clear();
  collidable.reserve(inBoxes.size() - excluded);
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    if (inBoxes.group(i) == 0 || inBoxes.mask(i) == 0) continue;
    const double low[3] = {inBoxes.lo[0][i], inBoxes.lo[1][i], inBoxes.lo[2][i]};
    const double high[3] = {inBoxes.hi[0][i], inBoxes.hi[1][i], inBoxes.hi[2][i]};
    collidable.add(inBoxes.ids[i], low, high, inBoxes.group(i), inBoxes.mask(i));
  }
  return collidable;
}

// Resting boxes (bit for bit unchanged, of group/mask classes that cannot pair among
// themselves) answer from an index; the rest is what the strategy sweeps.
const BoxSet& Broadphase::Impl::setAsideRestingBoxes(const BoxSet& inBoxes,
                                                     const FrameDelta& inDelta, int inThreads) {
  if (!config.index_static_boxes || config.method == Method::kBruteForce || !inDelta.sameIds() ||
      reusesLastPairs(config, inDelta, pairs_valid)) {
    resting.clear();
    return inBoxes;
  }
  PhaseTimer timer(report.ms_static);
  return resting.prepare(inBoxes, *inDelta.unchanged, inThreads) ? resting.moving() : inBoxes;
}

PlanInputs Broadphase::Impl::planInputs(const BoxSet& inBoxes, const BoxSet& inSwept,
                                        const FrameDelta& inDelta, int inThreads) {
  PlanInputs inputs;
  inputs.config = &config;
  inputs.delta = inDelta;
  inputs.boxes = inBoxes.size();
  inputs.swept = inSwept.size();
  inputs.threads = inThreads;
  inputs.last_pairs_valid = pairs_valid;
  inputs.kept_candidates = kept.valid();
  inputs.kept_skin = kept_skin;
  // Whether every box is still inside its skin is found out by the pass itself (one read of
  // the frame): until then the candidates may cover it when nothing but bounds changed.
  inputs.kept_covers = inputs.kept_candidates && inDelta.sameIds() && !inDelta.filters_changed;
  inputs.motion = recentMotion();
  inputs.costs = costs;
  return inputs;
}

// The kept-candidate pass: false (pairs untouched) when some box left its skin.
bool Broadphase::Impl::testKeptCandidates(const BoxSet& inSwept, int inThreads) {
  report.skin_candidates = kept.candidates();
  const Clock::time_point start = Clock::now();
  const bool covered = kept.collect(inSwept, inThreads, pairs);
  kept_times.ms_last_pass = millisecondsSince(start);
  kept_times.ms_passes += kept_times.ms_last_pass;
  report.ms_pairing += kept_times.ms_last_pass;
  return covered;
}

// Sweeps the boxes grown by the plan's skin; its pairs become the kept candidates, and the
// exact pairs are those of them that overlap now.
void Broadphase::Impl::sweepGrown(const BoxSet& inSwept, const FramePlan& inPlan) {
  const BoxSet* grown = nullptr;
  {
    PhaseTimer timer(report.ms_keys);
    PhaseTimer grow_timer(kept_times.ms_grow);
    grown = &kept.inflate(inSwept, inPlan.sweep_skin, inPlan.threads);
  }
  sweep.run(*grown, inPlan.sweep_path, inPlan.threads, report, pairs);
  {
    PhaseTimer timer(report.ms_pairing);
    PhaseTimer keep_timer(kept_times.ms_keep);
    kept.adopt(inSwept, pairs);
  }
  kept_skin = inPlan.sweep_skin;
  testKeptCandidates(inSwept, inPlan.threads);
}

// Runs the plan's strategy; false when the kept candidates turned out not to cover the
// frame (then nothing was computed and the frame must be planned again).
bool Broadphase::Impl::execute(const FramePlan& inPlan, const BoxSet& inBoxes,
                               const BoxSet& inSwept) {
  switch (inPlan.work) {
    case FrameWork::kEmpty:
      pairs.clear();
      break;
    case FrameWork::kReuse:
      break;  // pairs still hold this very frame's pairs
    case FrameWork::kBruteForce: {
      PhaseTimer timer(report.ms_pairing);
      pairs = bruteForcePairs(inBoxes);
      break;
    }
    case FrameWork::kKeptCandidates:
      return testKeptCandidates(inSwept, inPlan.threads);
    case FrameWork::kSmallFrame: {
      PhaseTimer timer(report.ms_pairing);
      kept.clear();
      pairSmallFrame(inSwept, small_frame, pairs);
      break;
    }
    case FrameWork::kSweep:
      if (inPlan.sweep_skin > 0.0) {
        sweepGrown(inSwept, inPlan);
      } else {
        kept.clear();
        sweep.run(inSwept, inPlan.sweep_path, inPlan.threads, report, pairs);
      }
      break;
  }
  return true;
}

void Broadphase::Impl::addRestingPairs(const BoxSet& inBoxes, int inThreads) {
  if (resting.indexedBoxes() == 0) return;
  PhaseTimer timer(report.ms_static);
  resting.crossPairs(inBoxes, inThreads, pairs);
  sortPairsCanonical(pairs, pair_scratch);
  report.static_boxes += resting.indexedBoxes();
}

// Pairs between this frame's boxes and the declared scenery, merged into canonical order.
void Broadphase::Impl::addSceneryPairs(const BoxSet& inBoxes, int inThreads) {
  if (scenery.size() == 0) return;
  PhaseTimer timer(report.ms_static);
  report.static_boxes += scenery.size();
  if (inBoxes.size() == 0) return;
  every_box.resize(inBoxes.size());
  std::iota(every_box.begin(), every_box.end(), 0u);
  const std::size_t before = pairs.size();
  scenery.queryAll(inBoxes, every_box, inThreads, pairs);
  if (pairs.size() != before) sortPairsCanonical(pairs, pair_scratch);
}

// What this frame's work cost, for the automatic skin's next choice. A grown sweep's frame
// holds four kinds of work: growing the boxes, the sweep itself, keeping its candidates and
// the pass that answers the frame; each is learnt as its own cost (SkinCosts).
void Broadphase::Impl::learnCosts(const FramePlan& inPlan, const BoxSet& inSwept,
                                  std::size_t inSweepPairs) {
  const double boxes = static_cast<double>(inSwept.size());
  if (inPlan.work == FrameWork::kSweep && inSwept.size() >= tuning::kMinSkinBoxes) {
    const bool grown_sweep = inPlan.sweep_skin > 0.0;
    const double candidates = static_cast<double>(grown_sweep ? kept.candidates() : inSweepPairs);
    const double ms_sweep_per_box =
        report.ms_keys + report.ms_sort + report.ms_candidates - kept_times.ms_grow;
    const double ms_sweep_per_item =
        report.ms_pairing + report.ms_output - kept_times.ms_keep - kept_times.ms_passes;
    costs.sweep_ns_per_box = std::max(0.0, ms_sweep_per_box) * 1e6 / boxes;
    costs.pairing_ns_per_item = std::max(0.0, ms_sweep_per_item) * 1e6 / (boxes + candidates);
    costs.reference_boxes = inSwept.size();
    costs.reference_candidates = candidates;
    costs.reference_skin = inPlan.sweep_skin;
    measureExtents(inSwept, inPlan.threads, costs);
    if (grown_sweep) {
      costs.grow_ns_per_box = smoothed(costs.grow_ns_per_box, kept_times.ms_grow * 1e6 / boxes);
      costs.keep_ns_per_candidate = smoothed(costs.keep_ns_per_candidate,
                                             kept_times.ms_keep * 1e6 / std::max(1.0, candidates));
    }
  }
  const bool answered_by_pass = inPlan.work == FrameWork::kKeptCandidates ||
                                (inPlan.work == FrameWork::kSweep && inPlan.sweep_skin > 0.0);
  if (answered_by_pass && kept.candidates() > 0) learnPassCosts(kept_times.ms_last_pass, boxes);
}

// The whole pass is charged to its candidates and boxes in the proportion of the initial
// estimates; what matters to the model is the pass's total at this size.
void Broadphase::Impl::learnPassCosts(double inMilliseconds, double inBoxes) {
  const double estimate = tuning::kInitialNsPerBox * inBoxes +
                          tuning::kInitialNsPerCandidate * static_cast<double>(kept.candidates());
  const double scale = inMilliseconds * 1e6 / estimate;
  costs.pass_ns_per_box = smoothed(costs.pass_ns_per_box, tuning::kInitialNsPerBox * scale);
  costs.pass_ns_per_candidate =
      smoothed(costs.pass_ns_per_candidate, tuning::kInitialNsPerCandidate * scale);
}

void Broadphase::Impl::rememberMotion(const FrameDelta& inDelta) {
  if (!inDelta.sameIds()) {
    for (double& motion : recent_motion) motion = 0.0;
    return;
  }
  recent_motion[motion_slot] = inDelta.max_displacement;
  motion_slot = (motion_slot + 1) % tuning::kMotionWindow;
}

double Broadphase::Impl::recentMotion() const {
  return *std::max_element(std::begin(recent_motion), std::end(recent_motion));
}

// Buffers sized for a burst of large frames are given back once frames have stayed much
// smaller for a while; the next frame sizes them again.
void Broadphase::Impl::giveBackMemoryAfterBursts(std::size_t inBoxes) {
  if (!give_back.shouldGiveBack(inBoxes, sweep.capacityBoxes())) return;
  sweep.releaseBuffers();
  history.shrinkToFit();
  kept = SkinList();  // the next grown sweep keeps candidates of the frame's size again
  collidable = BoxSet();
  pairs.shrink_to_fit();
  pair_scratch = PairSortScratch();
}

Broadphase::Broadphase(const BroadphaseConfig& inConfig) {
  if (auto problem = configProblem(inConfig)) throw std::invalid_argument(*problem);
  impl_ = std::make_unique<Impl>(inConfig);
}

Broadphase::~Broadphase() = default;
Broadphase::Broadphase(Broadphase&&) noexcept = default;
Broadphase& Broadphase::operator=(Broadphase&&) noexcept = default;

const PairList& Broadphase::update(const BoxSet& inBoxes) {
  Impl& impl = *impl_;
  const FrameReport last_report = impl.report;
  FrameReport& report = impl.report;
  report = FrameReport();
  impl.kept_times = Impl::KeptWorkTimes();
  {
    PhaseTimer total(report.ms_total);
    report.boxes = inBoxes.size();
    const int threads = resolveThreadCount(impl.config.threads);
    const BoxSet& boxes = impl.dropBoxesThatPairWithNothing(inBoxes);
    const FrameDelta delta = [&] {
      PhaseTimer timer(report.ms_history);
      return impl.history.compare(boxes, threads);
    }();
    impl.rememberMotion(delta);
    const BoxSet& swept = impl.setAsideRestingBoxes(boxes, delta, threads);
    PlanInputs inputs = impl.planInputs(boxes, swept, delta, threads);
    FramePlan plan = planFrame(inputs);
    if (!impl.execute(plan, boxes, swept)) {
      inputs.kept_covers = false;  // a box left its skin: plan again, knowing it
      plan = planFrame(inputs);
      impl.execute(plan, boxes, swept);
    }
    const std::size_t sweep_pairs = impl.pairs.size();
    if (plan.work != FrameWork::kReuse) {
      impl.addRestingPairs(boxes, threads);
      impl.addSceneryPairs(boxes, threads);
    }
    {
      PhaseTimer timer(report.ms_history);
      impl.history.remember(boxes);
    }
    impl.pairs_valid = true;
    impl.learnCosts(plan, swept, sweep_pairs);
    impl.giveBackMemoryAfterBursts(boxes.size());
    report.path = framePathOf(plan, impl.resting.indexedBoxes() > 0);
    report.threads = plan.threads;
    report.skin = plan.skin;
    report.skin_choice = plan.skin_choice;
    report.moved_boxes = delta.moved_boxes;
    report.max_displacement = delta.max_displacement;
    report.pairs = impl.pairs.size();
    if (plan.work != FrameWork::kSweep) {
      // No sort ran: the sweep's measures of the last sorted frame still describe it.
      report.dispersion_primary = last_report.dispersion_primary;
      report.dispersion_secondary = last_report.dispersion_secondary;
      report.slabs = last_report.slabs;
      report.primary_axis = impl.sweep.primaryAxis();
      report.secondary_axis = impl.sweep.secondaryAxis();
      if (plan.work == FrameWork::kReuse) report.static_boxes = last_report.static_boxes;
    }
    impl.config.primary_axis = impl.sweep.primaryAxis();
    impl.config.secondary_axis = impl.sweep.secondaryAxis();
  }
  return impl.pairs;
}

const FrameReport& Broadphase::stats() const {
  return impl_->report;
}
const BroadphaseConfig& Broadphase::config() const {
  return impl_->config;
}

void Broadphase::reset() {
  impl_->sweep.forgetCoherence();
  impl_->history.forget();
  impl_->kept.clear();
  impl_->resting.clear();
  impl_->pairs_valid = false;
}

void Broadphase::setStaticBoxes(const BoxSet& inStaticBoxes) {
  std::vector<uint32_t> every_box(inStaticBoxes.size());
  std::iota(every_box.begin(), every_box.end(), 0u);
  impl_->scenery.build(inStaticBoxes, every_box, resolveThreadCount(impl_->config.threads));
  impl_->pairs_valid = false;  // the last pairs were computed against other scenery
}

void Broadphase::clearStaticBoxes() {
  impl_->scenery = StaticIndex();
  impl_->pairs_valid = false;
}

std::size_t Broadphase::staticBoxCount() const {
  return impl_->scenery.size();
}

}  // namespace sap_broadphase
