// Entry points from the transport that check a message's bytes before roscpp deserializes them
// (roscpp believes every length prefix and allocates what it claims first), and that let no
// exception out: an exception leaving a callback ends the process.
#pragma once

#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <ros/service_callback_helper.h>
#include <ros/subscription_callback_helper.h>
#include <boost/make_shared.hpp>

#include "wire_layout.h"

namespace sap_broadphase {

/// What a refusal at the wire knows of the message: its publisher's connection header.
using WireRefusal = std::function<void(const ros::M_string& inConnection, const std::string&)>;
/// The refusal of a message of inConnection's publisher before its bytes are read (the
/// publisher's type or MD5 sum), or nothing.
using PublisherCheck = std::function<std::optional<std::string>(const ros::M_string&)>;

/// roscpp's subscription helper for callback parameter P whose deserialize() checks the
/// publisher (inCheckPublisher, when given) and the bytes against inLayout first: a refused
/// message is reported to inRefuse and never reaches the callback (roscpp skips a message that
/// deserializes to nothing). In process (a nodelet's BoxArray passed as a pointer) nothing is
/// deserialized and nothing checked: the message was built by code, not read from a socket.
template <typename P>
class CheckedSubscriptionHelper final : public ros::SubscriptionCallbackHelperT<P> {
 public:
  using Base = ros::SubscriptionCallbackHelperT<P>;
  CheckedSubscriptionHelper(const typename Base::Callback& inCallback, const WireLayout& inLayout,
                            PublisherCheck inCheckPublisher, WireRefusal inRefuse)
      : Base(inCallback),
        layout_(inLayout),
        check_publisher_(std::move(inCheckPublisher)),
        refuse_(std::move(inRefuse)) {}

  ros::VoidConstPtr deserialize(
      const ros::SubscriptionCallbackHelperDeserializeParams& inParams) override {
    static const ros::M_string kNoConnection;
    const ros::M_string& connection =
        inParams.connection_header ? *inParams.connection_header : kNoConnection;
    try {
      std::optional<std::string> reason;
      if (check_publisher_) reason = check_publisher_(connection);
      if (!reason) reason = layout_.check(inParams.buffer, inParams.length);
      if (!reason) return Base::deserialize(inParams);
      refuse_(connection, *reason);
    } catch (const std::exception& exception) {  // std::bad_alloc included
      refuse_(connection, layout_.typeName() + " that cannot be read: " + exception.what());
    }
    return ros::VoidConstPtr();
  }

 private:
  const WireLayout& layout_;
  PublisherCheck check_publisher_;
  WireRefusal refuse_;
};

/// roscpp's service helper for Spec whose request bytes are checked against inLayout (no
/// length prefix past the bytes, no byte left over) before they are deserialized. A refused or
/// unreadable request is answered, not failed: inRefusal(reason, response) fills the response
/// that says why.
template <typename Spec>
class CheckedServiceHelper final : public ros::ServiceCallbackHelper {
 public:
  using Request = typename Spec::RequestType;
  using Response = typename Spec::ResponseType;
  using Callback = std::function<bool(Request&, Response&)>;
  using Refusal = std::function<void(const std::string&, Response&)>;
  CheckedServiceHelper(Callback inCallback, const WireLayout& inLayout, Refusal inRefusal)
      : callback_(std::move(inCallback)), layout_(inLayout), refusal_(std::move(inRefusal)) {}

  bool call(ros::ServiceCallbackHelperCallParams& ioParams) override {
    namespace ser = ros::serialization;
    const ros::SerializedMessage& bytes = ioParams.request;
    const std::size_t length = bytes.num_bytes - (bytes.message_start - bytes.buf.get());
    Response response;
    bool ok = true;
    try {
      if (auto reason = layout_.check(bytes.message_start, length)) {
        refusal_(*reason, response);
      } else {
        Request request;
        ser::deserializeMessage(bytes, request);
        ok = callback_(request, response);
      }
    } catch (const std::exception& exception) {  // std::bad_alloc included
      response = Response();
      refusal_(layout_.typeName() + " that cannot be handled: " + exception.what(), response);
    }
    ioParams.response = ser::serializeServiceResponse(ok, response);
    return ok;
  }

 private:
  Callback callback_;
  const WireLayout& layout_;
  Refusal refusal_;
};

/// Advertises service inName of Spec on ioNode, answered on ioQueue (the service's own thread):
/// each request's bytes are checked against its layout first, and a refused or unreadable
/// request is answered through inRefusal (CheckedServiceHelper).
template <typename Spec>
ros::ServiceServer advertiseCheckedService(ros::NodeHandle& ioNode, const std::string& inName,
                                           ros::CallbackQueue& ioQueue,
                                           typename CheckedServiceHelper<Spec>::Callback inCallback,
                                           typename CheckedServiceHelper<Spec>::Refusal inRefusal) {
  using Request = typename Spec::RequestType;
  using Response = typename Spec::ResponseType;
  static const WireLayout kRequestLayout(ros::message_traits::DataType<Request>::value(),
                                         ros::message_traits::Definition<Request>::value());
  ros::AdvertiseServiceOptions options;
  options.init<Request, Response>(ioNode.resolveName(inName),
                                  [](Request&, Response&) { return false; });
  options.helper = boost::make_shared<CheckedServiceHelper<Spec>>(
      std::move(inCallback), kRequestLayout, std::move(inRefusal));
  options.callback_queue = &ioQueue;
  return ioNode.advertiseService(options);
}

/// Runs inBody; an exception it throws (std::bad_alloc included) goes to inReport instead of
/// ending the process. For every callback of the transport, tf and the worker's loop.
template <typename Body, typename Report>
void runGuarded(Body&& inBody, Report&& inReport) {
  try {
    inBody();
  } catch (const std::exception& exception) {
    inReport(std::string(exception.what()));
  } catch (...) {
    inReport(std::string("an exception of unknown type"));
  }
}

}  // namespace sap_broadphase
