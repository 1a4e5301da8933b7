// rviz wireframes of a frame's boxes.
#include "markers.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

bool isFinite(const FrameBoxes& inBoxes, std::size_t i) {
  const double* bounds = inBoxes.bounds(i);
  return std::all_of(bounds, bounds + kBoundsPerBox, [](double v) { return std::isfinite(v); });
}

/// Whether boxes i and j overlap, touch or lie less than inGap apart on every axis.
bool near(const FrameBoxes& inBoxes, std::size_t i, std::size_t j, double inGap) {
  for (int axis = 0; axis < 3; ++axis) {
    if (inBoxes.hi(axis, i) + inGap < inBoxes.lo(axis, j) ||
        inBoxes.hi(axis, j) + inGap < inBoxes.lo(axis, i))
      return false;
  }
  return true;
}

/// Which boxes a marker array draws, in frame order.
struct Selection {
  std::vector<std::size_t> colliding;  // drawn colliding boxes, moving and scenery
  std::vector<std::size_t> other;      // drawn moving boxes without a pair
  std::vector<char> drawn;             // by index: drawn as colliding
  uint32_t colliding_omitted = 0;
};

/// Under inMaxBoxes, the colliding boxes: the two sides of each pair in pair order while both
/// fit, then single sides while room is left (a pair drawn is a pair seen whole); then, if
/// inShowOthers, the moving boxes (index < inMovingCount) without a pair.
Selection selectBoxes(const FrameBoxes& inBoxes, std::size_t inMovingCount,
                      const IdIndex& inIndexOf, const PairList& inPairs, std::size_t inMaxBoxes,
                      bool inShowOthers) {
  Selection selection;
  const std::size_t count = inBoxes.size();
  std::vector<char> colliding(count, 0);
  selection.drawn.assign(count, 0);
  std::size_t drawn = 0;
  for (const IdPair& pair : inPairs) {
    const std::size_t a = inIndexOf(pair.a), b = inIndexOf(pair.b);
    std::size_t fresh = 0;
    for (const std::size_t side : {a, b}) {
      if (side == IdIndex::kAbsent) continue;
      colliding[side] = 1;
      fresh += selection.drawn[side] ? 0 : 1;
    }
    if (drawn + fresh > inMaxBoxes) continue;
    for (const std::size_t side : {a, b}) {
      if (side == IdIndex::kAbsent || selection.drawn[side]) continue;
      selection.drawn[side] = 1;
      ++drawn;
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (!colliding[i]) continue;
    if (!selection.drawn[i] && drawn < inMaxBoxes) {
      selection.drawn[i] = 1;
      ++drawn;
    }
    if (selection.drawn[i])
      selection.colliding.push_back(i);
    else
      ++selection.colliding_omitted;
  }
  if (!inShowOthers) return selection;
  for (std::size_t i = 0; i < inMovingCount && drawn < inMaxBoxes; ++i) {
    if (colliding[i]) continue;
    selection.other.push_back(i);
    ++drawn;
  }
  return selection;
}

/// By box index, the highest top among the box's drawn partners (-infinity: none).
std::vector<double> contactTops(const FrameBoxes& inBoxes, const IdIndex& inIndexOf,
                                const PairList& inPairs, const std::vector<char>& inDrawn) {
  std::vector<double> tops(inBoxes.size(), -std::numeric_limits<double>::infinity());
  for (const IdPair& pair : inPairs) {
    const std::size_t a = inIndexOf(pair.a), b = inIndexOf(pair.b);
    if (a == IdIndex::kAbsent || b == IdIndex::kAbsent || !inDrawn[a] || !inDrawn[b]) continue;
    tops[a] = std::max(tops[a], inBoxes.hi(2, b));
    tops[b] = std::max(tops[b], inBoxes.hi(2, a));
  }
  return tops;
}

/// A label of a body: its text, centred at position.
struct Label {
  std::string text;
  geometry_msgs::Point position;
  LabelExtent extent;
};

/// A named box: its index, its source (the name before ": ", or empty) and its part (the rest).
struct NamedBox {
  std::size_t index;
  std::string source;
  std::string part;
};

std::vector<NamedBox> namedBoxes(const FrameBoxes& inBoxes, const std::vector<std::size_t>& inDrawn,
                                 const BoxNames& inNames) {
  std::vector<NamedBox> named;
  for (std::size_t i : inDrawn) {
    const auto name = inNames.find(inBoxes.id(i));
    // An unbounded box (infinite extent) has no place to put a label at.
    if (name == inNames.end() || !isFinite(inBoxes, i)) continue;
    const std::size_t colon = name->second.find(": ");
    if (colon == std::string::npos)
      named.push_back({i, std::string(), name->second});
    else
      named.push_back({i, name->second.substr(0, colon), name->second.substr(colon + 2)});
  }
  return named;
}

/// Bodies: the named boxes of one source that are near each other (less than inGap apart),
/// directly or through others: a robot's parts, which touch or nearly touch. Returns, for each
/// of inNamed, the position in inNamed of its body's first box.
std::vector<std::size_t> findBodies(const FrameBoxes& inBoxes, const std::vector<NamedBox>& inNamed,
                                    double inGap) {
  std::vector<std::size_t> parent(inNamed.size());
  for (std::size_t k = 0; k < parent.size(); ++k) parent[k] = k;
  const auto root = [&parent](std::size_t k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  // Sweep along x within each source: a box meets the later ones whose x interval starts
  // before its own ends (plus the gap).
  std::vector<std::size_t> order(inNamed.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    if (inNamed[x].source != inNamed[y].source) return inNamed[x].source < inNamed[y].source;
    return inBoxes.lo(0, inNamed[x].index) < inBoxes.lo(0, inNamed[y].index);
  });
  for (std::size_t p = 0; p < order.size(); ++p) {
    const NamedBox& box = inNamed[order[p]];
    for (std::size_t q = p + 1; q < order.size(); ++q) {
      const NamedBox& later = inNamed[order[q]];
      if (later.source != box.source ||
          inBoxes.lo(0, later.index) > inBoxes.hi(0, box.index) + inGap)
        break;
      if (near(inBoxes, box.index, later.index, inGap)) {
        const std::size_t x = root(order[p]), y = root(order[q]);
        parent[std::max(x, y)] = std::min(x, y);  // the root is the body's first box
      }
    }
  }
  std::vector<std::size_t> body(inNamed.size());
  for (std::size_t k = 0; k < body.size(); ++k) body[k] = root(k);
  return body;
}

/// One label per body (its boxes less than a label's height apart), inHeight metres tall,
/// centred over the body above the top of the body and of what it touches (inContactTop: by
/// box index, the highest top among the box's drawn partners), in the order of the bodies'
/// first boxes.
std::vector<Label> bodyLabels(const FrameBoxes& inBoxes, const std::vector<std::size_t>& inDrawn,
                              const BoxNames& inNames, const std::vector<double>& inContactTop,
                              double inHeight) {
  const std::vector<NamedBox> named = namedBoxes(inBoxes, inDrawn, inNames);
  const std::vector<std::size_t> body = findBodies(inBoxes, named, inHeight);
  std::vector<Label> labels;
  for (std::size_t first = 0; first < named.size(); ++first) {
    if (body[first] != first) continue;
    double lo[3], hi[3], top = -std::numeric_limits<double>::infinity();
    std::string parts;
    for (std::size_t k = first; k < named.size(); ++k) {
      if (body[k] != first) continue;
      const std::size_t i = named[k].index;
      for (int axis = 0; axis < 3; ++axis) {
        lo[axis] = k == first ? inBoxes.lo(axis, i) : std::min(lo[axis], inBoxes.lo(axis, i));
        hi[axis] = k == first ? inBoxes.hi(axis, i) : std::max(hi[axis], inBoxes.hi(axis, i));
      }
      if (std::isfinite(inContactTop[i])) top = std::max(top, inContactTop[i]);
      parts += (parts.empty() ? "" : ", ") + named[k].part;
    }
    Label label;
    label.text = named[first].source.empty() ? parts : named[first].source + ": " + parts;
    label.extent = labelExtent(label.text, inHeight);
    // Half a line above the body and what it touches: clear of every outline of its pairs (a
    // label below a pillar's top is crossed by the pillar's lines).
    top = std::max(top, hi[2]);
    label.position =
        makePoint(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), top + 0.5 * label.extent.height);
    labels.push_back(std::move(label));
  }
  return labels;
}

/// Whether two labels would cover each other. rviz turns them to face the viewer, so a label
/// may be seen from any side: its room is a cylinder round its position, as wide as the text.
bool labelsCollide(const Label& inA, const Label& inB) {
  const double dx = inA.position.x - inB.position.x, dy = inA.position.y - inB.position.y;
  return std::abs(inA.position.z - inB.position.z) <
             0.5 * (inA.extent.height + inB.extent.height) &&
         std::hypot(dx, dy) < 0.5 * (inA.extent.width + inB.extent.width);
}

/// Lifts each label above the earlier ones it would cover, until it covers none.
void separateLabels(std::vector<Label>& ioLabels) {
  for (std::size_t k = 0; k < ioLabels.size(); ++k) {
    for (bool moved = true; moved;) {
      moved = false;
      for (std::size_t earlier = 0; earlier < k; ++earlier) {
        if (!labelsCollide(ioLabels[k], ioLabels[earlier])) continue;
        // Just above the earlier one (the height grows by a tenth against rounding).
        ioLabels[k].position.z =
            ioLabels[earlier].position.z +
            0.55 * (ioLabels[earlier].extent.height + ioLabels[k].extent.height);
        moved = true;
      }
    }
  }
}

/// Appends to ioMarkers the bodies' labels, inHeight metres tall (rviz's scale.z: the height
/// of a capital letter), facing the viewer.
void appendNames(const FrameBoxes& inBoxes, const std::vector<std::size_t>& inDrawn,
                 const BoxNames& inNames, const std::vector<double>& inContactTop,
                 const std_msgs::Header& inHeader, const std_msgs::ColorRGBA& inColor,
                 double inHeight, visualization_msgs::MarkerArray& ioMarkers) {
  std::vector<Label> labels = bodyLabels(inBoxes, inDrawn, inNames, inContactTop, inHeight);
  separateLabels(labels);
  int32_t next_id = 0;
  for (Label& label : labels) {
    visualization_msgs::Marker text = makeLineList(inHeader, kNamesNamespace, inColor);
    text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    text.id = next_id++;
    text.pose.position = label.position;
    text.scale.z = inHeight;
    text.text = std::move(label.text);
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

LabelExtent labelExtent(const std::string& inText, double inHeight) {
  // rviz's font: a glyph is at most about 0.6 of the height wide; a line, descenders and
  // spacing included, about 1.3 heights tall.
  return {0.6 * inHeight * static_cast<double>(inText.size()), 1.3 * inHeight};
}

MarkerCounts buildMarkers(const BoxFrame& inFrame, const PairList& inPairs,
                          const std_msgs::Header& inHeader, const MarkerOptions& inOptions,
                          visualization_msgs::MarkerArray& outMarkers, const BoxNames* inNames,
                          const BoxFrame* inScenery) {
  outMarkers.markers.clear();
  visualization_msgs::Marker clear_all;
  clear_all.header = inHeader;
  clear_all.action = visualization_msgs::Marker::DELETEALL;
  clear_all.pose.orientation.w = 1.0;
  outMarkers.markers.push_back(clear_all);

  // The moving boxes, then the scenery: index k < moving is a moving box.
  std::vector<BoxSpan> spans;
  for (std::size_t s = 0; s < inFrame.spanCount(); ++s) spans.push_back(inFrame.span(s));
  const std::size_t moving = FrameBoxes(inFrame).size();
  if (inScenery)
    for (std::size_t s = 0; s < inScenery->spanCount(); ++s) spans.push_back(inScenery->span(s));
  const BoxFrame world(spans);
  const FrameBoxes boxes(world);
  const IdIndex index_of(boxes);
  const Selection selection = selectBoxes(boxes, moving, index_of, inPairs, inOptions.max_boxes,
                                          inOptions.show_non_colliding);
  MarkerCounts counts;
  counts.drawn = static_cast<uint32_t>(selection.colliding.size() + selection.other.size());
  counts.colliding_omitted = selection.colliding_omitted;

  double width = inOptions.line_width;
  if (width <= 0.0) {
    // Scaled with the moving boxes: a wall of the scenery is no measure of the robots on it.
    std::vector<std::size_t> sized;
    for (std::size_t i : selection.colliding)
      if (i < moving) sized.push_back(i);
    if (sized.empty()) sized = selection.other.empty() ? selection.colliding : selection.other;
    width = 0.1 * meanEdge(boxes, sized);
    if (!(width > 0.0) || !std::isfinite(width)) width = 0.01;
  }

  if (!selection.colliding.empty()) {
    visualization_msgs::Marker colliding_marker =
        makeLineList(inHeader, kCollidingNamespace, inOptions.colliding_color);
    colliding_marker.scale.x = width;
    colliding_marker.points.reserve(24 * selection.colliding.size());
    for (std::size_t i : selection.colliding) appendWireframe(boxes, i, colliding_marker.points);
    outMarkers.markers.push_back(std::move(colliding_marker));

    // Filled as well as outlined: among many outlines, the colliding boxes stand out at a
    // glance (rviz draws TRIANGLE_LIST faces translucent with the colour's alpha).
    visualization_msgs::Marker fill_marker =
        makeLineList(inHeader, kCollidingFillNamespace, inOptions.colliding_fill_color);
    fill_marker.type = visualization_msgs::Marker::TRIANGLE_LIST;
    fill_marker.scale.x = fill_marker.scale.y = fill_marker.scale.z = 1.0;
    fill_marker.points.reserve(36 * selection.colliding.size());
    for (std::size_t i : selection.colliding) appendSolid(boxes, i, fill_marker.points);
    outMarkers.markers.push_back(std::move(fill_marker));
  }

  if (!selection.other.empty()) {
    visualization_msgs::Marker other_marker =
        makeLineList(inHeader, kNonCollidingNamespace, inOptions.non_colliding_color);
    other_marker.scale.x = 0.5 * width;
    other_marker.points.reserve(24 * selection.other.size());
    for (std::size_t i : selection.other) appendWireframe(boxes, i, other_marker.points);
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
      if (a == IdIndex::kAbsent || b == IdIndex::kAbsent || !selection.drawn[a] ||
          !selection.drawn[b])
        continue;
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
    appendNames(boxes, selection.colliding, *inNames,
                contactTops(boxes, index_of, inPairs, selection.drawn), inHeader,
                inOptions.name_color, 6.0 * width, outMarkers);
  }
  return counts;
}

}  // namespace sap_broadphase
