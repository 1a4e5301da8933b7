// SourceIngest: subscriptions, the latest frame of each source, tf2.
#include "source_ingest.h"

#include <algorithm>
#include <utility>

#include <ros/network.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <tf2/exceptions.h>
#include <topic_tools/shape_shifter.h>
#include <boost/make_shared.hpp>

#include "adapters.h"
#include "checked_callbacks.h"
#include "sap_broadphase/IdNames.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

/// Subscriber queue of a MarkerArray source at least: a burst of incremental updates (rviz
/// tools publish one marker per message) waits here while the callback converts.
constexpr int kStatefulQueueSize = 1000;
/// Wall seconds between two looks at roscpp's drop counts.
constexpr double kLossCheckSeconds = 0.5;

/// The check of each message's connection header against a source of inType: the type name
/// and MD5 sum its publisher declared.
PublisherCheck connectionTypeCheck(InputType inType) {
  return [inType](const ros::M_string& inConnection) {
    const auto field = [&](const char* inKey) {
      const auto found = inConnection.find(inKey);
      return found == inConnection.end() ? std::string() : found->second;
    };
    return checkPublishedType(inType, field("type"), field("md5sum"));
  };
}

/// The node's output topic that inTopic resolves to, or nullptr.
const char* ownOutputNamed(const ros::NodeHandle& inNode, const std::string& inTopic) {
  for (const char* output : {"pairs", "pair_events", "markers", "stats", "id_names"})
    if (inNode.resolveName(inTopic) == inNode.resolveName(output)) return output;
  return nullptr;
}

}  // namespace

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
  subscribeScenery(ioNode);
  for (const SourceSpec& spec : inParams.sources) {
    if (const char* output = ownOutputNamed(ioNode, spec.topic)) {
      // The node would read what it writes (e.g. `markers` as a MarkerArray source).
      ROS_ERROR(
          "sap_broadphase: ~sources topic '%s' is the node's own output '%s': not read; "
          "remap the source or the output",
          spec.topic.c_str(), output);
      continue;
    }
    subscribe(ioNode, spec, inParams.boxes_queue_size);
  }
  if (!adapters_.empty()) id_names_pub_ = ioNode.advertise<IdNames>("id_names", 1, true);
  publisher_probe_ = std::make_unique<PublisherProbe>(
      probed_topics_,
      [this](const std::string& inTopic, const std::string& inPublisher,
             const std::string& inReason) {
        status_.refuse(std_msgs::Header(), 0,
                       sourceName(SourceKey{inTopic, inPublisher, ""}) + ": " + inReason +
                           ": its connection is refused");
      },
      [this](const std::vector<std::string>& inRefused) {
        status_.setRefusedPublishers(inRefused);
      });
}

void SourceIngest::subscribe(ros::NodeHandle& ioNode, const SourceSpec& inSpec, int inQueueSize) {
  ros::SubscribeOptions options;
  const std::string topic = inSpec.topic;
  // A message refused at the wire (its publisher's type, a length prefix past its bytes) never
  // reaches the callbacks below: counted and named here.
  WireRefusal refuse = [this, topic](const ros::M_string& inConnection,
                                     const std::string& inReason) {
    status_.countReceived();
    const auto caller = inConnection.find("callerid");
    const SourceKey key{topic, caller == inConnection.end() ? "" : caller->second, ""};
    status_.refuse(std_msgs::Header(), 0, sourceName(key) + ": " + inReason);
  };
  const InputType type = inSpec.type;
  const WireLayout& layout = wireLayout(type);
  if (type == InputType::kMarkerArray) {
    // A MarkerArray only says what changed: a message lost in the queue is an update the
    // node never sees. Its queue holds a burst; what it still drops is counted.
    inQueueSize = std::max(inQueueSize, kStatefulQueueSize);
    stateful_topics_.push_back(ioNode.resolveName(topic));
  }
  if (inSpec.takesBoxArrayAsIs()) {
    using Event = const ros::MessageEvent<BoxArray const>&;
    options.initByFullCallbackType<Event>(topic, static_cast<uint32_t>(inQueueSize), [](Event) {});
    options.helper = boost::make_shared<CheckedSubscriptionHelper<Event>>(
        [this, topic](Event inEvent) {
          runGuarded([&] { deliver(topic, inEvent); },
                     [&](const std::string& inWhat) { refuseUnhandled(topic, inWhat); });
        },
        layout, PublisherCheck(), refuse);
  } else {
    // Any type (ShapeShifter): the type name and MD5 sum are checked per publisher, from the
    // connection header of each message. Every message is converted here, in order, since a
    // MarkerArray only tells what changed.
    adapters_.push_back(std::make_unique<SourceAdapter>(inSpec));
    SourceAdapter* adapter = adapters_.back().get();
    using Event = const ros::MessageEvent<topic_tools::ShapeShifter const>&;
    options.initByFullCallbackType<Event>(topic, static_cast<uint32_t>(inQueueSize), [](Event) {});
    options.helper = boost::make_shared<CheckedSubscriptionHelper<Event>>(
        [this, adapter, topic](Event inEvent) {
          runGuarded([&] { onAdaptedMessage(*adapter, inEvent); },
                     [&](const std::string& inWhat) { refuseUnhandled(topic, inWhat); });
        },
        layout, connectionTypeCheck(type), refuse);
    // The definition the node decodes, not "*": roscpp would fix the topic's MD5 sum to its
    // first publisher's, and one publisher of another definition would lock the others out.
    // Publishers of another definition are refused by roscpp and named by the probe.
    options.md5sum = inputTypeInfo(type).md5;
    options.datatype = inputTypeInfo(type).name;
  }
  options.transport_hints = ros::TransportHints().tcpNoDelay();
  subscribers_.push_back(ioNode.subscribe(options));
  probed_topics_.emplace_back(ioNode.resolveName(topic), [type](const PublishedType& inPublished) {
    return checkPublishedType(type, inPublished.type, inPublished.md5);
  });
}

void SourceIngest::refuseUnhandled(const std::string& inTopic, const std::string& inWhat) {
  status_.refuse(std_msgs::Header(), 0,
                 "'" + inTopic + "': a message that could not be handled (" + inWhat +
                     "): refused, the node goes on");
}

void SourceIngest::onAdaptedMessage(
    SourceAdapter& ioAdapter, const ros::MessageEvent<topic_tools::ShapeShifter const>& inEvent) {
  // The adapter writes records, the frame the engine reads.
  auto frame = std::make_shared<SourceFrame>();
  const std::string& publisher = inEvent.getPublisherName();
  if (auto reason = ioAdapter.convert(*inEvent.getConstMessage(), publisher, *frame)) {
    status_.countReceived();
    const SourceKey key{ioAdapter.spec().topic, publisher, frame->header.frame_id};
    status_.refuse(frame->header, frame->size(), sourceName(key) + ": " + *reason);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(id_names_mutex_);
    id_names_header_ = frame->header;
  }
  deliverFrame(ioAdapter.spec().topic, publisher, std::move(frame));
}

void SourceIngest::publishIdNames() {
  std::lock_guard<std::mutex> lock(id_names_mutex_);
  std::size_t names = 0;
  for (const auto& adapter : adapters_) names += adapter->nameCount();
  if (names == id_names_published_) return;  // names only grow: none is new
  auto msg = boost::make_shared<IdNames>();
  msg->header = id_names_header_;
  for (const auto& adapter : adapters_) adapter->appendIdNames(msg->ids, msg->names);
  id_names_published_ = msg->ids.size();
  // Names only grow and an id's name never changes: only the new ones are added.
  for (std::size_t k = 0; k < msg->ids.size(); ++k)
    id_names_.try_emplace(msg->ids[k], msg->names[k]);
  id_names_pub_.publish(msg);
}

void SourceIngest::subscribeScenery(ros::NodeHandle& ioNode) {
  ros::SubscribeOptions options;
  using Message = const BoxArrayConstPtr&;
  options.init<BoxArray>("static_boxes", 1, [](Message) {});
  const auto keep = [this](Message inMsg) {
    std::optional<std::string> reason = checkBoxArrayShape(*inMsg);
    if (!reason && !inMsg->bounds.empty()) reason = unplaceableFrame(inMsg->header.frame_id);
    if (reason) {
      status_.refuse(inMsg->header, inMsg->bounds.size() / 6,
                     std::string(kStaticSourceName) + ": " + *reason);
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending_scenery_ = inMsg;
      scenery_wait_logged_ = false;
      any_waiting_ = true;
    }
    wake_();
  };
  options.helper = boost::make_shared<CheckedSubscriptionHelper<Message>>(
      keep, wireLayout(InputType::kBoxArray), PublisherCheck(),
      [this](const ros::M_string&, const std::string& inReason) {
        status_.refuse(std_msgs::Header(), 0, std::string(kStaticSourceName) + ": " + inReason);
      });
  subscribers_.push_back(ioNode.subscribe(options));
}

SourceIngest::~SourceIngest() {
  stop();
}

void SourceIngest::stop() {
  publisher_probe_.reset();
  // A subscriber's shutdown waits for its callback in progress; the listener's reset joins its
  // thread, the only one that calls the tf2 change listener.
  for (ros::Subscriber& subscriber : subscribers_) subscriber.shutdown();
  if (tf_buffer_) tf_buffer_->_removeTransformsChangedListener(tf_changed_);
  tf_listener_.reset();
}

void SourceIngest::deliver(const std::string& inTopic,
                           const ros::MessageEvent<BoxArray const>& inEvent) {
  const BoxArrayConstPtr& msg = inEvent.getConstMessage();
  if (auto reason = checkBoxArrayShape(*msg)) {
    status_.countReceived();
    const SourceKey key{inTopic, inEvent.getPublisherName(), msg->header.frame_id};
    status_.refuse(msg->header, msg->bounds.size() / 6, sourceName(key) + ": " + *reason);
    return;
  }
  // Kept as published: the engine reads the message's records where they lie.
  auto frame = std::make_shared<SourceFrame>();
  frame->header = msg->header;
  frame->message = msg;
  deliverFrame(inTopic, inEvent.getPublisherName(), std::move(frame));
}

void SourceIngest::deliverFrame(const std::string& inTopic, const std::string& inPublisher,
                                std::shared_ptr<SourceFrame> inFrame) {
  status_.countReceived();
  const SourceKey key{inTopic, inPublisher, inFrame->header.frame_id};
  if (auto reason = unplaceableFrame(inFrame->header.frame_id)) {
    status_.refuse(inFrame->header, inFrame->size(), sourceName(key) + ": " + *reason);
    return;
  }
  store(key, Delivery{std::move(inFrame), ros::Time::now()});
}

void SourceIngest::store(const SourceKey& inKey, Delivery inDelivery) {
  const std_msgs::Header& header = inDelivery.frame->header;
  const bool ready = !tf_buffer_ || transformable(header.frame_id, header.stamp);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (ready) {
      // A frame of the same source still waiting for its transform is older: it goes.
      if (waiting_.erase(inKey) > 0) status_.countDropped();
      Delivery& slot = pending_[inKey];
      if (slot.frame) status_.countDropped();  // never started: the newer frame of the source wins
      slot = std::move(inDelivery);
    } else {
      Delivery& slot = waiting_[inKey];
      if (slot.frame) status_.countDropped();
      slot = std::move(inDelivery);
      any_waiting_ = true;
    }
  }
  if (ready) wake_();
}

std::optional<std::string> SourceIngest::unplaceableFrame(const std::string& inFrame) const {
  // tf2 would only print its own complaint on stderr, and the frame would wait for nothing.
  if (!tf_buffer_ || !inFrame.empty()) return std::nullopt;
  return "an empty header.frame_id: cannot be placed in ~fixed_frame '" + fixed_frame_ + "'";
}

std::optional<std::string> SourceIngest::placeInFixedFrame(const std_msgs::Header& inHeader,
                                                           BoxSet& ioBoxes) {
  if (!tf_buffer_) return std::nullopt;
  if (auto reason = unplaceableFrame(inHeader.frame_id)) return reason;
  std::string error;
  bool bad_transform = false;
  if (!moveIntoFixedFrame(inHeader.frame_id, inHeader.stamp, ioBoxes, error, bad_transform))
    return bad_transform ? error : "no transform into '" + fixed_frame_ + "': " + error;
  return std::nullopt;
}

bool SourceIngest::transformable(const std::string& inFrame, const ros::Time& inStamp) const {
  return tf_buffer_->canTransform(fixed_frame_, inFrame, inStamp);
}

void SourceIngest::releaseWaiting(const ros::Time& inNow) {
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    auto& [key, delivery] = *it;
    const std_msgs::Header& header = delivery.frame->header;
    if (transformable(header.frame_id, header.stamp)) {
      Delivery& slot = pending_[key];
      if (slot.frame && slot.frame->header.stamp > header.stamp) {
        status_.countDropped();  // a newer frame of the source is ready already
      } else {
        if (slot.frame) status_.countDropped();
        slot = std::move(delivery);
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

void SourceIngest::countLostMessages() {
  const auto now = std::chrono::steady_clock::now();
  if (stateful_topics_.empty() ||
      now - loss_checked_ < std::chrono::duration<double>(kLossCheckSeconds))
    return;
  loss_checked_ = now;
  // roscpp counts, per publisher link, the messages its full subscriber queue dropped, and
  // tells them only through the node's XML-RPC getBusStats: subscriptions are [[topic,
  // [[connection id, bytes, messages, drops, ...], ...]], ...].
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(ros::XMLRPCManager::instance()->getServerURI(), host, port)) return;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue params, result;
  params[0] = ros::this_node::getName();
  using Value = XmlRpc::XmlRpcValue;
  if (!client.execute("getBusStats", params, result) || result.getType() != Value::TypeArray ||
      result.size() < 2)
    return;
  // The protocol's answer is [code, text, [publications, subscriptions, services]]; roscpp's
  // server (noetic) writes its statistics over the code and text: [publications,
  // subscriptions, ...]. Both are read.
  Value* found = nullptr;
  if (result[0].getType() == Value::TypeArray)
    found = &result[1];
  else if (result.size() >= 3 && result[2].getType() == Value::TypeArray && result[2].size() >= 2)
    found = &result[2][1];
  if (!found || found->getType() != Value::TypeArray) return;
  Value& subscriptions = *found;
  std::map<std::pair<std::string, int>, int> drops;
  for (int i = 0; i < subscriptions.size(); ++i) {
    const std::string topic = subscriptions[i][0];
    if (std::find(stateful_topics_.begin(), stateful_topics_.end(), topic) ==
        stateful_topics_.end())
      continue;
    XmlRpc::XmlRpcValue& links = subscriptions[i][1];
    uint64_t lost = 0;
    for (int k = 0; k < links.size(); ++k) {
      const std::pair<std::string, int> link{topic, static_cast<int>(links[k][0])};
      const int count = links[k][3];
      const auto seen = drops_seen_.find(link);
      lost += static_cast<uint64_t>(count - (seen == drops_seen_.end() ? 0 : seen->second));
      drops[link] = count;
    }
    if (lost > 0) status_.lose(lost, topic);
  }
  drops_seen_ = std::move(drops);  // links gone are forgotten
}

void SourceIngest::forget(const SourceKey& inKey) {
  for (const auto& adapter : adapters_)
    if (adapter->spec().topic == inKey.topic) adapter->dropPublisher(inKey.publisher);
}

void SourceIngest::restartClock(const ros::Time& inNow) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto* deliveries : {&pending_, &waiting_})
    for (auto& [key, delivery] : *deliveries) delivery.received = inNow;
}

bool SourceIngest::placeFrame(const std::string& inName, const ros::Time& inStamp,
                              SourceFrame& ioFrame) {
  if (!tf_buffer_) return true;
  // Moved here, once a frame received, into records the engine then reads as any others, rather
  // than by the engine as it loads the frame. Measured at 2^17 boxes on 2 cores: the transform
  // takes 4.7 ms, the engine's load (copy and check) 1.5 ms of its 3 ms frame, copying the
  // records 1 to 1.6 ms. The transform's cost is its arithmetic, which the load would not save,
  // and the engine loads a source's frame again whenever another source delivers: here it is
  // paid once a frame received, and the engine stays free of transforms.
  if (ioFrame.message) {
    copyBoxArray(*ioFrame.message, ioFrame.records);
    ioFrame.message.reset();
  }
  std::string error;
  bool bad_transform = false;
  if (!moveIntoFixedFrame(ioFrame.header.frame_id, inStamp, ioFrame.records, error,
                          bad_transform)) {
    if (bad_transform)  // the frame's own transform is wrong: refused, as a wrong box is
      status_.refuse(ioFrame.header, ioFrame.size(), inName + ": " + error);
    else
      status_.skip(inName + " skipped: no transform into '" + fixed_frame_ + "': " + error);
    return false;
  }
  ioFrame.header.frame_id = fixed_frame_;  // moved there
  return true;
}

bool SourceIngest::moveIntoFixedFrame(const std::string& inFrame, const ros::Time& inStamp,
                                      BoxSet& ioBoxes, std::string& outError,
                                      bool& outBadTransform) {
  try {
    const geometry_msgs::TransformStamped transform =
        tf_buffer_->lookupTransform(fixed_frame_, inFrame, inStamp);
    if (const auto problem = nonFiniteTransform(transform.transform)) {
      outError = "the transform from '" + inFrame + "' into '" + fixed_frame_ + "' at " +
                 std::to_string(transform.header.stamp.toSec()) + " is not finite (" + *problem +
                 "): refused";
      outBadTransform = true;
      return false;
    }
    transformBoxes(transform.transform, ioBoxes);
    return true;
  } catch (const tf2::TransformException& exception) {
    outError = exception.what();
    return false;
  }
}

}  // namespace sap_broadphase
