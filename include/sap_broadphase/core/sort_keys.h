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

/// Sort key of a low endpoint (min): rounded down.
inline uint32_t lowKey(double inMin) {
  return floatToKey(roundDownToFloat(inMin));
}
/// Sort key of a high endpoint (max): rounded up.
inline uint32_t highKey(double inMax) {
  return floatToKey(roundUpToFloat(inMax));
}

}  // namespace sap_broadphase
