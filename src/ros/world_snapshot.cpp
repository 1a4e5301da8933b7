// WorldSnapshot: the last frame and the scenery for queries, indexed once.
#include "world_snapshot.h"

#include <algorithm>
#include <utility>

namespace sap_broadphase {

SceneryIndex::SceneryIndex(SourceFramePtr inScenery, const BroadphaseConfig& inConfig)
    : scenery_(std::move(inScenery)), index_(inConfig) {
  if (scenery_) index_.setStaticBoxes(scenery_->span());
}

void SceneryIndex::query(const BoxFrame& inQueries, QueryHitList& ioHits) const {
  if (index_.staticBoxCount() == 0) return;
  const QueryHitList hits = index_.query(inQueries);
  ioHits.insert(ioHits.end(), hits.begin(), hits.end());
}

WorldSnapshot::WorldSnapshot(const std_msgs::Header& inHeader, std::vector<SourceFramePtr> inFrames,
                             std::shared_ptr<const SceneryIndex> inScenery,
                             const BroadphaseConfig& inConfig)
    : header_(inHeader),
      frames_(std::move(inFrames)),
      scenery_(std::move(inScenery)),
      frame_index_(inConfig) {
  for (const SourceFramePtr& frame : frames_) spans_.push_back(frame->span());
}

void WorldSnapshot::index() const {
  // The frame's boxes were accepted by the worker's engine: indexing them again cannot throw
  // for them; a bad query box throws from the query, after this.
  std::call_once(indexed_, [this] { frame_index_.setStaticBoxes(BoxFrame(spans_)); });
}

QueryHitList WorldSnapshot::query(const BoxFrame& inQueries) const {
  // Checked here, as the engine checks them, whether or not the world has boxes.
  if (auto problem = validate(inQueries)) throw InvalidBoxes(*problem);
  asked_.store(true, std::memory_order_relaxed);
  index();  // already built by the worker while queries keep coming
  QueryHitList hits = frame_index_.query(inQueries);
  const std::size_t frame_hits = hits.size();
  scenery_->query(inQueries, hits);
  // Both parts are sorted and their world ids differ (a frame sharing an id with the
  // scenery is refused): one merge gives the engine's order.
  std::inplace_merge(hits.begin(), hits.begin() + static_cast<std::ptrdiff_t>(frame_hits),
                     hits.end());
  return hits;
}

}  // namespace sap_broadphase
