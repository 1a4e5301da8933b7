// A broad phase from another library (or our grid), driven on the same boxes as the engine.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "sap_broadphase/core/box_set.h"

namespace sap_bench {

/// A peer's answer for one frame: its pair count and the time of the work a user would pay
/// for in that mode (measured by the peer around exactly that work).
struct PeerResult {
  std::size_t pairs = 0;
  double ms = 0.0;
};

/// One peer. Counts are overlapping pairs under closed-interval semantics.
class Peer {
 public:
  virtual ~Peer() = default;
  /// Short name for tables ("cgal", "bullet_dbvt", ...).
  virtual std::string name() const = 0;
  /// Builds every structure from scratch for inBoxes, counts the pairs, frees the structure.
  virtual PeerResult oneShot(const sap_broadphase::BoxSet& inBoxes) = 0;
  /// Steady state, driven like an engine: the first call after begin() builds (untimed by the
  /// caller), later calls move the existing proxies to inBoxes and count the pairs.
  /// Peers without persistent state just run oneShot().
  virtual PeerResult step(const sap_broadphase::BoxSet& inBoxes) { return oneShot(inBoxes); }
  /// Forgets the steady state.
  virtual void begin() {}
  /// True when step() keeps proxies across frames.
  virtual bool incremental() const { return false; }
  /// How the peer's count relates to the exact closed-interval count.
  virtual std::string semantics() const = 0;
};

/// Every peer compiled in: the grid always, CGAL, Bullet and FCL when found at configure time.
std::vector<std::unique_ptr<Peer>> makePeers(int inThreads);

std::unique_ptr<Peer> makeGridPeer(int inThreads);
#ifdef SAP_BENCH_WITH_CGAL
std::unique_ptr<Peer> makeCgalPeer();
#endif
#ifdef SAP_BENCH_WITH_BULLET
std::unique_ptr<Peer> makeBulletPeer();
#endif
#ifdef SAP_BENCH_WITH_FCL
std::unique_ptr<Peer> makeFclPeer();
#endif

}  // namespace sap_bench
