// The node's private parameters: reading, checking and defaults.
#pragma once

#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/ros/markers.h"

namespace sap_broadphase {

/// Everything BroadphaseNode can be told through its private parameters.
struct NodeParams {
  BroadphaseConfig engine;      ///< ~threads, ~method, axes, swapping, ~parallel_min_boxes
  MarkerOptions markers;        ///< ~max_marker_boxes, ~show_non_colliding, ...
  bool publish_markers = true;  ///< ~publish_markers
  int boxes_queue_size = 10;    ///< ~boxes_queue_size: subscriber queue of each source topic
  int pairs_queue_size = 10;    ///< ~pairs_queue_size: publisher queue of `pairs`
  int refusal_log_period = 1;   ///< ~refusal_log_period: seconds between refusal errors
  std::vector<std::string> sources{"boxes"};  ///< ~sources: BoxArray topics merged into a world
  double source_timeout = 1.0;     ///< ~source_timeout: seconds of silence before a source drops
                                   ///< out; 0 = never
  double rate = 0.0;               ///< ~rate: Hz of fixed-rate frames; 0 = a frame per delivery
  std::string fixed_frame;         ///< ~fixed_frame: tf2 target frame; empty = no transforms
  double transform_timeout = 0.1;  ///< ~transform_timeout: seconds to wait for a transform
};

/// Parses an axis given as "x", "y", "z" (any case) or "0", "1", "2". False on anything else.
bool parseAxisName(const std::string& inName, int& outAxis);

/// Reads the private parameters of inPrivate over the defaults of NodeParams. Returns the
/// problem (unknown axis or method, equal axes, negative counts, no sources) or an empty string.
std::string loadNodeParams(const ros::NodeHandle& inPrivate, NodeParams& outParams);

/// One line of the parameters in force (threads, method, thresholds, skin, sources, frames),
/// logged once at start-up.
std::string describeNodeParams(const NodeParams& inParams);

}  // namespace sap_broadphase
