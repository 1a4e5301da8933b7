// PublisherProbe: the type and MD5 sum of each publisher of a source topic, checked per
// publisher. A source of another type than BoxArray is subscribed with the MD5 sum of the
// definition the node decodes, so roscpp connects only publishers of that definition and one
// publisher of another never locks the others out (with MD5 "*", roscpp fixes a topic's MD5 sum
// to its first publisher's). roscpp refuses the others at connection time without telling the
// subscriber; the probe asks each publisher the master lists, as a subscriber would (XML-RPC
// requestTopic, then a TCPROS connection header), for a type and MD5 sum no publisher has: the
// publisher refuses that connection, naming its own type and MD5 sum, and so never counts the
// probe as a subscriber (a publisher that publishes once when its first subscriber connects
// sends that message to the node's subscription, not to the probe). A publisher the node's
// subscription is linked to is not asked at all (roscpp links only publishers of the MD5 sum
// subscribed with). Publishers of another definition are refused by name.
#pragma once

#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace sap_broadphase {

/// A publisher's own account of a topic, from its TCPROS connection header.
struct PublishedType {
  std::string type;
  std::string md5;
};

/// Asks the node whose XML-RPC server is inNodeUri what it publishes on inTopic, as subscriber
/// inCallerId. Nothing, with outError, when it cannot be asked (gone, not a TCPROS publisher).
std::optional<PublishedType> askPublisher(const std::string& inNodeUri, const std::string& inTopic,
                                          const std::string& inCallerId, std::string& outError);

class PublisherProbe {
 public:
  /// Why a publisher of this type and MD5 sum cannot feed the topic, or nothing.
  using Check = std::function<std::optional<std::string>(const PublishedType&)>;
  /// A publisher (caller id) of a topic refused, with the reason (probe thread).
  using Refuse = std::function<void(const std::string& inTopic, const std::string& inPublisher,
                                    const std::string& inReason)>;
  /// The names of the publishers refused now, "topic: /publisher" (probe thread).
  using Refused = std::function<void(const std::vector<std::string>&)>;

  /// Starts the probe thread over inTopics (resolved names and their checks).
  PublisherProbe(std::vector<std::pair<std::string, Check>> inTopics, Refuse inRefuse,
                 Refused inRefused);
  /// Stops the thread (a probe in progress times out within a second).
  ~PublisherProbe();
  PublisherProbe(const PublisherProbe&) = delete;
  PublisherProbe& operator=(const PublisherProbe&) = delete;

 private:
  void run();
  /// One look at the master's publishers of every topic; asks the new ones.
  void probeOnce();

  std::vector<std::pair<std::string, Check>> topics_;
  Refuse refuse_;
  Refused refused_;
  // (topic, publisher) -> the node URI asked and whether it was refused: asked again only when
  // the publisher's URI changes (a node restarted under its name); forgotten when it leaves.
  std::map<std::pair<std::string, std::string>, std::pair<std::string, bool>> asked_;
  // (topic, publisher) seen at the last look without a link from the subscription, not asked
  // yet: asked at this look if still unlinked.
  std::set<std::pair<std::string, std::string>> unlinked_;
  std::mutex mutex_;
  std::condition_variable stop_signal_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace sap_broadphase
