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

TEST(Markers, NoPairsGiveAnEmptyCollidingList) {
  BoxSet boxes;
  const double lo_a[3] = {0, 0, 0}, hi_a[3] = {1, 1, 1}, lo_b[3] = {5, 5, 5}, hi_b[3] = {6, 6, 6};
  boxes.add(7, lo_a, hi_a);
  boxes.add(9, lo_b, hi_b);
  visualization_msgs::MarkerArray markers;
  MarkerOptions options;
  options.show_non_colliding = true;
  const MarkerCounts counts = buildMarkers(boxes, {}, std_msgs::Header(), options, markers);
  ASSERT_EQ(markers.markers.size(), 3u);
  EXPECT_TRUE(markers.markers[1].points.empty());
  const Marker* others = findNamespace(markers, kNonCollidingNamespace);
  ASSERT_NE(others, nullptr);
  EXPECT_EQ(others->points.size(), 48u);
  EXPECT_EQ(counts.drawn, 2u);
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
  ASSERT_EQ(texts.size(), 2u) << "boxes 100 and 103; 101.. have no name, 300 collides with none";
  std::set<int32_t> marker_ids;
  for (const Marker* text : texts) {
    EXPECT_EQ(text->type, Marker::TEXT_VIEW_FACING);
    EXPECT_EQ(text->action, Marker::ADD);
    EXPECT_EQ(text->header.frame_id, "map");
    marker_ids.insert(text->id);
  }
  EXPECT_EQ(marker_ids.size(), 2u) << "one marker (id) per name";
  const std::size_t index = std::find(boxes.ids.begin(), boxes.ids.end(), 103u) - boxes.ids.begin();
  const Marker* load = texts[0]->text == names.at(103) ? texts[0] : texts[1];
  ASSERT_EQ(load->text, names.at(103));
  EXPECT_DOUBLE_EQ(load->pose.position.x, 0.5 * (boxes.lo(0, index) + boxes.hi(0, index)));
  EXPECT_DOUBLE_EQ(load->pose.position.y, 0.5 * (boxes.lo(1, index) + boxes.hi(1, index)));
  EXPECT_GT(load->pose.position.z, boxes.hi(2, index)) << "above the box";
  EXPECT_GT(load->scale.z, 0.0);
  EXPECT_LT(load->scale.z, 1.0) << "smaller than the unit cube it names";
  EXPECT_LT(load->pose.position.z - 0.5 * load->scale.z, boxes.hi(2, index) + load->scale.z)
      << "just above the box, not floating away";

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
  EXPECT_EQ(namesOf(markers).size(), 10u) << "a name for each drawn box, none for the others";
}

}  // namespace
}  // namespace sap_broadphase
