// The world of a frame: the latest frame of every source, merged.
#include "sources.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>

#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>

#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Finds an id present in both sorted lists: walks the shorter one and searches the longer one
/// from where the last search ended, so a small moving frame against 10^6 scenery ids costs
/// O(small x log large).
bool firstCommonId(const std::vector<uint32_t>& inA, const std::vector<uint32_t>& inB,
                   uint32_t& outId) {
  const std::vector<uint32_t>& small = inA.size() <= inB.size() ? inA : inB;
  const std::vector<uint32_t>& large = inA.size() <= inB.size() ? inB : inA;
  auto from = large.begin();
  for (uint32_t id : small) {
    from = std::lower_bound(from, large.end(), id);
    if (from == large.end()) return false;
    if (*from == id) {
      outId = id;
      return true;
    }
  }
  return false;
}

/// Appends a group or mask array, completing with inDefault the side that has none.
void appendFilter(const std::vector<uint32_t>& inAdd, std::size_t inAddCount,
                  std::size_t inWorldCount, uint32_t inDefault, std::vector<uint32_t>& ioWorld) {
  if (inAdd.empty() && ioWorld.empty()) return;
  if (ioWorld.empty()) ioWorld.assign(inWorldCount, inDefault);
  if (inAdd.empty())
    ioWorld.insert(ioWorld.end(), inAddCount, inDefault);
  else
    ioWorld.insert(ioWorld.end(), inAdd.begin(), inAdd.end());
}

}  // namespace

std::string sourceName(const SourceKey& inKey) {
  std::string name = "'" + inKey.topic + "' from " + inKey.publisher;
  if (!inKey.frame_id.empty()) name += " in '" + inKey.frame_id + "'";
  return name;
}

void transformBoxes(const geometry_msgs::Transform& inTransform, BoxSet& ioBoxes) {
  const tf2::Matrix3x3 rotation(tf2::Quaternion(inTransform.rotation.x, inTransform.rotation.y,
                                                inTransform.rotation.z, inTransform.rotation.w));
  const double translation[3] = {inTransform.translation.x, inTransform.translation.y,
                                 inTransform.translation.z};
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    const double lo[3] = {ioBoxes.lo(0, i), ioBoxes.lo(1, i), ioBoxes.lo(2, i)};
    const double hi[3] = {ioBoxes.hi(0, i), ioBoxes.hi(1, i), ioBoxes.hi(2, i)};
    for (int out = 0; out < 3; ++out) {
      // The extremes over the 8 corners of row `out` of R x + t separate per input axis: each
      // term takes the smaller (larger) of R[out][in] * lo and R[out][in] * hi.
      double low = translation[out], high = translation[out];
      double magnitude = std::fabs(translation[out]);
      for (int in = 0; in < 3; ++in) {
        const double factor = rotation[out][in];
        if (factor == 0.0) continue;  // 0 x inf would be NaN; the axis does not contribute
        const double a = factor * lo[in], b = factor * hi[in];
        low += std::min(a, b);
        high += std::max(a, b);
        magnitude += std::max(std::fabs(a), std::fabs(b));
      }
      // Three products and four sums round at most 4 x (DBL_EPSILON / 2) x magnitude away
      // from the exact corner; widen by that and one more ulp so the box only grows.
      const double slack = 2.0 * DBL_EPSILON * magnitude;
      low = std::isnan(low) ? -kInfinity : std::nextafter(low - slack, -kInfinity);
      high = std::isnan(high) ? kInfinity : std::nextafter(high + slack, kInfinity);
      ioBoxes.lo(out, i) = low;
      ioBoxes.hi(out, i) = high;
    }
  }
}

void appendBoxes(const BoxSet& inAdd, BoxSet& ioWorld) {
  const std::size_t world_count = ioWorld.size();
  appendFilter(inAdd.groups, inAdd.size(), world_count, kDefaultGroup, ioWorld.groups);
  appendFilter(inAdd.masks, inAdd.size(), world_count, kDefaultMask, ioWorld.masks);
  ioWorld.ids.insert(ioWorld.ids.end(), inAdd.ids.begin(), inAdd.ids.end());
  ioWorld.bounds.insert(ioWorld.bounds.end(), inAdd.bounds.begin(), inAdd.bounds.end());
}

void shrinkBoxSet(BoxSet& ioBoxes) {
  ioBoxes.ids.shrink_to_fit();
  ioBoxes.bounds.shrink_to_fit();
  ioBoxes.groups.shrink_to_fit();
  ioBoxes.masks.shrink_to_fit();
}

void SourceSet::store(const SourceKey& inKey, BoxSet& ioBoxes, const std_msgs::Header& inHeader,
                      const ros::Time& inReceived) {
  auto [it, joined] = sources_.try_emplace(inKey);
  Source& source = it->second;
  if (joined) source.joined = next_join_++;
  ++source.frames;
  std::swap(source.boxes, ioBoxes);
  source.header = inHeader;
  source.received = inReceived;
  source.sorted_ids.clear();
  source.message.reset();
  source.accepted.reset();
  source.converted = nullptr;
  if (source.watch.shouldGiveBack(source.boxes.size(), source.boxes.ids.capacity())) {
    shrinkBoxSet(source.boxes);
    source.sorted_ids.shrink_to_fit();
  }
}

void SourceSet::storeMessage(const SourceKey& inKey, const BoxArrayConstPtr& inMessage,
                             const ros::Time& inReceived) {
  auto [it, joined] = sources_.try_emplace(inKey);
  Source& source = it->second;
  if (joined) source.joined = next_join_++;
  ++source.frames;
  source.message = inMessage;
  source.header = inMessage->header;
  source.received = inReceived;
  source.sorted_ids.clear();
}

bool SourceSet::accept(const SourceKey& inKey) {
  const auto it = sources_.find(inKey);
  if (it == sources_.end() || !it->second.message || it->second.accepted == it->second.message)
    return false;
  it->second.accepted = it->second.message;
  return true;
}

void SourceSet::refuse(const SourceKey& inKey) {
  const auto it = sources_.find(inKey);
  if (it != sources_.end() && !fallBack(it->second)) sources_.erase(it);
}

bool SourceSet::fallBack(Source& ioSource) {
  if (!ioSource.accepted || ioSource.accepted == ioSource.message) return false;
  ioSource.message = ioSource.accepted;
  ioSource.header = ioSource.message->header;
  ioSource.sorted_ids.clear();
  return true;
}

bool SourceSet::convertKept(const SourceKey& inKey, Source& ioSource, WorldAssembly& ioAssembly) {
  while (ioSource.unconverted()) {
    const BoxArray& message = *ioSource.message;
    if (auto reason = boxArrayToBoxSet(message, ioSource.boxes)) {
      ioSource.converted = nullptr;
      ioAssembly.refused_frames.push_back(RefusedFrame{message.header, message.bounds.size() / 6,
                                                       sourceName(inKey) + ": " + *reason});
      if (!fallBack(ioSource)) return false;
      continue;
    }
    ioSource.converted = ioSource.message.get();
    if (ioSource.accepted != ioSource.message) {
      ioSource.accepted = ioSource.message;
      ++ioAssembly.frames_accepted;
    }
    if (ioSource.watch.shouldGiveBack(ioSource.boxes.size(), ioSource.boxes.ids.capacity()))
      shrinkBoxSet(ioSource.boxes);
  }
  return true;
}

void SourceSet::restartClock(const ros::Time& inNow) {
  for (auto& [key, source] : sources_) source.received = inNow;
}

std::vector<SourceSet::Expired> SourceSet::expire(
    const ros::Time& inNow, const std::function<double(const SourceKey&)>& inTimeoutOf) {
  std::vector<Expired> expired;
  for (auto it = sources_.begin(); it != sources_.end();) {
    const double timeout = inTimeoutOf(it->first);
    if (timeout > 0.0 && (inNow - it->second.received).toSec() > timeout) {
      expired.push_back({it->first, it->second.frames});
      it = sources_.erase(it);
    } else {
      ++it;
    }
  }
  return expired;
}

const std::vector<uint32_t>& SourceSet::sortedIds(Source& ioSource) {
  const bool unconverted = ioSource.unconverted();
  const std::size_t count =
      unconverted ? ioSource.message->bounds.size() / 6 : ioSource.boxes.size();
  if (ioSource.sorted_ids.size() != count) {
    if (!unconverted) {
      ioSource.sorted_ids = ioSource.boxes.ids;
    } else if (ioSource.message->ids.empty()) {  // numbered 0..n-1: already sorted
      ioSource.sorted_ids.resize(count);
      std::iota(ioSource.sorted_ids.begin(), ioSource.sorted_ids.end(), 0u);
    } else {
      ioSource.sorted_ids = ioSource.message->ids;
    }
    std::sort(ioSource.sorted_ids.begin(), ioSource.sorted_ids.end());
  }
  return ioSource.sorted_ids;
}

std::string SourceSet::conflict(const SourceIt& inSource, const std::vector<SourceIt>& inMerged,
                                const std::vector<uint32_t>& inStaticIds,
                                const std::string& inWorldFrame,
                                const std::string& inWorldFrameOwner) {
  const std::string name = sourceName(inSource->first);
  const std::string& frame = inSource->second.header.frame_id;
  if (!inWorldFrame.empty() && frame != inWorldFrame) {
    return name + " publishes in frame '" + frame + "' but " + inWorldFrameOwner + " in frame '" +
           inWorldFrame + "': set ~fixed_frame to transform both, or publish in one frame";
  }
  // Ids are sorted only once a second source (or scenery) is there to collide with.
  if (inMerged.empty() && inStaticIds.empty()) return "";
  const std::vector<uint32_t>& ids = sortedIds(inSource->second);
  const char* advice = ": give each source its own id range (e.g. robot k uses ids k << 24 ...)";
  uint32_t id = 0;
  if (firstCommonId(ids, inStaticIds, id))
    return "id " + std::to_string(id) + " of " + name + " is also in " + kStaticSourceName + advice;
  for (const SourceIt& merged : inMerged) {
    if (firstCommonId(ids, sortedIds(merged->second), id)) {
      return "id " + std::to_string(id) + " of " + name + " is also in " +
             sourceName(merged->first) + advice;
    }
  }
  return "";
}

World SourceSet::assemble(const std::vector<uint32_t>& inStaticIds,
                          const std::string& inRequiredFrame, BoxSet& outWorld,
                          WorldAssembly& outAssembly, bool inNeedBoxes) {
  outAssembly = WorldAssembly();
  // Kept frames become boxes wherever the world is a BoxSet: a union, or markers to draw.
  if (inNeedBoxes || sources_.size() > 1) {
    for (auto it = sources_.begin(); it != sources_.end();)
      it = convertKept(it->first, it->second, outAssembly) ? std::next(it) : sources_.erase(it);
  }
  std::vector<SourceIt> by_join;
  for (auto it = sources_.begin(); it != sources_.end(); ++it) by_join.push_back(it);
  std::sort(by_join.begin(), by_join.end(), [](const SourceIt& a, const SourceIt& b) {
    return a->second.joined < b->second.joined;
  });
  std::string world_frame = inRequiredFrame;
  std::string world_frame_owner = kStaticSourceName;
  std::vector<SourceIt> merged;
  for (const SourceIt& source : by_join) {
    std::string reason = conflict(source, merged, inStaticIds, world_frame, world_frame_owner);
    if (!reason.empty()) {
      const std::size_t boxes = source->second.unconverted()
                                    ? source->second.message->bounds.size() / 6
                                    : source->second.boxes.size();
      outAssembly.refusals.push_back(RefusedFrame{source->second.header, boxes, std::move(reason)});
      continue;
    }
    if (world_frame.empty()) {
      world_frame = source->second.header.frame_id;
      world_frame_owner = sourceName(source->first);
    }
    if (merged.empty() || source->second.header.stamp > outAssembly.header.stamp)
      outAssembly.header.stamp = source->second.header.stamp;
    merged.push_back(source);
  }
  outAssembly.header.frame_id = world_frame;
  outAssembly.sources_merged = merged.size();
  outWorld.clear();
  World world;
  world.boxes = &outWorld;
  if (merged.size() == 1) {
    const Source& only = merged[0]->second;
    if (only.unconverted()) {
      world.boxes = nullptr;
      world.message = only.message.get();
      world.source = merged[0]->first;
    } else {
      world.boxes = &only.boxes;
    }
    return world;
  }
  for (const SourceIt& source : merged) appendBoxes(source->second.boxes, outWorld);
  return world;
}

}  // namespace sap_broadphase
