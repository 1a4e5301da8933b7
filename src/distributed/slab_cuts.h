// Slab borders along one axis: which slab holds a coordinate, and where to cut from a
// weighted sample of box positions.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace sap_broadphase::distributed {

/// The slab holding inX: slab s is [cuts[s-1], cuts[s]). Monotone in inX, and -0.0 and 0.0
/// land in the same slab (they compare equal), which the ownership rule relies on.
inline int slabOfCoordinate(const std::vector<double>& inCuts, double inX) {
  return static_cast<int>(std::upper_bound(inCuts.begin(), inCuts.end(), inX) - inCuts.begin());
}

/// The position a box is sampled (and homed) at on the slab axis: its centre, or its finite
/// end when the other one is infinite; nothing when both are infinite.
inline std::optional<double> samplePosition(double inMin, double inMax) {
  const bool minFinite = std::isfinite(inMin);
  const bool maxFinite = std::isfinite(inMax);
  // Halves first: (min + max) overflows for bounds near the largest double.
  if (minFinite && maxFinite) return inMin * 0.5 + inMax * 0.5;
  if (minFinite) return inMin;
  if (maxFinite) return inMax;
  return std::nullopt;
}

/// One sampled position and the share of the work it stands for.
struct WeightedSample {
  double position;
  double weight;
};

/// inSlabs - 1 non-decreasing cuts that split the weight of ioSamples into inSlabs equal
/// parts (ioSamples is sorted in place). Every rank calls it on the same samples and gets the
/// same cuts. No samples: every cut at 0.
std::vector<double> cutsFromSamples(std::vector<WeightedSample>& ioSamples, int inSlabs);

}  // namespace sap_broadphase::distributed
