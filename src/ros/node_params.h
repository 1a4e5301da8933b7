// The node's private parameters: reading, checking and defaults.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include "markers.h"
#include "sap_broadphase/core/config.h"
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

/// Where a node parameter lives in NodeParams, by the kind of value it holds.
using NodeParamAccess =
    std::variant<bool& (*)(NodeParams&), int& (*)(NodeParams&), std::size_t& (*)(NodeParams&),
                 double& (*)(NodeParams&), std::string& (*)(NodeParams&),
                 std::vector<SourceSpec>& (*)(NodeParams&)>;

/// One of the node's own parameters (the engine's are the rows of configFields()): the table
/// that loadNodeParams() walks. A number is checked against its row of the limits table ("node
/// parameter", "~" + name). test_ros_units checks every row against docs/NODE.md,
/// config/default.yaml and the launch files' arguments.
struct NodeParamRow {
  const char* name;          ///< without the "~"
  const char* type;          ///< as docs/NODE.md names it: bool, int, double, string, list
  const char* default_text;  ///< as config/default.yaml and docs/NODE.md write it
  const char* doc;           ///< one line, the launch files' argument doc
  NodeParamAccess access;    ///< its member of NodeParams
};

/// The node's own parameters, in the order they are read.
const std::vector<NodeParamRow>& nodeParamRows();

/// Reads inText as YAML into outValue, typed as the parameter server types a launch file's
/// rosparam (unquoted integers, numbers and booleans as such, the rest strings). Returns the
/// problem ("'...' is not YAML (...)") or an empty string.
std::string parseYamlParameter(const std::string& inText, XmlRpc::XmlRpcValue& outValue);

/// Reads the number parameter ~inName of inPrivate (an integer when inInteger) checked against
/// its row of the limits table (inEntry, "~" + inName); keeps ioValue when absent. Returns the
/// refusal ("~name must be ALLOWED, not VALUE", or of the wrong kind) or an empty string.
std::string readLimitedParam(const ros::NodeHandle& inPrivate, const char* inEntry,
                             const std::string& inName, bool inInteger, double& ioValue);

/// Reads the private parameters of inPrivate over the defaults of NodeParams: the engine's
/// fields by walking the core's table (configFields(): one parameter per field, same name),
/// then the node's own. Returns the problem (a value of the wrong kind or out of range, equal
/// axes, no sources) or an empty string.
std::string loadNodeParams(const ros::NodeHandle& inPrivate, NodeParams& outParams);

/// One line of the parameters in force (every engine field from the table, markers, sources,
/// frames), logged at start-up and after every accepted reconfigure.
std::string describeNodeParams(const NodeParams& inParams);

/// The run-time settings of inParams (engine and markers) as a dynamic_reconfigure config; the
/// engine's fields by name through the table (cfg/BroadphaseNode.cfg names them alike).
void toReconfigureConfig(const NodeParams& inParams, BroadphaseNodeConfig& outConfig);

/// Takes the run-time settings of inConfig into ioParams, checked as at start-up (axes, method,
/// skin, configProblem()). Returns the problem, with ioParams unchanged, or an empty string.
std::string fromReconfigureConfig(const BroadphaseNodeConfig& inConfig, NodeParams& ioParams);

/// True when both parameter sets draw the same markers (publish_markers and MarkerOptions'
/// settings that the node reads from parameters).
bool sameMarkerSettings(const NodeParams& inA, const NodeParams& inB);

}  // namespace sap_broadphase
