#include "core/strategies/frame_query.h"

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/frame/pair_sort.h"
#include "core/runner/work_units.h"
#include "core/tuning.h"
#include "sap_broadphase/core/config.h"  // kMaxQueryHits

namespace sap_broadphase {

namespace {

std::vector<uint32_t> everyIndex(std::size_t inCount) {
  std::vector<uint32_t> indexes(inCount);
  std::iota(indexes.begin(), indexes.end(), 0u);
  return indexes;
}

/// Refuses a query whose hits passed kMaxQueryHits (config.h): its answer would hold 16 bytes
/// a hit more, and a query_boxes response 8.
void checkQueryHits(std::size_t inHits) {
  if (inHits <= kMaxQueryHits) return;
  throw std::length_error(
      "query: more than " + std::to_string(kMaxQueryHits) +
      " hits (the most one query may answer, kMaxQueryHits): " + std::to_string(inHits) +
      " found before it stopped; ask with fewer or smaller boxes");
}

}  // namespace

void FrameQuery::setFrame(const BoxColumns& inFrame) {
  frame_ = &inFrame;
  indexed_.store(false, std::memory_order_release);
  scanned_queries_.store(0, std::memory_order_relaxed);
}

void FrameQuery::clear() {
  frame_ = nullptr;
  indexed_.store(false, std::memory_order_release);
}

// Rent or buy: scan while the scans of this frame, this one included, cost less than an index.
bool FrameQuery::shouldIndex(std::size_t inQueries) const {
  if (indexed()) return true;
  const std::size_t scanned = scanned_queries_.fetch_add(inQueries, std::memory_order_relaxed);
  return scanned + inQueries > tuning::kQueryScansPerIndexBuild;
}

void FrameQuery::buildIndex() const {
  std::lock_guard<std::mutex> lock(index_mutex_);
  if (indexed()) return;  // a concurrent query built it while this one waited
  index_.build(*frame_, everyIndex(frame_->size()));
  indexed_.store(true, std::memory_order_release);
}

void FrameQuery::query(const BoxColumns& inQueries, PairList& outHits) const {
  if (frame_ == nullptr || frame_->size() == 0 || inQueries.size() == 0) return;
  if (!shouldIndex(inQueries.size())) {
    scan(inQueries, outHits);
    return;
  }
  buildIndex();
  index_.queryAll(inQueries, everyIndex(inQueries.size()), outHits,
                  StaticIndex::PairOrder::kQueryFirst);
}

// Frame boxes in blocks, each block tested against every query box: the primary axis first, as
// the sweep does, since it rejects most boxes reading two of their six bounds.
void FrameQuery::scan(const BoxColumns& inQueries, PairList& outHits) const {
  const BoxColumns& frame = *frame_;
  const std::size_t boxes = frame.size();
  const std::size_t blocks = (boxes + tuning::kQueryScanBlock - 1) / tuning::kQueryScanBlock;
  // A scan too short to share keeps to fewer of the scope's threads.
  const NarrowedScope scan_threads(static_cast<int>(std::min<std::size_t>(
      passThreads(), std::max<std::size_t>(1, boxes / tuning::kMinScannedBoxesPerThread))));
  // A block a unit, each block's hits in its own part, the parts joined in block order: the
  // same hits in the same order on any thread count.
  // Every block stops once the hits of all blocks passed kMaxQueryHits: the query is refused,
  // and the hits held stay within the bound and a query row of a block for each thread.
  std::vector<PairList> parts(blocks);
  std::atomic<std::size_t> found{0};
  runUnits(blocks, [&](std::size_t inBlock) {
    PairList& hits = parts[inBlock];
    const std::size_t begin = inBlock * tuning::kQueryScanBlock;
    const std::size_t end = std::min(boxes, begin + tuning::kQueryScanBlock);
    for (std::size_t q = 0; q < inQueries.size(); ++q) {
      if (found.load(std::memory_order_relaxed) > kMaxQueryHits) return;
      const std::size_t before = hits.size();
      const double query_low = inQueries.lo[0][q];
      const double query_high = inQueries.hi[0][q];
      for (std::size_t i = begin; i < end; ++i) {
        if (frame.lo[0][i] > query_high || query_low > frame.hi[0][i]) continue;
        if (boxesOverlap(inQueries, q, frame, i) &&
            groupsMayPair(inQueries.group(q), inQueries.mask(q), frame.group(i), frame.mask(i)))
          hits.push_back(IdPair{inQueries.ids[q], frame.ids[i]});
      }
      if (hits.size() > before) found.fetch_add(hits.size() - before, std::memory_order_relaxed);
    }
  });
  checkQueryHits(found.load());
  for (const PairList& part : parts) outHits.insert(outHits.end(), part.begin(), part.end());
}

PairList answerQueries(const BoxColumns& inQueries, const FrameQuery& inFrame,
                       const StaticIndex& inScenery) {
  PairList hits;
  inFrame.query(inQueries, hits);
  checkQueryHits(hits.size());
  if (inScenery.size() > 0 && inQueries.size() > 0) {
    inScenery.queryAll(inQueries, everyIndex(inQueries.size()), hits,
                       StaticIndex::PairOrder::kQueryFirst);
    checkQueryHits(hits.size());
  }
  PairSortScratch scratch;
  sortPairsByAThenB(hits, scratch);  // (query id, world id): either may be the larger
  return hits;
}

}  // namespace sap_broadphase
