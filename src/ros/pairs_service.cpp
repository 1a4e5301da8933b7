// PairsService: compute_pairs on its own thread and engine.
#include "pairs_service.h"

#include <utility>

#include "checked_callbacks.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

PairsService::PairsService(ros::NodeHandle& ioNode, const BroadphaseConfig& inEngine,
                           int inLogPeriod)
    : log_period_(inLogPeriod), engine_(inEngine) {
  // The request's bytes are checked before roscpp deserializes them (a bounds prefix claiming
  // 2^27 values would reserve a gigabyte), and nothing thrown leaves the call.
  service_ =
      advertiseCheckedService<ros::ServiceSpec<ComputePairs::Request, ComputePairs::Response>>(
          ioNode, "compute_pairs", queue_,
          [this](ComputePairs::Request& inRequest, ComputePairs::Response& outResponse) {
            return onComputePairs(inRequest, outResponse);
          },
          [this](const std::string& inReason, ComputePairs::Response& outResponse) {
            refuse(inReason, outResponse);
          });
  spinner_.emplace(1, &queue_);
  spinner_->start();
}

PairsService::~PairsService() {
  spinner_->stop();
  service_.shutdown();
}

void PairsService::reconfigure(const BroadphaseConfig& inEngine) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_config_ = inEngine;
}

bool PairsService::onComputePairs(ComputePairs::Request& inRequest,
                                  ComputePairs::Response& outResponse) {
  std::optional<BroadphaseConfig> config;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::swap(config, pending_config_);
  }
  if (config) engine_ = Broadphase(*config);
  outResponse.header = inRequest.boxes.header;  // the frame answered on: the request's own
  outResponse.pairs.header = inRequest.boxes.header;
  std::optional<std::string> refusal = checkBoxArrayShape(inRequest.boxes);
  if (!refusal) {
    try {
      // The engine reads the request's bounds where they lie and checks them as it copies.
      const PairList& pairs = engine_.update(boxArrayRecords(inRequest.boxes));
      pairListToPairArray(pairs, inRequest.boxes.header, outResponse.pairs);
      outResponse.success = true;
      return true;
    } catch (const InvalidBoxes& invalid) {
      refusal = invalid.error().message();
    } catch (const TooManyPairs& too_many) {  // the engine is reset and answers the next call
      refusal = too_many.what();
    }
  }
  refuse(*refusal, outResponse);
  return true;  // the call itself succeeded; the answer says why the boxes were refused
}

void PairsService::refuse(const std::string& inReason, ComputePairs::Response& outResponse) {
  // The caller has the reason in the answer: the log only keeps a trace of it.
  ROS_INFO_THROTTLE(log_period_, "sap_broadphase: compute_pairs refused: %s", inReason.c_str());
  outResponse.success = false;
  outResponse.message = inReason;
}

}  // namespace sap_broadphase
