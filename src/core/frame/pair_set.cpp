#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

bool isCanonical(const PairList& inPairs) {
  for (std::size_t k = 0; k < inPairs.size(); ++k) {
    if (!(inPairs[k].a < inPairs[k].b)) return false;
    if (k > 0 && !(inPairs[k - 1] < inPairs[k])) return false;
  }
  return true;
}

}  // namespace sap_broadphase
