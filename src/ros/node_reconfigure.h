// NodeReconfigure: the dynamic_reconfigure server of the node's engine and marker settings.
// Checks what a client sends as the parameters are checked at start-up, answers with the
// settings in force, and hands accepted changes to the node.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include <ros/node_handle.h>
#include <boost/thread/recursive_mutex.hpp>

#include "node_params.h"

namespace dynamic_reconfigure {
template <class ConfigType>
class Server;
}  // namespace dynamic_reconfigure

namespace sap_broadphase {

class BroadphaseNodeConfig;  // generated from cfg/BroadphaseNode.cfg

class NodeReconfigure {
 public:
  /// Called (on inPrivate's callback queue) with accepted settings that changed something;
  /// inNewEngine when the engine settings changed (not only the markers').
  using Apply = std::function<void(const NodeParams& inSettings, bool inNewEngine)>;

  /// Serves dynamic_reconfigure on inPrivate, starting from inParams.
  NodeReconfigure(const ros::NodeHandle& inPrivate, const NodeParams& inParams, Apply inApply);
  ~NodeReconfigure();
  NodeReconfigure(const NodeReconfigure&) = delete;
  NodeReconfigure& operator=(const NodeReconfigure&) = delete;

 private:
  /// Checks ioConfig; refused settings are logged and ioConfig is set back to the settings in
  /// force, which the server then reports to its clients.
  void onReconfigure(BroadphaseNodeConfig& ioConfig, uint32_t inLevel);

  Apply apply_;
  NodeParams accepted_;  // the settings last accepted (the callback's own)
  // The server, with a mutex of ours, so that giving it the settings in force cannot deadlock
  // with a client's update.
  boost::recursive_mutex mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<BroadphaseNodeConfig>> server_;
};

}  // namespace sap_broadphase
