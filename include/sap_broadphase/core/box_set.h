// Boxes as a structure of arrays, and the one place where input is validated.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sap_broadphase {

/// Collision group bits a box has when none are given.
constexpr uint32_t kDefaultGroup = 0x1u;
/// Groups a box collides with when no mask is given.
constexpr uint32_t kDefaultMask = 0xFFFFFFFFu;
/// Most boxes one frame may hold: endpoint indexes 0..2n-1 must fit in 32 bits.
constexpr std::size_t kMaxBoxes = (std::size_t{1} << 31) - 1;

/// A set of axis-aligned boxes, closed intervals, float64, in structure-of-arrays layout.
/// Box i is [lo[0][i], hi[0][i]] x [lo[1][i], hi[1][i]] x [lo[2][i], hi[2][i]].
/// `groups` and `masks` are either empty (defaults above) or one per box.
struct BoxSet {
  std::vector<uint32_t> ids;
  std::vector<double> lo[3];
  std::vector<double> hi[3];
  std::vector<uint32_t> groups;
  std::vector<uint32_t> masks;

  /// Number of boxes.
  std::size_t size() const { return ids.size(); }
  /// Removes all boxes, keeping capacity.
  void clear();
  /// Reserves room for inCount boxes.
  void reserve(std::size_t inCount);
  /// Appends one box with the default group and mask (only valid while groups/masks are empty).
  void add(uint32_t inId, const double inMin[3], const double inMax[3]);
  /// Appends one box with an explicit group and mask (fills defaults for earlier boxes).
  void add(uint32_t inId, const double inMin[3], const double inMax[3], uint32_t inGroup,
           uint32_t inMask);
  /// Group bits of box i (default when none are stored).
  uint32_t group(std::size_t i) const { return groups.empty() ? kDefaultGroup : groups[i]; }
  /// Mask bits of box i (default when none are stored).
  uint32_t mask(std::size_t i) const { return masks.empty() ? kDefaultMask : masks[i]; }
  /// True when any box carries a non-default group or mask.
  bool hasFilters() const { return !groups.empty() || !masks.empty(); }
};

/// What is wrong, for callers that word the problem their own way (the text reader names
/// lines rather than boxes).
enum class BoxProblem : uint8_t {
  kShape,        ///< array lengths disagree, or more than kMaxBoxes boxes
  kNaN,          ///< a NaN bound: coordinate says which
  kMinAboveMax,  ///< min > max on axis coordinate % 3
  kDuplicateId,  ///< the id of an earlier box: earlier says which
};

/// Why a box set was refused: which box (its index and id) and what is wrong with it.
struct ValidationError {
  std::size_t index = 0;  ///< position of the offending box in the set
  uint32_t id = 0;        ///< its id
  std::string reason;     ///< e.g. "min_y (3) > max_y (2)" or "max_x is NaN"
  BoxProblem problem = BoxProblem::kShape;
  int coordinate = 0;       ///< kNaN, kMinAboveMax: 0..5 = min_x, min_y, min_z, max_x, ...
  std::size_t earlier = 0;  ///< kDuplicateId: index of the earlier box with the same id
  /// "box 7 (id 42): min_y (3) > max_y (2)"
  std::string message() const;
};

/// Boxes laid out as records, as a BoxArray message and many physics engines hold them: box i
/// is bounds[6 i .. 6 i + 5] = min_x min_y min_z max_x max_y max_z. A view: the caller owns the
/// memory, which must stay unchanged while the engine reads it (Broadphase::update).
struct InterleavedBoxes {
  std::size_t count = 0;
  const double* bounds = nullptr;    ///< 6 x count values
  const uint32_t* ids = nullptr;     ///< count ids, or null: the boxes are numbered 0..count-1
  const uint32_t* groups = nullptr;  ///< count groups, or null: kDefaultGroup (see below)
  const uint32_t* masks = nullptr;   ///< count masks, or null: kDefaultMask (see below)
  /// True when either filter is given; the other one is then completed with its default.
  bool hasFilters() const { return groups != nullptr || masks != nullptr; }
};

/// Copies inBoxes into outBoxes (replaced, capacity reused) in structure-of-arrays layout,
/// on up to inThreads threads: ids numbered 0..count-1 when none are given, a missing filter
/// completed with its default when the other is given. Nothing is checked (validate()).
void copyInterleaved(const InterleavedBoxes& inBoxes, BoxSet& outBoxes, int inThreads);

/// Checks every box: no NaN, min <= max on every axis (infinities allowed), unique ids,
/// groups/masks either empty or one per box, equal array lengths, at most kMaxBoxes boxes.
/// Returns the problem of the lowest box index (a box's NaN bounds in the order min_x, min_y,
/// min_z, max_x, max_y, max_z first, then min > max by axis, then a repeated id), or nothing.
std::optional<ValidationError> validate(const BoxSet& inBoxes);

/// What Broadphase::update() throws for boxes it validates itself (InterleavedBoxes): the
/// problem validate() would name.
class InvalidBoxes : public std::invalid_argument {
 public:
  explicit InvalidBoxes(ValidationError inError)
      : std::invalid_argument(inError.message()), error_(std::move(inError)) {}
  const ValidationError& error() const { return error_; }

 private:
  ValidationError error_;
};

/// True when box a of inBoxesA and box b of inBoxesB overlap on all three axes (closed
/// intervals: touching overlaps).
inline bool boxesOverlap(const BoxSet& inBoxesA, std::size_t a, const BoxSet& inBoxesB,
                         std::size_t b) {
  for (int axis = 0; axis < 3; ++axis) {
    if (inBoxesA.lo[axis][a] > inBoxesB.hi[axis][b] || inBoxesB.lo[axis][b] > inBoxesA.hi[axis][a])
      return false;
  }
  return true;
}

/// True when boxes a and b of inBoxes overlap on all three axes.
inline bool boxesOverlap(const BoxSet& inBoxes, std::size_t a, std::size_t b) {
  return boxesOverlap(inBoxes, a, inBoxes, b);
}

/// The group/mask rule: two boxes may pair when each one's group meets the other's mask
/// (both directions must agree, as in Box2D's and Bullet's filters). A box with group 0 or
/// mask 0 pairs with nothing.
inline bool groupsMayPair(uint32_t inGroupA, uint32_t inMaskA, uint32_t inGroupB,
                          uint32_t inMaskB) {
  return (inGroupA & inMaskB) != 0 && (inGroupB & inMaskA) != 0;
}

/// True when the group/mask filter lets boxes a and b of inBoxes collide.
inline bool filtersAllow(const BoxSet& inBoxes, std::size_t a, std::size_t b) {
  return groupsMayPair(inBoxes.group(a), inBoxes.mask(a), inBoxes.group(b), inBoxes.mask(b));
}

}  // namespace sap_broadphase
