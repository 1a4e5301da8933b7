// The property the multi-frame sequence fuzzer checks, shared by its libFuzzer target and the
// GoogleTest replay of its corpus. No ROS here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sap_broadphase::fuzz {

/// Bytes as a configuration, a first frame and a stream of edits, run through one engine frame
/// after frame; every frame must give the oracle's pairs, and the path a frame reports must be
/// one the configuration allows. Returns an empty string when it holds, else what went wrong.
///
/// Layout: byte 0 switches (bit 0 reuse of unchanged frames, bit 1 unused, bits 2-3 skin off /
/// automatic / 0.25 / 2, bit 4 declared scenery, bit 5 filters, bits 6-7 method); byte 1 threads
/// (1-4), slabs and axis pair; byte 2 the first frame's box count and byte 3 the scenery's; then
/// the boxes (an id-less stream of coordinates, filters when on), then edits, one byte each plus
/// its operands: move a bound, step a bound by ulps, add a box, remove one, swap two, change a
/// box's filters, flip every signed zero, translate every box; an edit byte with its top bit set
/// runs a frame after the edit (and the last edit always does).
std::string checkSequenceBytes(const uint8_t* inData, std::size_t inSize);

}  // namespace sap_broadphase::fuzz
