// The lists of peers this build has.
#include "peer.h"

namespace sap_bench {

Peers makePeers(int inThreads) {
  Peers peers;
  addGridPeer(inThreads, peers);
#ifdef SAP_BENCH_WITH_CGAL
  addCgalPeers(peers);
#endif
#ifdef SAP_BENCH_WITH_BULLET
  addBulletPeers(PeerOutput::kExact, peers);
#endif
#ifdef SAP_BENCH_WITH_FCL
  addFclPeers(PeerOutput::kExact, peers);
#endif
#ifdef SAP_BENCH_WITH_PHYSX
  addPhysxPeers(inThreads, peers);
#endif
  return peers;
}

Peers makeRawPeers() {
  Peers peers;
#ifdef SAP_BENCH_WITH_BULLET
  addBulletPeers(PeerOutput::kRaw, peers);
#endif
#ifdef SAP_BENCH_WITH_FCL
  addFclPeers(PeerOutput::kRaw, peers);
#endif
  return peers;
}

std::unique_ptr<Peer> makeFclDynamicTreePeer() {
#ifdef SAP_BENCH_WITH_FCL
  return makeFclPeer(PeerOutput::kExact);
#else
  return nullptr;
#endif
}

}  // namespace sap_bench
