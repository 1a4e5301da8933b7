// rviz wireframes of a frame's boxes.
#include "markers.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

#include <geometry_msgs/Point.h>

namespace sap_broadphase {

namespace {

std_msgs::ColorRGBA makeColor(float inRed, float inGreen, float inBlue, float inAlpha) {
  std_msgs::ColorRGBA color;
  color.r = inRed;
  color.g = inGreen;
  color.b = inBlue;
  color.a = inAlpha;
  return color;
}

geometry_msgs::Point makePoint(double inX, double inY, double inZ) {
  geometry_msgs::Point point;
  point.x = inX;
  point.y = inY;
  point.z = inZ;
  return point;
}

/// A marker of inNamespace (a LINE_LIST unless the caller changes its type).
visualization_msgs::Marker makeLineList(const std_msgs::Header& inHeader, const char* inNamespace,
                                        const std_msgs::ColorRGBA& inColor) {
  visualization_msgs::Marker marker;
  marker.header = inHeader;
  marker.ns = inNamespace;
  marker.id = 0;
  marker.type = visualization_msgs::Marker::LINE_LIST;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.color = inColor;
  return marker;
}

/// The boxes of a frame by their index k in it, whatever span holds them.
class FrameBoxes {
 public:
  explicit FrameBoxes(const BoxFrame& inFrame) : frame_(inFrame) {
    for (std::size_t s = 0; s < frame_.spanCount(); ++s) {
      first_.push_back(count_);
      count_ += frame_.span(s).count;
    }
  }
  std::size_t size() const { return count_; }
  /// min_x min_y min_z max_x max_y max_z of box k.
  const double* bounds(std::size_t k) const {
    const auto [span, i] = locate(k);
    return span.bounds + kBoundsPerBox * i;
  }
  double lo(int inAxis, std::size_t k) const { return bounds(k)[inAxis]; }
  double hi(int inAxis, std::size_t k) const { return bounds(k)[3 + inAxis]; }
  /// The id of box k (a frame the engine loaded: every id fits 32 bits).
  uint32_t id(std::size_t k) const {
    const auto [span, i] = locate(k);
    return static_cast<uint32_t>(span.idOf(i));
  }

 private:
  std::pair<const BoxSpan&, std::size_t> locate(std::size_t k) const {
    const std::size_t s = static_cast<std::size_t>(
                              std::upper_bound(first_.begin(), first_.end(), k) - first_.begin()) -
                          1;
    return {frame_.span(s), k - first_[s]};
  }

  const BoxFrame& frame_;
  std::vector<std::size_t> first_;  // index in the frame of each span's first box
  std::size_t count_ = 0;
};

/// Appends the 12 edges (24 points) of box i to ioPoints.
void appendWireframe(const FrameBoxes& inBoxes, std::size_t i,
                     std::vector<geometry_msgs::Point>& ioPoints) {
  const double x[2] = {inBoxes.lo(0, i), inBoxes.hi(0, i)};
  const double y[2] = {inBoxes.lo(1, i), inBoxes.hi(1, i)};
  const double z[2] = {inBoxes.lo(2, i), inBoxes.hi(2, i)};
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      ioPoints.push_back(makePoint(x[0], y[a], z[b]));  // edge along x
      ioPoints.push_back(makePoint(x[1], y[a], z[b]));
      ioPoints.push_back(makePoint(x[a], y[0], z[b]));  // edge along y
      ioPoints.push_back(makePoint(x[a], y[1], z[b]));
      ioPoints.push_back(makePoint(x[a], y[b], z[0]));  // edge along z
      ioPoints.push_back(makePoint(x[a], y[b], z[1]));
    }
  }
}

/// Appends the 6 faces of box i, 2 triangles each (36 points), to ioPoints.
void appendSolid(const FrameBoxes& inBoxes, std::size_t i,
                 std::vector<geometry_msgs::Point>& ioPoints) {
  const double lo[3] = {inBoxes.lo(0, i), inBoxes.lo(1, i), inBoxes.lo(2, i)};
  const double hi[3] = {inBoxes.hi(0, i), inBoxes.hi(1, i), inBoxes.hi(2, i)};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (const double level : {lo[axis], hi[axis]}) {
      // The face's corners (u, v) = (lo, lo), (hi, lo), (hi, hi), (lo, hi) at `level`.
      const auto corner = [&](bool inUHigh, bool inVHigh) {
        double c[3];
        c[axis] = level;
        c[u] = inUHigh ? hi[u] : lo[u];
        c[v] = inVHigh ? hi[v] : lo[v];
        return makePoint(c[0], c[1], c[2]);
      };
      for (const auto& [uh, vh] : {std::pair{false, false},
                                   {true, false},
                                   {true, true},
                                   {false, false},
                                   {true, true},
                                   {false, true}})
        ioPoints.push_back(corner(uh, vh));
    }
  }
}

geometry_msgs::Point boxCenter(const FrameBoxes& inBoxes, std::size_t i) {
  return makePoint(0.5 * (inBoxes.lo(0, i) + inBoxes.hi(0, i)),
                   0.5 * (inBoxes.lo(1, i) + inBoxes.hi(1, i)),
                   0.5 * (inBoxes.lo(2, i) + inBoxes.hi(2, i)));
}

/// Maps box ids to indices; ids 0..n-1 in order (the common case) need no table.
class IdIndex {
 public:
  static constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);
  explicit IdIndex(const FrameBoxes& inBoxes) : count_(inBoxes.size()) {
    for (std::size_t i = 0; i < count_ && identity_; ++i) identity_ = inBoxes.id(i) == i;
    if (identity_) return;
    table_.reserve(count_);
    for (std::size_t i = 0; i < count_; ++i) table_.emplace(inBoxes.id(i), i);
  }
  /// Index of the box with id inId, or kAbsent: a pair's other box may be one of the scenery
  /// (static_boxes), which the engine pairs with the moving boxes but the world does not hold.
  std::size_t operator()(uint32_t inId) const {
    if (identity_) return inId < count_ ? inId : kAbsent;
    const auto found = table_.find(inId);
    return found == table_.end() ? kAbsent : found->second;
  }

 private:
  std::size_t count_;
  bool identity_ = true;
  std::unordered_map<uint32_t, std::size_t> table_;
};

double meanEdge(const FrameBoxes& inBoxes, const std::vector<std::size_t>& inDrawn) {
  double sum = 0.0;
  for (std::size_t i : inDrawn) {
    for (int axis = 0; axis < 3; ++axis) sum += inBoxes.hi(axis, i) - inBoxes.lo(axis, i);
  }
  return inDrawn.empty() ? 0.0 : sum / (3.0 * static_cast<double>(inDrawn.size()));
}

/// Appends to ioMarkers a text above each box of inDrawn that inNames names, inHeight metres
/// tall (rviz's scale.z: the height of a capital letter), facing the viewer.
void appendNames(const FrameBoxes& inBoxes, const std::vector<std::size_t>& inDrawn,
                 const BoxNames& inNames, const std_msgs::Header& inHeader,
                 const std_msgs::ColorRGBA& inColor, double inHeight,
                 visualization_msgs::MarkerArray& ioMarkers) {
  int32_t next_id = 0;
  for (std::size_t i : inDrawn) {
    const auto name = inNames.find(inBoxes.id(i));
    if (name == inNames.end()) continue;
    geometry_msgs::Point position = boxCenter(inBoxes, i);
    // Centred half a line above the top face, clear of the box's outline.
    position.z = inBoxes.hi(2, i) + 0.75 * inHeight;
    // An unbounded box (infinite extent) has no place to put a label at.
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
      continue;
    visualization_msgs::Marker text = makeLineList(inHeader, kNamesNamespace, inColor);
    text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    text.id = next_id++;
    text.pose.position = position;
    text.scale.z = inHeight;
    text.text = name->second;
    ioMarkers.markers.push_back(std::move(text));
  }
}

}  // namespace

MarkerOptions::MarkerOptions()
    : colliding_color(makeColor(1.0f, 0.0f, 0.0f, 1.0f)),
      non_colliding_color(makeColor(0.2f, 0.8f, 0.3f, 0.5f)),
      pair_link_color(makeColor(1.0f, 0.9f, 0.1f, 1.0f)),
      colliding_fill_color(makeColor(1.0f, 0.1f, 0.1f, 0.35f)),
      name_color(makeColor(1.0f, 1.0f, 1.0f, 1.0f)) {}

MarkerCounts buildMarkers(const BoxFrame& inFrame, const PairList& inPairs,
                          const std_msgs::Header& inHeader, const MarkerOptions& inOptions,
                          visualization_msgs::MarkerArray& outMarkers, const BoxNames* inNames) {
  outMarkers.markers.clear();
  visualization_msgs::Marker clear_all;
  clear_all.header = inHeader;
  clear_all.action = visualization_msgs::Marker::DELETEALL;
  clear_all.pose.orientation.w = 1.0;
  outMarkers.markers.push_back(clear_all);

  const FrameBoxes boxes(inFrame);
  const std::size_t count = boxes.size();
  const IdIndex index_of(boxes);
  std::vector<char> colliding(count, 0);
  for (const IdPair& pair : inPairs) {
    for (const uint32_t id : {pair.a, pair.b}) {
      const std::size_t index = index_of(id);
      if (index != IdIndex::kAbsent) colliding[index] = 1;
    }
  }
  std::vector<char> drawn(count, 0);
  std::vector<std::size_t> drawn_colliding, drawn_other;
  MarkerCounts counts;
  for (std::size_t i = 0; i < count; ++i) {
    if (!colliding[i]) continue;
    if (drawn_colliding.size() < inOptions.max_boxes) {
      drawn_colliding.push_back(i);
      drawn[i] = 1;
    } else {
      ++counts.colliding_omitted;
    }
  }
  if (inOptions.show_non_colliding) {
    for (std::size_t i = 0; i < count; ++i) {
      if (colliding[i]) continue;
      if (drawn_colliding.size() + drawn_other.size() >= inOptions.max_boxes) break;
      drawn_other.push_back(i);
    }
  }
  counts.drawn = static_cast<uint32_t>(drawn_colliding.size() + drawn_other.size());

  double width = inOptions.line_width;
  if (width <= 0.0) {
    width = 0.1 * meanEdge(boxes, drawn_colliding.empty() ? drawn_other : drawn_colliding);
    if (!(width > 0.0)) width = 0.01;
  }

  visualization_msgs::Marker colliding_marker =
      makeLineList(inHeader, kCollidingNamespace, inOptions.colliding_color);
  colliding_marker.scale.x = width;
  colliding_marker.points.reserve(24 * drawn_colliding.size());
  for (std::size_t i : drawn_colliding) appendWireframe(boxes, i, colliding_marker.points);
  outMarkers.markers.push_back(std::move(colliding_marker));

  if (!drawn_colliding.empty()) {
    // Filled as well as outlined: among many outlines, the colliding boxes stand out at a
    // glance (rviz draws TRIANGLE_LIST faces translucent with the colour's alpha).
    visualization_msgs::Marker fill_marker =
        makeLineList(inHeader, kCollidingFillNamespace, inOptions.colliding_fill_color);
    fill_marker.type = visualization_msgs::Marker::TRIANGLE_LIST;
    fill_marker.scale.x = fill_marker.scale.y = fill_marker.scale.z = 1.0;
    fill_marker.points.reserve(36 * drawn_colliding.size());
    for (std::size_t i : drawn_colliding) appendSolid(boxes, i, fill_marker.points);
    outMarkers.markers.push_back(std::move(fill_marker));
  }

  if (!drawn_other.empty()) {
    visualization_msgs::Marker other_marker =
        makeLineList(inHeader, kNonCollidingNamespace, inOptions.non_colliding_color);
    other_marker.scale.x = 0.5 * width;
    other_marker.points.reserve(24 * drawn_other.size());
    for (std::size_t i : drawn_other) appendWireframe(boxes, i, other_marker.points);
    outMarkers.markers.push_back(std::move(other_marker));
  }

  if (inOptions.show_pair_links) {
    visualization_msgs::Marker link_marker =
        makeLineList(inHeader, kPairLinkNamespace, inOptions.pair_link_color);
    link_marker.scale.x = 0.5 * width;
    std::size_t links = 0;
    for (const IdPair& pair : inPairs) {
      if (links >= inOptions.max_boxes) break;
      const std::size_t a = index_of(pair.a), b = index_of(pair.b);
      if (a == IdIndex::kAbsent || b == IdIndex::kAbsent || !drawn[a] || !drawn[b]) continue;
      link_marker.points.push_back(boxCenter(boxes, a));
      link_marker.points.push_back(boxCenter(boxes, b));
      ++links;
    }
    if (!link_marker.points.empty()) outMarkers.markers.push_back(std::move(link_marker));
  }

  if (inOptions.show_names && inNames && !inNames->empty()) {
    // Text scaled with the boxes it names, as the lines are: 6 line widths (0.6 of the mean
    // edge by default), about the smallest rviz's font stays legible at a view of the whole
    // scene.
    appendNames(boxes, drawn_colliding, *inNames, inHeader, inOptions.name_color, 6.0 * width,
                outMarkers);
  }
  return counts;
}

}  // namespace sap_broadphase
