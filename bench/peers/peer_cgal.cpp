// CGAL box_intersection_d on closed boxes: a one-shot algorithm (no state across frames).
#include <CGAL/box_intersection_d.h>

#include "../bench_stats.h"
#include "peer.h"

namespace sap_bench {
namespace {

using CgalBox = CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_EXPLICIT>;

class CgalPeer : public Peer {
 public:
  std::string name() const override { return "cgal"; }
  PeerResult oneShot(const sap_broadphase::BoxSet& inBoxes) override {
    Stopwatch clock;
    std::vector<CgalBox> boxes;
    boxes.reserve(inBoxes.size());
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      double lo[3] = {inBoxes.lo[0][i], inBoxes.lo[1][i], inBoxes.lo[2][i]};
      double hi[3] = {inBoxes.hi[0][i], inBoxes.hi[1][i], inBoxes.hi[2][i]};
      boxes.emplace_back(lo, hi);
    }
    std::size_t count = 0;
    CGAL::box_self_intersection_d(
        boxes.begin(), boxes.end(), [&count](const CgalBox&, const CgalBox&) { ++count; },
        std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
    return {count, clock.ms()};
  }
  std::string semantics() const override { return "exact, closed boxes (CLOSED topology)"; }
};

}  // namespace

std::unique_ptr<Peer> makeCgalPeer() {
  return std::make_unique<CgalPeer>();
}

}  // namespace sap_bench
