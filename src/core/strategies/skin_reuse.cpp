#include "core/strategies/skin_reuse.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "core/assert.h"
#include "core/runner/memory_policy.h"
#include "core/runner/phase_timer.h"
#include "core/runner/work_units.h"
#include "core/strategies/ordered_units.h"
#include "core/sweep/axis_spread.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/sort_keys.h"

namespace sap_broadphase {
namespace {

double smoothed(double inAverage, double inSample) {
  return inAverage > 0.0 ? inAverage + tuning::kCostSmoothing * (inSample - inAverage) : inSample;
}

// Mean finite box extent and the span of the finite bounds on each axis (the skin cost
// model's picture of the frame).
void measureExtents(FrameSpread& ioSpread, SkinCosts& ioCosts) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisSpread& spread = ioSpread.axis(axis);
    ioCosts.mean_extent[axis] = spread.meanExtent();
    ioCosts.span[axis] = spread.span();
  }
}

// A successor's sweep is cut into the fewest slabs that keep each within
// kMostSuccessorSlabBoxes boxes, and at least kFewestSuccessorSlabs: its frames of building are
// then few, so that most frames of a cycle are a kept-candidate pass alone (the median frame),
// and its skin, grown by the motion of those frames, stays close to the plan's (fewer
// candidates for every pass). An earlier version spread the build over the whole cycle (as many
// slabs as its life allowed, at least 3): every steady frame then held a step, and the
// successor's skin was about twice the plan's. Measured on the 2-core VM (uniform, 1 % motion,
// 2 threads, 300 frames, both versions alternating in one run, medians of 3-4 runs): p50 at
// 2^12 0.112 -> 0.083 ms (d = 0.05) and 0.345 -> 0.318 (d = 0.35); 2^14 0.50 -> 0.31 and 1.42
// -> 1.35; 2^17 4.0 -> 2.1 and 8.9 -> 8.4; 2^20 29.6 -> 19 and 87 -> 83 (40 frames). p99 rose
// where a slab is half a grown sweep: 2^12 d = 0.35 0.50 -> 0.62 ms, 2^14 d = 0.35 1.83 -> 2.41;
// elsewhere within the noise. Peak RSS at 2^20 rose 18 % (d = 0.05) and 9 % (d = 0.35): a slab's
// kernel workspace covers half the boxes.
constexpr std::size_t kMostSuccessorSlabBoxes = std::size_t{1} << 19;
constexpr int kFewestSuccessorSlabs = 2;
constexpr int kMostSuccessorSlabs = 16;
// Frames between the successor's adoption and the frame the kept candidates are expected to
// stop covering: the motion measured is the recent largest, not a bound.
constexpr int kSuccessorSlackFrames = 1;
// Frames the successor's adoption is spread over, each doing kAdoptPartsPerStep of
// SkinList::continueAdopt's parts: two frames leave a short cycle room for its slabs, and
// each part costs well under a plain frame.
constexpr int kAdoptSteps = 2;
constexpr int kAdoptPartsPerStep = (SkinList::kAdoptParts + kAdoptSteps - 1) / kAdoptSteps;

AxisRanges lowEndSpread(const BoxColumns& inBoxes, std::size_t inBegin, std::size_t inEnd) {
  AxisRanges spread;
  for (int axis = 0; axis < 3; ++axis) {
    const double* low = inBoxes.lo[axis].data();
    for (std::size_t i = inBegin; i < inEnd; ++i) {
      spread.low[axis] = std::min(spread.low[axis], low[i]);
      spread.high[axis] = std::max(spread.high[axis], low[i]);
    }
  }
  return spread;
}

// Bytes of boxes' columns (capacities).
std::size_t columnBytes(const BoxColumns& inBoxes) {
  std::size_t bytes =
      (inBoxes.ids.capacity() + inBoxes.groups.capacity() + inBoxes.masks.capacity()) *
      sizeof(uint32_t);
  for (int axis = 0; axis < 3; ++axis)
    bytes += (inBoxes.lo[axis].capacity() + inBoxes.hi[axis].capacity()) * sizeof(double);
  return bytes;
}

// inBoxes' ids replaced by their ranks among them (the kernel's ids for a slab): outById lists
// the boxes by id, outIdOfRank (inBoxes.size() long) the real id of each rank.
void replaceIdsByRanks(BoxColumns& ioBoxes, Buffer<uint32_t>& outById,
                       Buffer<uint32_t>& outIdOfRank) {
  const std::size_t count = ioBoxes.size();
  resizeDiscarding(outById, count);
  indexesByKey(ioBoxes.ids.data(), count, outById.data());
  runOverItems(WorkUnits{count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t rank = inBegin; rank < inEnd; ++rank)
      outIdOfRank[rank] = ioBoxes.ids[outById[rank]];
  });
  runOverItems(WorkUnits{count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t rank = inBegin; rank < inEnd; ++rank)
      ioBoxes.ids[outById[rank]] = static_cast<uint32_t>(rank);
  });
}

// A slab's pairs of ranks (ioPairs) back to ids, in order, without those of two boxes before
// the slab (the first inReachers boxes of the slab: their pairs belong to an earlier slab).
// Each unit compacts its kept pairs to the front of its own range; the ranges are then closed
// up in unit order (a copy, not a pass that grows the list and zeroes it).
void keepSlabPairsAsIds(const Buffer<uint32_t>& inBoxOfRank, std::size_t inReachers,
                        const Buffer<uint32_t>& inIdOfRank, PairList& ioPairs) {
  const auto earlier = [&](const IdPair& inPair) {
    return inBoxOfRank[inPair.a] < inReachers && inBoxOfRank[inPair.b] < inReachers;
  };
  const WorkUnits units{ioPairs.size()};
  std::vector<std::size_t> kept_of_unit(units.count(), 0);
  runUnits(units.count(), [&](std::size_t inUnit) {
    IdPair* out = ioPairs.data() + units.begin(inUnit);
    for (std::size_t k = units.begin(inUnit); k < units.end(inUnit); ++k) {
      const IdPair pair = ioPairs[k];
      if (!earlier(pair)) *out++ = IdPair{inIdOfRank[pair.a], inIdOfRank[pair.b]};
    }
    kept_of_unit[inUnit] = static_cast<std::size_t>(out - (ioPairs.data() + units.begin(inUnit)));
  });
  std::size_t kept = 0;
  for (std::size_t unit = 0; unit < units.count(); ++unit) {
    const auto from = ioPairs.begin() + static_cast<std::ptrdiff_t>(units.begin(unit));
    if (kept != units.begin(unit))
      std::copy(from, from + static_cast<std::ptrdiff_t>(kept_of_unit[unit]),
                ioPairs.begin() + static_cast<std::ptrdiff_t>(kept));
    kept += kept_of_unit[unit];
  }
  ioPairs.resize(kept);
}

}  // namespace

void SkinReuse::startFrame(const FrameDelta& inDelta) {
  times_ = WorkTimes();
  over_budget_frame_ = false;
  if (!inDelta.sameIds()) {
    std::fill(std::begin(recent_motion_), std::end(recent_motion_), 0.0);
    return;
  }
  ++kept_age_;
  ++next_.age;
  recent_motion_[motion_slot_] = inDelta.max_displacement;
  motion_slot_ = (motion_slot_ + 1) % tuning::kMotionWindow;
}

double SkinReuse::recentMotion() const {
  return *std::max_element(std::begin(recent_motion_), std::end(recent_motion_));
}

bool SkinReuse::coversFrame(const BoxColumns& inSwept, FrameReport& ioReport) {
  times_.ms_pass = 0.0;  // the pass that answers the frame starts with this gather
  PhaseTimer timer(ioReport.ms_skin);
  PhaseTimer pass_timer(times_.ms_pass);
  if (kept_.gather(inSwept)) return true;
  if (!next_.ready) return false;
  // The kept candidates no longer cover the frame: whichever answers it (the successor, or a
  // sweep that replaces them), they answer no other. Given back before the successor's first
  // pass sizes its buffers, so the two lists' passes are never resident together.
  kept_.releaseCandidates();
  if (!next_.list.gather(inSwept)) return false;
  // The successor covers the frame (its own containment check): it takes over.
  std::swap(kept_, next_.list);
  skin_ = next_.skin;
  kept_age_ = next_.age;
  ++successors_taken_;
  recycleSuccessor();
  return true;
}

void SkinReuse::answerFromCandidates(FrameReport& ioReport, PairList& outPairs) {
  PhaseTimer timer(ioReport.ms_skin);
  PhaseTimer pass_timer(times_.ms_pass);
  ioReport.skin_candidates = kept_.candidates();
  kept_.collectGathered(outPairs);
}

const BoxColumns& SkinReuse::grow(const BoxColumns& inSwept, double inSkin, FrameReport& ioReport) {
  PhaseTimer timer(ioReport.ms_skin);
  PhaseTimer grow_timer(times_.ms_grow);
  // The grown sweep replaces the kept candidates at once, and runs (a frame's memory peak)
  // without a successor's boxes and candidates.
  next_ = Successor();
  skin_ = inSkin;
  kept_age_ = 0;
  if (inSkin >= over_budget_skin_ && inSwept.size() == over_budget_boxes_) {
    // This skin already found more candidates than the budget at this size: sweep the boxes
    // as they are (kept candidates of skin 0, for an unchanged frame) instead.
    skin_ = 0.0;
    over_budget_frame_ = true;
    ioReport.skin = 0.0;
    ioReport.skin_choice = SkinChoice::kOverBudget;
  }
  planned_skin_ = skin_;
  return kept_.inflate(inSwept, skin_);
}

void SkinReuse::keepAndAnswer(const BoxColumns& inSwept, FrameReport& ioReport, PairList& ioPairs) {
  {
    PhaseTimer timer(ioReport.ms_skin);
    PhaseTimer keep_timer(times_.ms_keep);
    if (ioPairs.size() > keptCandidateBudget(inSwept.size())) {
      keepNoCandidates(inSwept, ioReport, ioPairs);
      return;
    }
    kept_.adopt(inSwept, std::move(ioPairs));  // taken, not copied: ioPairs is rewritten below
  }
  // Every box lies inside its own grown box: the pass that answers the frame always runs.
  const bool covered = coversFrame(inSwept, ioReport);
  SAP_ASSERT(covered, "a box outside the skin it was just grown by");
  static_cast<void>(covered);
  answerFromCandidates(ioReport, ioPairs);
}

// Given up (a sweep or a small frame forgets the kept candidates, or its candidates went over
// the budget): every buffer goes, so that none is held through the frames that follow.
void SkinReuse::abandonSuccessor() {
  const bool built = next_.steps > 0;
  next_ = Successor();
  if (built) returnFreedHeapPages();  // its pair lists, freed into the heap
}

// Taken over: its list holds the replaced candidates' grown boxes (their candidates already
// given back), whose columns the next snapshot reuses; every other buffer goes.
void SkinReuse::recycleSuccessor() {
  SkinList replaced = std::move(next_.list);
  next_ = Successor();
  next_.list = std::move(replaced);
}

// After the last slab: the order, the slab's buffers, the kernel's workspace and the sorting
// scratch are dead; given back before the adoption sizes the candidates' arrays.
void SkinReuse::releaseSlabWork() {
  Buffer<uint32_t>().swap(next_.order);
  Buffer<double>().swap(next_.high_in_order);
  PairList().swap(next_.slab_pairs);
  Buffer<uint32_t>().swap(next_.slab_members);
  next_.slab_boxes = BoxColumns();
  next_.kernel = SmallFrameWorkspace();
  Buffer<uint32_t>().swap(next_.slab_by_id);
  // The slab's pair lists, freed into the heap: out of the resident set before the adoption's
  // arrays join it (measured at 2^17, d = 0.35: 10 bytes a box off the peak). Not done when the
  // successor takes over, which is no peak: there it only made the next lists fault again.
  returnFreedHeapPages();
}

// inSlabPairs (canonical, none in found) merged into found in place, from the back: no second
// list of all the candidates found. found is reserved for the candidates the slabs still to
// come are expected to add (as many a slab as so far), so that it is reallocated about once.
void SkinReuse::mergeSlabPairs(const PairList& inSlabPairs) {
  PairList& found = next_.found;
  const std::size_t before = found.size();
  const std::size_t after = before + inSlabPairs.size();
  if (after > found.capacity()) {
    const auto swept = static_cast<std::size_t>(next_.steps);  // slabs swept with this one
    const std::size_t expected = after * static_cast<std::size_t>(next_.slabs) / swept;
    found.reserve(expected + expected / 8);
  }
  found.resize(after);
  std::size_t from_found = before;
  std::size_t from_slab = inSlabPairs.size();
  for (std::size_t to = after; from_slab > 0;) {
    if (from_found > 0 && inSlabPairs[from_slab - 1] < found[from_found - 1])
      found[--to] = found[--from_found];
    else
      found[--to] = inSlabPairs[--from_slab];
  }
}

SkinReuse::SuccessorMemoryUse SkinReuse::successorMemoryUse() const {
  SuccessorMemoryUse use;
  use.list = next_.list.memoryUse();
  use.found = next_.found.capacity() * sizeof(IdPair);
  use.order =
      next_.order.capacity() * sizeof(uint32_t) + next_.high_in_order.capacity() * sizeof(double);
  use.slab = next_.slab_pairs.capacity() * sizeof(IdPair) +
             next_.slab_members.capacity() * sizeof(uint32_t) + columnBytes(next_.slab_boxes);
  use.kernel = next_.kernel.bytesHeld();
  use.slab_ids = next_.slab_by_id.capacity() * sizeof(uint32_t);
  return use;
}

// The plan's skin s lets a list live L = s / (2 motion) frames from its snapshot. Building a
// successor takes W = 1 + slabs + kAdoptSteps frames (snapshot, slabs, adoption), and it takes
// over when the kept candidates stop covering, W + slack frames after its snapshot: so it is
// grown by s plus the motion of those frames, and then lives L frames more, as the plan meant.
// Each cycle of L frames thus holds one build, started as late as it can be; a cycle shorter
// than the build starts it at once and grows it by more.
void SkinReuse::advanceSuccessor(const BoxColumns& inSwept, FrameReport& ioReport) {
  if (next_.ready || planned_skin_ <= 0.0 || !kept_.valid()) return;
  PhaseTimer timer(ioReport.ms_skin);
  if (next_.steps == 0) {
    const double motion = recentMotion();
    if (!(motion > 0.0)) return;  // nothing moves: the kept candidates last
    // Never more slabs than the cycle has room for: a longer build grows the successor by the
    // motion of more frames, past the candidate budget at 2^23 boxes (it was given up, and a
    // grown sweep ran instead, 3-4 times in 40 frames).
    const double fixed_frames = 1.0 + kAdoptSteps + kSuccessorSlackFrames;
    const double room = std::clamp(planned_skin_ / (2.0 * motion) - fixed_frames,
                                   double{kFewestSuccessorSlabs}, double{kMostSuccessorSlabs});
    const double by_size = std::ceil(static_cast<double>(inSwept.size()) /
                                     static_cast<double>(kMostSuccessorSlabBoxes));
    const int slabs =
        static_cast<int>(std::clamp(by_size, double{kFewestSuccessorSlabs}, std::floor(room)));
    const double lead_frames = slabs + fixed_frames;
    if (kept_age_ + lead_frames < skin_ / (2.0 * motion)) return;  // not due yet
    snapshotSuccessor(inSwept, planned_skin_ + 2.0 * motion * lead_frames, slabs);
  } else if (next_.steps <= next_.slabs) {
    sweepSuccessorSlab();
  } else {
    if (next_.steps == next_.slabs + 1) releaseSlabWork();
    adoptSuccessor();
  }
}

// Step 1: the frame's boxes grown by inSkin, ordered by grown low end on the axis where they
// spread widest (a slab of that order holds boxes near each other). The passes over the boxes
// run on the frame's threads, and so does the sort of the keys from radixSortPacked's
// threshold on.
void SkinReuse::snapshotSuccessor(const BoxColumns& inSwept, double inSkin, int inSlabs) {
  next_.skin = inSkin;
  next_.age = 0;
  next_.slabs = inSlabs;
  next_.steps = 1;
  next_.found.clear();
  const BoxColumns& grown = next_.list.inflate(inSwept, inSkin);
  const std::size_t n = grown.size();
  const WorkUnits units{n};
  const AxisRanges spread = reduceOverItems(
      units, AxisRanges(),
      [&](std::size_t inBegin, std::size_t inEnd) { return lowEndSpread(grown, inBegin, inEnd); },
      [](AxisRanges& ioAll, const AxisRanges& inPart) { ioAll.add(inPart); });
  int axis = 0;
  double widest = -1.0;
  for (int a = 0; a < 3; ++a) {
    const double extent = n == 0 ? 0.0 : spread.high[a] - spread.low[a];
    if (extent > widest) {
      widest = extent;
      axis = a;
    }
  }
  next_.axis = axis;
  Buffer<uint32_t>& keys = next_.order;  // the keys first, then (below) the order
  resizeDiscarding(keys, n);
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t i = inBegin; i < inEnd; ++i) keys[i] = lowKey(grown.lo[axis][i]);
  });
  Buffer<uint32_t> order;
  resizeDiscarding(order, n);
  indexesByKey(keys.data(), n, order.data());
  next_.order.swap(order);
  resizeDiscarding(next_.high_in_order, n);
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t p = inBegin; p < inEnd; ++p)
      next_.high_in_order[p] = grown.hi[axis][next_.order[p]];
  });
}

// One slab: positions [begin, end) of the order, with every box before it whose grown high end
// reaches the slab's lowest low end, swept by the small-frame kernel. A pair belongs to the
// slab of its later box: if that box is in the slab and the pair overlaps, the earlier box's
// high end is at least the later's low end, at least the slab's lowest, so it is among the
// boxes swept. Over all slabs every pair of the grown boxes is found once.
//
// The kernel is given, as the ids of the slab's boxes, the ranks of their real ids among them:
// its pairs, canonical in ranks, are then canonical in real ids once mapped back (the map is
// increasing), so the slab's pairs need no sort of their own, only a sort of the slab's ids.
// Every pass over the slab's boxes or pairs runs on the frame's threads, each unit's output
// behind the units' before it: the same candidates for any thread count. Measured on the
// 2-core VM under load 5-6 (uniform, default configuration, before and after alternating in one
// run, medians of 3): one thread's mean frame at 2^20 fell 99 -> 88 ms (d = 0.05) and 229 -> 204
// ms (d = 0.35), at 2^17 it stayed within the noise; two threads were no faster than one at that
// load, before or after, so the two-thread ratio is not measured here.
void SkinReuse::sweepSuccessorSlab() {
  const BoxColumns& grown = next_.list.reference();
  const std::size_t n = grown.size();
  const int slab = next_.steps - 1;
  const std::size_t begin = n * static_cast<std::size_t>(slab) / next_.slabs;
  const std::size_t end = n * static_cast<std::size_t>(slab + 1) / next_.slabs;
  const uint32_t* order = next_.order.data();
  const double* low_on_axis = grown.lo[next_.axis].data();
  const double lowest = reduceOverItems(
      WorkUnits{end - begin}, std::numeric_limits<double>::infinity(),
      [&](std::size_t inBegin, std::size_t inEnd) {
        double unit_lowest = std::numeric_limits<double>::infinity();
        for (std::size_t p = begin + inBegin; p < begin + inEnd; ++p)
          unit_lowest = std::min(unit_lowest, low_on_axis[order[p]]);
        return unit_lowest;
      },
      [](double& ioAll, const double& inPart) { ioAll = std::min(ioAll, inPart); });
  // Positions before begin that reach into the slab, then [begin, end), in that order.
  Buffer<uint32_t>& members = next_.slab_members;
  members.clear();
  const double* high_in_order = next_.high_in_order.data();
  appendItemsWhere(
      WorkUnits{begin}, [&](std::size_t inPosition) { return high_in_order[inPosition] >= lowest; },
      members);
  const std::size_t reachers = members.size();
  members.resize(reachers + (end - begin));
  std::iota(members.begin() + static_cast<std::ptrdiff_t>(reachers), members.end(),
            static_cast<uint32_t>(begin));
  const std::size_t count = members.size();
  BoxColumns& boxes = next_.slab_boxes;
  boxes.resize(count, grown.hasFilters());
  runOverItems(WorkUnits{count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) {
      const uint32_t i = order[members[k]];
      boxes.ids[k] = grown.ids[i];  // the real id until the ranks replace it
      for (int axis = 0; axis < 3; ++axis) {
        boxes.lo[axis][k] = grown.lo[axis][i];
        boxes.hi[axis][k] = grown.hi[axis][i];
      }
      if (boxes.hasFilters()) {
        boxes.groups[k] = grown.group(i);
        boxes.masks[k] = grown.mask(i);
      }
    }
  });
  // The members' list (read above for the last time) becomes the real id of each rank.
  Buffer<uint32_t>& id_of_rank = members;
  replaceIdsByRanks(boxes, next_.slab_by_id, id_of_rank);
  PairList& pairs = next_.slab_pairs;
  pairs.clear();
  if (count >= 2) pairSmallFrame(boxes, next_.kernel, pairs);
  keepSlabPairsAsIds(next_.slab_by_id, reachers, id_of_rank, pairs);
  SAP_ASSERT(isCanonical(pairs), "a slab's pairs out of canonical order after the ranks");
  mergeSlabPairs(pairs);
  ++next_.steps;
}

// The last steps: the candidates found become the successor's, adopted a part a frame
// (SkinList::continueAdopt); over the budget, the successor is given up instead (the kept
// candidates' end then brings a grown sweep, which decides).
void SkinReuse::adoptSuccessor() {
  const BoxColumns& grown = next_.list.reference();
  if (next_.steps == next_.slabs + 1) {
    if (next_.found.size() > keptCandidateBudget(grown.size())) {
      abandonSuccessor();
      return;
    }
    next_.list.startAdopt(std::move(next_.found));
  }
  for (int part = 0; part < kAdoptPartsPerStep && !next_.ready; ++part)
    next_.ready = next_.list.continueAdopt(grown);
  ++next_.steps;
}

// Over the budget: the grown sweep's candidates answer this frame once, tested exactly, and
// are not kept; their memory goes back at once.
void SkinReuse::keepNoCandidates(const BoxColumns& inSwept, FrameReport& ioReport,
                                 PairList& ioPairs) {
  over_budget_skin_ = skin_;
  over_budget_boxes_ = inSwept.size();
  over_budget_frame_ = true;
  kept_ = SkinList();  // gives back the last candidates' memory too
  SkinList::keepOverlapping(inSwept, ioPairs);
  ioPairs.shrink_to_fit();
  ioReport.skin = 0.0;
  ioReport.skin_candidates = 0;
  ioReport.skin_choice = SkinChoice::kOverBudget;
}

// A grown sweep's frame holds four kinds of work: growing the boxes, the sweep itself, keeping
// its candidates and the pass that answers the frame; each is learnt as its own cost
// (SkinCosts). The sweep's own phases (keys, sorts, candidates, pairing, output) hold only the
// sweep: the skin's work is in the report's ms_skin.
void SkinReuse::learn(const FramePlan& inPlan, FrameSpread& ioSwept, std::size_t inSweepPairs,
                      const FrameReport& inReport) {
  const BoxColumns& swept = ioSwept.boxes();
  const double boxes = static_cast<double>(swept.size());
  const bool grown = findsAllPairs(inPlan.path) && inPlan.sweep_skin > 0.0;
  if (findsAllPairs(inPlan.path) && swept.size() >= tuning::kMinSkinBoxes) {
    const double candidates = static_cast<double>(grown ? kept_.candidates() : inSweepPairs);
    // The small-frame kernel's phases are one (ms_pairing): its cost is charged per box and
    // candidate, as the cells' sweeps it is made of cost.
    const double ms_sweep_per_box = inReport.ms_keys + inReport.ms_sort + inReport.ms_candidates;
    const double ms_sweep_per_item = inReport.ms_pairing + inReport.ms_output;
    costs_.sweep_ns_per_box = ms_sweep_per_box * 1e6 / boxes;
    costs_.pairing_ns_per_item = ms_sweep_per_item * 1e6 / (boxes + candidates);
    costs_.reference_boxes = swept.size();
    costs_.reference_candidates = candidates;
    costs_.reference_skin = inPlan.sweep_skin;
    measureExtents(ioSwept, costs_);
    if (grown) {
      costs_.grow_ns_per_box = smoothed(costs_.grow_ns_per_box, times_.ms_grow * 1e6 / boxes);
      costs_.keep_ns_per_candidate =
          smoothed(costs_.keep_ns_per_candidate, times_.ms_keep * 1e6 / std::max(1.0, candidates));
    }
  }
  const bool answered_by_pass = inPlan.path == FramePath::kSkin || grown;
  if (answered_by_pass && kept_.candidates() > 0) learnPassCosts(times_.ms_pass, boxes);
}

// The whole pass is charged to its candidates and boxes in the proportion of the initial
// estimates; what matters to the model is the pass's total at this size.
void SkinReuse::learnPassCosts(double inMilliseconds, double inBoxes) {
  const double estimate = tuning::kInitialNsPerBox * inBoxes +
                          tuning::kInitialNsPerCandidate * static_cast<double>(kept_.candidates());
  const double scale = inMilliseconds * 1e6 / estimate;
  costs_.pass_ns_per_box = smoothed(costs_.pass_ns_per_box, tuning::kInitialNsPerBox * scale);
  costs_.pass_ns_per_candidate =
      smoothed(costs_.pass_ns_per_candidate, tuning::kInitialNsPerCandidate * scale);
}

}  // namespace sap_broadphase
