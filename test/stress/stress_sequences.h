// Multi-frame sequences for the paths where the engine skips work (unchanged frames, kept skin
// candidates, resting boxes in an index, declared scenery, boxes filtered out): boxes that rest,
// drift, jump, appear, vanish and are reordered; identical frames, one-ulp changes and -0.0
// after 0.0. All deterministic from a seed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/sweep/sweep_and_prune.h"
#include "core/tools/random.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase::stress {

/// What changes between two frames of a sequence.
enum class FrameChange : uint8_t {
  kNone,        ///< the same boxes again, bit for bit
  kDrift,       ///< every moving box moves 1/16 on some axes (well inside a skin of 1)
  kJump,        ///< a few boxes, resting ones included, move far away
  kAppear,      ///< boxes with new ids join at random places in the order
  kVanish,      ///< a few boxes leave
  kReorder,     ///< the same boxes in another order
  kUlp,         ///< a few bounds move by one ulp: touching boxes part, 1-ulp gaps close
  kSignedZero,  ///< every 0.0 bound becomes -0.0 and every -0.0 becomes 0.0 (same values)
  kFilters,     ///< a few boxes change group or mask (0 included: they collide with nothing)
};

/// The order of changes every skip sequence goes through: each change at least twice, after
/// rest and after motion, with identical frames after every kind of change.
const std::vector<FrameChange>& skipScript();
/// "drift", "ulp", ... for failure messages.
const char* frameChangeName(FrameChange inChange);

/// One box of a sequence, its fields together so that reordering, inserting and erasing boxes
/// move them as one.
struct SequenceBox {
  uint32_t id;
  double lo[3];
  double hi[3];
  uint32_t group;
  uint32_t mask;
};
/// Appends inBox to ioBoxes, with its group and mask when inFilters.
void appendBox(BoxSet& ioBoxes, const SequenceBox& inBox, bool inFilters);
/// Every 0.0 bound of inBox becomes -0.0 and every -0.0 becomes 0.0: the same values, other bits.
void flipSignedZeros(SequenceBox& ioBox);

/// A world of boxes on a 1/16 lattice around the origin, about 1 wide, its size growing with
/// the box count so that each box has a few pairs (many touch exactly, many have a 0.0 bound).
/// A share of the boxes rests: they never drift (only jumps move them); with filters, resting
/// boxes are scenery (group 2, mask 1: they pair with movers only, the static index's case)
/// and movers collide with everything.
class SkipWorld {
 public:
  /// Ids are inFirstId, inFirstId + 1, ... in order of appearance.
  SkipWorld(std::size_t inCount, double inRestingShare, bool inFilters, uint64_t inSeed,
            uint32_t inFirstId = 0);
  /// The current frame (groups and masks only when the world has filters).
  BoxSet boxes() const;
  /// Moves on to the next frame.
  void apply(FrameChange inChange);

 private:
  struct WorldBox {
    SequenceBox box;
    double velocity[3];
    bool resting;
  };
  WorldBox newBox();
  void placeRandomly(SequenceBox& ioBox);
  void drift();
  void nudgeOneUlp(SequenceBox& ioBox);
  void changeFilters(SequenceBox& ioBox);

  std::vector<WorldBox> world_;
  double half_side_;  // the world is [-half_side_, half_side_)^3
  double resting_share_;
  bool filters_;
  uint32_t next_id_;
  SplitMix64 random_;
};

/// The same boxes (ids, bounds, filters) in reverse order.
BoxSet reversedOrder(const BoxSet& inBoxes);

/// The key space a fresh engine puts a frame's keys in: keyOriginOf() every box of the frame
/// (those that pair with nothing are swept too), as SweepAndPrune places its KeyOrigin on a
/// first frame. The keys-only mode (exact_final_test = false) may add a pair only where these
/// keys overlap.
KeyOrigin firstFrameKeyOrigin(const BoxSet& inBoxes);
/// True when boxes a and b of inBoxes overlap in inOrigin's keys on all three axes.
bool keysOverlap(const KeyOrigin& inOrigin, const BoxSet& inBoxes, std::size_t a, std::size_t b);

/// Ids of declared scenery start here; SkipWorld ids stay below it.
constexpr uint32_t kFirstSceneryId = 1u << 24;

/// inCount boxes on the lattice of a SkipWorld of inCount boxes, ids from kFirstSceneryId, default
/// filters (scenery boxes overlap one another: those pairs must never be reported).
BoxSet sceneryBoxes(std::size_t inCount, uint64_t inSeed);
/// What update(inMoving) must give after setStaticBoxes(inScenery): the oracle's pairs of both
/// sets together minus the scenery x scenery pairs.
PairList declaredSceneryOracle(const BoxSet& inScenery, const BoxSet& inMoving);

}  // namespace sap_broadphase::stress
