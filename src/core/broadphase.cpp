// The per-frame flow (docs/ARCHITECTURE.md walks through it step by step):
//
//   a frame of records -> the frame history loads it: the one copy and check, and the delta
//         since the last frame -> do the kept candidates still cover the boxes? -> plan, once ->
//         one strategy:
//            reuse | kept candidates (then a step of their successor's build) | sweep (grown
//            by a skin or plain) | small frame | brute
//         -> learn the costs -> the declared scenery's pairs sorted on their own and merged
//            into the strategy's canonical list -> the contact events: one merge with the
//            last list -> remember the frame, give back memory a burst of large frames left
//            behind
#include "sap_broadphase/core/broadphase.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/assert.h"
#include "core/frame/contact_events.h"
#include "core/frame/frame_history.h"
#include "core/frame/frame_plan.h"
#include "core/frame/pair_sort.h"
#include "core/runner/memory_policy.h"
#include "core/runner/phase_timer.h"
#include "core/runner/work_units.h"
#include "core/strategies/frame_query.h"
#include "core/strategies/skin_audit.h"
#include "core/strategies/skin_reuse.h"
#include "core/strategies/small_frame.h"
#include "core/strategies/static_index.h"
#include "core/sweep/sweep_and_prune.h"
#include "core/tuning.h"

namespace sap_broadphase {

struct Broadphase::Impl {
  explicit Impl(const BroadphaseConfig& inConfig)
      : config(inConfig), runner(resolveThreadCount(inConfig.threads)), sweep(inConfig) {}

  const BroadphaseConfig config;  // as the user set it
  mutable WorkRunner runner;      // the engine's workers: every parallel pass (work_units.h)
  FrameReport report;
  FrameHistory history;               // the last frame, and what changed since
  SweepAndPrune sweep;                // the paper's sweep, with its partition bounds and axes
  SkinReuse skin;                     // kept candidates, motion and learnt costs
  SkinAudit skin_audit;               // whether the automatic skin's frames pay, measured
  StaticIndex scenery;                // boxes declared static (setStaticBoxes)
  FrameQuery world;                   // box queries against the last frame (the history's copy)
  PairList pairs;                     // the frame's one canonical pair list
  bool pairs_valid = false;           // pairs hold the last frame's whole answer
  std::vector<uint32_t> scenery_ids;  // the scenery's ids, sorted: a frame's ids must differ
  struct Buffers {
    SmallFrameWorkspace small_frame;  // the small-frame path's
    std::vector<uint32_t> every_box;  // 0..n-1: the scenery's queries
    PairSortScratch pair_sort;
    PairList scenery_pairs;  // the frame's pairs with the scenery, sorted, then merged
    PairList merged;         // the strategy's and the scenery's pairs, merged
  } buffers;
  GiveBackWatch give_back;
  ContactEventTracker events;  // began and ended pairs of the last frame

  std::optional<ValidationError> sceneryIdConflict(const BoxColumns& inBoxes,
                                                   const BoxFrame& inFrame) const;
  void countBoxesThatPairWithNothing(const BoxColumns& inBoxes);
  FramePlan plan(const BoxColumns& inBoxes, const FrameDelta& inDelta);
  void execute(const FramePlan& inPlan, FrameSpread& ioSpread);
  void addSceneryPairs(const BoxColumns& inBoxes);
  void describeFrame(const FramePlan& inPlan, const FrameDelta& inDelta);
  void giveBackMemoryAfterBursts(std::size_t inBoxes);
  void runFrame(const BoxColumns& inBoxes, const FrameDelta& inDelta);
  void checkPairCount(std::size_t inPairs) const;
  void dropRefusedFrame();
  void forgetFrames();
};

// A box with group 0 or mask 0 passes no filter: the strategies never pair it (each tests
// the filter), so it stays in the frame rather than being copied out of it; the report counts it.
void Broadphase::Impl::countBoxesThatPairWithNothing(const BoxColumns& inBoxes) {
  if (!inBoxes.hasFilters()) return;
  std::size_t excluded = 0;
  for (std::size_t i = 0; i < inBoxes.size(); ++i)
    excluded += inBoxes.groups[i] == 0 || inBoxes.masks[i] == 0;
  report.boxes_filtered_out = excluded;
}

// The scenery's ids and the frame's must differ (a pair names boxes by id): the lowest frame box
// whose id a scenery box has, named as a repeated id. Only a frame of other ids than the last
// one can have one.
std::optional<ValidationError> Broadphase::Impl::sceneryIdConflict(const BoxColumns& inBoxes,
                                                                   const BoxFrame& inFrame) const {
  if (scenery_ids.empty()) return std::nullopt;
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    if (!std::binary_search(scenery_ids.begin(), scenery_ids.end(), inBoxes.ids[i])) continue;
    ValidationError error{i, inBoxes.ids[i], "id of a static box (setStaticBoxes)"};
    error.problem = BoxProblem::kDuplicateId;
    error.earlier_span = ValidationError::kScenery;
    std::size_t first_box = 0;
    while (error.span + 1 < inFrame.spanCount() && i >= first_box + inFrame.span(error.span).count)
      first_box += inFrame.span(error.span++).count;
    return error;
  }
  return std::nullopt;
}

// The plan, made once: whether the kept candidates still cover the boxes is known before it
// (SkinReuse::coversFrame), so the plan cannot be wrong about them. Runs in the frame's scope:
// its threads are the frame's.
FramePlan Broadphase::Impl::plan(const BoxColumns& inBoxes, const FrameDelta& inDelta) {
  const int frame_threads = passThreads();
  PlanInputs inputs;
  inputs.config = &config;
  inputs.delta = inDelta;
  inputs.boxes = inBoxes.size();
  inputs.threads = frame_threads;
  inputs.last_pairs_valid = pairs_valid;
  inputs.kept_candidates = skin.hasCandidates();
  inputs.kept_skin = skin.skin();
  inputs.motion = skin.recentMotion();
  inputs.costs = skin.costs();
  inputs.skin_audit_allows = skin_audit.allowsSkin();
  inputs.kept_covers = planConsidersKeptCandidates(inputs) && skin.coversFrame(inBoxes, report);
  PhaseTimer timer(report.ms_plan);
  const FramePlan plan = planFrame(inputs);
  SAP_ASSERT(plan.path != FramePath::kSkin || inputs.kept_covers,
             "the plan answers from kept candidates that do not cover the frame");
  SAP_ASSERT(plan.sweep_skin == 0.0 || findsAllPairs(plan.path),
             "a skin to grow boxes by on a frame whose pairs are not found from scratch");
  SAP_ASSERT(plan.threads >= 1 && plan.threads <= frame_threads, "the plan's threads out of range");
  return plan;
}

// Runs the plan's strategy: this frame's pairs of the boxes of ioSpread go into pairs, in
// canonical order. ioSpread (the boxes' spread) is measured by whichever strategy needs it
// first and read again by the cost learning after it. Runs in the plan's scope (its threads
// are inPlan.threads), which every pass reads.
void Broadphase::Impl::execute(const FramePlan& inPlan, FrameSpread& ioSpread) {
  const BoxColumns& boxes = ioSpread.boxes();
  switch (inPlan.path) {
    case FramePath::kEmpty:
      pairs.clear();
      break;
    case FramePath::kReused:
      break;  // pairs still hold this very frame's pairs
    case FramePath::kBruteForce: {
      PhaseTimer timer(report.ms_pairing);
      pairs = bruteForcePairs(boxes);
      break;
    }
    case FramePath::kSkin:
      skin.answerFromCandidates(report, pairs);
      skin.advanceSuccessor(boxes, report);  // the next candidates, a step
      break;
    case FramePath::kSmallFrame:
      buffers.small_frame.max_pairs = config.max_pairs;  // Buffers() may have replaced it
      if (inPlan.sweep_skin > 0.0) {
        const BoxColumns& grown = skin.grow(boxes, inPlan.sweep_skin, report);
        FrameSpread grown_spread(grown);  // other boxes than the frame's: their own spread
        {
          PhaseTimer timer(report.ms_pairing);
          pairSmallFrame(grown, grown_spread, buffers.small_frame, pairs);
        }
        // The kept candidates answer the frames that follow without a sweep: the kernel's
        // buffers would sit idle through them, beside the kept-candidate passes' own. They are
        // given back before the candidates are kept, and the next sweep sizes them again.
        buffers.small_frame = SmallFrameWorkspace();
        skin.keepAndAnswer(boxes, report, pairs);
        returnFreedHeapPages();  // the lists the kept candidates replaced
      } else {
        PhaseTimer timer(report.ms_pairing);
        skin.forget();
        pairSmallFrame(boxes, ioSpread, buffers.small_frame, pairs);
      }
      break;
    case FramePath::kSequential:
    case FramePath::kParallel:
      if (inPlan.sweep_skin > 0.0) {
        const BoxColumns& grown = skin.grow(boxes, inPlan.sweep_skin, report);
        FrameSpread grown_spread(grown);  // other boxes than the frame's: their own spread
        sweep.run(grown, grown_spread, inPlan.path, report, pairs);
        sweep.releaseBuffers();  // idle through the kept-candidate frames, as the kernel's
        skin.keepAndAnswer(boxes, report, pairs);
        returnFreedHeapPages();
      } else {
        skin.forget();
        sweep.run(boxes, ioSpread, inPlan.path, report, pairs);
      }
      break;
  }
}

// The pairs with the declared scenery join the strategy's pairs, already in canonical order:
// only the scenery's pairs are sorted, then the two sorted lists are merged (no pair is in
// both: scenery ids differ from the frame's, and the strategy pairs frame boxes only). On the
// frame's threads.
void Broadphase::Impl::addSceneryPairs(const BoxColumns& inBoxes) {
  if (scenery.size() == 0 || inBoxes.size() == 0) return;
  PairList& scenery_pairs = buffers.scenery_pairs;
  scenery_pairs.clear();
  {
    PhaseTimer timer(report.ms_static);
    buffers.every_box.resize(inBoxes.size());
    std::iota(buffers.every_box.begin(), buffers.every_box.end(), 0u);
    scenery.queryAll(inBoxes, buffers.every_box, scenery_pairs);
  }
  if (scenery_pairs.empty()) return;
  checkPairCount(pairs.size() + scenery_pairs.size());
  PhaseTimer timer(report.ms_output);
  sortPairsCanonical(scenery_pairs, buffers.pair_sort);
  buffers.merged.resize(pairs.size() + scenery_pairs.size());
  std::merge(pairs.begin(), pairs.end(), scenery_pairs.begin(), scenery_pairs.end(),
             buffers.merged.begin());
  pairs.swap(buffers.merged);
}

// The report's rows that describe the frame as a whole (the phases and the sweep's rows were
// filled as the work ran).
void Broadphase::Impl::describeFrame(const FramePlan& inPlan, const FrameDelta& inDelta) {
  report.path = inPlan.path;
  report.threads = inPlan.threads;
  report.skin = skin.overBudget() ? 0.0 : inPlan.skin;
  report.skin_choice = skin.overBudget() ? SkinChoice::kOverBudget : inPlan.skin_choice;
  report.moved_boxes = inDelta.moved_boxes;
  report.max_displacement = inDelta.max_displacement;
  report.static_boxes = scenery.size();
  report.pairs = pairs.size();
  if (!isSweep(inPlan.path)) {
    report.primary_axis = sweep.primaryAxis();
    report.secondary_axis = sweep.secondaryAxis();
  }
}

// Buffers sized for a burst of large frames are given back once frames have stayed much
// smaller for a while (memory_policy.h); the next frame sizes them again.
void Broadphase::Impl::giveBackMemoryAfterBursts(std::size_t inBoxes) {
  if (!give_back.shouldGiveBack(inBoxes, sweep.capacityBoxes())) return;
  sweep.releaseBuffers();
  history.shrinkToFit();
  skin.releaseMemory();   // the next grown sweep keeps candidates of the frame's size again
  world.releaseMemory();  // the next frame's query index, if one is asked for, sizes itself
  pairs.shrink_to_fit();
  events.releaseMemory();
  buffers = Buffers();
}

Broadphase::Broadphase(const BroadphaseConfig& inConfig) {
  if (auto problem = configProblem(inConfig)) throw std::invalid_argument(*problem);
  impl_ = std::make_unique<Impl>(inConfig);
}

Broadphase::~Broadphase() = default;
Broadphase::Broadphase(Broadphase&&) noexcept = default;
Broadphase& Broadphase::operator=(Broadphase&&) noexcept = default;

// Everything of a frame after the history has compared (or loaded) it: inBoxes are the boxes
// that may pair, as the history now holds them. Runs in the frame's scope.
void Broadphase::Impl::runFrame(const BoxColumns& inBoxes, const FrameDelta& inDelta) {
  skin.startFrame(inDelta);
  const Clock::time_point work_start = Clock::now();
  const FramePlan frame_plan = plan(inBoxes, inDelta);
  FrameSpread spread(inBoxes);  // measured once, by the first part that needs it
  const bool reused = frame_plan.path == FramePath::kReused;
  if (!reused) events.keepLastList(pairs);  // the strategy writes the buffer of the list before
  {
    // The plan's work on the plan's threads: the frame's, or one for a sequential sweep.
    const RunnerScope plan_scope(runner, frame_plan.threads);
    SAP_ASSERT(passThreads() == frame_plan.threads,
               "the plan's work on other threads than its own");
    execute(frame_plan, spread);
    checkPairCount(pairs.size());  // the paths the bound does not stop as they go
    if (!config.skin) {            // the costs only feed the automatic skin's choice
      const double ms_work = millisecondsSince(work_start);
      PhaseTimer timer(report.ms_plan);
      skin.learn(frame_plan, spread, pairs.size(), report);
      skin_audit.record(frame_plan, inDelta, inBoxes.size(), ms_work);
    }
  }
  if (!reused) addSceneryPairs(inBoxes);
  if (reused) {
    events.sameListAsLast();
  } else {
    PhaseTimer timer(report.ms_output);
    events.compare(pairs);
  }
  history.remember();
  world.setFrame(history.remembered());
  pairs_valid = true;
  PhaseTimer timer(report.ms_plan);
  giveBackMemoryAfterBursts(inBoxes.size());
  describeFrame(frame_plan, inDelta);
}

// A frame past max_pairs is refused: the sweeps and the small-frame kernel throw as they go
// (PairBudget), the other paths here, once their pairs are found.
void Broadphase::Impl::checkPairCount(std::size_t inPairs) const {
  if (inPairs > config.max_pairs) throw TooManyPairs(config.max_pairs);
}

// After a frame refused for its pairs: a sweep stopped halfway leaves boxes in its active
// lists, so every strategy's buffers go, with the pairs held (the next frame sizes them again),
// and the engine starts afresh, as after reset(), but for the events: the last list returned
// goes back to them, so the next frame's events are those since it (events()).
void Broadphase::Impl::dropRefusedFrame() {
  forgetFrames();
  sweep.releaseBuffers();
  skin.releaseMemory();
  world.releaseMemory();
  events.restoreLastList(pairs);
  buffers = Buffers();
}

const PairList& Broadphase::update(const BoxFrame& inFrame) {
  Impl& impl = *impl_;
  impl.world.clear();  // the history's copy is about to change
  // The frame's threads, decided once (frame_plan.h, frameThreads) and installed in the runner's
  // scope for the whole frame: its loading and its plan's work run on them (passThreads()), the
  // plan may only keep a sequential sweep to one of them (runFrame's nested scope).
  const RunnerScope frame_scope(impl.runner,
                                frameThreads(impl.config, inFrame.size(), impl.runner.threads()));
  FrameReport& report = impl.report;
  report = FrameReport();
  impl.events.startFrame();
  {
    PhaseTimer total(report.ms_total);
    std::optional<ValidationError> problem;
    const FrameDelta delta = [&] {
      PhaseTimer timer(report.ms_history);
      return impl.history.load(inFrame, problem);
    }();
    const BoxColumns& boxes = impl.history.loaded();
    if (!problem && !delta.sameIds()) problem = impl.sceneryIdConflict(boxes, inFrame);
    if (problem) {
      // The kept state described a frame the caller has since replaced; the last pairs stay
      // the events' reference (events()).
      impl.forgetFrames();
      throw InvalidBoxes(std::move(*problem));
    }
    report.boxes = boxes.size();
    impl.countBoxesThatPairWithNothing(boxes);
    try {
      impl.runFrame(boxes, delta);
    } catch (const TooManyPairs&) {
      impl.dropRefusedFrame();
      throw;
    }
  }
  SAP_ASSERT(isCanonical(impl.pairs), "update() returns sorted, unique pairs with a < b");
  return impl.pairs;
}

const FrameReport& Broadphase::stats() const {
  return impl_->report;
}
const BroadphaseConfig& Broadphase::config() const {
  return impl_->config;
}

const ContactEvents& Broadphase::events() const {
  return impl_->events.events();
}

void Broadphase::Impl::forgetFrames() {
  sweep.forgetCoherence();
  history.forget();
  skin.forget();
  pairs_valid = false;
}

void Broadphase::reset() {
  impl_->forgetFrames();
  impl_->events.forget();
}

void Broadphase::setStaticBoxes(const BoxFrame& inStaticBoxes) {
  const RunnerScope scope(impl_->runner);  // the scenery is built on every thread of the runner
  BoxColumns scenery;
  copyFrame(inStaticBoxes, scenery);
  if (auto problem = checkColumns(scenery, inStaticBoxes)) throw InvalidBoxes(std::move(*problem));
  std::vector<uint32_t> every_box(scenery.size());
  std::iota(every_box.begin(), every_box.end(), 0u);
  impl_->scenery.build(scenery, every_box);
  impl_->scenery_ids = scenery.ids;
  std::sort(impl_->scenery_ids.begin(), impl_->scenery_ids.end());
  impl_->pairs_valid = false;  // the last pairs were computed against other scenery
  impl_->history.forget();     // the next frame's ids are checked against the new scenery
}

void Broadphase::clearStaticBoxes() {
  impl_->scenery = StaticIndex();
  impl_->scenery_ids.clear();
  impl_->pairs_valid = false;
}

std::size_t Broadphase::staticBoxCount() const {
  return impl_->scenery.size();
}

QueryHitList Broadphase::query(const BoxFrame& inQueries) const {
  // Every thread of the runner; a concurrent query finds it busy and runs inline.
  const RunnerScope scope(impl_->runner);
  BoxColumns queries;  // a query's own: queries may run concurrently
  copyFrame(inQueries, queries);
  if (auto problem = checkColumns(queries, inQueries)) throw InvalidBoxes(std::move(*problem));
  const PairList hits = answerQueries(queries, impl_->world, impl_->scenery);
  QueryHitList answer(hits.size());
  std::transform(hits.begin(), hits.end(), answer.begin(), [](const IdPair& inHit) {
    return QueryHit{inHit.a, inHit.b};
  });
  return answer;
}

}  // namespace sap_broadphase
