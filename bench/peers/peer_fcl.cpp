// FCL's broad-phase managers (dynamic AABB tree, its array variant, sweep and prune, interval
// tree), driven as FCL's documentation advises for moving objects: one collision object per
// box (an axis-aligned fcl::Box translated to the box centre), registered once; each frame
// moves the objects (setTranslation, computeAABB), calls the manager's update() and then
// collide(). The exact peers' callback keeps the pairs whose boxes overlap
// (closed test on the frame's boxes), as a narrow phase would; the raw peers keep every pair
// the manager reports.
#include <fcl/broadphase/broadphase_SaP.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree_array.h>
#include <fcl/broadphase/broadphase_interval_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include "../bench_stats.h"
#include "peer.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;
using sap_broadphase::PairList;

struct CollectData {
  const BoxSet* boxes;
  bool exact;
  PairList* pairs;
};

bool collectPair(fcl::CollisionObjectd* inFirst, fcl::CollisionObjectd* inSecond, void* ioData) {
  auto* data = static_cast<CollectData*>(ioData);
  const auto a = reinterpret_cast<std::size_t>(inFirst->getUserData());
  const auto b = reinterpret_cast<std::size_t>(inSecond->getUserData());
  if (!data->exact || sap_broadphase::boxesOverlap(*data->boxes, a, b))
    data->pairs->push_back(sap_broadphase::makeIdPair(data->boxes->ids[a], data->boxes->ids[b]));
  return false;  // keep going
}

fcl::Vector3d centre(const BoxSet& inBoxes, std::size_t i) {
  return fcl::Vector3d(0.5 * (inBoxes.lo(0, i) + inBoxes.hi(0, i)),
                       0.5 * (inBoxes.lo(1, i) + inBoxes.hi(1, i)),
                       0.5 * (inBoxes.lo(2, i) + inBoxes.hi(2, i)));
}

/// Equal up to rounding: centre +- half of an unchanged box may differ by an ulp per frame.
bool sameSize(const fcl::Vector3d& inA, const fcl::Vector3d& inB) {
  return ((inA - inB).cwiseAbs().array() <= 1e-9 * inA.cwiseAbs().array()).all();
}

using Objects = std::vector<std::unique_ptr<fcl::CollisionObjectd>>;
using ObjectPointers = std::vector<fcl::CollisionObjectd*>;

/// Makes one object per box; later calls move the objects and remake those whose box changed
/// size (an fcl::Box cannot be resized). Returns true when any object was remade; outMoved
/// tells whether any object moved.
bool syncObjects(const BoxSet& inBoxes, Objects& ioObjects, bool& outMoved) {
  bool remade = false;
  outMoved = false;
  if (ioObjects.size() != inBoxes.size()) ioObjects.clear();
  ioObjects.resize(inBoxes.size());
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    const fcl::Vector3d side(inBoxes.hi(0, i) - inBoxes.lo(0, i),
                             inBoxes.hi(1, i) - inBoxes.lo(1, i),
                             inBoxes.hi(2, i) - inBoxes.lo(2, i));
    auto& object = ioObjects[i];
    if (object &&
        sameSize(static_cast<const fcl::Boxd&>(*object->collisionGeometry()).side, side)) {
      const fcl::Vector3d position = centre(inBoxes, i);
      if (position == object->getTranslation()) continue;
      object->setTranslation(position);
      object->computeAABB();
      outMoved = true;
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

ObjectPointers pointers(const Objects& inObjects) {
  ObjectPointers result;
  result.reserve(inObjects.size());
  for (const auto& object : inObjects) result.push_back(object.get());
  return result;
}

template <typename Manager>
class FclPeer : public Peer {
 public:
  FclPeer(std::string inName, PeerOutput inOutput) : name_(std::move(inName)), output_(inOutput) {}
  std::string name() const override { return name_ + (output_ == PeerOutput::kRaw ? "_raw" : ""); }
  std::string family() const override { return "fcl"; }
  bool incremental() const override { return true; }
  std::string semantics() const override {
    return output_ == PeerOutput::kRaw
               ? "every pair the manager reports (AABB of fcl::Box at the centre)"
               : "AABB of fcl::Box at the centre (may round an ulp inward), exact test in "
                 "callback";
  }

  PeerResult oneShot(const BoxSet& inBoxes) override {
    bool moved = false;
    syncObjects(inBoxes, one_shot_objects_, moved);  // the user's scene, not the broad phase
    Stopwatch clock;
    Manager manager;
    manager.registerObjects(pointers(one_shot_objects_));
    manager.setup();
    PeerResult result;
    CollectData data{&inBoxes, output_ == PeerOutput::kExact, &result.pairs};
    manager.collide(&data, collectPair);
    result.ms = clock.ms();
    return result;
  }

  void begin() override {
    manager_.reset();
    steady_objects_.clear();
    one_shot_objects_.clear();
  }

  PeerResult step(const BoxSet& inBoxes) override {
    Stopwatch clock;
    bool moved = false;
    // Objects that changed size are new objects: the manager is then rebuilt (timed).
    if (syncObjects(inBoxes, steady_objects_, moved) || !manager_) {
      manager_ = std::make_unique<Manager>();
      manager_->registerObjects(pointers(steady_objects_));
      manager_->setup();
    } else if (moved) {
      // update() of every object, as FCL's examples do after moving objects: the managers'
      // update(object) is a delete and reinsert, linear in n for the interval tree.
      manager_->update();
    }
    PeerResult result;
    CollectData data{&inBoxes, output_ == PeerOutput::kExact, &result.pairs};
    manager_->collide(&data, collectPair);
    result.ms = clock.ms();
    return result;
  }

 private:
  std::string name_;
  PeerOutput output_;
  Objects one_shot_objects_;
  Objects steady_objects_;
  std::unique_ptr<Manager> manager_;
};

// User data of a query object: its index with this bit set, so that the callback tells the
// two managers' objects apart whatever order FCL hands them in.
constexpr std::size_t kQueryObjectBit = std::size_t{1} << 40;

struct QueryData {
  const BoxSet* world;
  const BoxSet* queries;
  sap_broadphase::QueryHitList* hits;
};

bool collectHit(fcl::CollisionObjectd* inFirst, fcl::CollisionObjectd* inSecond, void* ioData) {
  auto* data = static_cast<QueryData*>(ioData);
  auto first = reinterpret_cast<std::size_t>(inFirst->getUserData());
  auto second = reinterpret_cast<std::size_t>(inSecond->getUserData());
  if ((first & kQueryObjectBit) == 0) std::swap(first, second);
  const std::size_t query = first & ~kQueryObjectBit;
  if (sap_broadphase::boxesOverlap(*data->queries, query, *data->world, second))
    data->hits->push_back({data->queries->ids[query], data->world->ids[second]});
  return false;  // keep going
}

}  // namespace

struct FclTreeQuery::State {
  const BoxSet* world;
  Objects world_objects;
  fcl::DynamicAABBTreeCollisionManagerd world_manager;
  double build_ms = 0.0;
};

FclTreeQuery::FclTreeQuery(const BoxSet& inWorld) : state_(std::make_unique<State>()) {
  state_->world = &inWorld;
  bool moved = false;
  syncObjects(inWorld, state_->world_objects, moved);
  Stopwatch clock;
  state_->world_manager.registerObjects(pointers(state_->world_objects));
  state_->world_manager.setup();
  state_->build_ms = clock.ms();
}

double FclTreeQuery::worldBuildMs() const {
  return state_->build_ms;
}

FclTreeQuery::~FclTreeQuery() = default;

FclTreeQuery::Answer FclTreeQuery::query(const BoxSet& inQueries) {
  Objects objects;
  bool moved = false;
  syncObjects(inQueries, objects, moved);  // the user's scene, not the broad phase
  for (std::size_t q = 0; q < objects.size(); ++q)
    objects[q]->setUserData(reinterpret_cast<void*>(q | kQueryObjectBit));
  Answer answer;
  QueryData data{state_->world, &inQueries, &answer.hits};
  Stopwatch clock;
  fcl::DynamicAABBTreeCollisionManagerd manager;
  manager.registerObjects(pointers(objects));
  manager.setup();
  Stopwatch collide_clock;
  manager.collide(&state_->world_manager, &data, collectHit);
  answer.ms_collide = collide_clock.ms();
  answer.ms = clock.ms();
  return answer;
}

std::unique_ptr<Peer> makeFclPeer(PeerOutput inOutput) {
  return std::make_unique<FclPeer<fcl::DynamicAABBTreeCollisionManagerd>>("fcl_dynamic_aabb",
                                                                          inOutput);
}

void addFclPeers(PeerOutput inOutput, Peers& ioPeers) {
  ioPeers.push_back(makeFclPeer(inOutput));
  ioPeers.push_back(std::make_unique<FclPeer<fcl::DynamicAABBTreeCollisionManager_Arrayd>>(
      "fcl_dynamic_aabb_array", inOutput));
  ioPeers.push_back(std::make_unique<FclPeer<fcl::SaPCollisionManagerd>>("fcl_sap", inOutput));
  ioPeers.push_back(
      std::make_unique<FclPeer<fcl::IntervalTreeCollisionManagerd>>("fcl_interval_tree", inOutput));
}

}  // namespace sap_bench
