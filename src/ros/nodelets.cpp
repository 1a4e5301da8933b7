// The nodelet wrappers: BroadphaseNode and ScenePublisher loaded into a nodelet manager, so
// that publisher, node and subscribers in one process pass messages as shared pointers
// instead of serialising them through a socket. The classes are the ones the executables use
// (node_main.cpp, scene_publisher_main.cpp); only where the parameters come from differs.
#include <memory>
#include <string>

#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <pluginlib/class_list_macros.hpp>

#include "node.h"
#include "node_params.h"
#include "scene_publisher.h"

namespace sap_broadphase {

/// `sap_broadphase/BroadphaseNodelet`: the broad phase node inside a nodelet manager. Topics
/// and the service are relative to the nodelet's namespace, parameters are its private ones.
class BroadphaseNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    NodeParams params;
    const std::string error = loadNodeParams(getPrivateNodeHandle(), params);
    if (!error.empty()) {
      // A nodelet cannot end its manager: it says why and stays idle.
      NODELET_FATAL("%s", error.c_str());
      return;
    }
    // The boxes callback only hands the frame to the node's worker thread, so the manager's
    // shared callback queue is never held up by a frame being computed.
    node_ = std::make_unique<BroadphaseNode>(getNodeHandle(), getPrivateNodeHandle(), params);
  }

  std::unique_ptr<BroadphaseNode> node_;
};

/// `sap_broadphase/ScenePublisherNodelet`: scene_publisher inside a nodelet manager.
class ScenePublisherNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ScenePublisherParams params;
    const std::string error = loadScenePublisherParams(getPrivateNodeHandle(), params);
    if (!error.empty()) {
      NODELET_FATAL("%s", error.c_str());
      return;
    }
    publisher_ = std::make_unique<ScenePublisher>(getNodeHandle(), params);
  }

  std::unique_ptr<ScenePublisher> publisher_;
};

}  // namespace sap_broadphase

PLUGINLIB_EXPORT_CLASS(sap_broadphase::BroadphaseNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(sap_broadphase::ScenePublisherNodelet, nodelet::Nodelet)
