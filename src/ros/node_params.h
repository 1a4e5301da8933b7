// The node's private parameters: reading, checking and defaults.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "markers.h"
#include "sap_broadphase/core/broadphase.h"
#include "source_spec.h"

namespace sap_broadphase {

class BroadphaseNodeConfig;  // generated from cfg/BroadphaseNode.cfg (dynamic_reconfigure)

/// Everything BroadphaseNode can be told through its private parameters.
struct NodeParams {
  BroadphaseConfig engine;      ///< ~threads, ~method, axes, swapping, ~parallel_min_boxes
  MarkerOptions markers;        ///< ~max_marker_boxes, ~show_non_colliding, ...
  bool publish_markers = true;  ///< ~publish_markers
  int boxes_queue_size = 10;    ///< ~boxes_queue_size: subscriber queue of each source topic
  int pairs_queue_size = 10;    ///< ~pairs_queue_size: publisher queue of `pairs`
  int refusal_log_period = 1;   ///< ~refusal_log_period: seconds between refusal errors
  /// ~sources: topics (BoxArray) and {topic, type, id_offset, group, mask, timeout} entries
  /// whose publishers make up the world
  std::vector<SourceSpec> sources{SourceSpec{"boxes", InputType::kBoxArray, 0, {}, {}, {}}};
  double source_timeout = 1.0;     ///< ~source_timeout: seconds of silence before a source drops
                                   ///< out; 0 = never
  double rate = 0.0;               ///< ~rate: Hz of fixed-rate frames; 0 = a frame per delivery
  std::string fixed_frame;         ///< ~fixed_frame: tf2 target frame; empty = no transforms
  double transform_timeout = 0.1;  ///< ~transform_timeout: seconds to wait for a transform
};

/// Parses an axis given as "x", "y", "z" (any case) or "0", "1", "2". False on anything else.
bool parseAxisName(const std::string& inName, int& outAxis);

/// Parses a skin given as text: "auto" or "" (automatic), "off" (0) or a number (0 = off,
/// > 0 = fixed; configProblem() judges its range). False when the text is none of these.
bool parseSkin(const std::string& inText, std::optional<double>& outSkin);

/// The skin as parseSkin() reads it back: "auto", "off" or the shortest exact number.
std::string skinText(const std::optional<double>& inSkin);

/// Reads the private parameters of inPrivate over the defaults of NodeParams. Returns the
/// problem (unknown axis or method, equal axes, negative counts, no sources) or an empty string.
std::string loadNodeParams(const ros::NodeHandle& inPrivate, NodeParams& outParams);

/// One line of the parameters in force (threads, method, thresholds, skin, markers, sources,
/// frames), logged at start-up and after every accepted reconfigure.
std::string describeNodeParams(const NodeParams& inParams);

/// The run-time settings of inParams (engine and markers) as a dynamic_reconfigure config.
void toReconfigureConfig(const NodeParams& inParams, BroadphaseNodeConfig& outConfig);

/// Takes the run-time settings of inConfig into ioParams, checked as at start-up (axes, method,
/// skin, configProblem()). Returns the problem, with ioParams unchanged, or an empty string.
std::string fromReconfigureConfig(const BroadphaseNodeConfig& inConfig, NodeParams& ioParams);

/// True when both configurations build the same engine.
bool sameEngineConfig(const BroadphaseConfig& inA, const BroadphaseConfig& inB);

/// True when both parameter sets draw the same markers (publish_markers and MarkerOptions'
/// settings that the node reads from parameters).
bool sameMarkerSettings(const NodeParams& inA, const NodeParams& inB);

}  // namespace sap_broadphase
