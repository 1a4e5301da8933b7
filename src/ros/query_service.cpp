// QueryService: query_boxes on its own thread, against the worker's engine.
#include "query_service.h"

#include "checked_callbacks.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

QueryService::QueryService(ros::NodeHandle& ioNode, SourceIngest& ioIngest,
                           const FrameWorker& inWorker, int inLogPeriod)
    : ingest_(ioIngest), worker_(inWorker), log_period_(inLogPeriod) {
  service_ = advertiseCheckedService<ros::ServiceSpec<QueryBoxes::Request, QueryBoxes::Response>>(
      ioNode, "query_boxes", queue_,
      [this](QueryBoxes::Request& inRequest, QueryBoxes::Response& outResponse) {
        return onQuery(inRequest, outResponse);
      },
      [this](const std::string& inReason, QueryBoxes::Response& outResponse) {
        refuse(inReason, outResponse);
      });
  spinner_.emplace(1, &queue_);
  spinner_->start();
}

QueryService::~QueryService() {
  spinner_->stop();
  service_.shutdown();
}

bool QueryService::onQuery(QueryBoxes::Request& inRequest, QueryBoxes::Response& outResponse) {
  // The checks and words of a source frame: the shape, then each box (NaN, min > max, a
  // repeated id), then the frame it can be placed from.
  std::optional<std::string> refusal = boxArrayToBoxSet(inRequest.boxes, queries_);
  if (!refusal) refusal = ingest_.placeInFixedFrame(inRequest.boxes.header, queries_);
  if (refusal) {
    refuse("query boxes: " + *refusal, outResponse);
    return true;  // the call itself succeeded; the answer says why the boxes were refused
  }
  const QueryHitList hits = worker_.query(queries_);
  outResponse.hits.clear();
  outResponse.hits.reserve(2 * hits.size());
  for (const QueryHit& hit : hits) {
    outResponse.hits.push_back(hit.query);
    outResponse.hits.push_back(hit.world);
  }
  outResponse.success = true;
  return true;
}

void QueryService::refuse(const std::string& inReason, QueryBoxes::Response& outResponse) {
  ROS_INFO_THROTTLE(log_period_, "sap_broadphase: query_boxes refused: %s", inReason.c_str());
  outResponse.success = false;
  outResponse.message = inReason;
  outResponse.hits.clear();
}

}  // namespace sap_broadphase
