// The engine's one input, a frame of box records (BoxFrame, spans of BoxSpan), the BoxSet
// that builds one, and the words a refused box is named with. The engine copies and checks a
// frame in one place, as it loads it (Broadphase::update); validate() runs that same check.
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
/// Bounds of one box record: min_x min_y min_z max_x max_y max_z.
constexpr std::size_t kBoundsPerBox = 6;

/// Boxes laid out as records, as a BoxArray message, the text format, a numpy (n, 6) array
/// and many physics engines hold them: box i is bounds[6 i .. 6 i + 5] = min_x min_y min_z
/// max_x max_y max_z, closed intervals, float64. A view: the caller owns the memory, which must
/// stay unchanged while the engine reads it.
struct BoxSpan {
  std::size_t count = 0;
  const double* bounds = nullptr;    ///< 6 x count values
  const uint32_t* ids = nullptr;     ///< count ids, or null: the boxes are numbered 0..count-1
  uint32_t id_offset = 0;            ///< added to every id (given or numbered) of the span
  const uint32_t* groups = nullptr;  ///< count groups, or null: kDefaultGroup
  const uint32_t* masks = nullptr;   ///< count masks, or null: kDefaultMask
  /// The id box i of the span has in the frame (before the check that it fits 32 bits).
  uint64_t idOf(std::size_t i) const {
    return uint64_t{id_offset} + (ids ? ids[i] : static_cast<uint64_t>(i));
  }
  uint32_t groupOf(std::size_t i) const { return groups ? groups[i] : kDefaultGroup; }
  uint32_t maskOf(std::size_t i) const { return masks ? masks[i] : kDefaultMask; }
};

/// One frame: the boxes of one or several spans (one per source), in span order. Box k of the
/// frame is box k - (boxes of the spans before) of its span; refusals name boxes by k. A view
/// over the caller's spans (or one span it holds itself): no allocation.
class BoxFrame {
 public:
  BoxFrame() = default;
  /// A frame of one span (implicit: update(span) reads as it says).
  BoxFrame(const BoxSpan& inSpan) : single_(inSpan), spans_(&single_), span_count_(1) {}
  /// A frame of several spans; inSpans must outlive the frame.
  BoxFrame(const BoxSpan* inSpans, std::size_t inCount) : spans_(inSpans), span_count_(inCount) {}
  BoxFrame(const std::vector<BoxSpan>& inSpans) : BoxFrame(inSpans.data(), inSpans.size()) {}
  BoxFrame(const BoxFrame& inOther) { *this = inOther; }
  BoxFrame& operator=(const BoxFrame& inOther) {
    single_ = inOther.single_;
    spans_ = inOther.spans_ == &inOther.single_ ? &single_ : inOther.spans_;
    span_count_ = inOther.span_count_;
    return *this;
  }

  std::size_t spanCount() const { return span_count_; }
  const BoxSpan& span(std::size_t inSpan) const { return spans_[inSpan]; }
  /// Boxes of every span.
  std::size_t size() const {
    std::size_t total = 0;
    for (std::size_t s = 0; s < span_count_; ++s) total += spans_[s].count;
    return total;
  }
  /// True when some span gives groups or masks.
  bool hasFilters() const {
    for (std::size_t s = 0; s < span_count_; ++s)
      if (spans_[s].groups || spans_[s].masks) return true;
    return false;
  }

 private:
  BoxSpan single_;
  const BoxSpan* spans_ = nullptr;
  std::size_t span_count_ = 0;
};

/// A convenient builder of a frame of one span: records, ids, and groups and masks either
/// empty (the defaults above) or one per box. `engine.update(boxes)` reads it where it lies.
struct BoxSet {
  std::vector<uint32_t> ids;
  std::vector<double> bounds;  ///< kBoundsPerBox per box, as BoxSpan's
  std::vector<uint32_t> groups;
  std::vector<uint32_t> masks;

  /// Number of boxes.
  std::size_t size() const { return ids.size(); }
  /// Removes all boxes, keeping capacity.
  void clear();
  /// Reserves room for inCount boxes.
  void reserve(std::size_t inCount);
  /// Appends one box with the default group and mask (also when others have filters).
  void add(uint32_t inId, const double inMin[3], const double inMax[3]);
  /// Appends one box with an explicit group and mask (fills defaults for earlier boxes).
  void add(uint32_t inId, const double inMin[3], const double inMax[3], uint32_t inGroup,
           uint32_t inMask);
  /// Lower bound of box i on an axis (0, 1, 2 = x, y, z).
  double lo(int inAxis, std::size_t i) const { return bounds[kBoundsPerBox * i + inAxis]; }
  double& lo(int inAxis, std::size_t i) { return bounds[kBoundsPerBox * i + inAxis]; }
  /// Upper bound of box i on an axis.
  double hi(int inAxis, std::size_t i) const { return bounds[kBoundsPerBox * i + 3 + inAxis]; }
  double& hi(int inAxis, std::size_t i) { return bounds[kBoundsPerBox * i + 3 + inAxis]; }
  /// Group bits of box i (default when none are stored).
  uint32_t group(std::size_t i) const { return groups.empty() ? kDefaultGroup : groups[i]; }
  /// Mask bits of box i (default when none are stored).
  uint32_t mask(std::size_t i) const { return masks.empty() ? kDefaultMask : masks[i]; }
  /// True when any box carries a non-default group or mask.
  bool hasFilters() const { return !groups.empty() || !masks.empty(); }
  /// The boxes as a span (valid until the set changes). Throws InvalidBoxes (BoxProblem::kShape)
  /// when the arrays' lengths disagree: a span cannot say so.
  BoxSpan span() const;
  /// The boxes as a frame of one span: what update(), query() and setStaticBoxes() read.
  operator BoxFrame() const { return BoxFrame(span()); }
};

/// What is wrong, for callers that word the problem their own way (the text reader names
/// lines rather than boxes).
enum class BoxProblem : uint8_t {
  kShape,        ///< array lengths disagree, or more than kMaxBoxes boxes
  kNaN,          ///< a NaN bound: coordinate says which
  kMinAboveMax,  ///< min > max on axis coordinate % 3
  kDuplicateId,  ///< the id of an earlier box: earlier says which
  kIdOverflow,   ///< id_offset + id exceeds 2^32 - 1
};

/// Why a frame was refused: which box (its index in the frame, its span and id) and what is
/// wrong with it.
struct ValidationError {
  std::size_t index = 0;  ///< position of the offending box in the frame
  uint32_t id = 0;        ///< its id
  std::string reason;     ///< e.g. "min_y (3) > max_y (2)" or "max_x is NaN"
  BoxProblem problem = BoxProblem::kShape;
  int coordinate = 0;            ///< kNaN, kMinAboveMax: 0..5 = min_x, min_y, min_z, max_x, ...
  std::size_t earlier = 0;       ///< kDuplicateId: index in the frame of the earlier box, same id
  std::size_t span = 0;          ///< the span that holds box `index`
  std::size_t earlier_span = 0;  ///< kDuplicateId: the span that holds box `earlier`, or kScenery
  /// earlier_span of an id that a declared scenery box has (Broadphase::setStaticBoxes).
  static constexpr std::size_t kScenery = static_cast<std::size_t>(-1);
  /// "box 7 (id 42): min_y (3) > max_y (2)"
  std::string message() const;
};

/// Checks a frame as the engine does when it loads one: no NaN, min <= max on every axis
/// (infinities allowed), unique ids across every span, ids that fit 32 bits, at most kMaxBoxes
/// boxes (and, for a BoxSet, arrays of matching lengths). Returns the problem of the lowest box
/// index (a box's NaN bounds in the order min_x, min_y, min_z, max_x, max_y, max_z first, then
/// min > max by axis, then an id), or nothing.
std::optional<ValidationError> validate(const BoxFrame& inFrame);
/// The same for a BoxSet, whose array lengths are checked first.
std::optional<ValidationError> validate(const BoxSet& inBoxes);

/// What the engine throws for a frame it refuses: the problem validate() names.
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
    if (inBoxesA.lo(axis, a) > inBoxesB.hi(axis, b) || inBoxesB.lo(axis, b) > inBoxesA.hi(axis, a))
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
