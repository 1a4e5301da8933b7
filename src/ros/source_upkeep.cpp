// SourceUpkeep: ~id_names, queue losses and publishers gone, between frames.
#include "source_upkeep.h"

#include <algorithm>
#include <utility>

#include <ros/network.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <boost/make_shared.hpp>

#include "adapters.h"
#include "sap_broadphase/IdNames.h"

namespace sap_broadphase {

namespace {

/// Wall seconds between two looks at roscpp's drop counts.
constexpr double kLossCheckSeconds = 0.5;

}  // namespace

SourceUpkeep::SourceUpkeep(ros::NodeHandle& ioNode, std::vector<SourceAdapter*> inAdapters,
                           std::vector<std::string> inStatefulTopics,
                           const SourceMailbox& inMailbox, NodeStatus& ioStatus)
    : adapters_(std::move(inAdapters)),
      stateful_topics_(std::move(inStatefulTopics)),
      mailbox_(inMailbox),
      status_(ioStatus) {
  if (!adapters_.empty()) id_names_pub_ = ioNode.advertise<IdNames>("id_names", 1, true);
}

void SourceUpkeep::publishIdNames() {
  std::size_t names = 0;
  for (const auto& adapter : adapters_) names += adapter->nameCount();
  if (names == id_names_published_) return;  // names only grow: none is new
  auto msg = boost::make_shared<IdNames>();
  msg->header = mailbox_.lastConverted();
  for (const auto& adapter : adapters_) adapter->appendIdNames(msg->ids, msg->names);
  id_names_published_ = msg->ids.size();
  // Names only grow and an id's name never changes: only the new ones are added.
  for (std::size_t k = 0; k < msg->ids.size(); ++k)
    id_names_.try_emplace(msg->ids[k], msg->names[k]);
  id_names_pub_.publish(msg);
}

void SourceUpkeep::countLostMessages() {
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

void SourceUpkeep::forget(const SourceKey& inKey) {
  for (const auto& adapter : adapters_)
    if (adapter->spec().topic == inKey.topic) adapter->dropPublisher(inKey.publisher);
}

}  // namespace sap_broadphase
