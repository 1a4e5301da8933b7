// The properties the wire fuzzer checks (the node's message decoders against hostile bytes),
// shared with the replay test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sap_broadphase::fuzz {

/// What the wire fuzzer runs: the first byte picks a type the node reads from the wire
/// (sap_broadphase/BoxArray, visualization_msgs/MarkerArray, the vision_msgs and
/// jsk_recognition_msgs arrays, the compute_pairs and query_boxes requests), the rest is a message
/// of it as any process on the network can send. WireLayout::check must never read past the bytes
/// or crash; what it accepts must deserialize with roscpp (for the types the node deserializes so)
/// without an exception, reading every byte, and allocate no more elements than the bytes can
/// hold; what it refuses must say why, naming the type.
std::string checkWireInput(const uint8_t* inData, std::size_t inSize);

}  // namespace sap_broadphase::fuzz
