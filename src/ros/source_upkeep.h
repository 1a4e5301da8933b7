// SourceUpkeep: what the frame worker does for the sources between frames, on the worker
// thread only: ~id_names for the names the adapters gave, the MarkerArray messages roscpp
// dropped from full queues, and the state of publishers gone. It reads the adapters, each of
// which locks itself.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <ros/ros.h>

#include "markers.h"
#include "node_status.h"
#include "source_mailbox.h"
#include "sources.h"

namespace sap_broadphase {

class SourceAdapter;  // adapters.h

class SourceUpkeep {
 public:
  /// Advertises ~id_names on ioNode (latched) when there are adapters. inAdapters (owned by
  /// the subscriptions), inMailbox and ioStatus must outlive the upkeep.
  SourceUpkeep(ros::NodeHandle& ioNode, std::vector<SourceAdapter*> inAdapters,
               std::vector<std::string> inStatefulTopics, const SourceMailbox& inMailbox,
               NodeStatus& ioStatus);

  /// Publishes the names of every adapter's ids on ~id_names when some are new since the last
  /// time (once per round: a burst of new names costs one message, not one per name).
  void publishIdNames();
  /// The names of the last ~id_names by id, to label the markers (updated by publishIdNames
  /// only when names are added, never copied per frame).
  const BoxNames& idNames() const { return id_names_; }
  /// Counts the MarkerArray messages roscpp dropped from a full subscriber queue since the last
  /// call (roscpp's own count, read from the node's getBusStats) into the status. Looks at
  /// most every kLossCheckSeconds.
  void countLostMessages();
  /// The source inKey timed out: its adapter forgets the publisher's state.
  void forget(const SourceKey& inKey);

 private:
  std::vector<SourceAdapter*> adapters_;
  std::vector<std::string> stateful_topics_;
  const SourceMailbox& mailbox_;
  NodeStatus& status_;
  ros::Publisher id_names_pub_;                            // latched, while adapters name ids
  std::size_t id_names_published_ = 0;                     // names in the last ~id_names
  BoxNames id_names_;                                      // the names of the last ~id_names
  std::map<std::pair<std::string, int>, int> drops_seen_;  // by topic and connection id
  std::chrono::steady_clock::time_point loss_checked_;
};

}  // namespace sap_broadphase
