// Bullet's btDbvtBroadphase (double-precision build), driven like an engine: proxies created
// once, then setAabb() after each frame's motion and calculateOverlappingPairs().
//
// Bullet's pair cache holds the pairs whose *fattened* leaf volumes overlap (leaves grow by a
// margin and a velocity prediction, and stale pairs are only purged a few percent per frame),
// so the raw cache size over-counts. Bullet leaves the exact test to the narrow phase; we do
// it here, with the closed AABB test on the frame's boxes, and time it with the rest.
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>

#include "../bench_stats.h"
#include "peer.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;

class BulletPeer : public Peer {
 public:
  ~BulletPeer() override { release(steady_, steady_proxies_); }
  std::string name() const override { return "bullet_dbvt"; }
  bool incremental() const override { return true; }
  std::string semantics() const override {
    return "pair cache of fattened leaves, filtered by the exact closed AABB test";
  }

  PeerResult oneShot(const BoxSet& inBoxes) override {
    Stopwatch clock;
    std::vector<btBroadphaseProxy*> proxies;
    btDbvtBroadphase* broadphase = build(inBoxes, proxies);
    const std::size_t pairs = countPairs(*broadphase, inBoxes);
    const double ms = clock.ms();
    release(broadphase, proxies);
    return {pairs, ms};
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
                         nullptr);
      }
    }
    const std::size_t pairs = countPairs(*steady_, inBoxes);
    return {pairs, clock.ms()};
  }

 private:
  static btVector3 lowCorner(const BoxSet& inBoxes, std::size_t i) {
    return btVector3(inBoxes.lo[0][i], inBoxes.lo[1][i], inBoxes.lo[2][i]);
  }
  static btVector3 highCorner(const BoxSet& inBoxes, std::size_t i) {
    return btVector3(inBoxes.hi[0][i], inBoxes.hi[1][i], inBoxes.hi[2][i]);
  }

  static btDbvtBroadphase* build(const BoxSet& inBoxes,
                                 std::vector<btBroadphaseProxy*>& outProxies) {
    auto* broadphase = new btDbvtBroadphase();
    outProxies.resize(inBoxes.size());
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      // The user pointer carries the box index for the exact test.
      outProxies[i] = broadphase->createProxy(lowCorner(inBoxes, i), highCorner(inBoxes, i), 0,
                                              reinterpret_cast<void*>(i), 1, -1, nullptr);
    }
    return broadphase;
  }

  static std::size_t countPairs(btDbvtBroadphase& ioBroadphase, const BoxSet& inBoxes) {
    ioBroadphase.calculateOverlappingPairs(nullptr);
    const btBroadphasePairArray& pairs =
        ioBroadphase.getOverlappingPairCache()->getOverlappingPairArray();
    std::size_t count = 0;
    for (int k = 0; k < pairs.size(); ++k) {
      const auto a = reinterpret_cast<std::size_t>(pairs[k].m_pProxy0->m_clientObject);
      const auto b = reinterpret_cast<std::size_t>(pairs[k].m_pProxy1->m_clientObject);
      count += sap_broadphase::boxesOverlap(inBoxes, a, b) ? 1 : 0;
    }
    return count;
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

  btDbvtBroadphase* steady_ = nullptr;
  std::vector<btBroadphaseProxy*> steady_proxies_;
};

}  // namespace

std::unique_ptr<Peer> makeBulletPeer() {
  return std::make_unique<BulletPeer>();
}

}  // namespace sap_bench
