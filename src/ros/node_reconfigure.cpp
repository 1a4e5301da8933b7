// NodeReconfigure: dynamic_reconfigure of the engine and marker settings.
#include "node_reconfigure.h"

#include <string>
#include <utility>

#include <dynamic_reconfigure/server.h>
#include <ros/console.h>

#include "checked_callbacks.h"
#include "sap_broadphase/BroadphaseNodeConfig.h"

namespace sap_broadphase {

NodeReconfigure::NodeReconfigure(const ros::NodeHandle& inPrivate, const NodeParams& inParams,
                                 Apply inApply)
    : apply_(std::move(inApply)), accepted_(inParams) {
  // The server starts from whatever the parameter server holds in its own types: a skin of
  // 0.05 or an axis given as 2 would read as the .cfg defaults. The settings in force are
  // given to it before the callback is set, so that the callback's first call (with the
  // server's config) changes nothing.
  server_ = std::make_unique<dynamic_reconfigure::Server<BroadphaseNodeConfig>>(mutex_, inPrivate);
  BroadphaseNodeConfig in_force;
  toReconfigureConfig(accepted_, in_force);
  server_->updateConfig(in_force);
  server_->setCallback([this](BroadphaseNodeConfig& ioConfig, uint32_t inLevel) {
    // A service callback of dynamic_reconfigure: nothing thrown may leave it.
    runGuarded([&] { onReconfigure(ioConfig, inLevel); },
               [&](const std::string& inWhat) {
                 ROS_ERROR("sap_broadphase: reconfigure failed, the settings in force stay: %s",
                           inWhat.c_str());
                 toReconfigureConfig(accepted_, ioConfig);
               });
  });
}

NodeReconfigure::~NodeReconfigure() = default;

void NodeReconfigure::onReconfigure(BroadphaseNodeConfig& ioConfig, uint32_t /*inLevel*/) {
  NodeParams settings = accepted_;
  const std::string problem = fromReconfigureConfig(ioConfig, settings);
  if (!problem.empty()) {
    ROS_WARN("sap_broadphase: reconfigure refused, the settings in force stay: %s",
             problem.c_str());
    toReconfigureConfig(accepted_, ioConfig);
    return;
  }
  // Written back as the node reads them ("Z" -> "z", "0" -> "off"), so clients see the
  // settings in force.
  toReconfigureConfig(settings, ioConfig);
  const bool new_engine = !sameConfig(settings.engine, accepted_.engine);
  if (!new_engine && sameMarkerSettings(settings, accepted_)) return;
  accepted_ = settings;
  apply_(settings, new_engine);
}

}  // namespace sap_broadphase
