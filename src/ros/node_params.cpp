// The node's private parameters.
#include "sap_broadphase/ros/node_params.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include <xmlrpcpp/XmlRpcValue.h>

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

/// Reads ~sources, the topics whose publishers make up the world.
std::string readSources(const ros::NodeHandle& inPrivate, std::vector<std::string>& ioSources) {
  XmlRpc::XmlRpcValue value;
  if (!inPrivate.getParam("sources", value)) return "";
  if (value.getType() != XmlRpc::XmlRpcValue::TypeArray || value.size() == 0)
    return "~sources must be a non-empty list of BoxArray topics, e.g. [boxes, robot_a/boxes]";
  std::vector<std::string> topics;
  std::set<std::string> seen;
  for (int i = 0; i < value.size(); ++i) {
    if (value[i].getType() != XmlRpc::XmlRpcValue::TypeString)
      return "~sources[" + std::to_string(i) + "] must be a topic name (a string)";
    const std::string topic = static_cast<std::string>(value[i]);
    if (topic.empty() || !seen.insert(topic).second)
      return "~sources lists '" + topic + "' twice (or an empty name)";
    topics.push_back(topic);
  }
  ioSources = topics;
  return "";
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

// ~skin is "auto" (the default), 0 (off) or a fixed skin in metres.
std::string readSkin(const ros::NodeHandle& inPrivate, std::optional<double>& outSkin) {
  XmlRpc::XmlRpcValue value;
  if (!inPrivate.getParam("skin", value)) return "";
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString &&
      static_cast<std::string>(value) == "auto") {
    outSkin.reset();
    return "";
  }
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
       << (engine.axis_swapping ? " (swapping)" : "") << ", skin ";
  if (!engine.skin)
    text << "auto";
  else if (*engine.skin == 0.0)
    text << "off";
  else
    text << *engine.skin;
  text << ", sources [";
  for (std::size_t i = 0; i < inParams.sources.size(); ++i)
    text << (i ? ", " : "") << inParams.sources[i];
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

}  // namespace sap_broadphase
