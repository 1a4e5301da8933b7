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
  std::string family() const override { return "grid"; }
  PeerResult oneShot(const sap_broadphase::BoxSet& inBoxes) override {
    Stopwatch clock;
    const sap_broadphase::PairList& pairs = grid_.pairs(inBoxes);
    const double ms = clock.ms();  // the copy below is the harness's, not the grid's
    return {pairs, ms};
  }
  std::string semantics() const override { return "exact, closed intervals"; }

 private:
  int threads_;
  UniformGrid grid_;
};

}  // namespace

void addGridPeer(int inThreads, Peers& ioPeers) {
  ioPeers.push_back(std::make_unique<GridPeer>(inThreads));
}

}  // namespace sap_bench
