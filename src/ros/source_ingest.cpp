// SourceIngest: subscriptions, the latest frame of each source, tf2.
#include "source_ingest.h"

#include <utility>

#include <tf2/exceptions.h>

#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

SourceIngest::SourceIngest(ros::NodeHandle& ioNode, const NodeParams& inParams,
                           NodeStatus& ioStatus, Wake inWake)
    : status_(ioStatus),
      wake_(std::move(inWake)),
      fixed_frame_(inParams.fixed_frame),
      transform_timeout_(inParams.transform_timeout) {
  if (!fixed_frame_.empty()) {
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, ioNode);
    // Runs on the listener's thread after every transform tf2 takes in; it only wakes the
    // worker (no lock of ours), and only while a frame waits.
    tf_changed_ = tf_buffer_->_addTransformsChangedListener([this] {
      if (any_waiting_.load(std::memory_order_relaxed)) wake_();
    });
  }
  subscribers_.push_back(
      ioNode.subscribe<BoxArray>("static_boxes", 1, [this](const BoxArrayConstPtr& inMsg) {
        {
          std::lock_guard<std::mutex> lock(mutex_);
          pending_scenery_ = inMsg;
          scenery_wait_logged_ = false;
          any_waiting_ = true;
        }
        wake_();
      }));
  for (const std::string& topic : inParams.sources) {
    ros::SubscribeOptions options;
    options.initByFullCallbackType<const ros::MessageEvent<BoxArray const>&>(
        topic, static_cast<uint32_t>(inParams.boxes_queue_size),
        [this, topic](const ros::MessageEvent<BoxArray const>& inEvent) {
          deliver(topic, inEvent);
        });
    options.transport_hints = ros::TransportHints().tcpNoDelay();
    subscribers_.push_back(ioNode.subscribe(options));
  }
}

SourceIngest::~SourceIngest() {
  stop();
}

void SourceIngest::stop() {
  // A subscriber's shutdown waits for its callback in progress; the listener's reset joins its
  // thread, the only one that calls the tf2 change listener.
  for (ros::Subscriber& subscriber : subscribers_) subscriber.shutdown();
  if (tf_buffer_) tf_buffer_->_removeTransformsChangedListener(tf_changed_);
  tf_listener_.reset();
}

void SourceIngest::deliver(const std::string& inTopic,
                           const ros::MessageEvent<BoxArray const>& inEvent) {
  status_.countReceived();
  const BoxArrayConstPtr& msg = inEvent.getConstMessage();
  const SourceKey key{inTopic, inEvent.getPublisherName(), msg->header.frame_id};
  if (auto reason = checkBoxArrayShape(*msg)) {
    status_.refuse(msg->header, msg->bounds.size() / 6, sourceName(key) + ": " + *reason);
    return;
  }
  store(key, Delivery{msg, ros::Time::now()});
}

void SourceIngest::store(const SourceKey& inKey, const Delivery& inDelivery) {
  const bool ready =
      !tf_buffer_ || transformable(inDelivery.msg->header.frame_id, inDelivery.msg->header.stamp);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (ready) {
      // A frame of the same source still waiting for its transform is older: it goes.
      if (waiting_.erase(inKey) > 0) status_.countDropped();
      Delivery& slot = pending_[inKey];
      if (slot.msg) status_.countDropped();  // never started: the newer frame of the source wins
      slot = inDelivery;
    } else {
      Delivery& slot = waiting_[inKey];
      if (slot.msg) status_.countDropped();
      slot = inDelivery;
      any_waiting_ = true;
    }
  }
  if (ready) wake_();
}

bool SourceIngest::transformable(const std::string& inFrame, const ros::Time& inStamp) const {
  return tf_buffer_->canTransform(fixed_frame_, inFrame, inStamp);
}

void SourceIngest::releaseWaiting(const ros::Time& inNow) {
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    const auto& [key, delivery] = *it;
    if (transformable(delivery.msg->header.frame_id, delivery.msg->header.stamp)) {
      Delivery& slot = pending_[key];
      if (slot.msg && slot.msg->header.stamp > delivery.msg->header.stamp) {
        status_.countDropped();  // a newer frame of the source is ready already
      } else {
        if (slot.msg) status_.countDropped();
        slot = delivery;
      }
    } else if ((inNow - delivery.received).toSec() > transform_timeout_) {
      status_.skip(sourceName(key) + " skipped: no transform into '" + fixed_frame_ +
                   "' within ~transform_timeout (" + std::to_string(transform_timeout_) + " s)");
    } else {
      ++it;
      continue;
    }
    it = waiting_.erase(it);
  }
}

void SourceIngest::take(std::map<SourceKey, Delivery>& outDeliveries, BoxArrayConstPtr& ioScenery) {
  outDeliveries.clear();
  const ros::Time now = ros::Time::now();
  std::lock_guard<std::mutex> lock(mutex_);
  if (!waiting_.empty()) releaseWaiting(now);
  std::swap(outDeliveries, pending_);
  if (pending_scenery_) {
    const BoxArray& scenery = *pending_scenery_;
    // An empty scenery (clearing it) needs no frame.
    if (!tf_buffer_ || scenery.bounds.empty() ||
        transformable(scenery.header.frame_id, ros::Time(0))) {
      ioScenery = std::move(pending_scenery_);
      pending_scenery_.reset();
    } else if (!scenery_wait_logged_) {
      scenery_wait_logged_ = true;
      ROS_INFO("sap_broadphase: static_boxes waits for a transform from '%s' into '%s'",
               scenery.header.frame_id.c_str(), fixed_frame_.c_str());
    }
  }
  any_waiting_ = !waiting_.empty() || pending_scenery_;
}

bool SourceIngest::convert(const SourceKey& inKey, const BoxArray& inMsg, BoxSet& outBoxes) {
  if (auto reason = boxArrayToBoxSet(inMsg, outBoxes)) {
    status_.refuse(inMsg.header, inMsg.bounds.size() / 6, sourceName(inKey) + ": " + *reason);
    return false;
  }
  std::string error;
  if (tf_buffer_ &&
      !moveIntoFixedFrame(inMsg.header.frame_id, inMsg.header.stamp, outBoxes, error)) {
    status_.skip(sourceName(inKey) + " skipped: no transform into '" + fixed_frame_ +
                 "': " + error);
    return false;
  }
  return true;
}

bool SourceIngest::convertScenery(const BoxArray& inMsg, BoxSet& outBoxes) {
  if (auto reason = boxArrayToBoxSet(inMsg, outBoxes)) {
    status_.refuse(inMsg.header, inMsg.bounds.size() / 6,
                   std::string(kStaticSourceName) + ": " + *reason);
    return false;
  }
  std::string error;
  if (tf_buffer_ && outBoxes.size() > 0 &&
      !moveIntoFixedFrame(inMsg.header.frame_id, ros::Time(0), outBoxes, error)) {
    status_.skip(std::string(kStaticSourceName) + " skipped: no transform into '" + fixed_frame_ +
                 "': " + error);
    return false;
  }
  return true;
}

bool SourceIngest::moveIntoFixedFrame(const std::string& inFrame, const ros::Time& inStamp,
                                      BoxSet& ioBoxes, std::string& outError) {
  try {
    const geometry_msgs::TransformStamped transform =
        tf_buffer_->lookupTransform(fixed_frame_, inFrame, inStamp);
    transformBoxes(transform.transform, ioBoxes);
    return true;
  } catch (const tf2::TransformException& exception) {
    outError = exception.what();
    return false;
  }
}

}  // namespace sap_broadphase
