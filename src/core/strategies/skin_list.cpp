#include "core/strategies/skin_list.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/assert.h"
#include "core/runner/buffers.h"
#include "core/runner/work_units.h"
#include "core/strategies/ordered_units.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/sort_keys.h"
#include "core/tuning.h"

namespace sap_broadphase {
namespace {

/// Box i of inBoxes as a record (lane 3 zero).
BoundsRecord recordOf(const BoxColumns& inBoxes, std::size_t i) {
  return {{inBoxes.lo[0][i], inBoxes.lo[1][i], inBoxes.lo[2][i], 0.0},
          {inBoxes.hi[0][i], inBoxes.hi[1][i], inBoxes.hi[2][i], 0.0}};
}

/// std::nextafter(inValue, -infinity) without the library call: the next double below (NaN and
/// -infinity stay as they are).
inline double nextBelow(double inValue) {
  if (!(inValue > -std::numeric_limits<double>::infinity())) return inValue;
  if (inValue == 0.0) return -std::numeric_limits<double>::denorm_min();
  uint64_t bits;
  std::memcpy(&bits, &inValue, sizeof(bits));
  bits = inValue > 0.0 ? bits - 1 : bits + 1;
  std::memcpy(&inValue, &bits, sizeof(bits));
  return inValue;
}

/// std::nextafter(inValue, +infinity) likewise.
inline double nextAbove(double inValue) {
  return -nextBelow(-inValue);
}

/// True when box i of inBoxes lies inside box i of inOuter (closed: equal bounds are inside).
inline bool boxInside(const BoxColumns& inBoxes, const BoxColumns& inOuter, std::size_t i) {
  bool inside = true;
  for (int axis = 0; axis < 3; ++axis)
    inside &=
        (inBoxes.lo[axis][i] >= inOuter.lo[axis][i]) & (inBoxes.hi[axis][i] <= inOuter.hi[axis][i]);
  return inside;
}

/// True when the two boxes overlap on all three axes (closed intervals), as boxesOverlap().
/// With SSE2 (every x86-64): the lanes (x, y) and (z, 0) of the four bounds compared two at a
/// time, one mask for all; elsewhere the same comparisons lane by lane without branches.
inline bool recordsOverlap(const BoundsRecord& inA, const BoundsRecord& inB) {
#if defined(__SSE2__)
  const auto overlapping = [&](int inLane) {
    return _mm_and_pd(_mm_cmple_pd(_mm_load_pd(inA.lo + inLane), _mm_load_pd(inB.hi + inLane)),
                      _mm_cmple_pd(_mm_load_pd(inB.lo + inLane), _mm_load_pd(inA.hi + inLane)));
  };
  return _mm_movemask_pd(_mm_and_pd(overlapping(0), overlapping(2))) == 0x3;
#else
  bool overlap = true;
  for (int lane = 0; lane < 4; ++lane)
    overlap &= (inA.lo[lane] <= inB.hi[lane]) & (inB.lo[lane] <= inA.hi[lane]);
  return overlap;
#endif
}

/// The box index of an id of the reference: a table indexed by id when the ids are dense
/// (the usual 0..n-1), else open addressing with linear probing in twice the boxes' room.
class IndexOfId {
 public:
  explicit IndexOfId(const std::vector<uint32_t>& inIds) {
    const std::size_t n = inIds.size();
    const WorkUnits units{n};
    const uint32_t largest = reduceOverItems(
        units, uint32_t{0},
        [&](std::size_t inBegin, std::size_t inEnd) {
          return *std::max_element(inIds.begin() + static_cast<std::ptrdiff_t>(inBegin),
                                   inIds.begin() + static_cast<std::ptrdiff_t>(inEnd));
        },
        [](uint32_t& ioAll, const uint32_t& inPart) { ioAll = std::max(ioAll, inPart); });
    dense_ = largest < 4 * n + 1024;
    if (dense_) {
      // Ids are distinct: each unit writes its own slots, and only ids' slots are ever read.
      resizeDiscarding(slots_, std::size_t{largest} + 1);
      runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
        for (std::size_t i = inBegin; i < inEnd; ++i) slots_[inIds[i]] = static_cast<uint32_t>(i);
      });
      return;
    }
    while ((std::size_t{1} << shift_bits_) < 2 * n) ++shift_bits_;
    slots_.assign(std::size_t{2} << shift_bits_, kEmpty);  // (id, index) per slot
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t slot = home(inIds[i]);
      while (slots_[2 * slot + 1] != kEmpty) slot = next(slot);
      slots_[2 * slot] = inIds[i];
      slots_[2 * slot + 1] = static_cast<uint32_t>(i);
    }
  }
  /// The index of inId (which must be one of the ids).
  uint32_t operator()(uint32_t inId) const {
    if (dense_) return slots_[inId];
    std::size_t slot = home(inId);
    while (slots_[2 * slot] != inId || slots_[2 * slot + 1] == kEmpty) slot = next(slot);
    return slots_[2 * slot + 1];
  }

 private:
  static constexpr uint32_t kEmpty = std::numeric_limits<uint32_t>::max();  // > kMaxBoxes
  std::size_t home(uint32_t inId) const {
    return (uint64_t{inId} * 0x9E3779B97F4A7C15ull) >> (64 - shift_bits_);
  }
  std::size_t next(std::size_t inSlot) const {
    return (inSlot + 1) & ((std::size_t{1} << shift_bits_) - 1);
  }
  Buffer<uint32_t> slots_;
  int shift_bits_ = 1;
  bool dense_ = true;
};

/// The axis along which the finite lower bounds of inMembers spread widest: sorting along it
/// puts the fewest boxes between a box and its partners.
int widestAxis(const BoxColumns& inBoxes, const Buffer<uint32_t>& inMembers) {
  const AxisRanges spread = reduceOverItems(
      WorkUnits{inMembers.size()}, AxisRanges(),
      [&](std::size_t inBegin, std::size_t inEnd) {
        AxisRanges part;
        for (int axis = 0; axis < 3; ++axis) {
          const double* low = inBoxes.lo[axis].data();
          for (std::size_t j = inBegin; j < inEnd; ++j) {
            const double value = low[inMembers[j]];
            if (!std::isfinite(value)) continue;
            part.low[axis] = std::min(part.low[axis], value);
            part.high[axis] = std::max(part.high[axis], value);
          }
        }
        return part;
      },
      [](AxisRanges& ioAll, const AxisRanges& inPart) { ioAll.add(inPart); });
  int widest = 0;
  double widest_spread = -1.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (spread.high[axis] - spread.low[axis] > widest_spread) {
      widest = axis;
      widest_spread = spread.high[axis] - spread.low[axis];
    }
  }
  return widest;
}

constexpr int kPrefetchAhead = static_cast<int>(tuning::kSkinPrefetchAhead);

/// Start of part inPart of inParts contiguous ranges of [0, inCount), as even as integers allow.
std::size_t shareBegin(std::size_t inCount, int inPart, int inParts) {
  return inCount * static_cast<std::size_t>(inPart) / static_cast<std::size_t>(inParts);
}

/// Elements [inBegin, inEnd) of two vectors of equal size are bit for bit the same (absent
/// groups or masks: both empty).
bool sameSlice(const std::vector<uint32_t>& inA, const std::vector<uint32_t>& inB,
               std::size_t inBegin, std::size_t inEnd) {
  return inA.empty() || std::memcmp(inA.data() + inBegin, inB.data() + inBegin,
                                    (inEnd - inBegin) * sizeof(uint32_t)) == 0;
}

template <typename Vector>
std::size_t bytesOf(const Vector& inVector) {
  return inVector.capacity() * sizeof(typename Vector::value_type);
}

}  // namespace

void SkinList::releaseCandidates() {
  PairList().swap(canonical_pairs_);
  Buffer<uint32_t>().swap(position_of_);
  Buffer<uint32_t>().swap(run_begin_);
  Buffer<uint32_t>().swap(partner_positions_);
  Buffer<uint32_t>().swap(canonical_slots_);
  Buffer<BoundsRecord>().swap(gathered_);
  Buffer<uint64_t>().swap(verdicts_);
  spatial_count_ = 0;
  valid_ = frame_gathered_ = false;
}

SkinList::MemoryUse SkinList::memoryUse() const {
  MemoryUse use;
  use.reference = bytesOf(reference_.ids) + bytesOf(reference_.groups) + bytesOf(reference_.masks);
  for (int axis = 0; axis < 3; ++axis)
    use.reference += bytesOf(reference_.lo[axis]) + bytesOf(reference_.hi[axis]);
  use.candidates = bytesOf(canonical_pairs_) + bytesOf(partner_positions_) +
                   bytesOf(canonical_slots_) + bytesOf(run_begin_) + bytesOf(position_of_);
  use.pass = bytesOf(gathered_) + bytesOf(verdicts_);
  use.scratch = adopt_scratch_bytes_;
  return use;
}

std::size_t SkinList::scratchBytes() const {
  return bytesOf(scratch_.has_candidates) + bytesOf(scratch_.members) + bytesOf(scratch_.keys) +
         bytesOf(scratch_.order) + bytesOf(scratch_.fill);
}

bool SkinList::covers(const BoxColumns& inBoxes) const {
  if (!valid_ || !sameCounts(inBoxes)) return false;
  const std::size_t n = inBoxes.size();
  return reduceOverItems(
      WorkUnits{n}, true,
      [&](std::size_t inBegin, std::size_t inEnd) {
        bool inside = sameIdsAndFilters(inBoxes, inBegin, inEnd);
        for (std::size_t i = inBegin; i < inEnd && inside; ++i)
          inside = boxInside(inBoxes, reference_, i);
        return inside;
      },
      [](bool& ioAll, bool inUnit) { ioAll = ioAll && inUnit; });
}

const BoxColumns& SkinList::inflate(const BoxColumns& inBoxes, double inSkin) {
  const double margin = inSkin / 2;
  const std::size_t n = inBoxes.size();
  releaseCandidates();  // dead from here until adopt(): the grown sweep's peak does without them
  reference_.ids = inBoxes.ids;
  reference_.groups = inBoxes.groups;
  reference_.masks = inBoxes.masks;
  for (int axis = 0; axis < 3; ++axis) {
    resizeDiscarding(reference_.lo[axis], inBoxes.size());
    resizeDiscarding(reference_.hi[axis], inBoxes.size());
  }
  runOverItems(WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (int axis = 0; axis < 3; ++axis) {
      const double* low = inBoxes.lo[axis].data();
      const double* high = inBoxes.hi[axis].data();
      double* grown_low = reference_.lo[axis].data();
      double* grown_high = reference_.hi[axis].data();
      for (std::size_t i = inBegin; i < inEnd; ++i) {
        // One step further out than the rounded sum: the inflated box contains the exact one.
        grown_low[i] = nextBelow(low[i] - margin);
        grown_high[i] = nextAbove(high[i] + margin);
      }
    }
  });
  valid_ = false;  // until adopt() receives this sweep's candidates
  frame_gathered_ = false;
  return reference_;
}

void SkinList::keepOverlapping(const BoxColumns& inBoxes, PairList& ioPairs) {
  const IndexOfId index_of(inBoxes.ids);
  std::size_t kept = 0;
  for (const IdPair& pair : ioPairs) {
    const uint32_t a = index_of(pair.a);
    const uint32_t b = index_of(pair.b);
    if (recordsOverlap(recordOf(inBoxes, a), recordOf(inBoxes, b))) ioPairs[kept++] = pair;
  }
  ioPairs.resize(kept);
}

void SkinList::adopt(const BoxColumns& inBoxes, const PairList& inCandidates) {
  adopt(inBoxes, PairList(inCandidates));
}

void SkinList::adopt(const BoxColumns& inBoxes, PairList&& ioCandidates) {
  startAdopt(std::move(ioCandidates));
  while (!continueAdopt(inBoxes)) {
  }
}

void SkinList::startAdopt(PairList&& ioCandidates) {
  if (ioCandidates.size() > std::numeric_limits<uint32_t>::max())
    throw std::length_error("skin reuse keeps fewer than 2^32 candidate pairs");
  canonical_pairs_.swap(ioCandidates);
  PairList().swap(ioCandidates);  // the last candidates' memory, before the new ones' arrays
  valid_ = frame_gathered_ = false;
  adopt_step_ = 0;
}

// The parts of adopt(), each a pass over the candidates or the boxes.
bool SkinList::continueAdopt(const BoxColumns& inBoxes) {
  switch (adopt_step_++) {
    case 0:
      keepBoxIndexes(inBoxes);
      return false;
    case 1:
      keepSpatialOrder();
      return false;
    case 2:
      keepSpatialCandidates();
      return false;
    default:
      break;
  }
  sortRunsByPartner();
  adopt_scratch_bytes_ = scratchBytes();
  scratch_ = AdoptScratch();  // dead until the next adopt(): not held through the frames between
  valid_ = true;
  SAP_ASSERT(covers(inBoxes), "a box outside its grown box in the skin list");
  SAP_ASSERT(holdsEveryCandidate(), "a kept candidate whose box has no spatial position");
  return true;
}

bool SkinList::sameCandidates(const SkinList& inOther) const {
  return valid_ == inOther.valid_ && spatial_count_ == inOther.spatial_count_ &&
         canonical_pairs_ == inOther.canonical_pairs_ && position_of_ == inOther.position_of_ &&
         run_begin_ == inOther.run_begin_ && partner_positions_ == inOther.partner_positions_ &&
         canonical_slots_ == inOther.canonical_slots_;
}

bool SkinList::holdsEveryCandidate() const {
  const std::size_t count = canonical_pairs_.size();
  if (partner_positions_.size() != count || canonical_slots_.size() != count ||
      run_begin_.size() != std::size_t{spatial_count_} + 1 || run_begin_[spatial_count_] != count)
    return false;
  for (uint32_t first = 0; first < spatial_count_; ++first) {
    for (uint32_t k = run_begin_[first]; k < run_begin_[first + 1]; ++k) {
      const bool ordered =
          k == run_begin_[first] || partner_positions_[k - 1] < partner_positions_[k];
      if (!(first < partner_positions_[k] && partner_positions_[k] < spatial_count_ && ordered))
        return false;
    }
  }
  return true;
}

// The box indexes of each candidate's boxes, held in the arrays that later hold its spatial
// order (canonical_slots_: first box, partner_positions_: second box), so that sorting the
// candidates needs no list of its own.
void SkinList::keepBoxIndexes(const BoxColumns& inBoxes) {
  const std::size_t count = canonical_pairs_.size();
  const IndexOfId index_of(inBoxes.ids);
  resizeDiscarding(canonical_slots_, count);
  resizeDiscarding(partner_positions_, count);
  runOverItems(WorkUnits{count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) {
      canonical_slots_[k] = index_of(canonical_pairs_[k].a);
      partner_positions_[k] = index_of(canonical_pairs_[k].b);
    }
  });
}

// The boxes that have candidates, sorted by their inflated lower bound's sort key along the
// widest axis: partners overlap along that axis too, so they sit a few thousand positions
// apart at most.
void SkinList::keepSpatialOrder() {
  const std::size_t n = reference_.size();
  const std::size_t count = canonical_pairs_.size();
  Buffer<uint8_t>& has_candidates = scratch_.has_candidates;
  has_candidates.assign(n, 0);
  uint8_t* has = has_candidates.data();
  // Units of candidates may mark the same box: each mark is a relaxed atomic store of the same
  // value, so the marks are the same whichever unit writes last.
  runOverItems(WorkUnits{count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) {
      __atomic_store_n(has + canonical_slots_[k], uint8_t{1}, __ATOMIC_RELAXED);
      __atomic_store_n(has + partner_positions_[k], uint8_t{1}, __ATOMIC_RELAXED);
    }
  });
  Buffer<uint32_t>& members = scratch_.members;
  members.clear();
  appendItemsWhere(
      WorkUnits{n}, [&](std::size_t inBox) { return has[inBox] != 0; }, members);
  const auto spatial_count = static_cast<uint32_t>(members.size());
  const int axis = widestAxis(reference_, members);
  Buffer<uint32_t>& keys = scratch_.keys;
  Buffer<uint32_t>& order = scratch_.order;
  resizeDiscarding(keys, spatial_count);
  resizeDiscarding(order, spatial_count);
  const double* low = reference_.lo[axis].data();
  runOverItems(WorkUnits{spatial_count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t j = inBegin; j < inEnd; ++j) keys[j] = lowKey(low[members[j]]);
  });
  indexesByKey(keys.data(), spatial_count, order.data());
  resizeDiscarding(position_of_, n);
  runOverItems(WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
    std::fill(position_of_.begin() + static_cast<std::ptrdiff_t>(inBegin),
              position_of_.begin() + static_cast<std::ptrdiff_t>(inEnd), spatial_count);
  });
  runOverItems(WorkUnits{spatial_count}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t position = inBegin; position < inEnd; ++position)
      position_of_[members[order[position]]] = static_cast<uint32_t>(position);
  });
  spatial_count_ = spatial_count;
}

// The candidates by first position, a counting sort: the box indexes become positions in
// place, then one scatter puts each partner at its candidate's place (in a scratch list of the
// candidates' size, the only one adopt() needs) and leaves the place in the candidate's slot
// entry, which the slots' own scatter then reads.
//
// On several threads the counts and the places are taken with atomic additions, so the order
// of a run's candidates depends on the threads until sortRunsByPartner() sorts each run by
// partner: a run's partners differ (the candidates are distinct pairs), so the sorted runs, and
// the slots they carry, are the same for any thread count. One thread counts without atomics.
void SkinList::keepSpatialCandidates() {
  const std::size_t count = canonical_pairs_.size();
  const std::size_t spatial_count = spatial_count_;
  uint32_t* first_of = canonical_slots_.data();  // first box index in, first position out
  uint32_t* partner_of = partner_positions_.data();
  resizeDiscarding(run_begin_, spatial_count + 1);
  std::fill(run_begin_.begin(), run_begin_.end(), 0u);
  uint32_t* run_count = run_begin_.data() + 1;
  const bool shared = passThreads() > 1;
  const WorkUnits units{count};
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) {
      const uint32_t a = position_of_[first_of[k]];
      const uint32_t b = position_of_[partner_of[k]];
      first_of[k] = std::min(a, b);
      partner_of[k] = std::max(a, b);
      if (shared)
        __atomic_fetch_add(run_count + first_of[k], 1u, __ATOMIC_RELAXED);
      else
        ++run_count[first_of[k]];
    }
  });
  prefixSumInUnits(run_count, spatial_count);
  Buffer<uint32_t>& fill = scratch_.fill;  // by first position: its next candidate's place
  resizeDiscarding(fill, spatial_count);
  runOverItems(WorkUnits{spatial_count}, [&](std::size_t inBegin, std::size_t inEnd) {
    std::copy(run_begin_.begin() + static_cast<std::ptrdiff_t>(inBegin),
              run_begin_.begin() + static_cast<std::ptrdiff_t>(inEnd),
              fill.begin() + static_cast<std::ptrdiff_t>(inBegin));
  });
  Buffer<uint32_t>& placed = scratch_.members;  // reused: the members are sorted already
  resizeDiscarding(placed, count);
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) {
      const uint32_t place =
          shared ? __atomic_fetch_add(fill.data() + first_of[k], 1u, __ATOMIC_RELAXED)
                 : fill[first_of[k]]++;
      placed[place] = partner_of[k];
      first_of[k] = place;  // from here on: candidate k's place
    }
  });
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    std::copy(placed.begin() + static_cast<std::ptrdiff_t>(inBegin),
              placed.begin() + static_cast<std::ptrdiff_t>(inEnd),
              partner_positions_.begin() + static_cast<std::ptrdiff_t>(inBegin));
  });
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) placed[first_of[k]] = static_cast<uint32_t>(k);
  });
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    std::copy(placed.begin() + static_cast<std::ptrdiff_t>(inBegin),
              placed.begin() + static_cast<std::ptrdiff_t>(inEnd),
              canonical_slots_.begin() + static_cast<std::ptrdiff_t>(inBegin));
  });
}

// Each run of one first position sorted by partner, its slots carried along: runs hold a few
// candidates (an insertion sort), rarely many (a box that meets most others: a sort of packed
// words).
void SkinList::sortRunsByPartner() {
  constexpr uint32_t kShortRun = 32;
  uint32_t* partner = partner_positions_.data();
  uint32_t* slot = canonical_slots_.data();
  runOverItems(WorkUnits{spatial_count_}, [&](std::size_t inBegin, std::size_t inEnd) {
    std::vector<uint64_t> packed;
    for (std::size_t first = inBegin; first < inEnd; ++first) {
      const uint32_t begin = run_begin_[first], end = run_begin_[first + 1];
      if (end - begin <= kShortRun) {
        for (uint32_t k = begin + 1; k < end; ++k) {
          const uint32_t key = partner[k], carried = slot[k];
          uint32_t j = k;
          for (; j > begin && partner[j - 1] > key; --j) {
            partner[j] = partner[j - 1];
            slot[j] = slot[j - 1];
          }
          partner[j] = key;
          slot[j] = carried;
        }
        continue;
      }
      packed.clear();
      for (uint32_t k = begin; k < end; ++k) packed.push_back(uint64_t{partner[k]} << 32 | slot[k]);
      std::sort(packed.begin(), packed.end());
      for (uint32_t k = begin; k < end; ++k) {
        partner[k] = static_cast<uint32_t>(packed[k - begin] >> 32);
        slot[k] = static_cast<uint32_t>(packed[k - begin]);
      }
    }
  });
}

bool SkinList::gather(const BoxColumns& inBoxes) {
  frame_gathered_ = valid_ && sameCounts(inBoxes) && gatherInside(inBoxes);
  return frame_gathered_;
}

void SkinList::collectGathered(PairList& outPairs) {
  SAP_ASSERT(frame_gathered_, "kept candidates tested without a frame gathered inside their skin");
  frame_gathered_ = false;
  testSpatialCandidates();
  copyHits(outPairs);
}

bool SkinList::sameCounts(const BoxColumns& inBoxes) const {
  return reference_.ids.size() == inBoxes.ids.size() &&
         reference_.groups.size() == inBoxes.groups.size() &&
         reference_.masks.size() == inBoxes.masks.size();
}

// Boxes [inBegin, inEnd) have the reference's ids, groups and masks (after sameCounts()): each
// thread compares its own slice, so that no serial pass over the ids grows with the frame.
bool SkinList::sameIdsAndFilters(const BoxColumns& inBoxes, std::size_t inBegin,
                                 std::size_t inEnd) const {
  return sameSlice(reference_.ids, inBoxes.ids, inBegin, inEnd) &&
         sameSlice(reference_.groups, inBoxes.groups, inBegin, inEnd) &&
         sameSlice(reference_.masks, inBoxes.masks, inBegin, inEnd);
}

// The containment check fused with the gather into spatial order, each block's ids and filters
// compared first (after sameCounts()): inBoxes and the reference are read in index order, each box
// written once at its position (boxes without candidates onto their thread's scratch record behind
// the positions, which stays in the cache). Blocks of boxes end the pass early when one box has
// left its skin.
bool SkinList::gatherInside(const BoxColumns& inBoxes) {
  constexpr std::size_t kBlock = tuning::kGatherBlockBoxes;
  const std::size_t n = inBoxes.size();
  resizeDiscarding(gathered_, std::size_t{spatial_count_} + std::max(1, passThreads()));
  const uint32_t* position_of = position_of_.data();
  BoundsRecord* gathered = gathered_.data();
  const uint32_t scratch = spatial_count_;
  std::atomic<bool> inside{true};
  runOverItems(WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
    const int thread = currentWorker();  // its scratch record (0 when run inline)
    bool mine = inside.load(std::memory_order_relaxed);
    for (std::size_t block = inBegin; mine && block < inEnd; block += kBlock) {
      const std::size_t block_end = std::min(inEnd, block + kBlock);
      mine = sameIdsAndFilters(inBoxes, block, block_end);
      for (std::size_t i = block; i < block_end; ++i) {
        // The line written kPrefetchAhead boxes later is fetched now, so that the scattered
        // stores do not wait for their lines one by one.
        if (i + kPrefetchAhead < block_end)
          __builtin_prefetch(gathered + position_of[i + kPrefetchAhead], 1);
        mine &= boxInside(inBoxes, reference_, i);
        const uint32_t position = position_of[i];
        gathered[position == scratch ? position + thread : position] = recordOf(inBoxes, i);
      }
    }
    if (!mine) inside.store(false, std::memory_order_relaxed);
  });
  return inside.load();
}

// In (first, partner) order: the first box's record is read again and again, the partner's
// lies a little further on; the verdict goes to the candidate's canonical slot.
void SkinList::testSpatialCandidates() {
  const auto count = static_cast<std::ptrdiff_t>(partner_positions_.size());
  const std::size_t words = verdictWords();
  resizeDiscarding(verdicts_, words * static_cast<std::size_t>(std::max(1, passThreads())));
  const uint32_t* run_begin = run_begin_.data();
  const uint32_t* partner = partner_positions_.data();
  const uint32_t* slot = canonical_slots_.data();
  const BoundsRecord* gathered = gathered_.data();
  const WorkUnits units{static_cast<std::size_t>(count)};
  verdict_rows_ = teamForUnits(units.count(), passThreads());
  std::fill(verdicts_.begin(), verdicts_.begin() + words * verdict_rows_, 0);
  runOverItems(units, [&](std::size_t inBegin, std::size_t inEnd) {
    // Each worker sets bits in its own row (row 0 when run inline); copyHits merges them.
    uint64_t* verdicts = verdicts_.data() + words * static_cast<std::size_t>(currentWorker());
    const auto end = static_cast<std::ptrdiff_t>(inEnd);
    // The first position of candidate inBegin: the last run that starts at or before it.
    uint32_t first = static_cast<uint32_t>(
        std::upper_bound(run_begin, run_begin + spatial_count_ + 1, inBegin) - run_begin - 1);
    for (auto k = static_cast<std::ptrdiff_t>(inBegin); k < end; ++k) {
      while (run_begin[first + 1] <= k) ++first;  // empty runs are skipped too
      // Partners lie ahead of the first box, mostly in lines no candidate has read yet, and
      // the verdict bits of consecutive candidates lie anywhere in the bit set.
      if (k + kPrefetchAhead < end) {
        __builtin_prefetch(gathered + partner[k + kPrefetchAhead]);
        __builtin_prefetch(verdicts + slot[k + kPrefetchAhead] / 64, 1);
      }
      const uint64_t overlap = recordsOverlap(gathered[first], gathered[partner[k]]);
      verdicts[slot[k] / 64] |= overlap << (slot[k] % 64);
    }
  });
}

// Canonical candidates whose verdict is set, in order: the words are cut into shares (more
// than threads, claimed dynamically); each share's verdict rows are merged and counted, then
// its hits copied behind the shares before it, so the list is the same for any thread count.
void SkinList::copyHits(PairList& outPairs) {
  const std::size_t words = verdictWords();
  const int shares = unitsForThreads(passThreads());
  std::vector<std::size_t> share_start(static_cast<std::size_t>(shares) + 1, 0);
  uint64_t* merged = verdicts_.data();  // the first row receives the others'
  runUnits(shares, [&](std::size_t inShare) {
    const int share = static_cast<int>(inShare);
    std::size_t hits = 0;
    for (std::size_t word = shareBegin(words, share, shares);
         word < shareBegin(words, share + 1, shares); ++word) {
      for (int row = 1; row < verdict_rows_; ++row) merged[word] |= merged[words * row + word];
      hits += static_cast<std::size_t>(__builtin_popcountll(merged[word]));
    }
    share_start[share + 1] = hits;
  });
  for (int share = 0; share < shares; ++share) share_start[share + 1] += share_start[share];
  resizeDiscarding(outPairs, share_start[shares]);
  runUnits(shares, [&](std::size_t inShare) {
    const int share = static_cast<int>(inShare);
    IdPair* out = outPairs.data() + share_start[share];
    for (std::size_t word = shareBegin(words, share, shares);
         word < shareBegin(words, share + 1, shares); ++word) {
      const IdPair* candidates = canonical_pairs_.data() + 64 * word;
      for (uint64_t bits = merged[word]; bits != 0; bits &= bits - 1)
        *out++ = candidates[__builtin_ctzll(bits)];
    }
  });
}

}  // namespace sap_broadphase
