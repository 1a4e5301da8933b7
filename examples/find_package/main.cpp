// The README's C++ example: a row of boxes moving apart, one update() per frame, the pairs
// printed and checked against the brute-force oracle. Exits 1 if they ever differ.
#include <cstdint>
#include <cstdio>

#include <sap_broadphase/core/box_set.h>
#include <sap_broadphase/core/broadphase.h>
#include <sap_broadphase/core/brute_force.h>

namespace sap = sap_broadphase;

int main() {
  sap::BroadphaseConfig config;        // threads = 0: all cores where they pay; exact
  sap::Broadphase broadphase(config);  // keep it across frames: it reuses its state
  for (int frame = 0; frame < 3; ++frame) {
    sap::BoxSet boxes;  // records: ids, bounds (6 a box), groups, masks
    for (uint32_t id = 0; id < 5; ++id) {
      const double x = id * (1.0 + 0.5 * frame);  // unit boxes, gaps growing each frame
      const double lo[3] = {x, 0, 0}, hi[3] = {x + 1, 1, 1};
      boxes.add(id, lo, hi);
    }

    // Checked as it is read: a NaN, min > max or a repeated id throws sap::InvalidBoxes.
    const sap::PairList& pairs = broadphase.update(boxes);  // IdPair{a, b}, a < b, sorted
    const sap::FrameReport& report = broadphase.stats();    // path, ms per phase, axes
    std::printf("frame %d: %zu pairs (%s, %.3f ms):", frame, pairs.size(),
                sap::framePathName(report.path), report.ms_total);
    for (const sap::IdPair& pair : pairs) std::printf(" %u-%u", pair.a, pair.b);
    std::printf("\n");
    if (pairs != sap::bruteForcePairs(boxes)) return 1;
  }
  return 0;
}
