// The node's private parameters: reading, checking and defaults.
#pragma once

#include <string>

#include <ros/node_handle.h>

#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/ros/markers.h"

namespace sap_broadphase {

/// Everything BroadphaseNode can be told through its private parameters.
struct NodeParams {
  BroadphaseConfig engine;      ///< ~threads, ~method, axes, swapping, ~parallel_min_boxes
  MarkerOptions markers;        ///< ~max_marker_boxes, ~show_non_colliding, ...
  bool publish_markers = true;  ///< ~publish_markers
  int boxes_queue_size = 10;    ///< ~boxes_queue_size: subscriber queue of `boxes`
  int pairs_queue_size = 10;    ///< ~pairs_queue_size: publisher queue of `pairs`
  int refusal_log_period = 1;   ///< ~refusal_log_period: seconds between refusal errors
};

/// Parses an axis given as "x", "y", "z" (any case) or "0", "1", "2". False on anything else.
bool parseAxisName(const std::string& inName, int& outAxis);
/// Parses "auto", "parallel", "sequential" or "brute". False on anything else.
bool parseMethodName(const std::string& inName, Method& outMethod);

/// Reads the private parameters of inPrivate over the defaults of NodeParams. Returns the
/// problem (unknown axis or method, equal axes, negative counts) or an empty string.
std::string loadNodeParams(const ros::NodeHandle& inPrivate, NodeParams& outParams);

}  // namespace sap_broadphase
