// The node's private parameters. The node's own are a table (nodeParamRows()) that reading
// walks; the engine's settings are the core's table of BroadphaseConfig fields (configFields()),
// walked for rosparam, for dynamic_reconfigure and for the start-up log, and checked by
// configProblem(). Adding an engine field is a row in that table and a line in
// cfg/BroadphaseNode.cfg; adding a node parameter is a row of nodeParamRows() (and, for a
// number, of the limits table), its member of NodeParams, and the copies test_ros_units checks.
#include "node_params.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <dynamic_reconfigure/Config.h>
#include <ros/names.h>
#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include "adapters_sources.h"
#include "sap_broadphase/BroadphaseNodeConfig.h"

namespace sap_broadphase {

namespace {

/// A parameter server value as the table takes it; nothing for lists, structs and the like.
std::optional<ConfigValue> toConfigValue(XmlRpc::XmlRpcValue& inValue) {
  switch (inValue.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return ConfigValue(static_cast<bool>(inValue));
    case XmlRpc::XmlRpcValue::TypeInt:
      return ConfigValue(static_cast<int64_t>(static_cast<int>(inValue)));
    case XmlRpc::XmlRpcValue::TypeDouble:
      return ConfigValue(static_cast<double>(inValue));
    case XmlRpc::XmlRpcValue::TypeString:
      return ConfigValue(static_cast<std::string>(inValue));
    default:
      return std::nullopt;
  }
}

/// Reads every engine field given as a private parameter into ioEngine through its row.
std::string readEngine(const ros::NodeHandle& inPrivate, BroadphaseConfig& ioEngine) {
  for (const ConfigField& field : configFields()) {
    XmlRpc::XmlRpcValue raw;
    if (!inPrivate.getParam(field.name, raw)) continue;
    const std::optional<ConfigValue> value = toConfigValue(raw);
    if (!value) return std::string("~") + field.name + " must be " + field.allowed;
    if (const auto problem = field.set(ioEngine, *value)) return "~" + *problem;
  }
  if (const auto problem = configProblem(ioEngine)) return "~" + *problem;
  return "";
}

/// Writes inValue as the entry inName of ioMsg (of the value's kind; integers are clamped to
/// the int32 of dynamic_reconfigure).
void setEntry(dynamic_reconfigure::Config& ioMsg, const std::string& inName,
              const ConfigValue& inValue) {
  auto assign = [&](auto& ioEntries, auto inEntryValue) {
    for (auto& entry : ioEntries) {
      if (entry.name == inName) {
        entry.value = inEntryValue;
        return;
      }
    }
  };
  std::visit(
      [&](const auto& inValue) {
        using T = std::decay_t<decltype(inValue)>;
        if constexpr (std::is_same_v<T, bool>) {
          assign(ioMsg.bools, inValue);
        } else if constexpr (std::is_same_v<T, int64_t>) {
          constexpr int64_t kMax = std::numeric_limits<int32_t>::max();
          assign(ioMsg.ints, static_cast<int32_t>(std::clamp<int64_t>(inValue, -kMax, kMax)));
        } else if constexpr (std::is_same_v<T, double>) {
          assign(ioMsg.doubles, inValue);
        } else {
          assign(ioMsg.strs, inValue);
        }
      },
      inValue);
}

/// The entry inName of inMsg, of whatever kind it is; nothing when there is none.
std::optional<ConfigValue> getEntry(const dynamic_reconfigure::Config& inMsg,
                                    const std::string& inName) {
  for (const auto& entry : inMsg.bools)
    if (entry.name == inName) return ConfigValue(static_cast<bool>(entry.value));
  for (const auto& entry : inMsg.ints)
    if (entry.name == inName) return ConfigValue(static_cast<int64_t>(entry.value));
  for (const auto& entry : inMsg.doubles)
    if (entry.name == inName) return ConfigValue(entry.value);
  for (const auto& entry : inMsg.strs)
    if (entry.name == inName) return ConfigValue(entry.value);
  return std::nullopt;
}

/// Reads a number parameter (an integer given in YAML is not a double for the parameter
/// server: either is taken); keeps ioValue when absent. Returns the problem of a value of
/// another kind.
std::string readNumber(const ros::NodeHandle& inPrivate, const std::string& inName,
                       double& ioValue) {
  XmlRpc::XmlRpcValue raw;
  if (!inPrivate.getParam(inName, raw)) return "";
  if (raw.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    ioValue = static_cast<double>(raw);
  } else if (raw.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    ioValue = static_cast<int>(raw);
  } else {
    return "~" + inName + " must be a number";
  }
  return "";
}

/// Reads a node parameter checked against its row of the limits table (entry "node
/// parameter", name "~" + inName); keeps ioValue when absent. Returns the refusal.
template <typename Value>
std::string readLimited(const ros::NodeHandle& inPrivate, const std::string& inName,
                        Value& ioValue) {
  double value = static_cast<double>(ioValue);
  const std::string error =
      readLimitedParam(inPrivate, "node parameter", inName, std::is_integral_v<Value>, value);
  if (error.empty()) ioValue = static_cast<Value>(value);
  return error;
}

/// A YAML scalar as rospy's YAML loader types it: an unquoted integer, number or boolean is
/// one, everything else (quoted included) a string.
XmlRpc::XmlRpcValue yamlScalarToXmlRpc(const YAML::Node& inScalar) {
  const std::string& text = inScalar.Scalar();
  if (inScalar.Tag() != "!") {  // "!" marks a quoted scalar
    int integer = 0;
    double number = 0.0;
    bool boolean = false;
    if (YAML::convert<int>::decode(inScalar, integer)) return XmlRpc::XmlRpcValue(integer);
    if (YAML::convert<double>::decode(inScalar, number)) return XmlRpc::XmlRpcValue(number);
    if (YAML::convert<bool>::decode(inScalar, boolean)) return XmlRpc::XmlRpcValue(boolean);
  }
  return XmlRpc::XmlRpcValue(text);
}

/// How deep a YAML parameter may nest: ~sources needs two levels (a list of maps); an alias
/// inside the node it names (`&x [*x]`) nests without end, and would exhaust the stack.
constexpr int kMaxYamlDepth = 16;

/// A YAML parameter nested past kMaxYamlDepth (parseYamlParameter refuses it).
struct YamlTooDeep {};

XmlRpc::XmlRpcValue yamlToXmlRpc(const YAML::Node& inNode, int inDepth = 0) {
  if (inDepth > kMaxYamlDepth) throw YamlTooDeep{};
  XmlRpc::XmlRpcValue value;
  switch (inNode.Type()) {
    case YAML::NodeType::Sequence:
      value.setSize(static_cast<int>(inNode.size()));
      for (std::size_t i = 0; i < inNode.size(); ++i)
        value[static_cast<int>(i)] = yamlToXmlRpc(inNode[i], inDepth + 1);
      return value;
    case YAML::NodeType::Map:
      value.begin();  // an empty struct stays a struct
      for (const auto& entry : inNode)
        value[entry.first.as<std::string>()] = yamlToXmlRpc(entry.second, inDepth + 1);
      return value;
    case YAML::NodeType::Scalar:
      return yamlScalarToXmlRpc(inNode);
    default:
      return value;  // null: invalid, refused by the reader as a missing value
  }
}

/// Reads ~sources: topics and {topic, type, ...} entries whose publishers make up the world.
std::string readSources(const ros::NodeHandle& inPrivate, std::vector<SourceSpec>& ioSources) {
  XmlRpc::XmlRpcValue value;
  if (!inPrivate.getParam("sources", value)) return "";
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
    // roscpp hands a `_sources:=[...]` of the command line over as a string (rospy would have
    // read it as YAML): read as YAML, as the parameter server reads a launch file's rosparam.
    const std::string text = static_cast<std::string&>(value);
    std::string error = parseYamlParameter(text, value);
    if (!error.empty()) return "~sources: " + error;
  }
  std::string error = parseSourceSpecs(value, ioSources);
  if (!error.empty()) return error;
  // Topics resolve in the node's namespace (the private one's parent), as it subscribes.
  const ros::NodeHandle topics(ros::names::parentNamespace(inPrivate.getNamespace()));
  return checkResolvedSourceTopics(
      ioSources, [&](const std::string& inTopic) { return topics.resolveName(inTopic); });
}

/// Reads the parameter of inRow into its member of ioParams; returns the refusal.
std::string readNodeParam(const ros::NodeHandle& inPrivate, const NodeParamRow& inRow,
                          NodeParams& ioParams) {
  return std::visit(
      [&](auto inAccess) -> std::string {
        auto& value = inAccess(ioParams);
        using Value = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<Value, std::vector<SourceSpec>>) {
          return readSources(inPrivate, value);
        } else if constexpr (std::is_same_v<Value, bool> || std::is_same_v<Value, std::string>) {
          inPrivate.param<Value>(inRow.name, value, value);
          return "";
        } else {
          return readLimited(inPrivate, inRow.name, value);
        }
      },
      inRow.access);
}

}  // namespace

std::string parseYamlParameter(const std::string& inText, XmlRpc::XmlRpcValue& outValue) {
  try {
    outValue = yamlToXmlRpc(YAML::Load(inText));
    return "";
  } catch (const YAML::Exception& exception) {
    return "'" + inText + "' is not YAML (" + exception.what() + ")";
  } catch (const YamlTooDeep&) {
    return "'" + inText + "' nests deeper than " + std::to_string(kMaxYamlDepth) +
           " levels (an alias inside the node it names?)";
  }
}

std::string readLimitedParam(const ros::NodeHandle& inPrivate, const char* inEntry,
                             const std::string& inName, bool inInteger, double& ioValue) {
  const Limit* limit = findLimit(inEntry, "~" + inName);
  if (!limit) throw std::logic_error("~" + inName + " has no row in the limits table");
  double value = ioValue;
  std::string error = readNumber(inPrivate, inName, value);
  if (!error.empty()) return error;
  if (const auto problem = limitProblem(*limit, value)) return *problem;
  if (inInteger && std::trunc(value) != value)
    return "~" + inName + " must be an integer, not " + valueText(ConfigValue(value));
  ioValue = value;
  return "";
}

// Each row's member of NodeParams, for the table.
#define SAP_NODE_PARAM(type, member) +[](NodeParams& ioParams) -> type& { return ioParams.member; }

const std::vector<NodeParamRow>& nodeParamRows() {
  static const std::vector<NodeParamRow> rows = {
      {"publish_markers", "bool", "true", "build markers when 'markers' has subscribers",
       SAP_NODE_PARAM(bool, publish_markers)},
      {"max_marker_boxes", "int", "5000", "boxes drawn at most per frame",
       SAP_NODE_PARAM(std::size_t, markers.max_boxes)},
      {"show_non_colliding", "bool", "false", "also draw boxes without a pair",
       SAP_NODE_PARAM(bool, markers.show_non_colliding)},
      {"show_pair_links", "bool", "false", "draw a line between the centres of each pair",
       SAP_NODE_PARAM(bool, markers.show_pair_links)},
      {"show_names", "bool", "true",
       "write each drawn colliding box's name (from id_names) above it",
       SAP_NODE_PARAM(bool, markers.show_names)},
      {"marker_line_width", "double", "0.0", "metres; 0 = 10 % of the mean edge of the drawn boxes",
       SAP_NODE_PARAM(double, markers.line_width)},
      {"boxes_queue_size", "int", "10", "subscriber queue of each source topic",
       SAP_NODE_PARAM(int, boxes_queue_size)},
      {"pairs_queue_size", "int", "10", "publisher queue of 'pairs'",
       SAP_NODE_PARAM(int, pairs_queue_size)},
      {"refusal_log_period", "int", "1", "seconds between two error messages about refused frames",
       SAP_NODE_PARAM(int, refusal_log_period)},
      {"sources", "list", "[boxes]",
       "YAML list of topics or {topic, type, id_offset, group, mask, timeout} dicts",
       SAP_NODE_PARAM(std::vector<SourceSpec>, sources)},
      {"source_timeout", "double", "1.0", "seconds of silence before a source drops out; 0 = never",
       SAP_NODE_PARAM(double, source_timeout)},
      {"rate", "double", "0.0", "Hz of fixed-rate frames; 0 = a frame whenever a source delivers",
       SAP_NODE_PARAM(double, rate)},
      {"fixed_frame", "string", "\"\"", "tf2 frame the sources are transformed into",
       SAP_NODE_PARAM(std::string, fixed_frame)},
      {"transform_timeout", "double", "0.1", "seconds to wait for a source's transform",
       SAP_NODE_PARAM(double, transform_timeout)},
  };
  return rows;
}

#undef SAP_NODE_PARAM

std::string loadNodeParams(const ros::NodeHandle& inPrivate, NodeParams& outParams) {
  std::string error = readEngine(inPrivate, outParams.engine);
  for (auto row = nodeParamRows().begin(); error.empty() && row != nodeParamRows().end(); ++row)
    error = readNodeParam(inPrivate, *row, outParams);
  if (!outParams.fixed_frame.empty() && outParams.fixed_frame.front() == '/')
    outParams.fixed_frame.erase(0, 1);  // tf2 frame ids carry no leading slash
  return error;
}

std::string describeNodeParams(const NodeParams& inParams) {
  std::ostringstream text;
  text << "threads in force " << resolveThreadCount(inParams.engine.threads) << "; "
       << describeConfig(inParams.engine) << "; markers ";
  if (inParams.publish_markers)
    text << "at most " << inParams.markers.max_boxes << " boxes"
         << (inParams.markers.show_non_colliding ? " (non-colliding too)" : "")
         << (inParams.markers.show_pair_links ? " (pair links)" : "")
         << (inParams.markers.show_names ? " (names)" : "");
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
  // The .cfg's defaults first: a BroadphaseNodeConfig constructed as is holds uninitialised
  // members, and reading its bools below would be undefined (fuzz_reconfigure found it).
  outConfig = BroadphaseNodeConfig::__getDefault__();
  dynamic_reconfigure::Config message;
  outConfig.__toMessage__(message);  // every entry, so that each field finds its own
  for (const ConfigField& field : configFields())
    setEntry(message, field.name, field.get(inParams.engine));
  outConfig.__fromMessage__(message);
  const MarkerOptions& markers = inParams.markers;
  outConfig.publish_markers = inParams.publish_markers;
  outConfig.max_marker_boxes =
      static_cast<int>(std::min<std::size_t>(markers.max_boxes, std::numeric_limits<int>::max()));
  outConfig.show_non_colliding = markers.show_non_colliding;
  outConfig.show_pair_links = markers.show_pair_links;
  outConfig.show_names = markers.show_names;
  outConfig.marker_line_width = markers.line_width;
}

std::string fromReconfigureConfig(const BroadphaseNodeConfig& inConfig, NodeParams& ioParams) {
  dynamic_reconfigure::Config message;
  inConfig.__toMessage__(message);
  BroadphaseConfig engine = ioParams.engine;
  for (const ConfigField& field : configFields()) {
    const std::optional<ConfigValue> value = getEntry(message, field.name);
    if (!value) continue;  // a field the .cfg does not offer keeps its start-up value
    if (const auto problem = field.set(engine, *value)) return *problem;
  }
  if (const auto problem = configProblem(engine)) return *problem;
  if (const auto problem = limitProblem(*findLimit("dynamic_reconfigure", "max_marker_boxes"),
                                        inConfig.max_marker_boxes))
    return *problem;
  if (const auto problem = limitProblem(*findLimit("dynamic_reconfigure", "marker_line_width"),
                                        inConfig.marker_line_width))
    return *problem;

  ioParams.engine = engine;
  ioParams.publish_markers = inConfig.publish_markers;
  ioParams.markers.max_boxes = static_cast<std::size_t>(inConfig.max_marker_boxes);
  ioParams.markers.show_non_colliding = inConfig.show_non_colliding;
  ioParams.markers.show_pair_links = inConfig.show_pair_links;
  ioParams.markers.show_names = inConfig.show_names;
  ioParams.markers.line_width = inConfig.marker_line_width;
  return "";
}

bool sameMarkerSettings(const NodeParams& inA, const NodeParams& inB) {
  return inA.publish_markers == inB.publish_markers &&
         inA.markers.max_boxes == inB.markers.max_boxes &&
         inA.markers.show_non_colliding == inB.markers.show_non_colliding &&
         inA.markers.show_pair_links == inB.markers.show_pair_links &&
         inA.markers.show_names == inB.markers.show_names &&
         inA.markers.line_width == inB.markers.line_width;
}

}  // namespace sap_broadphase
