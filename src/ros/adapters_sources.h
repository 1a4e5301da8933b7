// ~sources: each entry a topic name (a BoxArray source) or a dict
// {topic, type, id_offset, group, mask, timeout}, as costmap_2d's observation sources.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <xmlrpcpp/XmlRpcValue.h>

#include "adapters.h"

namespace sap_broadphase {

/// Reads the ~sources list inValue into outSpecs (replaced only on success). Returns the problem,
/// naming the entry and the key (not a list, empty, a topic twice, an unknown type or key, a
/// negative or fractional number, an id_offset, group or mask past 2^32 - 1), or "".
std::string parseSourceSpecs(const XmlRpc::XmlRpcValue& inValue, std::vector<SourceSpec>& outSpecs);

/// The problem of inSpecs once each topic is resolved by inResolve as the node subscribes to
/// it (namespace, remappings): two entries that name one topic (`boxes` and `/ns/boxes` in
/// /ns), or an entry that is the scenery topic `static_boxes`; "" when there is none. Read
/// twice, every message of such a topic would be refused as its own duplicate on every frame.
std::string checkResolvedSourceTopics(
    const std::vector<SourceSpec>& inSpecs,
    const std::function<std::string(const std::string&)>& inResolve);

/// "obstacles (visualization_msgs/MarkerArray, id_offset 1000, group 0x2, timeout 0.5 s)", or
/// the bare topic for a BoxArray entry with nothing added: how start-up logs name a source.
std::string describeSourceSpec(const SourceSpec& inSpec);

}  // namespace sap_broadphase
