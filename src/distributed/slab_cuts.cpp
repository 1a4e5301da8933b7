#include "slab_cuts.h"

namespace sap_broadphase::distributed {

std::vector<double> cutsFromSamples(std::vector<WeightedSample>& ioSamples, int inSlabs) {
  std::vector<double> cuts(static_cast<std::size_t>(std::max(inSlabs - 1, 0)), 0.0);
  if (ioSamples.empty() || cuts.empty()) return cuts;
  std::sort(ioSamples.begin(), ioSamples.end(),
            [](const WeightedSample& x, const WeightedSample& y) {
              return x.position < y.position || (x.position == y.position && x.weight < y.weight);
            });
  double total = 0.0;
  for (const WeightedSample& sample : ioSamples) total += sample.weight;
  // Cut k sits at the first sample where the running weight reaches (k + 1) / slabs of the
  // total: that sample and everything after it belong to slab k + 1.
  std::size_t next = 0;
  double running = 0.0;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const double target = total * static_cast<double>(k + 1) / inSlabs;
    while (next + 1 < ioSamples.size() && running + ioSamples[next].weight < target) {
      running += ioSamples[next].weight;
      ++next;
    }
    cuts[k] = ioSamples[next].position;
  }
  return cuts;
}

}  // namespace sap_broadphase::distributed
