// The node's private parameters.
#include "node_params.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include <xmlrpcpp/XmlRpcValue.h>

#include "adapters_sources.h"
#include "sap_broadphase/BroadphaseNodeConfig.h"

namespace sap_broadphase {

namespace {

/// Reads an axis parameter given as a name or an integer; keeps ioAxis when absent.
std::string readAxis(const ros::NodeHandle& inPrivate, const std::string& inName, int& ioAxis) {
  XmlRpc::XmlRpcValue value;
  if (!inPrivate.getParam(inName, value)) return "";
  std::string text;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeInt)
    text = std::to_string(static_cast<int>(value));
  else if (value.getType() == XmlRpc::XmlRpcValue::TypeString)
    text = static_cast<std::string>(value);
  if (!parseAxisName(text, ioAxis)) return "~" + inName + " must be x, y, z (or 0, 1, 2)";
  return "";
}

/// Reads a non-negative integer parameter; keeps ioValue when absent.
template <typename Integer>
std::string readCount(const ros::NodeHandle& inPrivate, const std::string& inName,
                      Integer& ioValue) {
  int value = 0;
  if (!inPrivate.getParam(inName, value)) return "";
  if (value < 0) return "~" + inName + " must not be negative";
  ioValue = static_cast<Integer>(value);
  return "";
}

/// Reads a non-negative number of seconds or Hz; keeps ioValue when absent.
std::string readNonNegative(const ros::NodeHandle& inPrivate, const std::string& inName,
                            double& ioValue) {
  double value = ioValue;
  if (!inPrivate.getParam(inName, value)) {
    int integer = 0;  // an integer given in YAML is not a double for the parameter server
    if (!inPrivate.getParam(inName, integer)) return "";
    value = integer;
  }
  if (!(value >= 0.0) || !std::isfinite(value))
    return "~" + inName + " must be a finite number >= 0, not " + std::to_string(value);
  ioValue = value;
  return "";
}

/// Reads ~sources: topics and {topic, type, ...} entries whose publishers make up the world.
std::string readSources(const ros::NodeHandle& inPrivate, std::vector<SourceSpec>& ioSources) {
  XmlRpc::XmlRpcValue value;
  if (!inPrivate.getParam("sources", value)) return "";
  return parseSourceSpecs(value, ioSources);
}

}  // namespace

bool parseAxisName(const std::string& inName, int& outAxis) {
  std::string name = inName;
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const char* kNames[3][2] = {{"x", "0"}, {"y", "1"}, {"z", "2"}};
  for (int axis = 0; axis < 3; ++axis) {
    if (name == kNames[axis][0] || name == kNames[axis][1]) {
      outAxis = axis;
      return true;
    }
  }
  return false;
}

bool parseSkin(const std::string& inText, std::optional<double>& outSkin) {
  if (inText.empty() || inText == "auto") {
    outSkin.reset();
    return true;
  }
  if (inText == "off") {
    outSkin = 0.0;
    return true;
  }
  char* end = nullptr;
  const double value = std::strtod(inText.c_str(), &end);
  if (end == inText.c_str() || *end != '\0') return false;
  outSkin = value;
  return true;
}

std::string skinText(const std::optional<double>& inSkin) {
  if (!inSkin) return "auto";
  if (*inSkin == 0.0) return "off";
  // The shortest text that reads back as the same double, so that a skin written to the
  // parameter server by dynamic_reconfigure is the skin in force.
  for (int digits = 6; digits < 17; ++digits) {
    std::ostringstream text;
    text.precision(digits);
    text << *inSkin;
    if (std::strtod(text.str().c_str(), nullptr) == *inSkin) return text.str();
  }
  std::ostringstream text;
  text.precision(17);
  text << *inSkin;
  return text.str();
}

// ~skin is "auto" (the default), 0 (off) or a fixed skin in metres; as text also "off" or a
// number, the form dynamic_reconfigure writes back to the parameter server.
std::string readSkin(const ros::NodeHandle& inPrivate, std::optional<double>& outSkin) {
  XmlRpc::XmlRpcValue value;
  if (!inPrivate.getParam("skin", value)) return "";
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString &&
      parseSkin(static_cast<std::string>(value), outSkin))
    return "";
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble)
    outSkin = static_cast<double>(value);
  else if (value.getType() == XmlRpc::XmlRpcValue::TypeInt)
    outSkin = static_cast<int>(value);
  else
    return "~skin must be auto, 0 (off) or a skin > 0 in the boxes' units";
  return "";
}

std::string loadNodeParams(const ros::NodeHandle& inPrivate, NodeParams& outParams) {
  BroadphaseConfig& engine = outParams.engine;
  MarkerOptions& markers = outParams.markers;
  std::string error;
  if (!(error = readCount(inPrivate, "threads", engine.threads)).empty()) return error;
  std::string method = "auto";
  inPrivate.param<std::string>("method", method, method);
  const std::optional<Method> parsed_method = parseMethod(method);
  if (!parsed_method)
    return "~method must be auto, parallel, sequential or brute, not '" + method + "'";
  engine.method = *parsed_method;
  if (!(error = readAxis(inPrivate, "primary_axis", engine.primary_axis)).empty()) return error;
  if (!(error = readAxis(inPrivate, "secondary_axis", engine.secondary_axis)).empty()) return error;
  if (engine.primary_axis == engine.secondary_axis)
    return "~primary_axis and ~secondary_axis must differ";
  inPrivate.param("axis_swapping", engine.axis_swapping, engine.axis_swapping);
  inPrivate.param("axis_swap_threshold", engine.axis_swap_threshold, engine.axis_swap_threshold);
  if (!(error = readCount(inPrivate, "parallel_min_boxes", engine.parallel_min_boxes)).empty())
    return error;
  if (!(error = readCount(inPrivate, "third_axis_slabs", engine.third_axis_slabs)).empty())
    return error;
  inPrivate.param("exact_final_test", engine.exact_final_test, engine.exact_final_test);
  // Publishers often resend a scene that did not move: worth the engine's copy of the frame.
  engine.reuse_unchanged_frames = true;
  inPrivate.param("reuse_unchanged_frames", engine.reuse_unchanged_frames,
                  engine.reuse_unchanged_frames);
  inPrivate.param("index_static_boxes", engine.index_static_boxes, engine.index_static_boxes);
  if (!(error = readSkin(inPrivate, engine.skin)).empty()) return error;
  if (const auto problem = configProblem(engine)) return "~" + *problem;

  inPrivate.param("publish_markers", outParams.publish_markers, outParams.publish_markers);
  if (!(error = readCount(inPrivate, "max_marker_boxes", markers.max_boxes)).empty()) return error;
  inPrivate.param("show_non_colliding", markers.show_non_colliding, markers.show_non_colliding);
  inPrivate.param("show_pair_links", markers.show_pair_links, markers.show_pair_links);
  inPrivate.param("marker_line_width", markers.line_width, markers.line_width);

  if (!(error = readCount(inPrivate, "boxes_queue_size", outParams.boxes_queue_size)).empty())
    return error;
  if (!(error = readCount(inPrivate, "pairs_queue_size", outParams.pairs_queue_size)).empty())
    return error;
  if (!(error = readCount(inPrivate, "refusal_log_period", outParams.refusal_log_period)).empty())
    return error;
  outParams.boxes_queue_size = std::max(outParams.boxes_queue_size, 1);

  if (!(error = readSources(inPrivate, outParams.sources)).empty()) return error;
  if (!(error = readNonNegative(inPrivate, "source_timeout", outParams.source_timeout)).empty())
    return error;
  if (!(error = readNonNegative(inPrivate, "rate", outParams.rate)).empty()) return error;
  inPrivate.param<std::string>("fixed_frame", outParams.fixed_frame, outParams.fixed_frame);
  if (!outParams.fixed_frame.empty() && outParams.fixed_frame.front() == '/')
    outParams.fixed_frame.erase(0, 1);  // tf2 frame ids carry no leading slash
  if (!(error = readNonNegative(inPrivate, "transform_timeout", outParams.transform_timeout))
           .empty())
    return error;
  return "";
}

std::string describeNodeParams(const NodeParams& inParams) {
  const BroadphaseConfig& engine = inParams.engine;
  std::ostringstream text;
  text << "threads " << resolveThreadCount(engine.threads) << " (~threads " << engine.threads
       << "), method " << methodName(engine.method) << ", parallel_min_boxes "
       << engine.parallel_min_boxes << ", axes "
       << "xyz"[engine.primary_axis] << "xyz"[engine.secondary_axis]
       << (engine.axis_swapping ? " (swapping)" : "") << ", skin " << skinText(engine.skin);
  if (engine.third_axis_slabs > 0) text << ", third_axis_slabs " << engine.third_axis_slabs;
  if (!engine.exact_final_test) text << ", float32 final test (may report extra pairs)";
  if (!engine.reuse_unchanged_frames) text << ", unchanged frames swept again";
  if (engine.index_static_boxes) text << ", resting boxes indexed";
  text << ", markers ";
  if (inParams.publish_markers)
    text << "at most " << inParams.markers.max_boxes << " boxes"
         << (inParams.markers.show_non_colliding ? " (non-colliding too)" : "")
         << (inParams.markers.show_pair_links ? " (pair links)" : "");
  else
    text << "off";
  text << ", sources [";
  for (std::size_t i = 0; i < inParams.sources.size(); ++i)
    text << (i ? ", " : "") << describeSourceSpec(inParams.sources[i]);
  text << "], source_timeout " << inParams.source_timeout << " s, ";
  if (inParams.rate > 0.0)
    text << "rate " << inParams.rate << " Hz";
  else
    text << "a frame per delivery";
  text << ", fixed_frame ";
  if (inParams.fixed_frame.empty())
    text << "none (sources must share one frame_id)";
  else
    text << "'" << inParams.fixed_frame << "' (transform_timeout " << inParams.transform_timeout
         << " s)";
  return text.str();
}

void toReconfigureConfig(const NodeParams& inParams, BroadphaseNodeConfig& outConfig) {
  const BroadphaseConfig& engine = inParams.engine;
  outConfig.threads = engine.threads;
  outConfig.method = methodName(engine.method);
  outConfig.primary_axis = std::string(1, "xyz"[engine.primary_axis]);
  outConfig.secondary_axis = std::string(1, "xyz"[engine.secondary_axis]);
  outConfig.axis_swapping = engine.axis_swapping;
  outConfig.axis_swap_threshold = engine.axis_swap_threshold;
  outConfig.parallel_min_boxes = static_cast<int>(
      std::min<std::size_t>(engine.parallel_min_boxes, std::numeric_limits<int>::max()));
  outConfig.third_axis_slabs = engine.third_axis_slabs;
  outConfig.exact_final_test = engine.exact_final_test;
  outConfig.reuse_unchanged_frames = engine.reuse_unchanged_frames;
  outConfig.index_static_boxes = engine.index_static_boxes;
  outConfig.skin = skinText(engine.skin);
  const MarkerOptions& markers = inParams.markers;
  outConfig.publish_markers = inParams.publish_markers;
  outConfig.max_marker_boxes =
      static_cast<int>(std::min<std::size_t>(markers.max_boxes, std::numeric_limits<int>::max()));
  outConfig.show_non_colliding = markers.show_non_colliding;
  outConfig.show_pair_links = markers.show_pair_links;
  outConfig.marker_line_width = markers.line_width;
}

std::string fromReconfigureConfig(const BroadphaseNodeConfig& inConfig, NodeParams& ioParams) {
  BroadphaseConfig engine = ioParams.engine;
  if (inConfig.threads < 0) return "threads must not be negative";
  engine.threads = inConfig.threads;
  const std::optional<Method> method = parseMethod(inConfig.method);
  if (!method)
    return "method must be auto, parallel, sequential or brute, not '" + inConfig.method + "'";
  engine.method = *method;
  if (!parseAxisName(inConfig.primary_axis, engine.primary_axis))
    return "primary_axis must be x, y or z, not '" + inConfig.primary_axis + "'";
  if (!parseAxisName(inConfig.secondary_axis, engine.secondary_axis))
    return "secondary_axis must be x, y or z, not '" + inConfig.secondary_axis + "'";
  engine.axis_swapping = inConfig.axis_swapping;
  engine.axis_swap_threshold = inConfig.axis_swap_threshold;
  if (inConfig.parallel_min_boxes < 0) return "parallel_min_boxes must not be negative";
  engine.parallel_min_boxes = static_cast<std::size_t>(inConfig.parallel_min_boxes);
  engine.third_axis_slabs = inConfig.third_axis_slabs;
  engine.exact_final_test = inConfig.exact_final_test;
  engine.reuse_unchanged_frames = inConfig.reuse_unchanged_frames;
  engine.index_static_boxes = inConfig.index_static_boxes;
  if (!parseSkin(inConfig.skin, engine.skin))
    return "skin must be auto, off (or 0) or a skin > 0 in the boxes' units, not '" +
           inConfig.skin + "'";
  if (const auto problem = configProblem(engine)) return *problem;
  if (inConfig.max_marker_boxes < 0) return "max_marker_boxes must not be negative";
  if (!(inConfig.marker_line_width >= 0.0) || !std::isfinite(inConfig.marker_line_width))
    return "marker_line_width must be a finite number >= 0";

  ioParams.engine = engine;
  ioParams.publish_markers = inConfig.publish_markers;
  ioParams.markers.max_boxes = static_cast<std::size_t>(inConfig.max_marker_boxes);
  ioParams.markers.show_non_colliding = inConfig.show_non_colliding;
  ioParams.markers.show_pair_links = inConfig.show_pair_links;
  ioParams.markers.line_width = inConfig.marker_line_width;
  return "";
}

bool sameEngineConfig(const BroadphaseConfig& inA, const BroadphaseConfig& inB) {
  return inA.threads == inB.threads && inA.method == inB.method &&
         inA.primary_axis == inB.primary_axis && inA.secondary_axis == inB.secondary_axis &&
         inA.axis_swapping == inB.axis_swapping &&
         inA.axis_swap_threshold == inB.axis_swap_threshold &&
         inA.parallel_min_boxes == inB.parallel_min_boxes &&
         inA.third_axis_slabs == inB.third_axis_slabs &&
         inA.reuse_unchanged_frames == inB.reuse_unchanged_frames &&
         inA.index_static_boxes == inB.index_static_boxes && inA.skin == inB.skin &&
         inA.exact_final_test == inB.exact_final_test;
}

bool sameMarkerSettings(const NodeParams& inA, const NodeParams& inB) {
  return inA.publish_markers == inB.publish_markers &&
         inA.markers.max_boxes == inB.markers.max_boxes &&
         inA.markers.show_non_colliding == inB.markers.show_non_colliding &&
         inA.markers.show_pair_links == inB.markers.show_pair_links &&
         inA.markers.line_width == inB.markers.line_width;
}

}  // namespace sap_broadphase
