// Bullet's btDbvtBroadphase (double-precision build), driven as btCollisionWorld drives it:
// proxies created once, setAabb() after each frame's motion, then calculateOverlappingPairs()
// with a collision dispatcher, so that the pair cache is maintained (pairs whose fattened
// leaves part are removed through the dispatcher) as in an engine.
//
// The pair cache holds the pairs whose *fattened* leaf volumes overlap (leaves grow by a
// margin and a velocity prediction, and stale pairs are only purged a few percent per frame),
// so its raw size over-counts. Bullet leaves the exact test to the narrow phase; the exact
// peer does it here, with the closed AABB test on the frame's boxes, timed with the rest; the
// raw peer reports the cache as it is.
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>

#include "../bench_stats.h"
#include "peer.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;

class BulletPeer : public Peer {
 public:
  explicit BulletPeer(PeerOutput inOutput)
      : output_(inOutput), dispatcher_(&collision_configuration_) {}
  ~BulletPeer() override { release(steady_, steady_proxies_); }
  std::string name() const override {
    return output_ == PeerOutput::kRaw ? "bullet_dbvt_raw_cache" : "bullet_dbvt";
  }
  std::string family() const override { return "bullet"; }
  bool incremental() const override { return true; }
  std::string semantics() const override {
    return output_ == PeerOutput::kRaw
               ? "raw pair cache of fattened leaves"
               : "pair cache of fattened leaves, filtered by the exact closed AABB test";
  }

  PeerResult oneShot(const BoxSet& inBoxes) override {
    Stopwatch clock;
    std::vector<btBroadphaseProxy*> proxies;
    btDbvtBroadphase* broadphase = build(inBoxes, proxies);
    PeerResult result = collectPairs(*broadphase, inBoxes);
    result.ms = clock.ms();
    release(broadphase, proxies);
    return result;
  }

  void begin() override { release(steady_, steady_proxies_); }

  PeerResult step(const BoxSet& inBoxes) override {
    Stopwatch clock;
    if (!steady_ || steady_proxies_.size() != inBoxes.size()) {
      release(steady_, steady_proxies_);
      steady_ = build(inBoxes, steady_proxies_);
    } else {
      for (std::size_t i = 0; i < inBoxes.size(); ++i) {
        steady_->setAabb(steady_proxies_[i], lowCorner(inBoxes, i), highCorner(inBoxes, i),
                         &dispatcher_);
      }
    }
    PeerResult result = collectPairs(*steady_, inBoxes);
    result.ms = clock.ms();
    return result;
  }

 private:
  static btVector3 lowCorner(const BoxSet& inBoxes, std::size_t i) {
    return btVector3(inBoxes.lo(0, i), inBoxes.lo(1, i), inBoxes.lo(2, i));
  }
  static btVector3 highCorner(const BoxSet& inBoxes, std::size_t i) {
    return btVector3(inBoxes.hi(0, i), inBoxes.hi(1, i), inBoxes.hi(2, i));
  }

  btDbvtBroadphase* build(const BoxSet& inBoxes, std::vector<btBroadphaseProxy*>& outProxies) {
    auto* broadphase = new btDbvtBroadphase();
    outProxies.resize(inBoxes.size());
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      // The user pointer carries the box index for the exact test.
      outProxies[i] = broadphase->createProxy(lowCorner(inBoxes, i), highCorner(inBoxes, i), 0,
                                              reinterpret_cast<void*>(i), 1, -1, &dispatcher_);
    }
    return broadphase;
  }

  PeerResult collectPairs(btDbvtBroadphase& ioBroadphase, const BoxSet& inBoxes) {
    ioBroadphase.calculateOverlappingPairs(&dispatcher_);
    const btBroadphasePairArray& cache =
        ioBroadphase.getOverlappingPairCache()->getOverlappingPairArray();
    PeerResult result;
    result.pairs.reserve(cache.size());
    for (int k = 0; k < cache.size(); ++k) {
      const auto a = reinterpret_cast<std::size_t>(cache[k].m_pProxy0->m_clientObject);
      const auto b = reinterpret_cast<std::size_t>(cache[k].m_pProxy1->m_clientObject);
      if (output_ == PeerOutput::kExact && !sap_broadphase::boxesOverlap(inBoxes, a, b)) continue;
      result.pairs.push_back(sap_broadphase::makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
    }
    return result;
  }

  /// Deletes the broad phase, then the proxies it allocated (destroyProxy() one by one would
  /// scan the pair cache per proxy).
  static void release(btDbvtBroadphase*& ioBroadphase, std::vector<btBroadphaseProxy*>& ioProxies) {
    delete ioBroadphase;
    ioBroadphase = nullptr;
    for (btBroadphaseProxy* proxy : ioProxies) {
      static_cast<btDbvtProxy*>(proxy)->~btDbvtProxy();
      btAlignedFree(proxy);
    }
    ioProxies.clear();
  }

  PeerOutput output_;
  btDefaultCollisionConfiguration collision_configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase* steady_ = nullptr;
  std::vector<btBroadphaseProxy*> steady_proxies_;
};

}  // namespace

void addBulletPeers(PeerOutput inOutput, Peers& ioPeers) {
  ioPeers.push_back(std::make_unique<BulletPeer>(inOutput));
}

}  // namespace sap_bench
