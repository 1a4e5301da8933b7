// The world of a frame: the latest frame of every source, one span each.
#include "sources.h"

#include <algorithm>
#include <utility>

#include "core/tools/box_transform.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

/// What a refusal of ids shared by two sources advises.
constexpr const char* kIdRangeAdvice =
    ": give each source its own id range (e.g. robot k uses ids k << 24 ...)";

/// Tells inRefused why ioWorld's frame was refused (inError) and takes the member that holds
/// the problem back to its last accepted frame, or out of ioWorld without one.
void refuseMember(const ValidationError& inError, WorldAssembly& ioWorld, SourceSet& ioSources,
                  const MemberRefusal& inRefused) {
  // The one problem of the whole frame rather than of a box, more boxes than the engine takes,
  // goes to the newest source, as a shared id does.
  ValidationError error = inError;
  if (error.problem == BoxProblem::kShape) error.span = ioWorld.members.size() - 1;
  const std::size_t span = error.span;
  WorldMember& member = ioWorld.members.at(span);
  inRefused(*member.frame, worldRefusal(error, ioWorld));
  if (SourceFramePtr fallback = ioSources.refuse(member.key))
    member.frame = std::move(fallback);
  else
    ioWorld.members.erase(ioWorld.members.begin() + static_cast<std::ptrdiff_t>(span));
}

}  // namespace

std::string sourceName(const SourceKey& inKey) {
  std::string name = "'" + inKey.topic + "' from " + inKey.publisher;
  if (!inKey.frame_id.empty()) name += " in '" + inKey.frame_id + "'";
  return name;
}

RigidTransform rigidTransform(const geometry_msgs::Transform& inTransform) {
  RigidTransform transform;
  const geometry_msgs::Vector3& t = inTransform.translation;
  const geometry_msgs::Quaternion& q = inTransform.rotation;
  transform.translation[0] = t.x;
  transform.translation[1] = t.y;
  transform.translation[2] = t.z;
  transform.rotation[0] = q.x;
  transform.rotation[1] = q.y;
  transform.rotation[2] = q.z;
  transform.rotation[3] = q.w;
  return transform;
}

void transformBoxes(const geometry_msgs::Transform& inTransform, BoxSet& ioBoxes) {
  transformBoxes(rigidTransform(inTransform), ioBoxes);
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

const PairList* loadWorld(WorldAssembly& ioWorld, SourceSet& ioSources,
                          std::vector<BoxSpan>& ioSpans, const WorldUpdate& inUpdate,
                          const MemberRefusal& inRefused) {
  while (!ioWorld.members.empty()) {
    ioSpans.clear();
    for (const WorldMember& member : ioWorld.members) ioSpans.push_back(member.frame->span());
    try {
      return &inUpdate(BoxFrame(ioSpans));
    } catch (const InvalidBoxes& refusal) {
      refuseMember(refusal.error(), ioWorld, ioSources, inRefused);
    }
  }
  return nullptr;
}

}  // namespace sap_broadphase
