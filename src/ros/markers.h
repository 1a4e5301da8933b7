// rviz wireframes of a frame's boxes: colliding boxes, optionally the others and pair links.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>

#include <std_msgs/ColorRGBA.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// What the marker array shows. Colours are RGBA in [0, 1].
struct MarkerOptions {
  std::size_t max_boxes = 5000;     ///< boxes drawn at most (colliding first, then the others)
  bool show_non_colliding = false;  ///< also draw boxes without any pair
  bool show_pair_links = false;     ///< a line between the centres of each drawn pair
  bool show_names = true;           ///< the name of each drawn colliding box that has one, above it
  double line_width = 0.0;          ///< metres; 0 = 10 % of the mean edge of the drawn boxes
  std_msgs::ColorRGBA colliding_color;       ///< default red
  std_msgs::ColorRGBA non_colliding_color;   ///< default translucent green
  std_msgs::ColorRGBA pair_link_color;       ///< default yellow
  std_msgs::ColorRGBA colliding_fill_color;  ///< faces of colliding boxes; default translucent red
  std_msgs::ColorRGBA name_color;            ///< names of colliding boxes; default white
  MarkerOptions();
};

/// How many boxes a marker array shows and how many colliding ones the cap left out.
struct MarkerCounts {
  uint32_t drawn = 0;
  uint32_t colliding_omitted = 0;
};

/// Namespaces of the markers, one LINE_LIST each (the fill: a TRIANGLE_LIST), each sent only
/// when it has points (rviz shows an empty list marker as an error).
constexpr const char* kCollidingNamespace = "colliding";
constexpr const char* kCollidingFillNamespace = "colliding_fill";
constexpr const char* kNonCollidingNamespace = "non_colliding";
constexpr const char* kPairLinkNamespace = "pair_links";
/// One TEXT_VIEW_FACING marker per body that has names: the named colliding boxes of one
/// source that touch or nearly touch share one label (ids 0, 1, ...).
constexpr const char* kNamesNamespace = "names";

/// Box id -> the name users know it by (as on ~id_names); boxes without a name are absent.
using BoxNames = std::unordered_map<uint32_t, std::string>;

/// Fills outMarkers (replaced): a DELETEALL, then the colliding boxes of inPairs as one
/// LINE_LIST (24 points a box) and their faces as a TRIANGLE_LIST (36 points a box), both only
/// when some box collides; then, if enabled and not empty, the non-colliding boxes of inFrame and
/// the pair links (box centre to box centre); and, if enabled, labels naming the drawn colliding
/// boxes that inNames (when given) names. Header (frame and stamp) from inHeader.
///
/// Both sides of a pair are drawn: a pair's box is looked up in inFrame (whatever spans hold
/// it) and else in inScenery (the static_boxes the engine pairs the moving boxes with; when
/// given), whose boxes are drawn only when they collide. Under the max_boxes cap, whole pairs
/// are drawn first (in pair order), then single sides while room is left.
///
/// Labels: the named boxes of one source (the part of the name before ": ") that touch or
/// nearly touch (less than a label's height apart) are one body with one label,
/// "<source>: <part>, <part>", above the top of the body and of the boxes it pairs with; a
/// label that would cover an earlier one is lifted above it.
MarkerCounts buildMarkers(const BoxFrame& inFrame, const PairList& inPairs,
                          const std_msgs::Header& inHeader, const MarkerOptions& inOptions,
                          visualization_msgs::MarkerArray& outMarkers,
                          const BoxNames* inNames = nullptr, const BoxFrame* inScenery = nullptr);

/// The room a label of inText, inHeight metres tall (rviz's scale.z), takes: its width
/// (estimated from its length: rviz centres the text on its position) and height, in metres.
struct LabelExtent {
  double width;
  double height;
};
LabelExtent labelExtent(const std::string& inText, double inHeight);

}  // namespace sap_broadphase
