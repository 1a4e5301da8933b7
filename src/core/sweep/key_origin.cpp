#include "core/sweep/key_origin.h"

#include <cmath>

#include "core/tuning.h"

namespace sap_broadphase {

double axisKeyOrigin(const AxisSpread& inSpread) {
  const double low = inSpread.lowest, high = inSpread.highest;
  if (!(low <= high)) return 0.0;            // no finite bound: any origin serves
  const double centre = low / 2 + high / 2;  // halves first: no overflow
  const double half_span = high / 2 - low / 2;
  return std::fabs(centre) > tuning::kFarFromOriginInSpans * half_span ? centre : 0.0;
}

KeyOrigin keyOriginOf(FrameSpread& ioSpread) {
  KeyOrigin origin;
  for (int axis = 0; axis < 3; ++axis) origin.origin[axis] = axisKeyOrigin(ioSpread.axis(axis));
  return origin;
}

}  // namespace sap_broadphase
