#include "sap_broadphase/core/broadphase.h"
#include "core/buffers.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/axis_policy.h"
#include "core/radix_sort.h"
#include "core/skin_list.h"
#include "core/sort_keys.h"
#include "core/static_index.h"
#include "core/static_split.h"
#include "core/sweep.h"
#include "sap_broadphase/core/brute_force.h"

namespace sap_broadphase {
namespace {

// Sort partitions (m of Algorithm 2). More partitions than threads keeps them cache-sized and
// gives D a fine enough grain to notice clustering; they are handed out dynamically.
constexpr int kSortPartitions = 16;
// Below this many endpoints one partition is cheaper than bucketing.
constexpr std::size_t kMinPartitionedEndpoints = 8192;

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point inStart) {
  return std::chrono::duration<double, std::milli>(Clock::now() - inStart).count();
}

}  // namespace

const char* methodName(Method inMethod) {
  switch (inMethod) {
    case Method::kAuto:
      return "auto";
    case Method::kParallel:
      return "parallel";
    case Method::kSequential:
      return "sequential";
    case Method::kBruteForce:
      return "brute";
  }
  return "unknown";
}

std::optional<Method> parseMethod(const std::string& inName) {
  for (Method method : {Method::kAuto, Method::kParallel, Method::kSequential, Method::kBruteForce})
    if (inName == methodName(method)) return method;
  if (inName == "sap") return Method::kAuto;
  return std::nullopt;
}

std::optional<std::string> configProblem(const BroadphaseConfig& inConfig) {
  const auto valid_axis = [](int axis) { return axis >= 0 && axis <= 2; };
  if (!valid_axis(inConfig.primary_axis) || !valid_axis(inConfig.secondary_axis) ||
      inConfig.primary_axis == inConfig.secondary_axis)
    return "primary and secondary axes must be distinct values in 0..2, not " +
           std::to_string(inConfig.primary_axis) + " and " +
           std::to_string(inConfig.secondary_axis);
  if (inConfig.threads < 0)
    return "threads must be >= 0 (0 = all cores), not " + std::to_string(inConfig.threads);
  if (inConfig.skin && !(*inConfig.skin >= 0.0 && std::isfinite(*inConfig.skin)))
    return "skin must be a finite value >= 0 (or automatic), not " + std::to_string(*inConfig.skin);
  if (inConfig.third_axis_slabs < 0 || inConfig.third_axis_slabs > kMaxSlabs)
    return "third_axis_slabs must be in 0.." + std::to_string(kMaxSlabs) + ", not " +
           std::to_string(inConfig.third_axis_slabs);
  if (!(inConfig.axis_swap_threshold >= 0.0))
    return "axis_swap_threshold must be >= 0, not " + std::to_string(inConfig.axis_swap_threshold);
  return std::nullopt;
}

const char* skinChoiceName(SkinChoice inChoice) {
  switch (inChoice) {
    case SkinChoice::kOff:
      return "off";
    case SkinChoice::kFixed:
      return "fixed";
    case SkinChoice::kFirstFrame:
      return "first_frame";
    case SkinChoice::kIdsChanged:
      return "ids_changed";
    case SkinChoice::kKept:
      return "kept";
    case SkinChoice::kChosen:
      return "chosen";
    case SkinChoice::kTooFast:
      return "too_fast";
    case SkinChoice::kNotWorthIt:
      return "not_worth_it";
  }
  return "unknown";
}

const char* framePathName(FramePath inPath) {
  switch (inPath) {
    case FramePath::kEmpty:
      return "empty";
    case FramePath::kSequential:
      return "sequential";
    case FramePath::kParallel:
      return "parallel";
    case FramePath::kBruteForce:
      return "brute";
    case FramePath::kReused:
      return "reused";
    case FramePath::kSkin:
      return "skin";
    case FramePath::kStatic:
      return "static";
  }
  return "unknown";
}

int resolveThreadCount(int inRequested) {
  return inRequested > 0 ? inRequested : std::max(1, omp_get_max_threads());
}

struct Broadphase::Impl {
  BroadphaseConfig config;
  FrameReport stats;
  AxisBounds bounds[3];
  PartitionedSorter sorter;
  // 4n words: packed (key, index) items and the sort's scratch while sorting, then the
  // secondary stream (2 words per endpoint) while pairing.
  std::vector<uint64_t> endpoint_words;
  std::vector<uint32_t> sweep_order;  // 2n endpoint indexes: primary order, then secondary
  CandidateRanges ranges;
  std::vector<RankedKeys> ranked_keys;
  std::vector<RankedFilter> ranked_filters;
  std::vector<RankedSlabs> ranked_slabs;
  SlabGrid slab_grid;
  SweepWorkspace workspace;
  SuccTree sequential_tree;
  std::vector<PairChunks> pairs_per_thread;
  PairList pairs;
  PairSortScratch pair_scratch;
  BoxSet collidable;            // the frame without boxes that can collide with nothing
  BoxSet previous_boxes;        // the last swept frame, to recognise an unchanged one
  bool previous_valid = false;  // previous_boxes holds the last frame
  SkinList skin_list;
  StaticSplit static_split;
  BoxSet inflated;                    // the frame grown by the skin, while sweeping for skin reuse
  bool previous_reusable = false;     // pairs still holds previous_boxes' pairs
  StaticIndex declared_static;        // the scenery of setStaticBoxes()
  std::vector<uint32_t> all_indexes;  // 0..n-1, the queries of the declared static index
  void addDeclaredStaticPairs(const BoxSet& inBoxes, int inThreads);

  bool sameAsPreviousFrame(const BoxSet& inBoxes) const;
  void rememberFrame(const BoxSet& inBoxes, FramePath inPath);
  const BoxSet& dropBoxesThatCollideWithNothing(const BoxSet& inBoxes);

  FramePath choosePath(std::size_t inBoxes, int inThreads) const;
  double sortAxis(const BoxSet& inBoxes, int inAxis, int inThreads,
                  std::vector<uint32_t>& outOrder);
  void gatherByRank(const BoxSet& inBoxes, int inThreads);
  void pair(const BoxSet& inBoxes, FramePath inPath, int inThreads);
  void sweepAndPrune(const BoxSet& inBoxes, FramePath inPath, int inThreads);
  void sweepIntoPairs(const BoxSet& inBoxes, FramePath inPath, int inThreads);
  void skinFrame(const BoxSet& inBoxes, int inThreads);
  bool staticFrame(const BoxSet& inBoxes, int inThreads);
  void decideAxes(bool inWarm);
};

FramePath Broadphase::Impl::choosePath(std::size_t inBoxes, int inThreads) const {
  if (inBoxes < 2) return FramePath::kEmpty;
  switch (config.method) {
    case Method::kBruteForce:
      return FramePath::kBruteForce;
    case Method::kSequential:
      return FramePath::kSequential;
    case Method::kParallel:
      return FramePath::kParallel;
    case Method::kAuto:
      return (inThreads == 1 || inBoxes < config.parallel_min_boxes) ? FramePath::kSequential
                                                                     : FramePath::kParallel;
  }
  return FramePath::kSequential;
}

// Keys of one axis (lows at i, highs at i + n), packed with their indexes, then Algorithm 2.
// Returns D.
double Broadphase::Impl::sortAxis(const BoxSet& inBoxes, int inAxis, int inThreads,
                                  std::vector<uint32_t>& outOrder) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const std::size_t endpoints = 2 * std::size_t{n};
  const double* low = inBoxes.lo[inAxis].data();
  const double* high = inBoxes.hi[inAxis].data();
  const Clock::time_point start = Clock::now();
  resizeDiscarding(endpoint_words, 2 * endpoints);
  resizeDiscarding(outOrder, endpoints);
  uint64_t* packed = endpoint_words.data();
#pragma omp parallel for num_threads(inThreads) schedule(static)
  for (uint32_t i = 0; i < n; ++i) {
    packed[i] = packKeyIndex(lowKey(low[i]), i);
    packed[i + n] = packKeyIndex(highKey(high[i]), i + n);
  }
  stats.ms_keys += millisecondsSince(start);
  const int partitions = endpoints >= kMinPartitionedEndpoints ? kSortPartitions : 1;
  return sorter.sortPacked(packed, packed + endpoints, static_cast<uint32_t>(endpoints), partitions,
                           inThreads, bounds[inAxis], outOrder.data());
}

// Box data in primary-rank order, so a candidate range is a contiguous stretch of memory.
void Broadphase::Impl::gatherByRank(const BoxSet& inBoxes, int inThreads) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const bool filtered = inBoxes.hasFilters();
  resizeDiscarding(ranked_keys, n);
  resizeDiscarding(ranked_filters, filtered ? n : 0);
  const int third_axis = unusedAxis(config.primary_axis, config.secondary_axis);
  slab_grid = chooseSlabGrid(inBoxes, third_axis, config.third_axis_slabs, inThreads);
  const bool slabbed = slab_grid.count > 1;
  resizeDiscarding(ranked_slabs, slabbed ? n : 0);
  const double* third_low = inBoxes.lo[third_axis].data();
  const double* third_high = inBoxes.hi[third_axis].data();
  // Reads the boxes in input order (sequential streams of the SoA arrays) and writes each one's
  // record at its rank: one scattered write a box instead of six scattered reads.
  const RankRange* ranges_of_object = ranges.of_object.data();
#pragma omp parallel for num_threads(inThreads) schedule(static)
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t rank = ranges_of_object[i].rank;
    RankedKeys& keys = ranked_keys[rank];
    for (int axis = 0; axis < 3; ++axis) {
      keys.lo[axis] = lowKey(inBoxes.lo[axis][i]);
      keys.hi[axis] = highKey(inBoxes.hi[axis][i]);
    }
    if (slabbed)
      ranked_slabs[rank] = {static_cast<uint8_t>(slab_grid.slabOf(third_low[i])),
                            static_cast<uint8_t>(slab_grid.slabOf(third_high[i]))};
    if (filtered) ranked_filters[rank] = {inBoxes.group(i), inBoxes.mask(i)};
  }
}

void Broadphase::Impl::pair(const BoxSet& inBoxes, FramePath inPath, int inThreads) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  buildSecondaryStream(sweep_order.data(), n, ranges, inThreads, endpoint_words.data());
  PairingInput input;
  input.stream = endpoint_words.data();
  input.objects = n;
  input.object_of_rank = ranges.object_of_rank.data();
  input.keys = ranked_keys.data();
  input.boxes = config.exact_final_test ? &inBoxes : nullptr;
  input.filters = ranked_filters.empty() ? nullptr : ranked_filters.data();
  input.ids = inBoxes.ids.data();
  input.slabs = ranked_slabs.empty() ? nullptr : ranked_slabs.data();
  input.slab_count = slab_grid.count;
  stats.slabs = slab_grid.count;
  if (inPath == FramePath::kSequential) {
    pairs_per_thread.resize(1);
    pairs_per_thread[0].clear();
    pairSequential(input, workspace, pairs_per_thread[0]);
  } else {
    pairParallel(input, inThreads, workspace, pairs_per_thread);
  }
}

void Broadphase::Impl::sweepAndPrune(const BoxSet& inBoxes, FramePath inPath, int inThreads) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const int sort_threads = inPath == FramePath::kParallel ? inThreads : 1;
  const bool warm = bounds[config.primary_axis].from_previous_frame &&
                    bounds[config.secondary_axis].from_previous_frame;

  // The primary order is consumed by candidate generation before the secondary axis is
  // sorted, so both orders share one buffer (sweep_order).
  Clock::time_point phase = Clock::now();
  stats.dispersion_primary = sortAxis(inBoxes, config.primary_axis, sort_threads, sweep_order);
  stats.ms_sort = millisecondsSince(phase);

  phase = Clock::now();
  if (inPath == FramePath::kParallel) {
    computeCandidatesParallel(sweep_order.data(), n, inThreads, workspace, ranges);
  } else {
    computeCandidatesSequential(sweep_order.data(), n, sequential_tree, ranges);
  }
  stats.ms_candidates = millisecondsSince(phase);

  phase = Clock::now();
  stats.dispersion_secondary = sortAxis(inBoxes, config.secondary_axis, sort_threads, sweep_order);
  stats.ms_sort += millisecondsSince(phase) - stats.ms_keys;

  phase = Clock::now();
  gatherByRank(inBoxes, sort_threads);
  pair(inBoxes, inPath, sort_threads);
  stats.ms_pairing = millisecondsSince(phase);

  decideAxes(warm && config.axis_swapping && 2 * std::size_t{n} >= kMinPartitionedEndpoints);
}

void Broadphase::Impl::decideAxes(bool inWarm) {
  const AxisDecision decision =
      chooseAxes(config.primary_axis, config.secondary_axis, stats.dispersion_primary,
                 stats.dispersion_secondary, inWarm, config.axis_swap_threshold);
  stats.axes_swapped = decision.swapped;
  if (!decision.swapped) return;
  const int incoming =
      decision.primary != config.primary_axis ? decision.primary : decision.secondary;
  bounds[incoming].from_previous_frame = false;  // re-initialise B from the new axis's span
  config.primary_axis = decision.primary;
  config.secondary_axis = decision.secondary;
}

// A box with group 0 or mask 0 passes no filter: it is left out before the sweep. The copy is
// made only when such boxes exist.
const BoxSet& Broadphase::Impl::dropBoxesThatCollideWithNothing(const BoxSet& inBoxes) {
  if (!inBoxes.hasFilters()) return inBoxes;
  std::size_t excluded = 0;
  for (std::size_t i = 0; i < inBoxes.size(); ++i)
    excluded += inBoxes.group(i) == 0 || inBoxes.mask(i) == 0;
  stats.boxes_filtered_out = excluded;
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

// Bitwise comparison with the last swept frame (so -0.0 after 0.0 counts as a change).
bool Broadphase::Impl::sameAsPreviousFrame(const BoxSet& inBoxes) const {
  if (!previous_reusable || previous_boxes.size() != inBoxes.size()) return false;
  const auto same = [](const auto& inA, const auto& inB) {
    return inA.size() == inB.size() &&
           (inA.empty() || std::memcmp(inA.data(), inB.data(), inA.size() * sizeof inA[0]) == 0);
  };
  if (!same(previous_boxes.ids, inBoxes.ids) || !same(previous_boxes.groups, inBoxes.groups) ||
      !same(previous_boxes.masks, inBoxes.masks))
    return false;
  for (int axis = 0; axis < 3; ++axis)
    if (!same(previous_boxes.lo[axis], inBoxes.lo[axis]) ||
        !same(previous_boxes.hi[axis], inBoxes.hi[axis]))
      return false;
  return true;
}

void Broadphase::Impl::rememberFrame(const BoxSet& inBoxes, FramePath inPath) {
  previous_reusable = config.reuse_unchanged_frames && inPath != FramePath::kEmpty &&
                      inPath != FramePath::kBruteForce;
  if (!config.reuse_unchanged_frames && !config.index_static_boxes) {
    previous_valid = false;
    return;
  }
  const bool same_shape = previous_valid && static_split.compared() &&
                          previous_boxes.groups.size() == inBoxes.groups.size() &&
                          previous_boxes.masks.size() == inBoxes.masks.size();
  if (!same_shape) {
    previous_boxes = inBoxes;  // vectors keep their capacity
  } else {
    // Same ids in the same order: only the boxes that changed need copying.
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      if (static_split.unchanged(i)) continue;
      for (int axis = 0; axis < 3; ++axis) {
        previous_boxes.lo[axis][i] = inBoxes.lo[axis][i];
        previous_boxes.hi[axis][i] = inBoxes.hi[axis][i];
      }
      if (!inBoxes.groups.empty()) previous_boxes.groups[i] = inBoxes.groups[i];
      if (!inBoxes.masks.empty()) previous_boxes.masks[i] = inBoxes.masks[i];
    }
  }
  previous_valid = true;
}

void Broadphase::Impl::sweepIntoPairs(const BoxSet& inBoxes, FramePath inPath, int inThreads) {
  sweepAndPrune(inBoxes, inPath, inThreads);
  const Clock::time_point phase = Clock::now();
  // Each thread's pairs are disjoint from the others': merging them is the whole set. The
  // sweep order is dead by now: the sort borrows its memory for its histogram.
  std::swap(sweep_order, pair_scratch.offsets);
  sortPairsCanonical(pairs_per_thread, pairs, pair_scratch);
  std::swap(sweep_order, pair_scratch.offsets);
  stats.ms_output = millisecondsSince(phase);
}

// Skin reuse: test the kept candidates when every box is inside its skin, else sweep the
// grown boxes for new candidates first.
void Broadphase::Impl::skinFrame(const BoxSet& inBoxes, int inThreads) {
  Clock::time_point phase = Clock::now();
  if (skin_list.covers(inBoxes, inThreads)) {
    stats.path = FramePath::kSkin;
    stats.threads = inThreads;
  } else {
    skin_list.inflate(inBoxes, *config.skin, inflated);
    stats.ms_keys += millisecondsSince(phase);
    sweepIntoPairs(inflated, stats.path, inThreads);
    skin_list.adopt(inBoxes, pairs);
  }
  phase = Clock::now();
  skin_list.collect(inBoxes, inThreads, pairs);
  stats.ms_pairing += millisecondsSince(phase);
  stats.skin_candidates = skin_list.candidates();
}

// Static boxes: when the index covers part of the frame, sweep only the moving boxes and ask
// the index for their pairs with the resting ones.
bool Broadphase::Impl::staticFrame(const BoxSet& inBoxes, int inThreads) {
  if (!config.index_static_boxes || !previous_valid) return false;
  Clock::time_point phase = Clock::now();
  const bool split = static_split.prepare(inBoxes, previous_boxes, inThreads);
  stats.ms_keys += millisecondsSince(phase);
  if (!split) return false;
  const BoxSet& moving = static_split.moving();
  const FramePath sweep_path = choosePath(moving.size(), inThreads);
  if (sweep_path == FramePath::kSequential || sweep_path == FramePath::kParallel)
    sweepIntoPairs(moving, sweep_path, inThreads);
  else
    pairs = bruteForcePairs(moving);  // fewer than two boxes, or the brute-force method
  phase = Clock::now();
  static_split.crossPairs(inBoxes, inThreads, pairs);
  sortPairsCanonical(pairs, pair_scratch);
  stats.ms_pairing += millisecondsSince(phase);
  stats.path = FramePath::kStatic;
  stats.threads = inThreads;
  stats.static_boxes = static_split.indexedBoxes();
  return true;
}

// Pairs between this frame's boxes and the declared scenery, merged into canonical order.
void Broadphase::Impl::addDeclaredStaticPairs(const BoxSet& inBoxes, int inThreads) {
  if (declared_static.size() == 0 || inBoxes.size() == 0) return;
  const Clock::time_point phase = Clock::now();
  all_indexes.resize(inBoxes.size());
  for (std::size_t i = 0; i < all_indexes.size(); ++i) all_indexes[i] = static_cast<uint32_t>(i);
  const std::size_t before = pairs.size();
  declared_static.queryAll(inBoxes, all_indexes, inThreads, pairs);
  if (pairs.size() != before) sortPairsCanonical(pairs, pair_scratch);
  stats.static_boxes += declared_static.size();
  stats.ms_static = millisecondsSince(phase);
}

Broadphase::Broadphase(const BroadphaseConfig& inConfig) : impl_(std::make_unique<Impl>()) {
  if (auto problem = configProblem(inConfig)) throw std::invalid_argument(*problem);
  impl_->config = inConfig;
}

Broadphase::~Broadphase() = default;
Broadphase::Broadphase(Broadphase&&) noexcept = default;
Broadphase& Broadphase::operator=(Broadphase&&) noexcept = default;

const PairList& Broadphase::update(const BoxSet& inBoxes) {
  Impl& impl = *impl_;
  const Clock::time_point start = Clock::now();
  const int threads = resolveThreadCount(impl.config.threads);
  FrameReport& stats = impl.stats;
  const FrameReport previous_stats = stats;
  stats = FrameReport();
  stats.boxes = inBoxes.size();
  const BoxSet& boxes = impl.dropBoxesThatCollideWithNothing(inBoxes);
  stats.primary_axis = impl.config.primary_axis;
  stats.secondary_axis = impl.config.secondary_axis;
  stats.path = impl.choosePath(boxes.size(), threads);
  stats.threads = stats.path == FramePath::kParallel ? threads : 1;
  if ((stats.path == FramePath::kSequential || stats.path == FramePath::kParallel) &&
      impl.sameAsPreviousFrame(boxes)) {
    stats.path = FramePath::kReused;
    stats.threads = 1;
    stats.dispersion_primary = previous_stats.dispersion_primary;
    stats.dispersion_secondary = previous_stats.dispersion_secondary;
    stats.slabs = previous_stats.slabs;
  }

  switch (stats.path) {
    case FramePath::kEmpty:
      impl.pairs.clear();
      break;
    case FramePath::kReused:
      break;  // impl.pairs still holds this very frame's pairs
    case FramePath::kBruteForce: {
      const Clock::time_point phase = Clock::now();
      impl.pairs = bruteForcePairs(boxes);
      stats.ms_pairing = millisecondsSince(phase);
      break;
    }
    case FramePath::kSequential:
    case FramePath::kParallel:
      if (impl.staticFrame(boxes, threads)) break;
      if (impl.config.skin.value_or(0.0) > 0)
        impl.skinFrame(boxes, threads);
      else
        impl.sweepIntoPairs(boxes, stats.path, threads);
      break;
    case FramePath::kSkin:
    case FramePath::kStatic:
      break;  // decided and computed inside skinFrame() and staticFrame()
  }
  if (stats.path != FramePath::kReused) {
    impl.rememberFrame(boxes, stats.path);
    impl.addDeclaredStaticPairs(boxes, threads);
  } else {
    stats.static_boxes = previous_stats.static_boxes;
  }
  stats.pairs = impl.pairs.size();
  stats.ms_total = millisecondsSince(start);
  return impl.pairs;
}

void Broadphase::setStaticBoxes(const BoxSet& inStaticBoxes) {
  std::vector<uint32_t> every_box(inStaticBoxes.size());
  for (std::size_t i = 0; i < every_box.size(); ++i) every_box[i] = static_cast<uint32_t>(i);
  impl_->declared_static.build(inStaticBoxes, every_box, resolveThreadCount(impl_->config.threads));
  impl_->previous_reusable = false;  // the last pairs were computed against other scenery
}

void Broadphase::clearStaticBoxes() {
  impl_->declared_static = StaticIndex();
  impl_->previous_reusable = false;
}

std::size_t Broadphase::staticBoxCount() const {
  return impl_->declared_static.size();
}

const FrameReport& Broadphase::stats() const {
  return impl_->stats;
}
const BroadphaseConfig& Broadphase::config() const {
  return impl_->config;
}

void Broadphase::reset() {
  for (AxisBounds& axis_bounds : impl_->bounds) axis_bounds.from_previous_frame = false;
  impl_->previous_reusable = false;
  impl_->skin_list.clear();
  impl_->static_split.clear();
  impl_->previous_valid = false;
}

}  // namespace sap_broadphase
