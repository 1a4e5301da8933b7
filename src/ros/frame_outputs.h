// FrameOutputs: what a computed frame publishes besides its stats: `pairs`, `pair_events` (the
// engine's contact events, published only while someone listens) and `markers` (built only
// while someone subscribes).
#pragma once

#include <ros/ros.h>
#include <std_msgs/Header.h>

#include "markers.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// The publishers of a frame's results (worker thread only).
class FrameOutputs {
 public:
  /// Advertises `pairs`, `pair_events` and, with inPublishMarkers, `markers` on ioNode.
  FrameOutputs(ros::NodeHandle& ioNode, int inPairsQueueSize, bool inPublishMarkers,
               const MarkerOptions& inMarkers);

  /// Publishes `pairs` and returns the milliseconds spent filling and sending the message.
  double publishPairs(const PairList& inPairs, const std_msgs::Header& inHeader);
  /// Publishes what changed since the previous published frame, while someone listens:
  /// inEvents and inPairs are Broadphase::events() and the list of the update() just published.
  /// The first message after nobody listened reports every pair of its frame as began.
  void publishEvents(const ContactEvents& inEvents, const PairList& inPairs,
                     const std_msgs::Header& inHeader);
  /// Call before the engine runs an update() whose pairs are not published or is replaced (its
  /// events then no longer start from the last published list): keeps a copy of that list, so
  /// that the next message still tells what changed since it.
  void holdLastPairs();
  /// The engine failed and was replaced before holdLastPairs() could run: the next message
  /// reports every pair of its frame as began, as to a new listener.
  void restartEvents();
  /// True when markers are on and somebody subscribes to them (a frame then needs its boxes).
  bool wantsMarkers() const;
  /// Publishes the markers of the world and its pairs, with the names of inNames, while someone
  /// listens; the scenery's boxes (when given) that are in a pair are drawn too.
  MarkerCounts publishMarkers(const BoxFrame& inWorld, const PairList& inPairs,
                              const std_msgs::Header& inHeader, const BoxNames& inNames,
                              const BoxFrame* inScenery = nullptr);
  /// Takes marker settings changed at run time: `markers` advertised or shut down.
  void setMarkers(bool inPublishMarkers, const MarkerOptions& inMarkers);

 private:
  ros::NodeHandle node_;  // to advertise `markers` when they are switched on at run time
  ros::Publisher pairs_pub_;
  ros::Publisher events_pub_;
  ros::Publisher markers_pub_;
  bool publish_markers_;
  MarkerOptions markers_;
  // The engine's list last published with its events (valid until the engine's next update()),
  // while someone listens.
  const PairList* last_published_ = nullptr;
  PairList held_pairs_;  // a copy of it across an update() not published (holdLastPairs)
  bool holding_ = false;
};

}  // namespace sap_broadphase
