// Unit tests of the marker builder (no ROS master needed).
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "markers.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_frames.h"

namespace sap_broadphase {
namespace {

using visualization_msgs::Marker;

const Marker* findNamespace(const visualization_msgs::MarkerArray& inMarkers, const char* inNs) {
  for (const Marker& marker : inMarkers.markers)
    if (marker.ns == inNs) return &marker;
  return nullptr;
}

// The node draws the spans it hands the engine, one a source: boxes are found by their ids in
// the frame (a span's id_offset included), whatever span holds them.
TEST(Markers, BoxesOfSeveralSpansFoundByTheirFrameIds) {
  const double a_lo[3] = {0, 0, 0}, a_hi[3] = {1, 1, 1};
  const double b_lo[3] = {0.5, 0.5, 0.5}, b_hi[3] = {2, 2, 2};
  const double far_lo[3] = {10, 10, 10}, far_hi[3] = {11, 11, 11};
  BoxSet first, second;
  first.add(0, far_lo, far_hi);
  first.add(1, a_lo, a_hi);
  second.add(1, b_lo, b_hi);  // id 1001 in the frame
  std::vector<BoxSpan> spans = {first.span(), second.span()};
  spans[1].id_offset = 1000;
  visualization_msgs::MarkerArray markers;
  MarkerOptions options;
  options.show_pair_links = true;
  const MarkerCounts counts =
      buildMarkers(BoxFrame(spans), {{1, 1001}}, std_msgs::Header(), options, markers);
  EXPECT_EQ(counts.drawn, 2u);
  const Marker* colliding = findNamespace(markers, kCollidingNamespace);
  ASSERT_TRUE(colliding);
  ASSERT_EQ(colliding->points.size(), 48u);
  EXPECT_EQ(colliding->points[0].x, 0.0) << "box 1 of the first span";
  EXPECT_EQ(colliding->points[24 + 1].x, 2.0) << "box 0 of the second span";
  const Marker* links = findNamespace(markers, kPairLinkNamespace);
  ASSERT_TRUE(links);
  ASSERT_EQ(links->points.size(), 2u);
  EXPECT_EQ(links->points[0].x, 0.5);
  EXPECT_EQ(links->points[1].x, 1.25);
}

TEST(Markers, DeleteAllFirstThenCollidingWireframes) {
  const BoxSet boxes = test::touchingGrid(2, 100);  // 8 cubes, all touching each other
  std_msgs::Header header;
  header.frame_id = "world";
  header.stamp = ros::Time(5, 6);
  visualization_msgs::MarkerArray markers;
  const MarkerCounts counts =
      buildMarkers(boxes, bruteForcePairs(boxes), header, MarkerOptions(), markers);
  ASSERT_EQ(markers.markers.size(), 3u);
  EXPECT_EQ(markers.markers[0].action, Marker::DELETEALL);
  const Marker& colliding = markers.markers[1];
  const Marker& fill = markers.markers[2];
  EXPECT_EQ(fill.type, Marker::TRIANGLE_LIST);
  EXPECT_EQ(fill.ns, kCollidingFillNamespace);
  ASSERT_EQ(fill.points.size(), 36u * 8u);
  EXPECT_LT(fill.color.a, 1.0f) << "translucent: the outlines show through";
  // Every corner of a face lies on the first cube's surface, and each triangle has area 1/2.
  for (std::size_t k = 0; k < 36; k += 3) {
    const auto& a = fill.points[k];
    const auto& b = fill.points[k + 1];
    const auto& c = fill.points[k + 2];
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
    const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    EXPECT_DOUBLE_EQ(0.5 * std::sqrt(cx * cx + cy * cy + cz * cz), 0.5) << "triangle " << k / 3;
  }
  EXPECT_EQ(colliding.type, Marker::LINE_LIST);
  EXPECT_EQ(colliding.ns, kCollidingNamespace);
  EXPECT_EQ(colliding.header.frame_id, "world");
  EXPECT_EQ(colliding.header.stamp, ros::Time(5, 6));
  EXPECT_EQ(colliding.points.size(), 24u * 8u);
  EXPECT_EQ(colliding.pose.orientation.w, 1.0);
  EXPECT_GT(colliding.scale.x, 0.0);
  EXPECT_EQ(counts.drawn, 8u);
  EXPECT_EQ(counts.colliding_omitted, 0u);
  // The 12 edges of the first cube each have length 1 along one axis.
  for (std::size_t k = 0; k < 24; k += 2) {
    const auto& a = colliding.points[k];
    const auto& b = colliding.points[k + 1];
    EXPECT_DOUBLE_EQ(std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z), 1.0);
  }
}

// rviz shows a list marker without points as an error: a frame without pairs sends none.
TEST(Markers, NoPairsSendNoCollidingList) {
  BoxSet boxes;
  const double lo_a[3] = {0, 0, 0}, hi_a[3] = {1, 1, 1}, lo_b[3] = {5, 5, 5}, hi_b[3] = {6, 6, 6};
  boxes.add(7, lo_a, hi_a);
  boxes.add(9, lo_b, hi_b);
  visualization_msgs::MarkerArray markers;
  MarkerOptions options;
  options.show_non_colliding = true;
  options.show_pair_links = true;
  const MarkerCounts counts = buildMarkers(boxes, {}, std_msgs::Header(), options, markers);
  ASSERT_EQ(markers.markers.size(), 2u) << "the DELETEALL and the boxes without a pair";
  EXPECT_EQ(markers.markers[0].action, Marker::DELETEALL);
  EXPECT_EQ(findNamespace(markers, kCollidingNamespace), nullptr);
  EXPECT_EQ(findNamespace(markers, kCollidingFillNamespace), nullptr);
  EXPECT_EQ(findNamespace(markers, kPairLinkNamespace), nullptr);
  const Marker* others = findNamespace(markers, kNonCollidingNamespace);
  ASSERT_NE(others, nullptr);
  EXPECT_EQ(others->points.size(), 48u);
  EXPECT_EQ(counts.drawn, 2u);

  options.show_non_colliding = false;
  buildMarkers(boxes, {}, std_msgs::Header(), options, markers);
  ASSERT_EQ(markers.markers.size(), 1u) << "nothing to draw: the DELETEALL alone";
}

TEST(Markers, CapCountsWhatWasLeftOutAndLinksOnlyDrawnBoxes) {
  const BoxSet boxes = test::randomBoxes(400, 1.5, true, 8);
  const PairList pairs = bruteForcePairs(boxes);
  MarkerOptions options;
  options.max_boxes = 10;
  options.show_non_colliding = true;
  options.show_pair_links = true;
  visualization_msgs::MarkerArray markers;
  const MarkerCounts counts = buildMarkers(boxes, pairs, std_msgs::Header(), options, markers);
  std::set<uint32_t> colliding_ids;
  for (const IdPair& pair : pairs) colliding_ids.insert({pair.a, pair.b});
  ASSERT_GT(colliding_ids.size(), 10u);
  EXPECT_EQ(counts.drawn, 10u);
  EXPECT_EQ(counts.colliding_omitted, colliding_ids.size() - 10);
  EXPECT_EQ(findNamespace(markers, kCollidingNamespace)->points.size(), 240u);
  EXPECT_EQ(findNamespace(markers, kNonCollidingNamespace), nullptr);
  if (const Marker* links = findNamespace(markers, kPairLinkNamespace)) {
    EXPECT_EQ(links->points.size() % 2, 0u);
    EXPECT_LE(links->points.size(), 2u * options.max_boxes);
  }
}

/// Pairs of the moving boxes inBoxes with scenery boxes, whose ids the moving set does not hold:
/// as the engine reports a moving box overlapping a static_boxes box.
void expectSceneryPairsDrawMovingSideOnly(const BoxSet& inBoxes) {
  const uint32_t scenery_id = 4000000;  // no moving box has it
  PairList pairs = {makeIdPair(inBoxes.ids[1], scenery_id),
                    makeIdPair(scenery_id + 1, inBoxes.ids[3])};
  std::sort(pairs.begin(), pairs.end());
  MarkerOptions options;
  options.show_pair_links = true;
  visualization_msgs::MarkerArray markers;
  const MarkerCounts counts = buildMarkers(inBoxes, pairs, std_msgs::Header(), options, markers);
  EXPECT_EQ(counts.drawn, 2u);
  EXPECT_EQ(findNamespace(markers, kCollidingNamespace)->points.size(), 48u);
  EXPECT_EQ(findNamespace(markers, kPairLinkNamespace), nullptr);
}

TEST(Markers, PairsWithSceneryBoxesDrawTheMovingBoxWhateverItsIds) {
  expectSceneryPairsDrawMovingSideOnly(test::touchingGrid(2, 0));    // ids 0..n-1: no table
  expectSceneryPairsDrawMovingSideOnly(test::touchingGrid(2, 100));  // ids through the table
}

std::vector<const Marker*> namesOf(const visualization_msgs::MarkerArray& inMarkers) {
  std::vector<const Marker*> names;
  for (const Marker& marker : inMarkers.markers)
    if (marker.ns == kNamesNamespace) names.push_back(&marker);
  return names;
}

TEST(Markers, NamesAboveNamedCollidingBoxesOnly) {
  BoxSet boxes = test::touchingGrid(2, 100);  // 8 colliding unit cubes, ids 100..107
  const double lo[3] = {50, 50, 50}, hi[3] = {51, 51, 51};
  boxes.add(300, lo, hi);  // alone: drawn as non-colliding, never named
  const BoxNames names = {{100, "robot_a/boxes: body/0"},
                          {103, "robot_a/boxes: load/0[2]"},
                          {300, "robot_a/boxes: lonely/0"}};
  MarkerOptions options;
  options.show_non_colliding = true;
  std_msgs::Header header;
  header.frame_id = "map";
  visualization_msgs::MarkerArray markers;
  buildMarkers(boxes, bruteForcePairs(boxes), header, options, markers, &names);
  const std::vector<const Marker*> texts = namesOf(markers);
  // 100 ([0,1]^3) and 103 ([0,1]x[1,2]x[1,2]) touch along an edge: one body, one label.
  ASSERT_EQ(texts.size(), 1u) << "101.. have no name, 300 collides with none";
  const Marker& label = *texts[0];
  EXPECT_EQ(label.text, "robot_a/boxes: body/0, load/0[2]");
  EXPECT_EQ(label.type, Marker::TEXT_VIEW_FACING);
  EXPECT_EQ(label.action, Marker::ADD);
  EXPECT_EQ(label.header.frame_id, "map");
  EXPECT_DOUBLE_EQ(label.pose.position.x, 0.5) << "centred on the body";
  EXPECT_DOUBLE_EQ(label.pose.position.y, 1.0);
  EXPECT_GT(label.pose.position.z, 2.0) << "above the body";
  EXPECT_GT(label.scale.z, 0.0);
  EXPECT_LT(label.scale.z, 1.0) << "smaller than the unit cube it names";
  EXPECT_LT(label.pose.position.z - 0.5 * label.scale.z, 2.0 + label.scale.z)
      << "just above the body, not floating away";

  options.show_names = false;
  buildMarkers(boxes, bruteForcePairs(boxes), header, options, markers, &names);
  EXPECT_TRUE(namesOf(markers).empty()) << "switched off";
  options.show_names = true;
  buildMarkers(boxes, bruteForcePairs(boxes), header, options, markers);
  EXPECT_TRUE(namesOf(markers).empty()) << "no names given";
}

TEST(Markers, NamesAreBoundedByTheDrawnBoxes) {
  const BoxSet boxes = test::randomBoxes(400, 1.5, true, 8);
  const PairList pairs = bruteForcePairs(boxes);
  BoxNames names;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    names[boxes.ids[i]] = "box " + std::to_string(boxes.ids[i]);
  MarkerOptions options;
  options.max_boxes = 10;
  visualization_msgs::MarkerArray markers;
  const MarkerCounts counts =
      buildMarkers(boxes, pairs, std_msgs::Header(), options, markers, &names);
  ASSERT_GT(counts.colliding_omitted, 0u) << "the cap must bite for this test to mean anything";
  std::size_t named = 0;
  for (const Marker* text : namesOf(markers))
    named += static_cast<std::size_t>(std::count(text->text.begin(), text->text.end(), ',')) + 1;
  EXPECT_EQ(named, 10u) << "a name for each drawn box, none for the others";
}

/// The boxes a colliding LINE_LIST draws, as min x, y, z, max x, y, z of each 24 points.
std::set<std::vector<double>> wireframeBoxes(const Marker& inList) {
  std::set<std::vector<double>> boxes;
  for (std::size_t k = 0; k + 24 <= inList.points.size(); k += 24) {
    std::vector<double> box = {inList.points[k].x, inList.points[k].y, inList.points[k].z,
                               inList.points[k].x, inList.points[k].y, inList.points[k].z};
    for (std::size_t p = k; p < k + 24; ++p) {
      const double xyz[3] = {inList.points[p].x, inList.points[p].y, inList.points[p].z};
      for (int axis = 0; axis < 3; ++axis) {
        box[axis] = std::min(box[axis], xyz[axis]);
        box[3 + axis] = std::max(box[3 + axis], xyz[axis]);
      }
    }
    boxes.insert(box);
  }
  return boxes;
}

std::vector<double> boundsOf(const BoxSet& inBoxes, uint32_t inId) {
  const std::size_t i =
      std::find(inBoxes.ids.begin(), inBoxes.ids.end(), inId) - inBoxes.ids.begin();
  if (i == inBoxes.size()) return {};
  return {inBoxes.lo(0, i), inBoxes.lo(1, i), inBoxes.lo(2, i),
          inBoxes.hi(0, i), inBoxes.hi(1, i), inBoxes.hi(2, i)};
}

/// What rviz would show in Error: a list marker added without points, a text without text.
void expectNothingEmpty(const visualization_msgs::MarkerArray& inMarkers) {
  for (const Marker& marker : inMarkers.markers) {
    if (marker.action != Marker::ADD) continue;
    if (marker.type == Marker::TEXT_VIEW_FACING)
      EXPECT_FALSE(marker.text.empty()) << marker.ns << "/" << marker.id;
    else
      EXPECT_FALSE(marker.points.empty())
          << "an empty list marker: " << marker.ns << "/" << marker.id;
  }
}

/// No two labels on top of each other: apart in height, or apart in the plane by their widths
/// (rviz turns a label to face the viewer: seen from any side, it spans its width round its
/// position).
void expectLabelsApart(const visualization_msgs::MarkerArray& inMarkers) {
  const std::vector<const Marker*> texts = namesOf(inMarkers);
  for (std::size_t a = 0; a < texts.size(); ++a) {
    for (std::size_t b = a + 1; b < texts.size(); ++b) {
      const LabelExtent ea = labelExtent(texts[a]->text, texts[a]->scale.z);
      const LabelExtent eb = labelExtent(texts[b]->text, texts[b]->scale.z);
      const auto& pa = texts[a]->pose.position;
      const auto& pb = texts[b]->pose.position;
      const bool apart_in_height = std::abs(pa.z - pb.z) >= 0.5 * (ea.height + eb.height);
      const bool apart_in_plane =
          std::hypot(pa.x - pb.x, pa.y - pb.y) >= 0.5 * (ea.width + eb.width);
      EXPECT_TRUE(apart_in_height || apart_in_plane)
          << "'" << texts[a]->text << "' and '" << texts[b]->text << "' overlap";
    }
  }
}

/// The engine's pairs of moving boxes with each other and with the scenery (never scenery
/// with scenery), by brute force.
PairList pairsWithScenery(const BoxSet& inMoving, const BoxSet& inScenery) {
  const std::vector<BoxSpan> spans = {inMoving.span(), inScenery.span()};
  PairList pairs;
  for (const IdPair& pair : bruteForcePairs(BoxFrame(spans))) {
    const bool a_scenery = !boundsOf(inScenery, pair.a).empty();
    const bool b_scenery = !boundsOf(inScenery, pair.b).empty();
    if (!(a_scenery && b_scenery)) pairs.push_back(pair);
  }
  return pairs;
}

// A scene of moving boxes in a room of scenery, frame after frame, some frames without any
// pair: no empty list marker ever, both sides of every pair drawn (the scenery's included) and
// linked, labels apart.
TEST(Markers, FramesWithAndWithoutPairsDrawBothSidesOfEveryPair) {
  BoxSet scenery;  // a wall and two pillars, ids 500.., apart from each other
  const double wall_lo[3] = {-1, -1, 0}, wall_hi[3] = {11, -0.5, 1};
  const double pillar_lo[3] = {3, 3, 0}, pillar_hi[3] = {3.5, 3.5, 10};
  const double far_lo[3] = {8, 8, 0}, far_hi[3] = {8.5, 8.5, 10};
  scenery.add(500, wall_lo, wall_hi);
  scenery.add(501, pillar_lo, pillar_hi);
  scenery.add(502, far_lo, far_hi);
  MarkerOptions options;
  options.show_non_colliding = true;
  options.show_pair_links = true;
  std::size_t frames_with_pairs = 0, frames_without = 0, scenery_pairs = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    // Odd seeds: a few small boxes (often no pair); even: many (pairs with the scenery too).
    const BoxSet moving = test::randomBoxes(seed % 2 ? 3 : 60, seed % 2 ? 0.3 : 1.5, false, seed);
    BoxNames names;
    for (uint32_t id : moving.ids)
      names[id] = "robot_" + std::to_string(id % 3) + "/boxes: part/" + std::to_string(id);
    const PairList pairs = pairsWithScenery(moving, scenery);
    (pairs.empty() ? frames_without : frames_with_pairs) += 1;
    const BoxFrame scenery_frame(scenery.span());
    visualization_msgs::MarkerArray markers;
    const MarkerCounts counts =
        buildMarkers(moving, pairs, std_msgs::Header(), options, markers, &names, &scenery_frame);
    SCOPED_TRACE("seed " + std::to_string(seed));
    expectNothingEmpty(markers);
    expectLabelsApart(markers);
    EXPECT_EQ(counts.colliding_omitted, 0u);
    const Marker* colliding = findNamespace(markers, kCollidingNamespace);
    if (pairs.empty()) {
      EXPECT_EQ(colliding, nullptr);
      continue;
    }
    ASSERT_NE(colliding, nullptr);
    const std::set<std::vector<double>> drawn = wireframeBoxes(*colliding);
    for (const IdPair& pair : pairs) {
      for (uint32_t id : {pair.a, pair.b}) {
        std::vector<double> bounds = boundsOf(moving, id);
        if (bounds.empty()) {
          bounds = boundsOf(scenery, id);
          ++scenery_pairs;
        }
        EXPECT_EQ(drawn.count(bounds), 1u) << "box " << id << " of pair (" << pair.a << ", "
                                           << pair.b << ") not drawn as colliding";
      }
    }
    const Marker* links = findNamespace(markers, kPairLinkNamespace);
    ASSERT_NE(links, nullptr);
    EXPECT_EQ(links->points.size(), 2 * pairs.size()) << "a link for each pair";
  }
  EXPECT_GT(frames_with_pairs, 0u);
  EXPECT_GT(frames_without, 0u);
  EXPECT_GT(scenery_pairs, 0u) << "the scene must meet the scenery for this test to mean anything";
}

// A robot (body and three load cubes just above it, all named) against a pillar of the
// scenery, another robot against the same pillar: one label per robot naming its parts, above
// the pillar's top, the two labels apart, the pillar drawn red.
TEST(Markers, PartsOfOneBodyShareOneLabelAndBodiesLabelsStayApart) {
  BoxSet robots;
  const double body_lo[3] = {0, 0, 0}, body_hi[3] = {1, 1, 1};
  robots.add(1000, body_lo, body_hi);
  for (uint32_t k = 0; k < 3; ++k) {
    // On the body, a little above it (as a robot's load): still part of the body.
    const double lo[3] = {0.3 * k, 0, 1.05}, hi[3] = {0.3 * k + 0.3, 0.3, 1.35};
    robots.add(1001 + k, lo, hi);
  }
  const double other_lo[3] = {1.2, 0, 0}, other_hi[3] = {2.2, 1, 1};
  robots.add(2000, other_lo, other_hi);
  BoxSet pillar;
  const double pillar_lo[3] = {0.8, -0.5, 0}, pillar_hi[3] = {1.4, 1.5, 2};
  pillar.add(4, pillar_lo, pillar_hi);
  const BoxNames names = {{1000, "robot_a/boxes: body/0"},
                          {1001, "robot_a/boxes: load/0[0]"},
                          {1002, "robot_a/boxes: load/0[1]"},
                          {1003, "robot_a/boxes: load/0[2]"},
                          {2000, "robot_b/boxes: body/0"}};
  // Every robot box meets the pillar; the robots' own pairs are filtered out (groups).
  PairList pairs;
  for (uint32_t id : robots.ids) pairs.push_back(makeIdPair(4, id));
  std::sort(pairs.begin(), pairs.end());
  const BoxFrame scenery(pillar.span());
  visualization_msgs::MarkerArray markers;
  buildMarkers(robots, pairs, std_msgs::Header(), MarkerOptions(), markers, &names, &scenery);
  expectNothingEmpty(markers);
  std::set<std::string> texts;
  for (const Marker* text : namesOf(markers)) texts.insert(text->text);
  EXPECT_EQ(texts, (std::set<std::string>{"robot_a/boxes: body/0, load/0[0], load/0[1], load/0[2]",
                                          "robot_b/boxes: body/0"}));
  expectLabelsApart(markers);
  for (const Marker* text : namesOf(markers))
    EXPECT_GT(text->pose.position.z - 0.5 * text->scale.z, 2.0) << "above the pillar's top";
  const Marker* colliding = findNamespace(markers, kCollidingNamespace);
  ASSERT_NE(colliding, nullptr);
  EXPECT_EQ(wireframeBoxes(*colliding).count(boundsOf(pillar, 4)), 1u) << "the pillar is red";
  EXPECT_EQ(colliding->points.size(), 24u * 6u) << "five robot boxes and the pillar";
  // Lines scaled with the robots, not with the scenery.
  EXPECT_LT(colliding->scale.x, 0.1);
}

// Under the cap, pairs are drawn whole: each drawn box's partner is drawn too, while room is
// left for both.
TEST(Markers, CapDrawsPairsWhole) {
  BoxSet boxes;
  for (uint32_t k = 0; k < 10; ++k) {  // five separate pairs: 2k and 2k+1 overlap
    const double lo[3] = {10.0 * (k / 2) + 0.5 * (k % 2), 0, 0};
    const double hi[3] = {lo[0] + 1, 1, 1};
    boxes.add(k, lo, hi);
  }
  const PairList pairs = bruteForcePairs(boxes);
  ASSERT_EQ(pairs.size(), 5u);
  MarkerOptions options;
  options.max_boxes = 7;
  options.show_pair_links = true;
  visualization_msgs::MarkerArray markers;
  const MarkerCounts counts = buildMarkers(boxes, pairs, std_msgs::Header(), options, markers);
  EXPECT_EQ(counts.drawn, 7u);
  EXPECT_EQ(counts.colliding_omitted, 3u);
  const Marker* links = findNamespace(markers, kPairLinkNamespace);
  ASSERT_NE(links, nullptr);
  EXPECT_EQ(links->points.size(), 2u * 3u) << "three whole pairs, then one box alone";
}

}  // namespace
}  // namespace sap_broadphase
