// NVIDIA PhysX 5's CPU broad phases: ABP (automatic box pruning, one thread), PABP (its parallel
// version, on a PxDefaultCpuDispatcher of the chosen threads) and MBP (multi box pruning, 4 x 4
// regions over the first frame's bounds), compiled from the checkout named by SAP_PHYSX_DIR.
//
// Driven as PxCreateBroadPhase's object drives it (ImmCPUBP in PhysX's immediate mode, which this
// build leaves out: it pulls in the whole dynamics library): a Bp::BroadPhase of the type, a
// PxBroadPhaseUpdateData-like batch of created / updated handles over persistent bounds, group and
// distance arrays, then preBroadPhase, update (with a continuation task for PABP, so that its tasks
// run on the dispatcher's workers), fetchBroadPhaseResults and the created and deleted pairs.
// Every box is a dynamic object of its own group (no filtering) with distance 0.
//
// PhysX reports pairs incrementally: found and lost pairs since the last update. The current
// pair set is those accumulated. Bounds are float32: each double box is rounded outward (low
// corner down, high corner up), so that PhysX's pairs hold every exact pair; ABP's overlap tests
// count touching boxes as overlapping (closed intervals: a box is rejected only when its max is
// strictly below the other's min), so boxes touching in double precision stay a pair. The
// accumulated pairs are then filtered by the exact closed AABB test on the double boxes, dropping
// the few that only the rounding made overlap.
//
// Timed: converting the frame's boxes to float bounds (and finding those that changed), the
// update and the fetch of found and lost pairs: what a PhysX user pays for a frame. Keeping the
// pair set and the exact filter are the harness's, untimed.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "BpBroadPhase.h"
#include "BpBroadPhaseUpdate.h"
#include "BpFiltering.h"
#include "PxcScratchAllocator.h"
#include "extensions/PxDefaultCpuDispatcher.h"
#include "foundation/PxAllocatorCallback.h"
#include "foundation/PxErrorCallback.h"
#include "foundation/PxFoundation.h"
#include "foundation/PxPhysicsVersion.h"
#include "foundation/PxSync.h"
#include "task/PxTask.h"
#include "task/PxTaskManager.h"

#include "../bench_stats.h"
#include "peer.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;
using namespace physx;

class AlignedAllocator : public PxAllocatorCallback {
 public:
  void* allocate(size_t inSize, const char*, const char*, int) override {
    // PhysX needs 16-byte alignment; aligned_alloc needs a multiple of the alignment.
    return std::aligned_alloc(16, (inSize + 15) & ~size_t{15});
  }
  void deallocate(void* inPointer) override { std::free(inPointer); }
};

class StderrErrors : public PxErrorCallback {
 public:
  void reportError(PxErrorCode::Enum inCode, const char* inMessage, const char* inFile,
                   int inLine) override {
    std::fprintf(stderr, "PhysX error %d: %s (%s:%d)\n", static_cast<int>(inCode), inMessage,
                 inFile, inLine);
  }
};

StderrErrors& errorCallback() {
  static StderrErrors errors;
  return errors;
}

/// PhysX's foundation, made on first use (never before a peer runs, so that a peer forked into
/// a process of its own makes it there) and kept for the process's life.
PxFoundation& foundation() {
  static AlignedAllocator allocator;
  static PxFoundation* made = PxCreateFoundation(PX_PHYSICS_VERSION, allocator, errorCallback());
  return *made;
}

/// The task PABP's work continues into: it runs when the broad phase's last task is done and
/// wakes the thread that waits for the frame.
class FrameDoneTask : public PxLightCpuTask {
 public:
  const char* getName() const override { return "sap_bench.physx.frame_done"; }
  void run() override { done_.set(); }
  void wait() {
    done_.wait();
    done_.reset();
  }

 private:
  PxSync done_;
};

/// Worker threads and the task manager that feeds them, for PABP.
struct Workers {
  explicit Workers(int inThreads)
      : dispatcher(PxDefaultCpuDispatcherCreate(static_cast<PxU32>(inThreads))),
        manager(PxTaskManager::createTaskManager(errorCallback(), dispatcher)) {}
  ~Workers() {
    manager->release();
    dispatcher->release();
  }
  PxDefaultCpuDispatcher* dispatcher;
  PxTaskManager* manager;
  FrameDoneTask done;
};

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Bounds rounded outward to float: the float box holds the double one.
PxBounds3 outwardBounds(const BoxSet& inBoxes, std::size_t i) {
  PxVec3 low, high;
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = inBoxes.lo(axis, i), hi = inBoxes.hi(axis, i);
    float l = static_cast<float>(lo), h = static_cast<float>(hi);
    if (static_cast<double>(l) > lo) l = std::nextafter(l, -kInfinity);
    if (static_cast<double>(h) < hi) h = std::nextafter(h, kInfinity);
    low[static_cast<PxU32>(axis)] = l;
    high[static_cast<PxU32>(axis)] = h;
  }
  return PxBounds3(low, high);
}

uint64_t pairKey(PxU32 a, PxU32 b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(a) << 32) | b;
}

/// One broad phase and the arrays it reads (PhysX keeps pointers to them between updates).
class BroadPhaseState {
 public:
  BroadPhaseState(PxBroadPhaseType::Enum inType, Workers* inWorkers)
      : type_(inType), workers_(inWorkers), filter_(false, false) {
    broadphase_ =
        Bp::BroadPhase::create(inType, inType == PxBroadPhaseType::eMBP ? 16 : 0, 0, 0, 0, 0);
  }
  ~BroadPhaseState() { broadphase_->release(); }
  BroadPhaseState(const BroadPhaseState&) = delete;
  BroadPhaseState& operator=(const BroadPhaseState&) = delete;

  std::size_t size() const { return handles_.size(); }

  /// Adds every box (the first update): the found pairs are all pairs.
  void build(const BoxSet& inBoxes) {
    const std::size_t n = inBoxes.size();
    // One spare bound: PhysX may load 4 bytes past the last one.
    bounds_.resize(n + 1);
    groups_.resize(n + 1);
    distances_.assign(n + 1, 0.0f);
    handles_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      bounds_[i] = outwardBounds(inBoxes, i);
      groups_[i] = Bp::getFilterGroup_Dynamics(static_cast<PxU32>(i), false);
      handles_[i] = static_cast<Bp::ShapeHandle>(i);
    }
    bounds_[n] = bounds_[n > 0 ? n - 1 : 0];
    groups_[n] = Bp::FilterGroup::eINVALID;
    if (type_ == PxBroadPhaseType::eMBP) addRegions(n);
    run(handles_.data(), static_cast<PxU32>(n), nullptr, 0);
  }

  /// Moves the boxes whose float bounds changed.
  void move(const BoxSet& inBoxes) {
    moved_.clear();
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      const PxBounds3 now = outwardBounds(inBoxes, i);
      if (now.minimum == bounds_[i].minimum && now.maximum == bounds_[i].maximum) continue;
      bounds_[i] = now;
      moved_.push_back(static_cast<Bp::ShapeHandle>(i));
    }
    run(nullptr, 0, moved_.data(), static_cast<PxU32>(moved_.size()));
  }

  const Bp::BroadPhasePair* created(PxU32& outCount) const {
    return broadphase_->getCreatedPairs(outCount);
  }
  const Bp::BroadPhasePair* deleted(PxU32& outCount) const {
    return broadphase_->getDeletedPairs(outCount);
  }
  /// Frees the update's temporary buffers, after its pairs were read.
  void endFrame() { broadphase_->freeBuffers(); }

 private:
  void run(const Bp::ShapeHandle* inCreated, PxU32 inCreatedCount, const Bp::ShapeHandle* inUpdated,
           PxU32 inUpdatedCount) {
    const Bp::BroadPhaseUpdateData data(inCreated, inCreatedCount, inUpdated, inUpdatedCount,
                                        nullptr, 0, bounds_.data(), groups_.data(),
                                        distances_.data(), nullptr,
                                        static_cast<PxU32>(handles_.size()), filter_, true, true);
    broadphase_->preBroadPhase(data);
    if (workers_) {
      workers_->done.setContinuation(*workers_->manager, nullptr);
      broadphase_->update(&scratch_, data, &workers_->done);
      workers_->done.removeReference();
      workers_->done.wait();
    } else {
      broadphase_->update(&scratch_, data, nullptr);
    }
    broadphase_->fetchBroadPhaseResults();
  }

  /// MBP needs regions: 4 x 4 over x and z of the first frame's bounds (as
  /// PxBroadPhaseExt::createRegionsFromWorldBounds makes them), grown by a tenth so that moving
  /// boxes stay inside.
  void addRegions(std::size_t inCount) {
    PxBounds3 world = PxBounds3::empty();
    for (std::size_t i = 0; i < inCount; ++i) world.include(bounds_[i]);
    world.fattenFast(0.1f * world.getExtents().maxElement());
    const PxVec3 step = (world.maximum - world.minimum) * 0.25f;
    for (int x = 0; x < 4; ++x) {
      for (int z = 0; z < 4; ++z) {
        PxBroadPhaseRegion region;
        region.mBounds.minimum =
            PxVec3(world.minimum.x + x * step.x, world.minimum.y, world.minimum.z + z * step.z);
        region.mBounds.maximum = PxVec3(region.mBounds.minimum.x + step.x, world.maximum.y,
                                        region.mBounds.minimum.z + step.z);
        region.mUserData = nullptr;
        broadphase_->addRegion(region, false, bounds_.data(), distances_.data());
      }
    }
  }

  PxBroadPhaseType::Enum type_;
  Workers* workers_;
  Bp::BroadPhase* broadphase_ = nullptr;
  Bp::BpFilter filter_;
  PxcScratchAllocator scratch_;
  std::vector<PxBounds3> bounds_;
  std::vector<Bp::FilterGroup::Enum> groups_;
  std::vector<float> distances_;
  std::vector<Bp::ShapeHandle> handles_, moved_;
};

class PhysxPeer : public Peer {
 public:
  PhysxPeer(PxBroadPhaseType::Enum inType, int inThreads) : type_(inType), threads_(inThreads) {}
  std::string name() const override {
    switch (type_) {
      case PxBroadPhaseType::ePABP:
        return "physx_pabp_t" + std::to_string(threads_);
      case PxBroadPhaseType::eMBP:
        return "physx_mbp";
      default:
        return "physx_abp";
    }
  }
  std::string family() const override { return "physx"; }
  bool incremental() const override { return true; }
  bool ownProcess() const override { return true; }
  std::string semantics() const override {
    return "found/lost pairs accumulated (float32 bounds rounded outward, touching = pair), "
           "filtered by the exact closed AABB test";
  }

  PeerResult oneShot(const BoxSet& inBoxes) override {
    foundation();
    Stopwatch clock;
    BroadPhaseState state(type_, workers());
    state.build(inBoxes);
    PxU32 count = 0;
    const Bp::BroadPhasePair* found = state.created(count);
    std::vector<uint64_t> keys(count);
    for (PxU32 k = 0; k < count; ++k) keys[k] = pairKey(found[k].mVolA, found[k].mVolB);
    state.endFrame();
    PeerResult result;
    result.ms = clock.ms();
    result.pairs = exactPairs(keys.begin(), keys.end(), inBoxes);
    return result;
  }

  void begin() override {
    steady_.reset();
    current_.clear();
  }

  PeerResult step(const BoxSet& inBoxes) override {
    foundation();
    Stopwatch clock;
    updateSteady(inBoxes);
    PxU32 createdCount = 0, deletedCount = 0;
    const Bp::BroadPhasePair* created = steady_->created(createdCount);
    const Bp::BroadPhasePair* deleted = steady_->deleted(deletedCount);
    PeerResult result;
    result.ms = clock.ms();
    for (PxU32 k = 0; k < deletedCount; ++k)
      current_.erase(pairKey(deleted[k].mVolA, deleted[k].mVolB));
    for (PxU32 k = 0; k < createdCount; ++k)
      current_.insert(pairKey(created[k].mVolA, created[k].mVolB));
    steady_->endFrame();
    result.pairs = exactPairs(current_.begin(), current_.end(), inBoxes);
    return result;
  }

  bool stepKeepingNoPairs(const BoxSet& inBoxes) override {
    foundation();
    updateSteady(inBoxes);
    PxU32 createdCount = 0, deletedCount = 0;
    steady_->created(createdCount);
    steady_->deleted(deletedCount);
    steady_->endFrame();
    return true;
  }

 private:
  /// Builds the steady state on the first frame (or a frame of another size), else moves it.
  void updateSteady(const BoxSet& inBoxes) {
    if (!steady_ || steady_->size() != inBoxes.size()) {
      steady_.reset();
      current_.clear();
      steady_ = std::make_unique<BroadPhaseState>(type_, workers());
      steady_->build(inBoxes);
    } else {
      steady_->move(inBoxes);
    }
  }

  /// The dispatcher's workers (PABP only), made on first use.
  Workers* workers() {
    if (type_ != PxBroadPhaseType::ePABP) return nullptr;
    if (!workers_) workers_ = std::make_unique<Workers>(threads_);
    return workers_.get();
  }

  template <class Iterator>
  static sap_broadphase::PairList exactPairs(Iterator inBegin, Iterator inEnd,
                                             const BoxSet& inBoxes) {
    sap_broadphase::PairList pairs;
    for (Iterator it = inBegin; it != inEnd; ++it) {
      const auto a = static_cast<std::size_t>(*it >> 32);
      const auto b = static_cast<std::size_t>(*it & 0xffffffffu);
      if (sap_broadphase::boxesOverlap(inBoxes, a, b))
        pairs.push_back(sap_broadphase::makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
    }
    return pairs;
  }

  PxBroadPhaseType::Enum type_;
  int threads_;
  std::unique_ptr<Workers> workers_;
  std::unique_ptr<BroadPhaseState> steady_;
  std::unordered_set<uint64_t> current_;
};

}  // namespace

void addPhysxPeers(int inThreads, Peers& ioPeers) {
  ioPeers.push_back(std::make_unique<PhysxPeer>(PxBroadPhaseType::eABP, 1));
  ioPeers.push_back(std::make_unique<PhysxPeer>(PxBroadPhaseType::ePABP, inThreads));
  ioPeers.push_back(std::make_unique<PhysxPeer>(PxBroadPhaseType::eMBP, 1));
}

}  // namespace sap_bench
