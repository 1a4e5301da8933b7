// Order-preserving map of float64 coordinates to uint32 sort keys, rounded outward.
//
// Keys are float32 bit patterns made monotone as unsigned integers. A box's low endpoint is
// rounded down and its high endpoint up, so two boxes whose exact intervals overlap also
// overlap in key space: sweeping keys yields a superset of the true pairs, and the final
// overlap test on the exact float64 values removes the extras. Both zeros map to one key.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace sap_broadphase {

/// Monotone unsigned image of a float: a < b (as floats) iff key(a) < key(b); -0 and +0 equal.
inline uint32_t floatToKey(float inValue) {
  if (inValue == 0.0f) inValue = 0.0f;  // -0.0 and +0.0 share one key
  uint32_t bits;
  std::memcpy(&bits, &inValue, sizeof bits);
  // Negative floats: flip all bits (reverses their order); positive: set the sign bit.
  return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

/// Inverse of floatToKey (returns +0.0 for the zero key).
inline float keyToFloat(uint32_t inKey) {
  const uint32_t bits = (inKey & 0x80000000u) ? (inKey & 0x7FFFFFFFu) : ~inKey;
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// Largest float <= inValue (never NaN for non-NaN input; -inf for very negative values).
inline float roundDownToFloat(double inValue) {
  float nearest = static_cast<float>(inValue);
  if (static_cast<double>(nearest) > inValue)
    nearest = std::nextafter(nearest, -std::numeric_limits<float>::infinity());
  return nearest;
}

/// Smallest float >= inValue.
inline float roundUpToFloat(double inValue) {
  float nearest = static_cast<float>(inValue);
  if (static_cast<double>(nearest) < inValue)
    nearest = std::nextafter(nearest, std::numeric_limits<float>::infinity());
  return nearest;
}

/// Key of the positive zero; the negative zero maps here too.
constexpr uint32_t kZeroKey = 0x80000000u;

/// Sort key of a low endpoint (min): the key of roundDownToFloat(inMin), computed without
/// nextafter: one float down is one key down, except just below zero, where -0.0 has no key
/// of its own and the next float down is two keys down.
inline uint32_t lowKey(double inMin) {
  const float nearest = static_cast<float>(inMin);
  uint32_t key = floatToKey(nearest);
  if (static_cast<double>(nearest) > inMin) key -= (key == kZeroKey) ? 2 : 1;
  return key;
}
/// Sort key of a high endpoint (max): the key of roundUpToFloat(inMax) (again two keys up
/// from the key of -denorm_min, over the missing key of -0.0).
inline uint32_t highKey(double inMax) {
  const float nearest = static_cast<float>(inMax);
  uint32_t key = floatToKey(nearest);
  if (static_cast<double>(nearest) < inMax) key += (key == kZeroKey - 2) ? 2 : 1;
  return key;
}

}  // namespace sap_broadphase
