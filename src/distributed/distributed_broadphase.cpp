// The distributed broad phase: a frame is (1) cut the slabs when they are out of balance,
// (2) send each changed box to the other slabs it overlaps, (3) one Broadphase on the rank's
// own boxes (the pairs among them), (4) one on the slab's border set (the boxes received and
// the own boxes they may touch), keeping the pairs of boxes of two owners that this slab owns,
// (5) deliver them. docs/DISTRIBUTED.md has the why.
#include "sap_broadphase/distributed/distributed_broadphase.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "core/frame/pair_sort.h"
#include "core/runner/work_units.h"
#include "slab_cuts.h"

namespace sap_broadphase::distributed {

namespace {

/// One box on the wire and in a slab's store of boxes received from other ranks.
struct BoxRecord {
  uint32_t id;
  uint32_t group;
  uint32_t mask;
  uint32_t padding;
  double lo[3];
  double hi[3];
};
static_assert(sizeof(BoxRecord) == 64, "box records travel as raw bytes");

/// Header of the bytes one rank sends another in a frame (omitted when there is nothing).
struct DeltaHeader {
  uint32_t upserts;   ///< box records that follow: new or changed boxes in the slab
  uint32_t removals;  ///< ids that follow: boxes that left the slab
};

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point inStart) {
  return std::chrono::duration<double, std::milli>(Clock::now() - inStart).count();
}

void checkMpi(int inStatus, const char* inWhat) {
  if (inStatus != MPI_SUCCESS) throw std::runtime_error(std::string("MPI call failed: ") + inWhat);
}

/// An MPI count: the exchange's counts are ints; a frame that needs more fails loudly.
int mpiCount(std::size_t inBytes, const char* inWhat) {
  if (inBytes > static_cast<std::size_t>(INT_MAX))
    throw std::runtime_error(std::string("distributed broad phase: ") + inWhat +
                             " exceeds 2 GiB to one rank in one frame; use more ranks");
  return static_cast<int>(inBytes);
}

/// Offsets of consecutive blocks of inCounts.
std::vector<int> displacements(const std::vector<int>& inCounts) {
  std::vector<int> offsets(inCounts.size(), 0);
  std::size_t offset = 0;
  for (std::size_t k = 0; k < inCounts.size(); ++k) {
    offsets[k] = mpiCount(offset, "the receive buffer");
    offset += static_cast<std::size_t>(inCounts[k]);
  }
  return offsets;
}

std::size_t sum(const std::vector<int>& inCounts) {
  std::size_t total = 0;
  for (int count : inCounts) total += static_cast<std::size_t>(count);
  return total;
}

/// What this rank tells each other rank in a frame, indexed by rank: boxes new to its slab or
/// changed there, and ids of boxes that left it.
struct SlabDeltas {
  std::vector<std::vector<BoxRecord>> upserts;
  std::vector<std::vector<uint32_t>> removals;
  explicit SlabDeltas(int inRanks)
      : upserts(static_cast<std::size_t>(inRanks)), removals(static_cast<std::size_t>(inRanks)) {}
};

/// The bytes of one all-to-all exchange: per rank its count and offset in `bytes`.
struct WireBytes {
  std::vector<int> counts;
  std::vector<int> offsets;
  std::vector<unsigned char> bytes;
};

/// Box inIndex of inBoxes as it travels.
BoxRecord recordOf(const BoxSet& inBoxes, std::size_t inIndex) {
  BoxRecord box{inBoxes.ids[inIndex], inBoxes.group(inIndex), inBoxes.mask(inIndex), 0, {}, {}};
  for (int axis = 0; axis < 3; ++axis) {
    box.lo[axis] = inBoxes.lo(axis, inIndex);
    box.hi[axis] = inBoxes.hi(axis, inIndex);
  }
  return box;
}

/// Writes the header, the box records and the ids to outBytes (room for all of them).
void packDelta(const std::vector<BoxRecord>& inUpserts, const std::vector<uint32_t>& inRemovals,
               unsigned char* outBytes) {
  const DeltaHeader header{static_cast<uint32_t>(inUpserts.size()),
                           static_cast<uint32_t>(inRemovals.size())};
  std::memcpy(outBytes, &header, sizeof header);
  outBytes += sizeof header;
  std::memcpy(outBytes, inUpserts.data(), inUpserts.size() * sizeof(BoxRecord));
  outBytes += inUpserts.size() * sizeof(BoxRecord);
  std::memcpy(outBytes, inRemovals.data(), inRemovals.size() * sizeof(uint32_t));
}

/// Reads what packDelta wrote: the changed boxes and the gone ids, each sorted by id.
void unpackDelta(const unsigned char* inBytes, std::vector<BoxRecord>& outChanged,
                 std::vector<uint32_t>& outGone) {
  DeltaHeader header;
  std::memcpy(&header, inBytes, sizeof header);
  inBytes += sizeof header;
  outChanged.resize(header.upserts);
  std::memcpy(outChanged.data(), inBytes, header.upserts * sizeof(BoxRecord));
  inBytes += header.upserts * sizeof(BoxRecord);
  outGone.resize(header.removals);
  std::memcpy(outGone.data(), inBytes, header.removals * sizeof(uint32_t));
  const auto byId = [](const BoxRecord& x, const BoxRecord& y) { return x.id < y.id; };
  if (!std::is_sorted(outChanged.begin(), outChanged.end(), byId))
    std::sort(outChanged.begin(), outChanged.end(), byId);
  std::sort(outGone.begin(), outGone.end());
}

/// inHeld (sorted by id) with inChanged put in (replacing boxes of the same id) and the boxes
/// of inGone left out, still sorted by id. inChanged and inGone are sorted.
std::vector<BoxRecord> mergeById(const std::vector<BoxRecord>& inHeld,
                                 const std::vector<BoxRecord>& inChanged,
                                 const std::vector<uint32_t>& inGone) {
  std::vector<BoxRecord> merged;
  merged.reserve(inHeld.size() + inChanged.size());
  std::size_t held = 0, changed = 0, gone = 0;
  while (held < inHeld.size() || changed < inChanged.size()) {
    const bool changedNext = changed < inChanged.size() &&
                             (held == inHeld.size() || inChanged[changed].id <= inHeld[held].id);
    if (changedNext) {
      if (held < inHeld.size() && inHeld[held].id == inChanged[changed].id) ++held;  // replaced
      merged.push_back(inChanged[changed++]);
      continue;
    }
    while (gone < inGone.size() && inGone[gone] < inHeld[held].id) ++gone;
    if (gone == inGone.size() || inGone[gone] != inHeld[held].id) merged.push_back(inHeld[held]);
    ++held;
  }
  return merged;
}

}  // namespace

struct DistributedBroadphase::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0;
  int ranks = 1;
  DistributedConfig config;
  // Pairs among this rank's own boxes: the boxes exactly as the caller gives them, so the
  // engine's temporal coherence (kept candidates, reuse) works as in one process.
  Broadphase own_engine;
  // Pairs between boxes of two owners, on the border set: what other ranks sent and the own
  // boxes in this slab that reach the same stretch of the slab axis.
  Broadphase border_engine;

  std::vector<double> cuts;
  bool have_cuts = false;
  double last_imbalance = 1.0;
  double last_engine_ms = 0.0;

  // What this rank sent last frame, per own box: the slab range and the bounds the other
  // slabs hold. Valid while have_sent (a re-cut makes every slab start empty).
  bool have_sent = false;
  std::vector<uint32_t> sent_ids;
  std::vector<int> sent_first;
  std::vector<int> sent_last;
  std::vector<BoxRecord> sent_boxes;
  std::vector<BoxRecord> sent_boxes_scratch;

  // This frame's slab range of each own box.
  std::vector<int> first_slab;
  std::vector<int> last_slab;

  // Boxes received from each rank that overlap this slab, sorted by id: kept across frames.
  std::vector<std::vector<BoxRecord>> resident;

  // The border set, with ids 0..m-1 (dense ids keep the engine's pair sort a counting
  // sort), and per position the box's real id, its owner rank and the slab its min is in.
  BoxSet border;
  std::vector<uint32_t> border_ids;
  std::vector<int> border_owner;
  std::vector<int> border_min_slab;

  PairList result;
  PairSortScratch sort_scratch;
  DistributedReport report;

  Impl(MPI_Comm inComm, const DistributedConfig& inConfig)
      : config(inConfig), own_engine(inConfig.engine), border_engine(inConfig.engine) {
    if (inConfig.slab_axis < 0 || inConfig.slab_axis > 2)
      throw std::invalid_argument("slab_axis must be 0, 1 or 2");
    checkMpi(MPI_Comm_dup(inComm, &comm), "MPI_Comm_dup");
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
    resident.resize(static_cast<std::size_t>(ranks));
  }
  ~Impl() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }

  int slabOf(double inX) const { return slabOfCoordinate(cuts, inX); }

  void cutSlabs(const BoxSet& inBoxes);
  // The exchange of a frame's boxes, one job each: place every own box in the slabs its
  // range reaches, list what each other slab must add or forget since the last frame, pack
  // the lists, send and receive them, merge what was received into the slab's store.
  void exchangeBoxes(const BoxSet& inBoxes);
  void placeInSlabs(const BoxSet& inBoxes);
  SlabDeltas deltasSinceLastFrame(const BoxSet& inBoxes);
  // Box inIndex (last frame's index inLastIndex, -1 when new) into the slabs' lists, and its
  // record as sent into ioSent[inIndex] (ioSent may be sent_boxes itself: read first).
  void addBoxDelta(const BoxSet& inBoxes, std::size_t inIndex, int64_t inLastIndex,
                   std::vector<BoxRecord>& ioSent, SlabDeltas& ioDeltas) const;
  void forgetGoneBoxes(const std::vector<char>& inStillHere, SlabDeltas& ioDeltas) const;
  WireBytes packForRanks(const SlabDeltas& inDeltas);
  WireBytes exchangeWithRanks(const WireBytes& inSend);
  void mergeReceived(const WireBytes& inReceived);
  void matchPrevious(const std::vector<uint32_t>& inIds, std::vector<int64_t>& outPrevious,
                     std::vector<char>& outStillHere) const;
  void assembleBorderSet(const BoxSet& inBoxes);
  void keepOwnedPairs(const PairList& inBorderPairs, PairDelivery inDelivery,
                      std::vector<std::vector<IdPair>>& outByRank);
  void deliverToOwners(const PairList& inOwnPairs, std::vector<std::vector<IdPair>>& ioByRank);
  void gatherAtRoot(const PairList& inOwnPairs, std::vector<IdPair>& ioCrossPairs, int inRoot);
  void measureImbalance();
};

void DistributedBroadphase::Impl::cutSlabs(const BoxSet& inBoxes) {
  const int axis = config.slab_axis;
  const std::size_t n = inBoxes.size();
  const std::size_t wanted = std::max<std::size_t>(config.samples_per_rank, 1);
  const std::size_t stride = std::max<std::size_t>(n / wanted, 1);
  std::vector<double> local;
  for (std::size_t i = stride / 2; i < n; i += stride) {
    if (auto position = samplePosition(inBoxes.lo(axis, i), inBoxes.hi(axis, i)))
      local.push_back(*position);
  }
  // A sample stands for stride boxes, so a rank with more boxes weighs more.
  const double weight = local.empty() ? 0.0 : static_cast<double>(n) / local.size();
  std::vector<double> mine;
  mine.reserve(2 * local.size());
  for (double position : local) {
    mine.push_back(position);
    mine.push_back(weight);
  }
  int myCount = mpiCount(mine.size(), "the sample");
  std::vector<int> counts(static_cast<std::size_t>(ranks));
  checkMpi(MPI_Allgather(&myCount, 1, MPI_INT, counts.data(), 1, MPI_INT, comm), "MPI_Allgather");
  const std::vector<int> offsets = displacements(counts);
  std::vector<double> all(sum(counts));
  checkMpi(MPI_Allgatherv(mine.data(), myCount, MPI_DOUBLE, all.data(), counts.data(),
                          offsets.data(), MPI_DOUBLE, comm),
           "MPI_Allgatherv");
  report.control_bytes_sent += static_cast<uint64_t>(ranks - 1) * (sizeof(int) + myCount * 8);

  std::vector<WeightedSample> samples(all.size() / 2);
  for (std::size_t k = 0; k < samples.size(); ++k) samples[k] = {all[2 * k], all[2 * k + 1]};

  if (config.balance == SlabBalance::kCost && have_cuts) {
    // Each old slab's measured engine time, spread over the samples that fell in it: the cut
    // then follows the cost density, not the box density.
    std::vector<double> slabMs(static_cast<std::size_t>(ranks));
    checkMpi(MPI_Allgather(&last_engine_ms, 1, MPI_DOUBLE, slabMs.data(), 1, MPI_DOUBLE, comm),
             "MPI_Allgather");
    report.control_bytes_sent += static_cast<uint64_t>(ranks - 1) * sizeof(double);
    std::vector<double> slabWeight(static_cast<std::size_t>(ranks), 0.0);
    double totalMs = 0.0;
    for (double ms : slabMs) totalMs += ms;
    for (const WeightedSample& sample : samples)
      slabWeight[slabOf(sample.position)] += sample.weight;
    if (totalMs > 0.0) {
      for (WeightedSample& sample : samples) {
        const int slab = slabOf(sample.position);
        sample.weight *= slabMs[slab] / slabWeight[slab];
      }
    }
  }
  cuts = cutsFromSamples(samples, ranks);
  have_cuts = true;
}

/// outPrevious[i]: the index last frame of box i (-1: new); outStillHere[j]: last frame's box j
/// is still here.
void DistributedBroadphase::Impl::matchPrevious(const std::vector<uint32_t>& inIds,
                                                std::vector<int64_t>& outPrevious,
                                                std::vector<char>& outStillHere) const {
  outPrevious.assign(inIds.size(), -1);
  outStillHere.assign(sent_ids.size(), 0);
  if (std::is_sorted(inIds.begin(), inIds.end()) &&
      std::is_sorted(sent_ids.begin(), sent_ids.end())) {
    std::size_t j = 0;
    for (std::size_t i = 0; i < inIds.size(); ++i) {
      while (j < sent_ids.size() && sent_ids[j] < inIds[i]) ++j;
      if (j == sent_ids.size()) break;
      if (sent_ids[j] != inIds[i]) continue;
      outPrevious[i] = static_cast<int64_t>(j);
      outStillHere[j] = 1;
    }
    return;
  }
  std::unordered_map<uint32_t, uint32_t> indexOf;
  indexOf.reserve(sent_ids.size());
  for (std::size_t j = 0; j < sent_ids.size(); ++j)
    indexOf.emplace(sent_ids[j], static_cast<uint32_t>(j));
  for (std::size_t i = 0; i < inIds.size(); ++i) {
    auto found = indexOf.find(inIds[i]);
    if (found == indexOf.end()) continue;
    outPrevious[i] = found->second;
    outStillHere[found->second] = 1;
  }
}

void DistributedBroadphase::Impl::exchangeBoxes(const BoxSet& inBoxes) {
  placeInSlabs(inBoxes);
  const SlabDeltas deltas = deltasSinceLastFrame(inBoxes);
  const WireBytes received = exchangeWithRanks(packForRanks(deltas));
  mergeReceived(received);
}

void DistributedBroadphase::Impl::placeInSlabs(const BoxSet& inBoxes) {
  const int axis = config.slab_axis;
  const std::size_t n = inBoxes.size();
  first_slab.resize(n);
  last_slab.resize(n);
  // On the engine's thread count, through the process's runner (outside the engine's calls).
  const ThreadsScope threads(resolveThreadCount(config.engine.threads));
  runOverItems(WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t i = inBegin; i < inEnd; ++i) {
      first_slab[i] = slabOf(inBoxes.lo(axis, i));
      last_slab[i] = slabOf(inBoxes.hi(axis, i));
    }
  });
}

SlabDeltas DistributedBroadphase::Impl::deltasSinceLastFrame(const BoxSet& inBoxes) {
  // Which own box was which last frame: the same ids in the same order (a simulation's usual
  // frame) match by index; ids in increasing order (bodies kept sorted, some joining or
  // leaving) by a merge; anything else by a hash of the ids.
  const bool sameOrder = have_sent && sent_ids == inBoxes.ids;
  std::vector<int64_t> previous;
  std::vector<char> stillHere;
  if (have_sent && !sameOrder) matchPrevious(inBoxes.ids, previous, stillHere);

  SlabDeltas deltas(ranks);
  // The bounds the other slabs hold, per box with a slab other than this one in its range
  // (entries of boxes that stay home are never read). Same order: updated in place.
  std::vector<BoxRecord>& nowSent = sameOrder ? sent_boxes : sent_boxes_scratch;
  nowSent.resize(inBoxes.size());
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    const int64_t lastIndex = !have_sent ? -1 : sameOrder ? static_cast<int64_t>(i) : previous[i];
    addBoxDelta(inBoxes, i, lastIndex, nowSent, deltas);
  }
  forgetGoneBoxes(stillHere, deltas);
  if (!sameOrder) {
    sent_ids = inBoxes.ids;
    sent_boxes.swap(sent_boxes_scratch);
  }
  sent_first = first_slab;
  sent_last = last_slab;
  have_sent = true;
  return deltas;
}

void DistributedBroadphase::Impl::addBoxDelta(const BoxSet& inBoxes, std::size_t inIndex,
                                              int64_t inLastIndex, std::vector<BoxRecord>& ioSent,
                                              SlabDeltas& ioDeltas) const {
  const int firstNow = first_slab[inIndex];
  const int lastNow = last_slab[inIndex];
  const bool homeBefore =
      inLastIndex < 0 || (sent_first[inLastIndex] == rank && sent_last[inLastIndex] == rank);
  if (firstNow == rank && lastNow == rank && homeBefore)
    return;  // lives in this slab only, now and before: nothing to tell anyone
  const BoxRecord box = recordOf(inBoxes, inIndex);
  int firstBefore = 1;
  int lastBefore = 0;  // empty range: nobody holds it yet
  bool changed = true;
  if (inLastIndex >= 0) {
    firstBefore = sent_first[inLastIndex];
    lastBefore = sent_last[inLastIndex];
    // Bit for bit: a slab that holds old bounds would miss or invent pairs. (Read only when
    // another slab holds the box, i.e. when the entry was written.)
    changed = std::memcmp(&box, &sent_boxes[inLastIndex], sizeof(BoxRecord)) != 0;
  }
  for (int slab = firstNow; slab <= lastNow; ++slab) {
    const bool heldBefore = slab >= firstBefore && slab <= lastBefore;
    if (slab != rank && (changed || !heldBefore)) ioDeltas.upserts[slab].push_back(box);
  }
  for (int slab = firstBefore; slab <= lastBefore; ++slab) {
    const bool heldNow = slab >= firstNow && slab <= lastNow;
    if (slab != rank && !heldNow) ioDeltas.removals[slab].push_back(box.id);
  }
  ioSent[inIndex] = box;
}

void DistributedBroadphase::Impl::forgetGoneBoxes(const std::vector<char>& inStillHere,
                                                  SlabDeltas& ioDeltas) const {
  for (std::size_t last = 0; last < inStillHere.size(); ++last) {
    if (inStillHere[last]) continue;  // a box that is gone: every slab that held it forgets it
    for (int slab = sent_first[last]; slab <= sent_last[last]; ++slab) {
      if (slab != rank) ioDeltas.removals[slab].push_back(sent_ids[last]);
    }
  }
}

WireBytes DistributedBroadphase::Impl::packForRanks(const SlabDeltas& inDeltas) {
  WireBytes wire;
  wire.counts.assign(static_cast<std::size_t>(ranks), 0);
  for (int to = 0; to < ranks; ++to) {
    const std::size_t upserts = inDeltas.upserts[to].size();
    const std::size_t removals = inDeltas.removals[to].size();
    if (upserts == 0 && removals == 0) continue;
    wire.counts[to] =
        mpiCount(sizeof(DeltaHeader) + upserts * sizeof(BoxRecord) + removals * sizeof(uint32_t),
                 "the boxes sent");
    report.boxes_sent += upserts;
    report.removals_sent += removals;
    report.box_bytes_sent += static_cast<uint64_t>(wire.counts[to]);
  }
  wire.offsets = displacements(wire.counts);
  wire.bytes.resize(sum(wire.counts));
  for (int to = 0; to < ranks; ++to) {
    if (wire.counts[to] > 0)
      packDelta(inDeltas.upserts[to], inDeltas.removals[to], wire.bytes.data() + wire.offsets[to]);
  }
  return wire;
}

WireBytes DistributedBroadphase::Impl::exchangeWithRanks(const WireBytes& inSend) {
  WireBytes received;
  received.counts.assign(static_cast<std::size_t>(ranks), 0);
  checkMpi(MPI_Alltoall(inSend.counts.data(), 1, MPI_INT, received.counts.data(), 1, MPI_INT, comm),
           "MPI_Alltoall");
  report.control_bytes_sent += static_cast<uint64_t>(ranks - 1) * sizeof(int);
  received.offsets = displacements(received.counts);
  received.bytes.resize(sum(received.counts));
  checkMpi(MPI_Alltoallv(inSend.bytes.data(), inSend.counts.data(), inSend.offsets.data(), MPI_BYTE,
                         received.bytes.data(), received.counts.data(), received.offsets.data(),
                         MPI_BYTE, comm),
           "MPI_Alltoallv");
  return received;
}

void DistributedBroadphase::Impl::mergeReceived(const WireBytes& inReceived) {
  for (int from = 0; from < ranks; ++from) {
    if (inReceived.counts[from] == 0) continue;
    std::vector<BoxRecord> changedBoxes;
    std::vector<uint32_t> gone;
    unpackDelta(inReceived.bytes.data() + inReceived.offsets[from], changedBoxes, gone);
    resident[from] = mergeById(resident[from], changedBoxes, gone);
  }
}

/// The x-ranges (slab axis) covered by the boxes received, merged into disjoint sorted
/// intervals: an own box outside them cannot touch a received box.
std::vector<std::pair<double, double>> receivedStretches(
    const std::vector<std::vector<BoxRecord>>& inResident, int inAxis) {
  std::vector<std::pair<double, double>> stretches;
  for (const std::vector<BoxRecord>& boxes : inResident) {
    for (const BoxRecord& box : boxes) stretches.emplace_back(box.lo[inAxis], box.hi[inAxis]);
  }
  std::sort(stretches.begin(), stretches.end());
  std::size_t kept = 0;
  for (const auto& stretch : stretches) {
    if (kept > 0 && stretch.first <= stretches[kept - 1].second) {
      stretches[kept - 1].second = std::max(stretches[kept - 1].second, stretch.second);
    } else {
      stretches[kept++] = stretch;
    }
  }
  stretches.resize(kept);
  return stretches;
}

/// True when [inLo, inHi] meets one of the disjoint sorted inStretches (closed intervals).
bool meetsStretch(const std::vector<std::pair<double, double>>& inStretches, double inLo,
                  double inHi) {
  // The first stretch that does not end before inLo.
  auto next = std::lower_bound(
      inStretches.begin(), inStretches.end(), inLo,
      [](const std::pair<double, double>& stretch, double x) { return stretch.second < x; });
  return next != inStretches.end() && next->first <= inHi;
}

void DistributedBroadphase::Impl::assembleBorderSet(const BoxSet& inBoxes) {
  const int axis = config.slab_axis;
  const std::vector<std::pair<double, double>> stretches = receivedStretches(resident, axis);
  std::size_t held = 0;
  bool filters = inBoxes.hasFilters();
  for (const std::vector<BoxRecord>& boxes : resident) {
    held += boxes.size();
    for (const BoxRecord& box : boxes)
      filters |= box.group != kDefaultGroup || box.mask != kDefaultMask;
  }
  std::size_t inSlab = 0;
  std::vector<uint32_t> ownTouching;
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    if (first_slab[i] > rank || rank > last_slab[i]) continue;
    ++inSlab;
    if (!stretches.empty() && meetsStretch(stretches, inBoxes.lo(axis, i), inBoxes.hi(axis, i)))
      ownTouching.push_back(static_cast<uint32_t>(i));
  }
  report.resident_boxes = held;
  report.slab_boxes = inSlab + held;
  const std::size_t m = held == 0 ? 0 : ownTouching.size() + held;
  report.border_boxes = m;

  border.ids.resize(m);
  border.bounds.resize(kBoundsPerBox * m);
  border.groups.resize(filters ? m : 0);
  border.masks.resize(filters ? m : 0);
  border_ids.resize(m);
  border_owner.resize(m);
  border_min_slab.resize(m);
  if (m == 0) return;
  std::size_t k = 0;
  for (uint32_t i : ownTouching) {
    border.ids[k] = static_cast<uint32_t>(k);
    for (int a = 0; a < 3; ++a) {
      border.lo(a, k) = inBoxes.lo(a, i);
      border.hi(a, k) = inBoxes.hi(a, i);
    }
    if (filters) {
      border.groups[k] = inBoxes.group(i);
      border.masks[k] = inBoxes.mask(i);
    }
    border_ids[k] = inBoxes.ids[i];
    border_owner[k] = rank;
    border_min_slab[k] = first_slab[i];
    ++k;
  }
  for (int p = 0; p < ranks; ++p) {
    for (const BoxRecord& box : resident[p]) {
      border.ids[k] = static_cast<uint32_t>(k);
      for (int a = 0; a < 3; ++a) {
        border.lo(a, k) = box.lo[a];
        border.hi(a, k) = box.hi[a];
      }
      if (filters) {
        border.groups[k] = box.group;
        border.masks[k] = box.mask;
      }
      border_ids[k] = box.id;
      border_owner[k] = p;
      border_min_slab[k] = slabOf(box.lo[axis]);
      ++k;
    }
  }
}

/// The pairs of boxes of two owners that this slab owns: under kToOwners listed under each
/// owner rank, under kGatherAtRoot once, under this rank.
void DistributedBroadphase::Impl::keepOwnedPairs(const PairList& inBorderPairs,
                                                 PairDelivery inDelivery,
                                                 std::vector<std::vector<IdPair>>& outByRank) {
  const bool toOwners = inDelivery == PairDelivery::kToOwners;
  for (const IdPair& pair : inBorderPairs) {
    const int ownerA = border_owner[pair.a];
    const int ownerB = border_owner[pair.b];
    // Two boxes of one owner: that owner's own engine found the pair.
    if (ownerA == ownerB) continue;
    // The ownership rule. Both boxes overlap on the slab axis, so the larger of their mins m
    // lies in both boxes; the slab holding m is in both boxes' slab ranges (slabOf is
    // monotone), so that one slab holds both boxes and keeps the pair. The larger min's slab
    // is the larger of the two min slabs, again because slabOf is monotone.
    if (std::max(border_min_slab[pair.a], border_min_slab[pair.b]) != rank) continue;
    const IdPair found = makeIdPair(border_ids[pair.a], border_ids[pair.b]);
    ++report.cross_pairs;
    if (!toOwners) {
      outByRank[rank].push_back(found);
      continue;
    }
    outByRank[ownerA].push_back(found);
    outByRank[ownerB].push_back(found);
  }
}

/// This rank's own pairs and the pairs of boxes of two owners that involve its boxes, sorted.
void DistributedBroadphase::Impl::deliverToOwners(const PairList& inOwnPairs,
                                                  std::vector<std::vector<IdPair>>& ioByRank) {
  std::vector<int> sendCounts(static_cast<std::size_t>(ranks), 0);
  for (int s = 0; s < ranks; ++s) {
    if (s == rank) continue;
    sendCounts[s] = mpiCount(ioByRank[s].size() * sizeof(IdPair), "the pairs sent");
    report.pair_bytes_sent += static_cast<uint64_t>(sendCounts[s]);
  }
  const std::vector<int> sendOffsets = displacements(sendCounts);
  std::vector<unsigned char> sendBytes(sum(sendCounts));
  for (int s = 0; s < ranks; ++s) {
    if (sendCounts[s] > 0)
      std::memcpy(sendBytes.data() + sendOffsets[s], ioByRank[s].data(), sendCounts[s]);
  }
  std::vector<int> receiveCounts(static_cast<std::size_t>(ranks), 0);
  checkMpi(MPI_Alltoall(sendCounts.data(), 1, MPI_INT, receiveCounts.data(), 1, MPI_INT, comm),
           "MPI_Alltoall");
  report.control_bytes_sent += static_cast<uint64_t>(ranks - 1) * sizeof(int);
  const std::vector<int> receiveOffsets = displacements(receiveCounts);
  PairList& cross = ioByRank[rank];
  const std::size_t found = cross.size();
  cross.resize(found + sum(receiveCounts) / sizeof(IdPair));
  checkMpi(MPI_Alltoallv(sendBytes.data(), sendCounts.data(), sendOffsets.data(), MPI_BYTE,
                         cross.data() + found, receiveCounts.data(), receiveOffsets.data(),
                         MPI_BYTE, comm),
           "MPI_Alltoallv");
  // Own pairs come sorted from the engine; the few cross pairs are sorted and merged in.
  sortPairsCanonical(cross, sort_scratch);
  result.resize(inOwnPairs.size() + cross.size());
  std::merge(inOwnPairs.begin(), inOwnPairs.end(), cross.begin(), cross.end(), result.begin());
}

/// Every pair, once, sorted on the root.
void DistributedBroadphase::Impl::gatherAtRoot(const PairList& inOwnPairs,
                                               std::vector<IdPair>& ioCrossPairs, int inRoot) {
  ioCrossPairs.insert(ioCrossPairs.end(), inOwnPairs.begin(), inOwnPairs.end());
  const std::vector<IdPair>& mine = ioCrossPairs;
  const int myBytes = mpiCount(mine.size() * sizeof(IdPair), "the pairs sent");
  if (rank != inRoot) report.pair_bytes_sent += static_cast<uint64_t>(myBytes);
  std::vector<int> counts(static_cast<std::size_t>(ranks), 0);
  checkMpi(MPI_Gather(&myBytes, 1, MPI_INT, counts.data(), 1, MPI_INT, inRoot, comm), "MPI_Gather");
  if (rank != inRoot) report.control_bytes_sent += sizeof(int);
  std::vector<int> offsets;
  if (rank == inRoot) {
    offsets = displacements(counts);
    result.resize(sum(counts) / sizeof(IdPair));
  } else {
    result.clear();
  }
  checkMpi(MPI_Gatherv(mine.data(), myBytes, MPI_BYTE, result.data(), counts.data(), offsets.data(),
                       MPI_BYTE, inRoot, comm),
           "MPI_Gatherv");
  if (rank == inRoot) sortPairsCanonical(result, sort_scratch);
}

void DistributedBroadphase::Impl::measureImbalance() {
  // Fullest slab against the mean, by the measure the cuts balance. One allgather rather than
  // a max and a sum: every collective costs a round of waiting for the slowest rank.
  const double mine = config.balance == SlabBalance::kCost ? last_engine_ms
                                                           : static_cast<double>(report.slab_boxes);
  std::vector<double> all(static_cast<std::size_t>(ranks));
  checkMpi(MPI_Allgather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm), "MPI_Allgather");
  report.control_bytes_sent += static_cast<uint64_t>(ranks - 1) * sizeof(double);
  double largest = 0.0;
  double total = 0.0;
  for (double value : all) {
    largest = std::max(largest, value);
    total += value;
  }
  const double mean = total / ranks;
  last_imbalance = mean > 0.0 ? largest / mean : 1.0;
  report.imbalance = last_imbalance;
}

DistributedBroadphase::DistributedBroadphase(MPI_Comm inCommunicator,
                                             const DistributedConfig& inConfig)
    : impl_(std::make_unique<Impl>(inCommunicator, inConfig)) {}

DistributedBroadphase::~DistributedBroadphase() = default;

const PairList& DistributedBroadphase::update(const BoxSet& inLocalBoxes, PairDelivery inDelivery,
                                              int inRoot) {
  Impl& self = *impl_;
  if (inRoot < 0 || inRoot >= self.ranks) throw std::invalid_argument("root rank out of range");
  const Clock::time_point frameStart = Clock::now();
  self.report = DistributedReport();
  self.report.local_boxes = inLocalBoxes.size();

  Clock::time_point start = Clock::now();
  if (!self.have_cuts || self.last_imbalance - 1.0 > self.config.recut_imbalance) {
    self.cutSlabs(inLocalBoxes);
    // New slabs start empty: every box is sent afresh to the slabs it overlaps.
    for (std::vector<BoxRecord>& held : self.resident) held.clear();
    self.have_sent = false;
    self.report.recut = true;
  }
  self.report.ms_cut = msSince(start);

  start = Clock::now();
  self.exchangeBoxes(inLocalBoxes);
  self.report.ms_exchange = msSince(start);

  start = Clock::now();
  self.assembleBorderSet(inLocalBoxes);
  self.report.ms_assemble = msSince(start);

  start = Clock::now();
  const PairList& ownPairs = self.own_engine.update(inLocalBoxes);
  self.report.ms_own_engine = msSince(start);
  self.report.own_pairs = ownPairs.size();
  self.report.engine = self.own_engine.stats();
  start = Clock::now();
  // Nothing received: no pair across owners can be this slab's (one process, or a slab no
  // other rank's box reaches), and the engine is not even asked.
  static const PairList kNoPairs;
  const PairList& borderPairs =
      self.border.size() == 0 ? kNoPairs : self.border_engine.update(self.border);
  self.report.ms_border_engine = msSince(start);
  if (self.border.size() > 0) self.report.border_engine = self.border_engine.stats();
  self.report.ms_engine = self.report.ms_own_engine + self.report.ms_border_engine;
  self.last_engine_ms = self.report.ms_engine;

  start = Clock::now();
  std::vector<std::vector<IdPair>> byRank(static_cast<std::size_t>(self.ranks));
  self.keepOwnedPairs(borderPairs, inDelivery, byRank);
  self.report.ms_filter = msSince(start);

  start = Clock::now();
  if (inDelivery == PairDelivery::kToOwners)
    self.deliverToOwners(ownPairs, byRank);
  else
    self.gatherAtRoot(ownPairs, byRank[self.rank], inRoot);
  self.report.pairs_returned = self.result.size();
  self.measureImbalance();
  self.report.ms_deliver = msSince(start);
  self.report.ms_total = msSince(frameStart);
  return self.result;
}

const DistributedReport& DistributedBroadphase::stats() const {
  return impl_->report;
}

const std::vector<double>& DistributedBroadphase::cuts() const {
  return impl_->cuts;
}

int DistributedBroadphase::slabOf(double inX) const {
  return impl_->slabOf(inX);
}

int DistributedBroadphase::homeRank(double inMin, double inMax) const {
  return impl_->slabOf(samplePosition(inMin, inMax).value_or(0.0));
}

int DistributedBroadphase::rank() const {
  return impl_->rank;
}

int DistributedBroadphase::ranks() const {
  return impl_->ranks;
}

void DistributedBroadphase::reset() {
  Impl& self = *impl_;
  self.own_engine.reset();
  self.border_engine.reset();
  self.cuts.clear();
  self.have_cuts = false;
  self.have_sent = false;
  self.last_imbalance = 1.0;
  self.last_engine_ms = 0.0;
  for (std::vector<BoxRecord>& held : self.resident) held.clear();
  checkMpi(MPI_Barrier(self.comm), "MPI_Barrier");
}

}  // namespace sap_broadphase::distributed
