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

/// Appends the pairs of inFrom that are not in inWithout (both canonical) as consecutive ids.
void appendDifference(const PairList& inFrom, const PairList& inWithout,
                      std::vector<uint32_t>& outIds) {
  PairList difference;
  std::set_difference(inFrom.begin(), inFrom.end(), inWithout.begin(), inWithout.end(),
                      std::back_inserter(difference));
  outIds.reserve(2 * difference.size());
  for (const IdPair& pair : difference) {
    outIds.push_back(pair.a);
    outIds.push_back(pair.b);
  }
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

void FrameOutputs::publishEvents(const PairList& inPairs, const std_msgs::Header& inHeader) {
  if (events_pub_.getNumSubscribers() == 0) {
    // Nobody listens: no copy of the pairs is kept; the next listener's first message reports
    // every pair of its first frame as began.
    previous_pairs_valid_ = false;
    PairList().swap(previous_pairs_);
    return;
  }
  auto events = boost::make_shared<PairEvents>();
  events->header = inHeader;
  static const PairList kNone;
  const PairList& previous = previous_pairs_valid_ ? previous_pairs_ : kNone;
  appendDifference(inPairs, previous, events->began);
  appendDifference(previous, inPairs, events->ended);
  events_pub_.publish(events);
  previous_pairs_.assign(inPairs.begin(), inPairs.end());
  previous_pairs_valid_ = true;
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
