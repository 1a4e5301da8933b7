// The properties the ~sources fuzzer checks (the node's list of inputs, as YAML text or as the
// parameter server's XML-RPC values), shared with the replay test. Needs the ROS layer
// (src/ros/adapters_sources.cpp, node_params.cpp), no roscore.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sap_broadphase::fuzz {

/// What the ~sources fuzzer runs. The first byte picks the input:
/// - even: the rest is YAML text, read by parseYamlParameter as a `_sources:=...` of the
///   command line is (a text that is not YAML is refused, nothing thrown);
/// - odd: the rest builds an XML-RPC value directly (lists, dicts with the known keys and
///   others, integers, raw double bits, text, booleans), as `rosparam set` can hand the node.
/// The value goes through parseSourceSpecs and checkResolvedSourceTopics (topics resolved in
/// a namespace of the check's own): a refusal says "~sources", names the entry and leaves the
/// specs untouched; an accepted list has only entries that read back as given (topic, type,
/// id_offset, group, mask, timeout, ids), no empty or repeated topic, and the resolved check
/// refuses exactly the lists with one topic twice or the scenery topic.
std::string checkSourcesInput(const uint8_t* inData, std::size_t inSize);

}  // namespace sap_broadphase::fuzz
