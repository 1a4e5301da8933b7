// Dynamic choice of sweeping axes (paper §5).
//
// Temporal coherence keeps the sort partitions balanced; when endpoints cluster on a sweep
// axis, many coincide and fall into one partition, and the dispersion D of eq. (1) rises.
// The clustered axis is then swapped with the unused one, whose B must be re-initialised.
#pragma once

namespace sap_broadphase {

/// The axis that is neither inFirst nor inSecond (both in 0..2, distinct).
inline int unusedAxis(int inFirst, int inSecond) {
  return 3 - inFirst - inSecond;
}

/// Outcome of one frame's axis decision.
struct AxisDecision {
  int primary;
  int secondary;
  bool swapped;
};

/// Decides next frame's axes from this frame's dispersions. A D is only trusted when the
/// bounds it was measured with came from the previous frame (inWarm), since span-based bounds
/// of a first frame say nothing about coherence. The primary axis is checked first; at most
/// one axis is swapped per frame.
inline AxisDecision chooseAxes(int inPrimary, int inSecondary, double inPrimaryD,
                               double inSecondaryD, bool inWarm, double inThreshold) {
  const int unused = unusedAxis(inPrimary, inSecondary);
  if (inWarm && inPrimaryD > inThreshold && inPrimaryD >= inSecondaryD)
    return {unused, inSecondary, true};
  if (inWarm && inSecondaryD > inThreshold) return {inPrimary, unused, true};
  return {inPrimary, inSecondary, false};
}

}  // namespace sap_broadphase
