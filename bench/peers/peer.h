// A broad phase from another library (or our grid), driven on the same boxes as the engine.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_bench {

/// What a peer hands back: the exact pairs (its candidates filtered by the closed AABB test,
/// as the narrow phase of an engine built on it would) or the raw candidates of its broad
/// phase (what a user gets without that test: the run-time-against-error chart).
enum class PeerOutput { kExact, kRaw };

/// A peer's answer for one frame: its pairs as ids (a < b, in the peer's own order; callers
/// sort them, untimed) and the time of the work a user would pay for in that mode (measured
/// by the peer around exactly that work, collecting the pairs included).
struct PeerResult {
  sap_broadphase::PairList pairs;
  double ms = 0.0;
};

/// One peer. Pairs are overlapping pairs under closed-interval semantics (kExact) or the
/// library's candidates (kRaw).
class Peer {
 public:
  virtual ~Peer() = default;
  /// Short name for tables ("cgal_c1000", "bullet_dbvt", ...).
  virtual std::string name() const = 0;
  /// The library the peer comes from ("cgal", "fcl", ...): knob sweeps report the best of a
  /// family.
  virtual std::string family() const = 0;
  /// Builds every structure from scratch for inBoxes, collects the pairs, frees the structure.
  virtual PeerResult oneShot(const sap_broadphase::BoxSet& inBoxes) = 0;
  /// Steady state, driven like an engine: the first call after begin() builds (untimed by the
  /// caller), later calls move the existing proxies to inBoxes and collect the pairs.
  /// Peers without persistent state just run oneShot().
  virtual PeerResult step(const sap_broadphase::BoxSet& inBoxes) { return oneShot(inBoxes); }
  /// Forgets the steady state.
  virtual void begin() {}
  /// True when step() keeps proxies across frames (else step() is oneShot()).
  virtual bool incremental() const { return false; }
  /// A steady frame for a memory measure: as step(), but no pair set is accumulated or handed
  /// back, so that what the process holds is the library's own (its structures, the input arrays
  /// it reads, the found and lost pairs it reports). False when the peer has no such frame.
  virtual bool stepKeepingNoPairs(const sap_broadphase::BoxSet&) { return false; }
  /// True when the peer runs its frames in a child process of its own (peer_runs.h,
  /// runPeerPass), so that its heap, page faults and peak memory are its own.
  virtual bool ownProcess() const { return false; }
  /// How the peer's pairs relate to the exact closed-interval pairs.
  virtual std::string semantics() const = 0;
};

using Peers = std::vector<std::unique_ptr<Peer>>;

/// Every exact peer compiled in, each knob setting its own peer: the grid always; CGAL,
/// Bullet and FCL when found at configure time; PhysX when built from SAP_PHYSX_DIR. inThreads:
/// threads of the grid.
Peers makePeers(int inThreads);
/// The peers whose raw candidates differ from the exact pairs (Bullet's pair cache, FCL's
/// managers), in raw mode, for the error chart.
Peers makeRawPeers();
/// FCL's dynamic AABB tree manager, exact (the coherence benchmark's peer); null without FCL.
std::unique_ptr<Peer> makeFclDynamicTreePeer();

void addGridPeer(int inThreads, Peers& ioPeers);
#ifdef SAP_BENCH_WITH_CGAL
/// Sequential CGAL at several cutoffs, and the TBB version on two threads when built with it.
void addCgalPeers(Peers& ioPeers);
#endif
#ifdef SAP_BENCH_WITH_BULLET
void addBulletPeers(PeerOutput inOutput, Peers& ioPeers);
#endif
#ifdef SAP_BENCH_WITH_FCL
/// FCL's broad-phase managers: dynamic AABB tree, its array variant, SaP, interval tree.
void addFclPeers(PeerOutput inOutput, Peers& ioPeers);
std::unique_ptr<Peer> makeFclPeer(PeerOutput inOutput);  ///< dynamic AABB tree
#endif
#ifdef SAP_BENCH_WITH_PHYSX
/// PhysX 5's CPU broad phases: ABP (one thread), PABP on inThreads workers, MBP (one thread).
/// Each runs in a process of its own.
void addPhysxPeers(int inThreads, Peers& ioPeers);
#endif

/// What a batch of query boxes overlaps in a world, asked of FCL's dynamic AABB tree: the
/// world's manager is built once (untimed); each batch is a manager of its own, built and
/// collided against the world's (FCL's collide(manager, manager)), the exact closed test in the
/// callback. Objects are the user's scene and are made untimed, as in the other FCL peers.
/// Defined in peer_fcl.cpp, built only when FCL is found (SAP_BENCH_WITH_FCL).
class FclTreeQuery {
 public:
  struct Answer {
    sap_broadphase::QueryHitList hits;  ///< {query id, world id}, in FCL's order
    double ms = 0.0;                    ///< the batch's manager built, set up and collided
    double ms_collide = 0.0;            ///< of which the collide
  };
  explicit FclTreeQuery(const sap_broadphase::BoxSet& inWorld);
  ~FclTreeQuery();
  Answer query(const sap_broadphase::BoxSet& inQueries);
  /// ms the world's manager took to build (registerObjects + setup), once.
  double worldBuildMs() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sap_bench
