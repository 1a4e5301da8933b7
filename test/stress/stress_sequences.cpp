#include "stress_sequences.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/frame/box_columns.h"
#include "sap_broadphase/core/brute_force.h"

namespace sap_broadphase::stress {
namespace {

constexpr double kLattice = 1.0 / 16.0;
// 600 boxes in [-12, 12)^3, about 1 wide: many touch, a few pairs each. Larger worlds keep
// that density.
constexpr double kBoxesPerUnitVolume = 600.0 / (24.0 * 24.0 * 24.0);
constexpr int kMaxEdgeSteps = 24;  // edges 0..1.5, zero extent included
constexpr uint32_t kSceneryGroup = 0x2;
constexpr uint32_t kMoverGroup = 0x1;
constexpr std::size_t kBoxesPerEvent = 5;  // boxes a jump, appearance, vanishing... touches

// Half the side of a world of inCount boxes, a whole number.
double halfWorldSide(std::size_t inCount) {
  return std::ceil(0.5 * std::cbrt(static_cast<double>(inCount) / kBoxesPerUnitVolume));
}

// A lattice coordinate in [-inHalfSide, inHalfSide).
double latticeCoordinate(SplitMix64& ioRandom, double inHalfSide) {
  const uint64_t steps = static_cast<uint64_t>(2 * inHalfSide / kLattice);
  return static_cast<double>(ioRandom.below(steps)) * kLattice - inHalfSide;
}

}  // namespace

const std::vector<FrameChange>& skipScript() {
  using C = FrameChange;
  static const std::vector<FrameChange> kScript = {
      C::kDrift,      C::kNone,  C::kDrift,   C::kDrift, C::kUlp,     C::kNone,       C::kDrift,
      C::kSignedZero, C::kNone,  C::kDrift,   C::kJump,  C::kNone,    C::kDrift,      C::kAppear,
      C::kNone,       C::kDrift, C::kVanish,  C::kDrift, C::kReorder, C::kNone,       C::kDrift,
      C::kFilters,    C::kNone,  C::kDrift,   C::kUlp,   C::kDrift,   C::kSignedZero, C::kDrift,
      C::kJump,       C::kDrift, C::kFilters, C::kDrift, C::kReorder, C::kDrift,      C::kVanish,
      C::kAppear,     C::kDrift, C::kNone,
  };
  return kScript;
}

const char* frameChangeName(FrameChange inChange) {
  static const char* const kNames[] = {"none",    "drift", "jump",        "appear", "vanish",
                                       "reorder", "ulp",   "signed zero", "filters"};
  return kNames[static_cast<std::size_t>(inChange)];
}

void appendBox(BoxSet& ioBoxes, const SequenceBox& inBox, bool inFilters) {
  if (inFilters)
    ioBoxes.add(inBox.id, inBox.lo, inBox.hi, inBox.group, inBox.mask);
  else
    ioBoxes.add(inBox.id, inBox.lo, inBox.hi);
}

void flipSignedZeros(SequenceBox& ioBox) {
  for (int axis = 0; axis < 3; ++axis)
    for (double* bound : {&ioBox.lo[axis], &ioBox.hi[axis]})
      if (*bound == 0.0) *bound = std::signbit(*bound) ? 0.0 : -0.0;
}

SkipWorld::SkipWorld(std::size_t inCount, double inRestingShare, bool inFilters, uint64_t inSeed,
                     uint32_t inFirstId)
    : half_side_(halfWorldSide(inCount)),
      resting_share_(inRestingShare),
      filters_(inFilters),
      next_id_(inFirstId),
      random_(inSeed) {
  world_.reserve(inCount);
  for (std::size_t i = 0; i < inCount; ++i) world_.push_back(newBox());
}

SkipWorld::WorldBox SkipWorld::newBox() {
  WorldBox world_box{};
  world_box.resting = random_.chance(resting_share_);
  for (int axis = 0; axis < 3; ++axis)
    world_box.velocity[axis] = static_cast<double>(random_.below(3)) * kLattice - kLattice;
  SequenceBox& box = world_box.box;
  box.id = next_id_++;
  box.group = world_box.resting ? kSceneryGroup : kMoverGroup;
  box.mask = world_box.resting ? kMoverGroup : kDefaultMask;
  placeRandomly(box);
  return world_box;
}

void SkipWorld::placeRandomly(SequenceBox& ioBox) {
  for (int axis = 0; axis < 3; ++axis) {
    ioBox.lo[axis] = latticeCoordinate(random_, half_side_);
    ioBox.hi[axis] =
        ioBox.lo[axis] + static_cast<double>(random_.below(kMaxEdgeSteps + 1)) * kLattice;
  }
}

BoxSet SkipWorld::boxes() const {
  BoxSet boxes;
  boxes.reserve(world_.size());
  for (const WorldBox& world_box : world_) appendBox(boxes, world_box.box, filters_);
  return boxes;
}

// Movers step by their velocity and bounce off the world's walls.
void SkipWorld::drift() {
  for (WorldBox& world_box : world_) {
    if (world_box.resting) continue;
    SequenceBox& box = world_box.box;
    for (int axis = 0; axis < 3; ++axis) {
      double& velocity = world_box.velocity[axis];
      if (box.lo[axis] + velocity < -half_side_ || box.hi[axis] + velocity > half_side_)
        velocity = -velocity;
      box.lo[axis] += velocity;
      box.hi[axis] += velocity;
    }
  }
}

// One bound of one axis one ulp out or in (in only where the box keeps lo <= hi).
void SkipWorld::nudgeOneUlp(SequenceBox& ioBox) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int axis = static_cast<int>(random_.below(3));
  double& low = ioBox.lo[axis];
  double& high = ioBox.hi[axis];
  switch (random_.below(4)) {
    case 0:
      low = std::nextafter(low, -kInf);
      break;
    case 1:
      high = std::nextafter(high, kInf);
      break;
    case 2:
      if (low < high) low = std::nextafter(low, kInf);
      break;
    default:
      if (low < high) high = std::nextafter(high, -kInf);
      break;
  }
}

void SkipWorld::changeFilters(SequenceBox& ioBox) {
  static const uint32_t kGroups[] = {0, kMoverGroup, kSceneryGroup, 0x4};
  static const uint32_t kMasks[] = {0, kMoverGroup, kSceneryGroup | 0x4, kDefaultMask};
  ioBox.group = kGroups[random_.below(4)];
  ioBox.mask = kMasks[random_.below(4)];
}

void SkipWorld::apply(FrameChange inChange) {
  switch (inChange) {
    case FrameChange::kNone:
      break;
    case FrameChange::kDrift:
      drift();
      break;
    case FrameChange::kJump:
      for (std::size_t k = 0; k < kBoxesPerEvent && !world_.empty(); ++k)
        placeRandomly(world_[random_.below(world_.size())].box);
      break;
    case FrameChange::kAppear:
      for (std::size_t k = 0; k < kBoxesPerEvent; ++k) {
        const std::size_t at = random_.below(world_.size() + 1);
        world_.insert(world_.begin() + static_cast<std::ptrdiff_t>(at), newBox());
      }
      break;
    case FrameChange::kVanish:
      for (std::size_t k = 0; k < kBoxesPerEvent && !world_.empty(); ++k)
        world_.erase(world_.begin() + static_cast<std::ptrdiff_t>(random_.below(world_.size())));
      break;
    case FrameChange::kReorder:
      for (std::size_t k = world_.size(); k > 1; --k)
        std::swap(world_[k - 1], world_[random_.below(k)]);
      break;
    case FrameChange::kUlp:
      for (std::size_t k = 0; k < 4 * kBoxesPerEvent && !world_.empty(); ++k)
        nudgeOneUlp(world_[random_.below(world_.size())].box);
      break;
    case FrameChange::kSignedZero:
      for (WorldBox& world_box : world_) flipSignedZeros(world_box.box);
      break;
    case FrameChange::kFilters:
      for (std::size_t k = 0; k < kBoxesPerEvent && !world_.empty(); ++k)
        changeFilters(world_[random_.below(world_.size())].box);
      break;
  }
}

BoxSet sceneryBoxes(std::size_t inCount, uint64_t inSeed) {
  return SkipWorld(inCount, 1.0, false, inSeed, kFirstSceneryId).boxes();
}

BoxSet reversedOrder(const BoxSet& inBoxes) {
  BoxSet reversed = inBoxes;
  std::reverse(reversed.ids.begin(), reversed.ids.end());
  for (std::size_t i = 0, j = reversed.size(); i + 1 < j; ++i, --j) {
    double* first = &reversed.bounds[kBoundsPerBox * i];
    std::swap_ranges(first, first + kBoundsPerBox, &reversed.bounds[kBoundsPerBox * (j - 1)]);
  }
  std::reverse(reversed.groups.begin(), reversed.groups.end());
  std::reverse(reversed.masks.begin(), reversed.masks.end());
  return reversed;
}

KeyOrigin firstFrameKeyOrigin(const BoxSet& inBoxes) {
  const BoxColumns swept = columnsOf(inBoxes);
  FrameSpread spread(swept);
  return keyOriginOf(spread);
}

bool keysOverlap(const KeyOrigin& inOrigin, const BoxSet& inBoxes, std::size_t a, std::size_t b) {
  for (int axis = 0; axis < 3; ++axis)
    if (inOrigin.low(axis, inBoxes.lo(axis, a)) > inOrigin.high(axis, inBoxes.hi(axis, b)) ||
        inOrigin.low(axis, inBoxes.lo(axis, b)) > inOrigin.high(axis, inBoxes.hi(axis, a)))
      return false;
  return true;
}

PairList declaredSceneryOracle(const BoxSet& inScenery, const BoxSet& inMoving) {
  const BoxSpan both[2] = {inScenery.span(), inMoving.span()};  // one frame, read where it lies
  PairList pairs = bruteForcePairs(BoxFrame(both, 2));
  std::vector<uint32_t> scenery_ids = inScenery.ids;
  std::sort(scenery_ids.begin(), scenery_ids.end());
  const auto is_scenery = [&](uint32_t inId) {
    return std::binary_search(scenery_ids.begin(), scenery_ids.end(), inId);
  };
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](const IdPair& inPair) {
                               return is_scenery(inPair.a) && is_scenery(inPair.b);
                             }),
              pairs.end());
  return pairs;
}

}  // namespace sap_broadphase::stress
