// QueryService: query_boxes on its own thread, against the worker's engine.
#include "query_service.h"

#include "checked_callbacks.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

/// Threads that answer query_boxes: calls beyond them wait in the queue for a free thread (never
/// for a frame: each reads the last frame's snapshot).
constexpr uint32_t kQueryThreads = 8;

}  // namespace

QueryService::QueryService(ros::NodeHandle& ioNode, const SourceIngest& inIngest,
                           const FrameWorker& inWorker, int inLogPeriod)
    : placement_(inIngest.placement()), worker_(inWorker), log_period_(inLogPeriod) {
  service_ = advertiseCheckedService<ros::ServiceSpec<QueryBoxes::Request, QueryBoxes::Response>>(
      ioNode, "query_boxes", queue_,
      [this](QueryBoxes::Request& inRequest, QueryBoxes::Response& outResponse) {
        return onQuery(inRequest, outResponse);
      },
      [this](const std::string& inReason, QueryBoxes::Response& outResponse) {
        refuse(inReason, outResponse);
      });
  spinner_.emplace(kQueryThreads, &queue_);
  spinner_->start();
}

QueryService::~QueryService() {
  spinner_->stop();
  service_.shutdown();
}

bool QueryService::onQuery(QueryBoxes::Request& inRequest, QueryBoxes::Response& outResponse) {
  // The checks and words of a source frame: the shape and the frame it can be placed from
  // here, each box (NaN, min > max, a repeated id) by the engine as it reads the queries.
  const BoxArray& boxes = inRequest.boxes;
  std::optional<std::string> refusal = checkBoxArrayShape(boxes);
  // The query boxes as a source frame of this call's own (the request outlives it): read
  // where they lie, or moved into ~fixed_frame as records, by the rule the sources follow.
  SourceFrame queries;
  queries.header = boxes.header;
  queries.message = BoxArrayConstPtr(&boxes, [](const BoxArray*) {});
  if (!refusal) {
    if (auto unplaced = placement_.place(boxes.header.stamp, queries)) refusal = unplaced->reason;
  }
  QueryAnswer answer;
  if (!refusal) {
    try {
      answer = worker_.query(BoxFrame(queries.span()));
    } catch (const InvalidBoxes& invalid) {
      refusal = invalid.error().message();
    }
  }
  if (refusal) {
    refuse("query boxes: " + *refusal, outResponse);
    return true;  // the call itself succeeded; the answer says why the boxes were refused
  }
  outResponse.header = answer.header;
  outResponse.hits.clear();
  outResponse.hits.reserve(2 * answer.hits.size());
  for (const QueryHit& hit : answer.hits) {
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
