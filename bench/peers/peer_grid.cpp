// Our uniform grid as a peer: rebuilt each frame, so one-shot and steady state coincide.
#include "../bench_stats.h"
#include "peer.h"
#include "uniform_grid.h"

namespace sap_bench {
namespace {

class GridPeer : public Peer {
 public:
  explicit GridPeer(int inThreads) : threads_(inThreads), grid_(inThreads) {}
  std::string name() const override { return "grid_t" + std::to_string(threads_); }
  PeerResult oneShot(const sap_broadphase::BoxSet& inBoxes) override {
    Stopwatch clock;
    const std::size_t pairs = grid_.pairs(inBoxes).size();
    return {pairs, clock.ms()};
  }
  std::string semantics() const override { return "exact, closed intervals"; }

 private:
  int threads_;
  UniformGrid grid_;
};

}  // namespace

std::unique_ptr<Peer> makeGridPeer(int inThreads) {
  return std::make_unique<GridPeer>(inThreads);
}

}  // namespace sap_bench
