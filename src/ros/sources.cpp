// The world of a frame: the latest frame of every source, one span each.
#include "sources.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <utility>

#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>

#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// What a refusal of ids shared by two sources advises.
constexpr const char* kIdRangeAdvice =
    ": give each source its own id range (e.g. robot k uses ids k << 24 ...)";

}  // namespace

std::string sourceName(const SourceKey& inKey) {
  std::string name = "'" + inKey.topic + "' from " + inKey.publisher;
  if (!inKey.frame_id.empty()) name += " in '" + inKey.frame_id + "'";
  return name;
}

std::optional<std::string> nonFiniteTransform(const geometry_msgs::Transform& inTransform) {
  const geometry_msgs::Vector3& t = inTransform.translation;
  const geometry_msgs::Quaternion& q = inTransform.rotation;
  const std::pair<const char*, double> components[] = {
      {"translation.x", t.x}, {"translation.y", t.y}, {"translation.z", t.z}, {"rotation.x", q.x},
      {"rotation.y", q.y},    {"rotation.z", q.z},    {"rotation.w", q.w}};
  for (const auto& [name, value] : components) {
    if (!std::isfinite(value)) return std::string(name) + " is " + std::to_string(value);
  }
  return std::nullopt;
}

void transformBoxes(const geometry_msgs::Transform& inTransform, BoxSet& ioBoxes) {
  const tf2::Matrix3x3 rotation(tf2::Quaternion(inTransform.rotation.x, inTransform.rotation.y,
                                                inTransform.rotation.z, inTransform.rotation.w));
  const double translation[3] = {inTransform.translation.x, inTransform.translation.y,
                                 inTransform.translation.z};
  for (std::size_t i = 0; i < ioBoxes.size(); ++i) {
    const double lo[3] = {ioBoxes.lo(0, i), ioBoxes.lo(1, i), ioBoxes.lo(2, i)};
    const double hi[3] = {ioBoxes.hi(0, i), ioBoxes.hi(1, i), ioBoxes.hi(2, i)};
    // `lo <= hi` fails exactly for a NaN bound or min > max: moved, such a box could pass as
    // a box (NaN becomes infinite below), so it stays as published and the engine names it.
    if (!(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2])) continue;
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

BoxSpan SourceFrame::span() const {
  BoxSpan boxes = message ? boxArrayRecords(*message) : records.span();
  boxes.id_offset = id_offset;
  return boxes;
}

std_msgs::Header WorldAssembly::header() const {
  std_msgs::Header result;
  result.frame_id = frame_id;
  for (const WorldMember& member : members)
    if (member.frame->header.stamp > result.stamp) result.stamp = member.frame->header.stamp;
  return result;
}

std::string worldRefusal(const ValidationError& inError, const WorldAssembly& inWorld) {
  const std::string name = sourceName(inWorld.members.at(inError.span).key);
  if (inError.problem == BoxProblem::kDuplicateId && inError.earlier_span != inError.span) {
    const std::string other = inError.earlier_span == ValidationError::kScenery
                                  ? std::string(kStaticSourceName)
                                  : sourceName(inWorld.members.at(inError.earlier_span).key);
    return "id " + std::to_string(inError.id) + " of " + name + " is also in " + other +
           kIdRangeAdvice;
  }
  // A problem of the source's own frame: the engine's words, its boxes numbered as the source
  // numbers them (the engine numbers the boxes of the whole world). Checked alone, the frame
  // shows the same box first: every box before it passed, and its problem is its own.
  const auto own = validate(BoxFrame(inWorld.members[inError.span].frame->span()));
  return name + ": " + (own ? own->message() : inError.message());
}

void SourceSet::store(const SourceKey& inKey, SourceFramePtr inFrame, const ros::Time& inReceived) {
  auto [it, joined] = sources_.try_emplace(inKey);
  Source& source = it->second;
  if (joined) source.joined = next_join_++;
  ++source.frames;
  source.latest = std::move(inFrame);
  source.received = inReceived;
}

bool SourceSet::accept(const SourceKey& inKey) {
  const auto it = sources_.find(inKey);
  if (it == sources_.end() || it->second.accepted == it->second.latest) return false;
  it->second.accepted = it->second.latest;
  return true;
}

SourceFramePtr SourceSet::refuse(const SourceKey& inKey) {
  const auto it = sources_.find(inKey);
  if (it == sources_.end()) return nullptr;
  Source& source = it->second;
  if (!source.accepted || source.accepted == source.latest) {
    sources_.erase(it);
    return nullptr;
  }
  source.latest = source.accepted;
  return source.latest;
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

void SourceSet::assemble(const std::string& inRequiredFrame, WorldAssembly& outWorld) const {
  outWorld.members.clear();
  outWorld.left_out.clear();
  std::vector<std::map<SourceKey, Source>::const_iterator> by_join;
  for (auto it = sources_.begin(); it != sources_.end(); ++it) by_join.push_back(it);
  std::sort(by_join.begin(), by_join.end(),
            [](const auto& a, const auto& b) { return a->second.joined < b->second.joined; });
  outWorld.frame_id = inRequiredFrame;
  std::string frame_owner = kStaticSourceName;
  for (const auto& source : by_join) {
    const SourceFrame& frame = *source->second.latest;
    const std::string name = sourceName(source->first);
    if (!outWorld.frame_id.empty() && frame.header.frame_id != outWorld.frame_id) {
      outWorld.left_out.push_back(
          LeftOutSource{{source->first, source->second.latest},
                        name + " publishes in frame '" + frame.header.frame_id + "' but " +
                            frame_owner + " in frame '" + outWorld.frame_id +
                            "': set ~fixed_frame to transform both, or publish in one frame"});
      continue;
    }
    if (outWorld.frame_id.empty()) {
      outWorld.frame_id = frame.header.frame_id;
      frame_owner = name;
    }
    outWorld.members.push_back(WorldMember{source->first, source->second.latest});
  }
}

}  // namespace sap_broadphase
