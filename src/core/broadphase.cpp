#include "sap_broadphase/core/broadphase.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

#include "sap_broadphase/core/axis_policy.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/radix_sort.h"
#include "sap_broadphase/core/sort_keys.h"
#include "sap_broadphase/core/sweep.h"

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

void checkConfig(const BroadphaseConfig& inConfig) {
  const auto valid_axis = [](int axis) { return axis >= 0 && axis <= 2; };
  if (!valid_axis(inConfig.primary_axis) || !valid_axis(inConfig.secondary_axis) ||
      inConfig.primary_axis == inConfig.secondary_axis)
    throw std::invalid_argument("primary and secondary axes must be distinct values in 0..2");
  if (inConfig.threads < 0) throw std::invalid_argument("threads must be >= 0");
  if (inConfig.third_axis_slabs < 0 || inConfig.third_axis_slabs > kMaxSlabs)
    throw std::invalid_argument("third_axis_slabs must be in 0..64");
}

}  // namespace

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
  }
  return "unknown";
}

int resolveThreadCount(int inRequested) {
  return inRequested > 0 ? inRequested : std::max(1, omp_get_max_threads());
}

struct Broadphase::Impl {
  BroadphaseConfig config;
  FrameStats stats;
  AxisBounds bounds[3];
  PartitionedSorter sorter;
  std::vector<uint32_t> keys;
  std::vector<uint32_t> primary_order;
  std::vector<uint32_t> secondary_order;
  CandidateRanges ranges;
  std::vector<RankedBox> ranked_boxes;
  std::vector<RankedKeys> ranked_keys;
  std::vector<RankedFilter> ranked_filters;
  std::vector<RankedSlabs> ranked_slabs;
  std::vector<SecondaryEndpoint> secondary_stream;
  SlabGrid slab_grid;
  SweepWorkspace workspace;
  SuccTree sequential_tree;
  std::vector<PairList> pairs_per_thread;
  PairList pairs;
  PairSortScratch pair_scratch;
  BoxSet collidable;                   // the frame without boxes that can collide with nothing
  std::vector<uint32_t> previous_ids;  // ids of the last swept frame, by object index
  bool previous_reusable = false;      // the last frame's buffers describe its boxes exactly

  bool sameAsPreviousFrame(const BoxSet& inBoxes) const;
  void rememberFrame(const BoxSet& inBoxes, FramePath inPath);
  const BoxSet& dropBoxesThatCollideWithNothing(const BoxSet& inBoxes);

  FramePath choosePath(std::size_t inBoxes, int inThreads) const;
  double sortAxis(const BoxSet& inBoxes, int inAxis, int inThreads,
                  std::vector<uint32_t>& outOrder);
  void gatherByRank(const BoxSet& inBoxes, int inThreads);
  void pair(const BoxSet& inBoxes, FramePath inPath, int inThreads);
  void sweepAndPrune(const BoxSet& inBoxes, FramePath inPath, int inThreads);
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

// Keys of one axis (lows at i, highs at i + n), then Algorithm 2. Returns D.
double Broadphase::Impl::sortAxis(const BoxSet& inBoxes, int inAxis, int inThreads,
                                  std::vector<uint32_t>& outOrder) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const double* low = inBoxes.lo[inAxis].data();
  const double* high = inBoxes.hi[inAxis].data();
  const Clock::time_point start = Clock::now();
  keys.resize(2 * std::size_t{n});
  outOrder.resize(2 * std::size_t{n});
#pragma omp parallel for num_threads(inThreads) schedule(static)
  for (uint32_t i = 0; i < n; ++i) {
    keys[i] = lowKey(low[i]);
    keys[i + n] = highKey(high[i]);
  }
  stats.ms_keys += millisecondsSince(start);
  const int partitions = keys.size() >= kMinPartitionedEndpoints ? kSortPartitions : 1;
  return sorter.sort(keys.data(), 2 * n, partitions, inThreads, bounds[inAxis], outOrder.data());
}

// Box data in primary-rank order, so a candidate range is a contiguous stretch of memory.
void Broadphase::Impl::gatherByRank(const BoxSet& inBoxes, int inThreads) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const uint32_t* object_of_rank = ranges.object_of_rank.data();
  const bool filtered = inBoxes.hasFilters();
  if (config.exact_final_test)
    ranked_boxes.resize(n);
  else
    ranked_keys.resize(n);
  ranked_filters.resize(filtered ? n : 0);
  const int third_axis = unusedAxis(config.primary_axis, config.secondary_axis);
  slab_grid = chooseSlabGrid(inBoxes, third_axis, config.third_axis_slabs, inThreads);
  const bool slabbed = slab_grid.count > 1;
  ranked_slabs.resize(slabbed ? n : 0);
  const double* third_low = inBoxes.lo[third_axis].data();
  const double* third_high = inBoxes.hi[third_axis].data();
#pragma omp parallel for num_threads(inThreads) schedule(static)
  for (uint32_t rank = 0; rank < n; ++rank) {
    const uint32_t i = object_of_rank[rank];
    if (slabbed)
      ranked_slabs[rank] = {static_cast<uint8_t>(slab_grid.slabOf(third_low[i])),
                            static_cast<uint8_t>(slab_grid.slabOf(third_high[i]))};
    for (int axis = 0; axis < 3; ++axis) {
      if (config.exact_final_test) {
        ranked_boxes[rank].lo[axis] = inBoxes.lo[axis][i];
        ranked_boxes[rank].hi[axis] = inBoxes.hi[axis][i];
      } else {
        ranked_keys[rank].lo[axis] = lowKey(inBoxes.lo[axis][i]);
        ranked_keys[rank].hi[axis] = highKey(inBoxes.hi[axis][i]);
      }
    }
    if (filtered) ranked_filters[rank] = {inBoxes.group(i), inBoxes.mask(i)};
  }
}

void Broadphase::Impl::pair(const BoxSet& inBoxes, FramePath inPath, int inThreads) {
  buildSecondaryStream(secondary_order.data(), static_cast<uint32_t>(inBoxes.size()), ranges,
                       ranked_slabs.empty() ? nullptr : ranked_slabs.data(), inThreads,
                       secondary_stream);
  PairingInput input;
  input.stream = secondary_stream.data();
  input.objects = static_cast<uint32_t>(inBoxes.size());
  input.object_of_rank = ranges.object_of_rank.data();
  input.boxes = config.exact_final_test ? ranked_boxes.data() : nullptr;
  input.keys = config.exact_final_test ? nullptr : ranked_keys.data();
  input.filters = ranked_filters.empty() ? nullptr : ranked_filters.data();
  input.ids = inBoxes.ids.data();
  input.slabs = ranked_slabs.empty() ? nullptr : ranked_slabs.data();
  input.slab_count = slab_grid.count;
  stats.slabs = slab_grid.count;
  pairs.clear();
  if (inPath == FramePath::kSequential) {
    pairSequential(input, workspace, pairs);
    return;
  }
  pairParallel(input, inThreads, workspace, pairs_per_thread);
  // Each thread's pairs are disjoint from the others': concatenation is the whole set.
  std::vector<std::size_t> offsets(pairs_per_thread.size() + 1, 0);
  for (std::size_t t = 0; t < pairs_per_thread.size(); ++t)
    offsets[t + 1] = offsets[t] + pairs_per_thread[t].size();
  pairs.resize(offsets.back());
#pragma omp parallel for num_threads(inThreads) schedule(static, 1)
  for (std::size_t t = 0; t < pairs_per_thread.size(); ++t)
    std::copy(pairs_per_thread[t].begin(), pairs_per_thread[t].end(), pairs.begin() + offsets[t]);
}

void Broadphase::Impl::sweepAndPrune(const BoxSet& inBoxes, FramePath inPath, int inThreads) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const int sort_threads = inPath == FramePath::kParallel ? inThreads : 1;
  const bool warm = bounds[config.primary_axis].from_previous_frame &&
                    bounds[config.secondary_axis].from_previous_frame;

  Clock::time_point phase = Clock::now();
  stats.dispersion_primary = sortAxis(inBoxes, config.primary_axis, sort_threads, primary_order);
  stats.dispersion_secondary =
      sortAxis(inBoxes, config.secondary_axis, sort_threads, secondary_order);
  stats.ms_sort = millisecondsSince(phase) - stats.ms_keys;

  phase = Clock::now();
  if (inPath == FramePath::kParallel) {
    computeCandidatesParallel(primary_order.data(), n, inThreads, workspace, ranges);
  } else {
    computeCandidatesSequential(primary_order.data(), n, sequential_tree, ranges);
  }
  stats.ms_candidates = millisecondsSince(phase);

  phase = Clock::now();
  gatherByRank(inBoxes, sort_threads);
  pair(inBoxes, inPath, sort_threads);
  stats.ms_pairing = millisecondsSince(phase);

  decideAxes(warm && config.axis_swapping && keys.size() >= kMinPartitionedEndpoints);
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

// Exact comparison with the last swept frame, through the rank-ordered copies the pipeline
// keeps anyway (bounds, filters) plus the previous ids: no second copy of the input is held.
bool Broadphase::Impl::sameAsPreviousFrame(const BoxSet& inBoxes) const {
  const std::size_t n = inBoxes.size();
  if (!previous_reusable || previous_ids.size() != n) return false;
  if (inBoxes.hasFilters() != !ranked_filters.empty()) return false;
  if (!std::equal(previous_ids.begin(), previous_ids.end(), inBoxes.ids.begin())) return false;
  const uint32_t* object_of_rank = ranges.object_of_rank.data();
  for (std::size_t rank = 0; rank < n; ++rank) {
    const uint32_t i = object_of_rank[rank];
    const RankedBox& box = ranked_boxes[rank];
    for (int axis = 0; axis < 3; ++axis) {
      // Bitwise equality: -0.0 and 0.0 give the same pairs, but a changed bit is a change.
      if (std::memcmp(&box.lo[axis], &inBoxes.lo[axis][i], sizeof(double)) != 0 ||
          std::memcmp(&box.hi[axis], &inBoxes.hi[axis][i], sizeof(double)) != 0)
        return false;
    }
    if (!ranked_filters.empty() && (ranked_filters[rank].group != inBoxes.group(i) ||
                                    ranked_filters[rank].mask != inBoxes.mask(i)))
      return false;
  }
  return true;
}

void Broadphase::Impl::rememberFrame(const BoxSet& inBoxes, FramePath inPath) {
  previous_reusable = config.reuse_unchanged_frames && config.exact_final_test &&
                      (inPath == FramePath::kSequential || inPath == FramePath::kParallel);
  if (previous_reusable) previous_ids.assign(inBoxes.ids.begin(), inBoxes.ids.end());
}

Broadphase::Broadphase(const BroadphaseConfig& inConfig) : impl_(std::make_unique<Impl>()) {
  checkConfig(inConfig);
  impl_->config = inConfig;
}

Broadphase::~Broadphase() = default;
Broadphase::Broadphase(Broadphase&&) noexcept = default;
Broadphase& Broadphase::operator=(Broadphase&&) noexcept = default;

const PairList& Broadphase::update(const BoxSet& inBoxes) {
  Impl& impl = *impl_;
  const Clock::time_point start = Clock::now();
  const int threads = resolveThreadCount(impl.config.threads);
  FrameStats& stats = impl.stats;
  const FrameStats previous_stats = stats;
  stats = FrameStats();
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
    case FramePath::kParallel: {
      impl.sweepAndPrune(boxes, stats.path, threads);
      const Clock::time_point phase = Clock::now();
      sortPairsCanonical(impl.pairs, impl.pair_scratch);
      stats.ms_output = millisecondsSince(phase);
      break;
    }
  }
  if (stats.path != FramePath::kReused) impl.rememberFrame(boxes, stats.path);
  stats.pairs = impl.pairs.size();
  stats.ms_total = millisecondsSince(start);
  return impl.pairs;
}

const FrameStats& Broadphase::stats() const {
  return impl_->stats;
}
const BroadphaseConfig& Broadphase::config() const {
  return impl_->config;
}

void Broadphase::reset() {
  for (AxisBounds& axis_bounds : impl_->bounds) axis_bounds.from_previous_frame = false;
  impl_->previous_reusable = false;
}

}  // namespace sap_broadphase
