// FrameOutputs: pairs, pair events and markers of a computed frame.
#include "frame_outputs.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <vector>

#include <visualization_msgs/MarkerArray.h>
#include <boost/make_shared.hpp>

#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/PairEvents.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

/// Appends inPairs (canonical) to outIds as consecutive ids, as PairArray lays them out.
void appendPairs(const PairList& inPairs, std::vector<uint32_t>& outIds) {
  outIds.reserve(outIds.size() + 2 * inPairs.size());
  for (const IdPair& pair : inPairs) {
    outIds.push_back(pair.a);
    outIds.push_back(pair.b);
  }
}

/// The pairs of inFrom that are not in inWithout (both canonical).
PairList difference(const PairList& inFrom, const PairList& inWithout) {
  PairList difference;
  std::set_difference(inFrom.begin(), inFrom.end(), inWithout.begin(), inWithout.end(),
                      std::back_inserter(difference));
  return difference;
}

}  // namespace

FrameOutputs::FrameOutputs(ros::NodeHandle& ioNode, int inPairsQueueSize, bool inPublishMarkers,
                           const MarkerOptions& inMarkers)
    : node_(ioNode),
      pairs_pub_(ioNode.advertise<PairArray>("pairs", inPairsQueueSize)),
      events_pub_(ioNode.advertise<PairEvents>("pair_events", inPairsQueueSize)),
      publish_markers_(false),
      markers_(inMarkers) {
  setMarkers(inPublishMarkers, inMarkers);
}

double FrameOutputs::publishPairs(const PairList& inPairs, const std_msgs::Header& inHeader) {
  const auto start = std::chrono::steady_clock::now();
  auto message = boost::make_shared<PairArray>();
  pairListToPairArray(inPairs, inHeader, *message);
  pairs_pub_.publish(message);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

void FrameOutputs::publishEvents(const ContactEvents& inEvents, const PairList& inPairs,
                                 const std_msgs::Header& inHeader) {
  if (events_pub_.getNumSubscribers() == 0) {
    // Nobody listens: nothing kept; the next listener's first message reports every pair of
    // its first frame as began.
    last_published_ = nullptr;
    holding_ = false;
    PairList().swap(held_pairs_);
    return;
  }
  auto events = boost::make_shared<PairEvents>();
  events->header = inHeader;
  if (holding_) {
    // The engine's events start from a list never published: the difference from the held
    // copy instead (after a source dropout or a new engine only).
    appendPairs(difference(inPairs, held_pairs_), events->began);
    appendPairs(difference(held_pairs_, inPairs), events->ended);
    holding_ = false;
    PairList().swap(held_pairs_);
  } else if (last_published_) {
    appendPairs(inEvents.began, events->began);
    appendPairs(inEvents.ended, events->ended);
  } else {
    appendPairs(inPairs, events->began);
  }
  events_pub_.publish(events);
  last_published_ = &inPairs;
}

void FrameOutputs::holdLastPairs() {
  if (!last_published_ || holding_) return;  // nobody listens, or already held
  held_pairs_ = *last_published_;
  holding_ = true;
  last_published_ = nullptr;  // the engine's list is about to change or go
}

void FrameOutputs::restartEvents() {
  last_published_ = nullptr;
  holding_ = false;
  PairList().swap(held_pairs_);
}

bool FrameOutputs::wantsMarkers() const {
  return publish_markers_ && markers_pub_.getNumSubscribers() > 0;
}

MarkerCounts FrameOutputs::publishMarkers(const BoxFrame& inWorld, const PairList& inPairs,
                                          const std_msgs::Header& inHeader, const BoxNames& inNames,
                                          const BoxFrame* inScenery) {
  if (!wantsMarkers()) return MarkerCounts{};
  auto markers = boost::make_shared<visualization_msgs::MarkerArray>();
  const MarkerCounts counts =
      buildMarkers(inWorld, inPairs, inHeader, markers_, *markers, &inNames, inScenery);
  markers_pub_.publish(markers);
  return counts;
}

void FrameOutputs::setMarkers(bool inPublishMarkers, const MarkerOptions& inMarkers) {
  if (inPublishMarkers && !markers_pub_)
    markers_pub_ = node_.advertise<visualization_msgs::MarkerArray>("markers", 1);
  else if (!inPublishMarkers && markers_pub_)
    markers_pub_.shutdown();
  publish_markers_ = inPublishMarkers;
  markers_ = inMarkers;
}

}  // namespace sap_broadphase
