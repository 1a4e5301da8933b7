// PublisherProbe: each publisher of a source topic asked for its type and MD5 sum.
#include "publisher_probe.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include <ros/header.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcClient.h>

namespace sap_broadphase {

namespace {

/// Wall seconds between two looks at the master.
constexpr double kProbePeriodSeconds = 1.0;
/// Largest connection header read back (roscpp's are a few hundred bytes; a definition may
/// be several kilobytes).
constexpr uint32_t kMaxHeaderBytes = 1u << 20;

/// A TCP connection with one-second send and receive time-outs, closed on destruction.
class Socket {
 public:
  Socket(const std::string& inHost, int inPort, std::string& outError) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (getaddrinfo(inHost.c_str(), std::to_string(inPort).c_str(), &hints, &found) != 0) {
      outError = "cannot resolve " + inHost;
      return;
    }
    for (addrinfo* a = found; a && fd_ < 0; a = a->ai_next) {
      fd_ = socket(a->ai_family, a->ai_socktype, a->ai_protocol);
      if (fd_ < 0) continue;
      timeval limit{1, 0};
      setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
      setsockopt(fd_, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
      if (connect(fd_, a->ai_addr, a->ai_addrlen) != 0) {
        close(fd_);
        fd_ = -1;
      }
    }
    freeaddrinfo(found);
    if (fd_ < 0) outError = "cannot connect to " + inHost + ":" + std::to_string(inPort);
  }
  ~Socket() {
    if (fd_ >= 0) close(fd_);
  }
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;
  bool open() const { return fd_ >= 0; }
  bool sendAll(const uint8_t* inData, std::size_t inSize) {
    while (inSize > 0) {
      const ssize_t sent = send(fd_, inData, inSize, MSG_NOSIGNAL);
      if (sent <= 0) return false;
      inData += sent;
      inSize -= static_cast<std::size_t>(sent);
    }
    return true;
  }
  bool receiveAll(uint8_t* outData, std::size_t inSize) {
    while (inSize > 0) {
      const ssize_t got = recv(fd_, outData, inSize, 0);
      if (got <= 0) return false;
      outData += got;
      inSize -= static_cast<std::size_t>(got);
    }
    return true;
  }

 private:
  int fd_ = -1;
};

/// The TCPROS host and port inNodeUri offers for inTopic (XML-RPC requestTopic).
bool requestTopic(const std::string& inNodeUri, const std::string& inTopic,
                  const std::string& inCallerId, std::string& outHost, int& outPort,
                  std::string& outError) {
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(inNodeUri, host, port)) {
    outError = "not a node URI: " + inNodeUri;
    return false;
  }
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue params, result, protocols;
  protocols[0][0] = std::string("TCPROS");
  params[0] = inCallerId;
  params[1] = inTopic;
  params[2] = protocols;
  using Value = XmlRpc::XmlRpcValue;
  if (!client.execute("requestTopic", params, result) || result.getType() != Value::TypeArray ||
      result.size() < 3 || result[2].getType() != Value::TypeArray || result[2].size() < 3 ||
      result[2][1].getType() != Value::TypeString || result[2][2].getType() != Value::TypeInt) {
    outError = "no TCPROS answer to requestTopic from " + inNodeUri;
    return false;
  }
  outHost = static_cast<std::string>(result[2][1]);
  outPort = static_cast<int>(result[2][2]);
  return true;
}

}  // namespace

std::optional<PublishedType> askPublisher(const std::string& inNodeUri, const std::string& inTopic,
                                          const std::string& inCallerId, std::string& outError) {
  std::string host;
  int port = 0;
  if (!requestTopic(inNodeUri, inTopic, inCallerId, host, port, outError)) return std::nullopt;
  Socket socket(host, port, outError);
  if (!socket.open()) return std::nullopt;
  // A subscriber's header with type and MD5 "*": every publisher answers with its own.
  boost::shared_array<uint8_t> request;
  uint32_t request_size = 0;
  ros::Header::write({{"callerid", inCallerId},
                      {"topic", inTopic},
                      {"md5sum", "*"},
                      {"type", "*"},
                      {"tcp_nodelay", "1"}},
                     request, request_size);
  const uint32_t length = request_size;
  uint8_t length_bytes[4];
  std::memcpy(length_bytes, &length, 4);  // little-endian, as TCPROS
  uint32_t answer_size = 0;
  if (!socket.sendAll(length_bytes, 4) || !socket.sendAll(request.get(), request_size) ||
      !socket.receiveAll(length_bytes, 4)) {
    outError = "no connection header from " + host + ":" + std::to_string(port);
    return std::nullopt;
  }
  std::memcpy(&answer_size, length_bytes, 4);
  if (answer_size > kMaxHeaderBytes) {
    outError = "a connection header of " + std::to_string(answer_size) + " bytes";
    return std::nullopt;
  }
  boost::shared_array<uint8_t> answer(new uint8_t[answer_size]);
  ros::Header header;
  if (!socket.receiveAll(answer.get(), answer_size) ||
      !header.parse(answer, answer_size, outError)) {
    if (outError.empty()) outError = "a connection header cut short";
    return std::nullopt;
  }
  std::string error;
  if (header.getValue("error", error)) {
    outError = error;
    return std::nullopt;
  }
  PublishedType published;
  header.getValue("type", published.type);
  header.getValue("md5sum", published.md5);
  return published;
}

PublisherProbe::PublisherProbe(std::vector<std::pair<std::string, Check>> inTopics, Refuse inRefuse,
                               Refused inRefused)
    : topics_(std::move(inTopics)),
      refuse_(std::move(inRefuse)),
      refused_(std::move(inRefused)),
      thread_(&PublisherProbe::run, this) {}

PublisherProbe::~PublisherProbe() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_signal_.notify_all();
  thread_.join();
}

void PublisherProbe::run() {
  for (;;) {
    try {
      probeOnce();
    } catch (const std::exception& exception) {  // never the end of the node
      ROS_WARN_THROTTLE(10, "sap_broadphase: publisher check failed: %s", exception.what());
    }
    std::unique_lock<std::mutex> lock(mutex_);
    if (stop_signal_.wait_for(lock, std::chrono::duration<double>(kProbePeriodSeconds),
                              [this] { return stopping_; }))
      return;
  }
}

void PublisherProbe::probeOnce() {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", request, response, payload, false) ||
      payload.getType() != XmlRpc::XmlRpcValue::TypeArray || payload.size() < 1)
    return;
  XmlRpc::XmlRpcValue& publications = payload[0];  // [[topic, [node, ...]], ...]
  std::map<std::pair<std::string, std::string>, std::pair<std::string, bool>> asked;
  std::vector<std::string> refused;
  for (int i = 0; i < publications.size(); ++i) {
    const std::string topic = publications[i][0];
    const auto entry = std::find_if(topics_.begin(), topics_.end(),
                                    [&](const auto& inTopic) { return inTopic.first == topic; });
    if (entry == topics_.end()) continue;
    XmlRpc::XmlRpcValue& nodes = publications[i][1];
    for (int k = 0; k < nodes.size(); ++k) {
      const std::string node = nodes[k];
      XmlRpc::XmlRpcValue lookup, lookup_response, uri;
      lookup[0] = ros::this_node::getName();
      lookup[1] = node;
      if (!ros::master::execute("lookupNode", lookup, lookup_response, uri, false) ||
          uri.getType() != XmlRpc::XmlRpcValue::TypeString)
        continue;
      const auto key = std::make_pair(topic, node);
      const auto before = asked_.find(key);
      bool is_refused = false;
      if (before != asked_.end() && before->second.first == static_cast<std::string>(uri)) {
        is_refused = before->second.second;
      } else {
        std::string error;
        const auto published =
            askPublisher(uri, topic, ros::this_node::getName() + "/publisher_check", error);
        if (!published) continue;  // not reachable now: asked again next time
        if (const auto reason = entry->second(*published)) {
          is_refused = true;
          refuse_(topic, node, *reason);
        }
      }
      asked[key] = {static_cast<std::string>(uri), is_refused};
      if (is_refused) refused.push_back(topic + ": " + node);
    }
  }
  asked_ = std::move(asked);  // publishers gone are forgotten
  refused_(refused);
}

}  // namespace sap_broadphase
