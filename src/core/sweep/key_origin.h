// Where the sort keys of an axis are measured from: shared by the sweep (sweep_and_prune.h)
// and the small-frame path (small_frame.h), whose float tests must round exactly as the
// sweep's keys do.
#pragma once

#include <cstdint>
#include <cstring>

#include "core/frame/box_columns.h"
#include "core/sweep/axis_spread.h"
#include "core/sweep/sort_keys.h"

namespace sap_broadphase {

/// Where the sort keys of one axis are measured from. Keys are float32 images of
/// (coordinate - origin), rounded outward exactly (the float64 difference is rounded to
/// nearest, and its rounding error, recovered exactly by TwoSum, decides whether the key must
/// step one further out). Near the origin float32 resolves far finer than at 4e6 m (UTM,
/// ECEF), where boxes of a few centimetres would all share keys and become mutual candidates.
///
/// low() and high() are defined below, inline with the branch-free key functions (lowKeyFlat,
/// highKeyFlat): the sweep makes keys for every endpoint and six per box in its gather.
struct KeyOrigin {
  double origin[3] = {0.0, 0.0, 0.0};
  uint32_t low(int inAxis, double inValue) const;
  uint32_t high(int inAxis, double inValue) const;
};

/// The origin of one axis for a frame of that spread: 0 (keys of the coordinates themselves)
/// unless the frame lies far from 0 compared with its own size (tuning::kFarFromOriginInSpans),
/// where keys of the coordinates would be coarse; then the centre of the finite bounds.
double axisKeyOrigin(const AxisSpread& inSpread);

/// The key origin a sweep of inSpread's boxes starts from: axisKeyOrigin() of each axis
/// (measured on the scope's threads if not measured yet). Later frames keep an origin while the
/// frame stays near it.
KeyOrigin keyOriginOf(FrameSpread& ioSpread);

// x - origin = outDifference + (returned error), exactly (TwoSum, Knuth), unless x is
// infinite (then the error is NaN and the difference the same infinity).
inline double differenceError(double inValue, double inOrigin, double& outDifference) {
  const double difference = inValue - inOrigin;
  const double back = difference - inValue;
  outDifference = difference;
  return (inValue - (difference - back)) + (-inOrigin - back);
}

// lowKey / highKey of sort_keys.h without branches. Coordinates' signs and whether a double
// rounds up or down onto a float are random in a frame, so the branches of the plain versions
// mispredict about half the time; keys are made for every endpoint of both sweep axes and six
// times per box in gatherByRank. Same keys, bit for bit: the float's bits flipped by a mask of
// its sign, -0.0's key (0x7FFFFFFF) moved onto +0.0's, then one key down (two onto and over
// the missing key of -0.0) when rounding went the wrong way.
inline uint32_t floatKeyFlat(float inValue) {
  uint32_t bits;
  std::memcpy(&bits, &inValue, sizeof bits);
  const uint32_t key = bits ^ (static_cast<uint32_t>(static_cast<int32_t>(bits) >> 31) | kZeroKey);
  return key + static_cast<uint32_t>(key == kZeroKey - 1);
}
inline uint32_t lowKeyFlat(double inMin, bool& outExact) {
  const float nearest = static_cast<float>(inMin);
  const uint32_t key = floatKeyFlat(nearest);
  outExact = static_cast<double>(nearest) == inMin;
  return key - (static_cast<uint32_t>(static_cast<double>(nearest) > inMin)
                << static_cast<uint32_t>(key == kZeroKey));
}
inline uint32_t highKeyFlat(double inMax, bool& outExact) {
  const float nearest = static_cast<float>(inMax);
  const uint32_t key = floatKeyFlat(nearest);
  outExact = static_cast<double>(nearest) == inMax;
  return key + (static_cast<uint32_t>(static_cast<double>(nearest) < inMax)
                << static_cast<uint32_t>(key == kZeroKey - 2));
}

inline uint32_t KeyOrigin::low(int inAxis, double inValue) const {
  double difference;
  const double error = differenceError(inValue, origin[inAxis], difference);
  bool exact;  // the difference is a float, so lowKeyFlat did not round it
  const uint32_t key = lowKeyFlat(difference, exact);
  // The difference was rounded up onto a float: the exact value lies below that float.
  return key -
         (static_cast<uint32_t>(error < 0.0 && exact) << static_cast<uint32_t>(key == kZeroKey));
}

inline uint32_t KeyOrigin::high(int inAxis, double inValue) const {
  double difference;
  const double error = differenceError(inValue, origin[inAxis], difference);
  bool exact;
  const uint32_t key = highKeyFlat(difference, exact);
  return key + (static_cast<uint32_t>(error > 0.0 && exact)
                << static_cast<uint32_t>(key == kZeroKey - 2));
}

}  // namespace sap_broadphase
