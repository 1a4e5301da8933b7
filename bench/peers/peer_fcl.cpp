// FCL's DynamicAABBTreeCollisionManager, driven like an engine: one collision object per box
// (an axis-aligned fcl::Box translated to the box centre), registered once; each frame moves
// the objects, calls update() and collide(). The callback counts pairs whose boxes overlap
// (closed test on the frame's boxes): FCL's leaves are only refit when an object leaves them,
// so leaf overlap alone over-counts.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include "../bench_stats.h"
#include "peer.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;

struct CountData {
  const BoxSet* boxes;
  std::size_t count;
};

bool countPair(fcl::CollisionObjectd* inFirst, fcl::CollisionObjectd* inSecond, void* ioData) {
  auto* data = static_cast<CountData*>(ioData);
  const auto a = reinterpret_cast<std::size_t>(inFirst->getUserData());
  const auto b = reinterpret_cast<std::size_t>(inSecond->getUserData());
  data->count += sap_broadphase::boxesOverlap(*data->boxes, a, b) ? 1 : 0;
  return false;  // keep going
}

fcl::Vector3d centre(const BoxSet& inBoxes, std::size_t i) {
  return fcl::Vector3d(0.5 * (inBoxes.lo[0][i] + inBoxes.hi[0][i]),
                       0.5 * (inBoxes.lo[1][i] + inBoxes.hi[1][i]),
                       0.5 * (inBoxes.lo[2][i] + inBoxes.hi[2][i]));
}

/// Equal up to rounding: centre +- half of an unchanged box may differ by an ulp per frame.
bool sameSize(const fcl::Vector3d& inA, const fcl::Vector3d& inB) {
  return ((inA - inB).cwiseAbs().array() <= 1e-9 * inA.cwiseAbs().array()).all();
}

class FclPeer : public Peer {
 public:
  std::string name() const override { return "fcl_dynamic_aabb"; }
  bool incremental() const override { return true; }
  std::string semantics() const override {
    return "AABB of fcl::Box at the centre (may round an ulp inward), exact test in callback";
  }

  PeerResult oneShot(const BoxSet& inBoxes) override {
    syncObjects(inBoxes, one_shot_objects_);  // the user's scene, not the broad phase: untimed
    Stopwatch clock;
    fcl::DynamicAABBTreeCollisionManagerd manager;
    manager.registerObjects(pointers(one_shot_objects_));
    manager.setup();
    CountData data{&inBoxes, 0};
    manager.collide(&data, countPair);
    return {data.count, clock.ms()};
  }

  void begin() override {
    manager_.reset();
    steady_objects_.clear();
    one_shot_objects_.clear();
  }

  PeerResult step(const BoxSet& inBoxes) override {
    Stopwatch clock;
    // Objects that changed size are new objects: the manager is then rebuilt (timed).
    if (syncObjects(inBoxes, steady_objects_) || !manager_) {
      manager_ = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
      manager_->registerObjects(pointers(steady_objects_));
      manager_->setup();
    } else {
      manager_->update();
    }
    CountData data{&inBoxes, 0};
    manager_->collide(&data, countPair);
    return {data.count, clock.ms()};
  }

 private:
  using Objects = std::vector<std::unique_ptr<fcl::CollisionObjectd>>;

  /// Makes one object per box; later calls move the objects and remake those whose box
  /// changed size (an fcl::Box cannot be resized). Returns true when any object was remade.
  static bool syncObjects(const BoxSet& inBoxes, Objects& ioObjects) {
    bool remade = false;
    if (ioObjects.size() != inBoxes.size()) ioObjects.clear();
    ioObjects.resize(inBoxes.size());
    for (std::size_t i = 0; i < inBoxes.size(); ++i) {
      const fcl::Vector3d side(inBoxes.hi[0][i] - inBoxes.lo[0][i],
                               inBoxes.hi[1][i] - inBoxes.lo[1][i],
                               inBoxes.hi[2][i] - inBoxes.lo[2][i]);
      auto& object = ioObjects[i];
      if (object &&
          sameSize(static_cast<const fcl::Boxd&>(*object->collisionGeometry()).side, side)) {
        object->setTranslation(centre(inBoxes, i));
        object->computeAABB();
        continue;
      }
      fcl::Transform3d pose = fcl::Transform3d::Identity();
      pose.translation() = centre(inBoxes, i);
      object = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Boxd>(side), pose);
      object->setUserData(reinterpret_cast<void*>(i));
      remade = true;
    }
    return remade;
  }

  static std::vector<fcl::CollisionObjectd*> pointers(const Objects& inObjects) {
    std::vector<fcl::CollisionObjectd*> result;
    result.reserve(inObjects.size());
    for (const auto& object : inObjects) result.push_back(object.get());
    return result;
  }

  Objects one_shot_objects_;
  Objects steady_objects_;
  std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager_;
};

}  // namespace

std::unique_ptr<Peer> makeFclPeer() {
  return std::make_unique<FclPeer>();
}

}  // namespace sap_bench
