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
#include <ros/xmlrpc_manager.h>
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

/// The type and MD5 sum the check asks for: no publisher has them, so every publisher refuses
/// the check's connection, and says in its refusal what it publishes.
constexpr const char* kNoType = "sap_broadphase/PublisherCheck";
constexpr const char* kNoMd5 = "00000000000000000000000000000000";

/// The text of inText between inOpening and the next "]", or nothing.
std::optional<std::string> bracketAfter(const std::string& inText, const std::string& inOpening) {
  const std::size_t start = inText.find(inOpening);
  if (start == std::string::npos) return std::nullopt;
  const std::size_t from = start + inOpening.size();
  const std::size_t end = inText.find(']', from);
  if (end == std::string::npos) return std::nullopt;
  return inText.substr(from, end - from);
}

/// What a publisher's refusal says it publishes: roscpp and rospy both answer a subscriber of
/// another MD5 sum "... but our version has [type/md5] ...".
std::optional<PublishedType> versionInRefusal(const std::string& inError) {
  const auto version = bracketAfter(inError, "our version has [");
  if (!version) return std::nullopt;
  const std::size_t slash = version->rfind('/');
  if (slash == std::string::npos) return std::nullopt;
  return PublishedType{version->substr(0, slash), version->substr(slash + 1)};
}

/// One exchange of connection headers with the TCPROS server at inHost:inPort: the
/// publisher's answer, or nothing with outError.
std::optional<ros::Header> exchangeHeaders(const std::string& inHost, int inPort,
                                           const ros::M_string& inFields, std::string& outError) {
  Socket socket(inHost, inPort, outError);
  if (!socket.open()) return std::nullopt;
  boost::shared_array<uint8_t> request;
  uint32_t request_size = 0;
  ros::Header::write(inFields, request, request_size);
  uint8_t length_bytes[4];
  std::memcpy(length_bytes, &request_size, 4);  // little-endian, as TCPROS
  if (!socket.sendAll(length_bytes, 4) || !socket.sendAll(request.get(), request_size) ||
      !socket.receiveAll(length_bytes, 4)) {
    outError = "no connection header from " + inHost + ":" + std::to_string(inPort);
    return std::nullopt;
  }
  uint32_t answer_size = 0;
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
  return header;
}

/// (topic, publisher's node URI) of every publisher this node's subscriptions are linked to,
/// from the node's own XML-RPC getBusInfo: [code, text, [[id, publisher URI, "i", transport,
/// topic, ...], ...]]. Empty when the node's server cannot be asked.
std::set<std::pair<std::string, std::string>> linkedPublishers() {
  std::set<std::pair<std::string, std::string>> linked;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(ros::XMLRPCManager::instance()->getServerURI(), host, port))
    return linked;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue params, result;
  params[0] = ros::this_node::getName();
  using Value = XmlRpc::XmlRpcValue;
  if (!client.execute("getBusInfo", params, result) || result.getType() != Value::TypeArray ||
      result.size() < 3 || result[2].getType() != Value::TypeArray)
    return linked;
  Value& info = result[2];
  for (int i = 0; i < info.size(); ++i) {
    Value& link = info[i];
    if (link.getType() != Value::TypeArray || link.size() < 5 ||
        link[1].getType() != Value::TypeString || link[2].getType() != Value::TypeString ||
        link[4].getType() != Value::TypeString || static_cast<std::string>(link[2]) != "i")
      continue;
    linked.emplace(static_cast<std::string>(link[4]), static_cast<std::string>(link[1]));
  }
  return linked;
}

}  // namespace

std::optional<PublishedType> askPublisher(const std::string& inNodeUri, const std::string& inTopic,
                                          const std::string& inCallerId, std::string& outError) {
  std::string host;
  int port = 0;
  if (!requestTopic(inNodeUri, inTopic, inCallerId, host, port, outError)) return std::nullopt;
  // Asked for a type and MD5 sum it does not have, a publisher refuses the connection and names
  // its own in the refusal: it never counts the check as a subscriber. (Accepted, with MD5 "*",
  // the check was the first subscriber of a publisher that waits for one and publishes once,
  // and took that message from the real subscription.) rospy compares the type first and
  // names only its own type then: asked again with that type, it names its MD5 sum too.
  std::string asked_type = kNoType;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const auto header = exchangeHeaders(host, port,
                                        {{"callerid", inCallerId},
                                         {"topic", inTopic},
                                         {"md5sum", kNoMd5},
                                         {"type", asked_type},
                                         {"tcp_nodelay", "1"}},
                                        outError);
    if (!header) return std::nullopt;
    std::string error;
    if (!header->getValue("error", error)) {
      // Accepted: a publisher of MD5 "*" takes any subscriber, and names itself in its header.
      PublishedType published;
      header->getValue("type", published.type);
      header->getValue("md5sum", published.md5);
      return published;
    }
    if (auto published = versionInRefusal(error)) return published;
    const auto own_type = bracketAfter(error, "] vs. [");  // rospy: "types do not match"
    if (!own_type || *own_type == asked_type) {
      outError = error;
      return std::nullopt;
    }
    asked_type = *own_type;
  }
  outError = "no type and MD5 sum in the publisher's answers";
  return std::nullopt;
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
  const auto linked = linkedPublishers();
  std::set<std::pair<std::string, std::string>> unlinked;  // seen unlinked, not asked yet
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
      // A publisher the subscription is linked to has the MD5 sum subscribed with (roscpp
      // links no other; a link it then drops for its MD5 sum is gone by the next look): it is
      // not asked, and so never disturbed while it connects.
      if (linked.count({topic, static_cast<std::string>(uri)}) > 0) continue;
      const auto key = std::make_pair(topic, node);
      const auto before = asked_.find(key);
      bool is_refused = false;
      if (before != asked_.end() && before->second.first == static_cast<std::string>(uri)) {
        is_refused = before->second.second;
      } else if (unlinked_.count(key) == 0) {
        // Seen unlinked for the first time: the subscription may be linking it now. Asked at
        // the next look if still unlinked (a publisher refused for its MD5 sum, or a link
        // slow to come): a publisher's log then names the check's refused connection only
        // where something is wrong.
        unlinked.insert(key);
        continue;
      } else {
        std::string error;
        const auto published =
            askPublisher(uri, topic, ros::this_node::getName() + "/publisher_check", error);
        if (!published) {  // not reachable now: asked again next time
          unlinked.insert(key);
          continue;
        }
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
  unlinked_ = std::move(unlinked);
  refused_(refused);
}

}  // namespace sap_broadphase
