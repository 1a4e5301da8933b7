// SourceSubscriptions: the inputs' callbacks, which check, convert and post.
#include "source_subscriptions.h"

#include <algorithm>
#include <optional>
#include <utility>

#include <topic_tools/shape_shifter.h>
#include <boost/make_shared.hpp>

#include "adapters.h"
#include "checked_callbacks.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

/// Subscriber queue of a MarkerArray source at least: a burst of incremental updates (rviz
/// tools publish one marker per message) waits here while the callback converts.
constexpr int kStatefulQueueSize = 1000;

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

SourceSubscriptions::SourceSubscriptions(ros::NodeHandle& ioNode, const NodeParams& inParams,
                                         NodeStatus& ioStatus, SourceMailbox& ioMailbox,
                                         const SourcePlacement& inPlacement)
    : status_(ioStatus), mailbox_(ioMailbox), placement_(inPlacement) {
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

SourceSubscriptions::~SourceSubscriptions() {
  stop();
}

void SourceSubscriptions::stop() {
  publisher_probe_.reset();
  // A subscriber's shutdown waits for its callback in progress.
  for (ros::Subscriber& subscriber : subscribers_) subscriber.shutdown();
}

std::vector<SourceAdapter*> SourceSubscriptions::adapters() const {
  std::vector<SourceAdapter*> adapters;
  for (const auto& adapter : adapters_) adapters.push_back(adapter.get());
  return adapters;
}

void SourceSubscriptions::subscribe(ros::NodeHandle& ioNode, const SourceSpec& inSpec,
                                    int inQueueSize) {
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

void SourceSubscriptions::refuseUnhandled(const std::string& inTopic, const std::string& inWhat) {
  status_.refuse(std_msgs::Header(), 0,
                 "'" + inTopic + "': a message that could not be handled (" + inWhat +
                     "): refused, the node goes on");
}

void SourceSubscriptions::onAdaptedMessage(
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
  mailbox_.noteConverted(frame->header);
  deliverFrame(ioAdapter.spec().topic, publisher, std::move(frame));
}

void SourceSubscriptions::subscribeScenery(ros::NodeHandle& ioNode) {
  ros::SubscribeOptions options;
  using Message = const BoxArrayConstPtr&;
  options.init<BoxArray>("static_boxes", 1, [](Message) {});
  options.helper = boost::make_shared<CheckedSubscriptionHelper<Message>>(
      [this](Message inMsg) { keepScenery(inMsg); }, wireLayout(InputType::kBoxArray),
      PublisherCheck(),
      [this](const ros::M_string&, const std::string& inReason) {
        status_.refuse(std_msgs::Header(), 0, std::string(kStaticSourceName) + ": " + inReason);
      });
  subscribers_.push_back(ioNode.subscribe(options));
}

void SourceSubscriptions::keepScenery(const BoxArrayConstPtr& inMsg) {
  std::optional<std::string> reason = checkBoxArrayShape(*inMsg);
  if (!reason && !inMsg->bounds.empty())
    reason = placement_.unplaceableFrame(inMsg->header.frame_id);
  if (reason) {
    status_.refuse(inMsg->header, inMsg->bounds.size() / 6,
                   std::string(kStaticSourceName) + ": " + *reason);
    return;
  }
  mailbox_.postScenery(inMsg);
}

void SourceSubscriptions::deliver(const std::string& inTopic,
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

void SourceSubscriptions::deliverFrame(const std::string& inTopic, const std::string& inPublisher,
                                       std::shared_ptr<SourceFrame> inFrame) {
  status_.countReceived();
  const SourceKey key{inTopic, inPublisher, inFrame->header.frame_id};
  if (auto reason = placement_.unplaceableFrame(inFrame->header.frame_id)) {
    status_.refuse(inFrame->header, inFrame->size(), sourceName(key) + ": " + *reason);
    return;
  }
  mailbox_.post(key, std::move(inFrame));
}

}  // namespace sap_broadphase
