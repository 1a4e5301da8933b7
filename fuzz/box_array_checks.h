// The properties the BoxArray fuzzer checks (ROS message layer), shared with the replay test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sap_broadphase::fuzz {

/// Bytes as a serialized sap_broadphase/BoxArray, the way a hostile publisher could send them:
/// deserialization may throw (roscpp catches and logs that, so do we); a message that
/// deserializes goes through checkBoxArrayShape and boxArrayToBoxSet, which must agree with
/// validate() and never crash; an accepted frame must give the oracle's pairs (small n) and
/// survive pairListToPairArray / pairArrayToPairList and boxSetToBoxArray unchanged.
std::string checkBoxArrayBytes(const uint8_t* inData, std::size_t inSize);

/// Bytes decoded as in checkBoxSetBytes, turned into a BoxArray (bounds, ids, groups, masks,
/// with broken lengths on request), then converted: the conversion must refuse exactly what
/// validate() refuses and keep every value bit for bit.
std::string checkBoxArrayFromBoxSetBytes(const uint8_t* inData, std::size_t inSize);

/// What the BoxArray fuzzer runs: the first byte picks the kind of input (odd: built from a
/// decoded box set, even: serialized bytes), the rest is that input.
std::string checkBoxArrayInput(const uint8_t* inData, std::size_t inSize);

}  // namespace sap_broadphase::fuzz
