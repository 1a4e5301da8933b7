// The list of peers this build has.
#include "peer.h"

namespace sap_bench {

std::vector<std::unique_ptr<Peer>> makePeers(int inThreads) {
  std::vector<std::unique_ptr<Peer>> peers;
  peers.push_back(makeGridPeer(inThreads));
#ifdef SAP_BENCH_WITH_CGAL
  peers.push_back(makeCgalPeer());
#endif
#ifdef SAP_BENCH_WITH_BULLET
  peers.push_back(makeBulletPeer());
#endif
#ifdef SAP_BENCH_WITH_FCL
  peers.push_back(makeFclPeer());
#endif
  return peers;
}

}  // namespace sap_bench
