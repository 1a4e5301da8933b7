// BoxColumns, the engine's working layout, and the check of a frame made on it (validate()
// of a BoxFrame is answered here: the check reads the boxes in columns, as the engine's load
// does).
#include "core/frame/box_columns.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

#include "core/runner/work_units.h"
#include "core/sweep/radix_sort.h"

namespace sap_broadphase {
namespace {

constexpr const char* kAxisNames[3] = {"x", "y", "z"};

std::string formatNumber(double inValue) {
  std::ostringstream text;
  text.precision(17);
  text << inValue;
  return text.str();
}

// Why box i cannot be used: NaN in a bound (in field order min_x .. max_z), or min > max on
// some axis. Called only for a box that is not usable.
ValidationError coordinateProblem(const BoxColumns& inBoxes, std::size_t i) {
  ValidationError error{i, inBoxes.ids[i], ""};
  for (int coordinate = 0; coordinate < 6; ++coordinate) {
    const int axis = coordinate % 3;
    const bool is_max = coordinate >= 3;
    if (!std::isnan(is_max ? inBoxes.hi[axis][i] : inBoxes.lo[axis][i])) continue;
    error.problem = BoxProblem::kNaN;
    error.coordinate = coordinate;
    error.reason = std::string(is_max ? "max_" : "min_") + kAxisNames[axis] + " is NaN";
    return error;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const double low = inBoxes.lo[axis][i];
    const double high = inBoxes.hi[axis][i];
    if (!(low > high)) continue;
    error.problem = BoxProblem::kMinAboveMax;
    error.coordinate = axis;
    error.reason = std::string("min_") + kAxisNames[axis] + " (" + formatNumber(low) + ") > max_" +
                   kAxisNames[axis] + " (" + formatNumber(high) + ")";
    return error;
  }
  return error;  // unreachable for a box that is not usable
}

// First box with an unusable coordinate. `low <= high` is false exactly when either is NaN or
// low > high, so the scan is one comparison a bound and a message is built only for a bad box.
std::optional<ValidationError> findBadCoordinate(const BoxColumns& inBoxes) {
  const std::size_t n = inBoxes.size();
  for (std::size_t i = 0; i < n; ++i) {
    bool usable = true;
    for (int axis = 0; axis < 3; ++axis) usable &= inBoxes.lo[axis][i] <= inBoxes.hi[axis][i];
    if (!usable) return coordinateProblem(inBoxes, i);
  }
  return std::nullopt;
}

ValidationError duplicateAt(const BoxColumns& inBoxes, std::size_t inIndex, std::size_t inEarlier) {
  ValidationError error{inIndex, inBoxes.ids[inIndex],
                        "duplicate id (also box " + std::to_string(inEarlier) + ")"};
  error.problem = BoxProblem::kDuplicateId;
  error.earlier = inEarlier;
  return error;
}

// First repeated id (the smallest index whose id an earlier box has). Ids are usually dense
// (0..n-1, or a robot's range): then one pass over a bit per possible id finds it; sparse ids
// are radix-sorted instead, O(n) passes either way.
std::optional<ValidationError> findDuplicateId(const BoxColumns& inBoxes) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  if (n < 2) return std::nullopt;
  const auto [smallest, largest] = std::minmax_element(inBoxes.ids.begin(), inBoxes.ids.end());
  const uint64_t id_range = uint64_t{*largest} - *smallest + 1;
  if (id_range <= 8 * uint64_t{n}) {
    std::vector<uint64_t> seen((id_range + 63) / 64, 0);
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t bit = inBoxes.ids[k] - *smallest;
      const uint64_t mask = uint64_t{1} << (bit % 64);
      if ((seen[bit / 64] & mask) == 0) {
        seen[bit / 64] |= mask;
        continue;
      }
      const auto earlier = std::find(inBoxes.ids.begin(), inBoxes.ids.begin() + k, inBoxes.ids[k]);
      return duplicateAt(inBoxes, k, static_cast<std::size_t>(earlier - inBoxes.ids.begin()));
    }
    return std::nullopt;
  }
  std::vector<uint32_t> order(n);
  radixIndexSort(inBoxes.ids.data(), n, order.data());
  std::optional<ValidationError> first;
  for (uint32_t k = 1; k < n; ++k) {
    if (inBoxes.ids[order[k]] != inBoxes.ids[order[k - 1]]) continue;
    // The stable sort keeps index order among equal ids: order[k] is a later repeat.
    if (!first || order[k] < first->index) first = duplicateAt(inBoxes, order[k], order[k - 1]);
  }
  return first;
}

// The first box whose span's id_offset + id does not fit 32 bits (a span's ids are checked
// only when it has an offset: without one every id fits).
std::optional<ValidationError> findIdOverflow(const BoxFrame& inFrame) {
  std::size_t first_box = 0;
  for (std::size_t s = 0; s < inFrame.spanCount(); ++s) {
    const BoxSpan& span = inFrame.span(s);
    for (std::size_t i = 0; span.id_offset != 0 && i < span.count; ++i) {
      if (span.idOf(i) <= UINT32_MAX) continue;
      // Named by the id its sender gave it: the sum wrapped past 32 bits names another box.
      const uint64_t own_id = span.idOf(i) - span.id_offset;
      ValidationError error{first_box + i, static_cast<uint32_t>(own_id),
                            "id offset " + std::to_string(span.id_offset) + " + id " +
                                std::to_string(own_id) + " exceeds 4294967295"};
      error.problem = BoxProblem::kIdOverflow;
      return error;
    }
    first_box += span.count;
  }
  return std::nullopt;
}

// The filters of a box about to be added (before its id): earlier boxes get the defaults.
void addFilters(BoxColumns& ioBoxes, uint32_t inGroup, uint32_t inMask) {
  ioBoxes.groups.resize(ioBoxes.size(), kDefaultGroup);
  ioBoxes.masks.resize(ioBoxes.size(), kDefaultMask);
  ioBoxes.groups.push_back(inGroup);
  ioBoxes.masks.push_back(inMask);
}

ValidationError shapeError(std::string inReason) {
  return ValidationError{0, 0, std::move(inReason)};
}

// The index in its span of frame box inIndex: the span, and the boxes before it.
std::size_t spanOf(const BoxFrame& inFrame, std::size_t inIndex) {
  std::size_t first_box = 0;
  for (std::size_t s = 0; s < inFrame.spanCount(); ++s) {
    if (inIndex < first_box + inFrame.span(s).count) return s;
    first_box += inFrame.span(s).count;
  }
  return inFrame.spanCount();
}

}  // namespace

void BoxColumns::clear() {
  ids.clear();
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].clear();
    hi[axis].clear();
  }
  groups.clear();
  masks.clear();
}

void BoxColumns::reserve(std::size_t inCount) {
  ids.reserve(inCount);
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].reserve(inCount);
    hi[axis].reserve(inCount);
  }
}

void BoxColumns::resize(std::size_t inCount, bool inFiltered) {
  ids.resize(inCount);
  for (int axis = 0; axis < 3; ++axis) {
    resizeDiscarding(lo[axis], inCount);
    resizeDiscarding(hi[axis], inCount);
  }
  groups.resize(inFiltered ? inCount : 0);
  masks.resize(inFiltered ? inCount : 0);
}

void BoxColumns::add(uint32_t inId, const double inMin[3], const double inMax[3]) {
  ids.push_back(inId);
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].push_back(inMin[axis]);
    hi[axis].push_back(inMax[axis]);
  }
  if (!groups.empty()) groups.push_back(kDefaultGroup);
  if (!masks.empty()) masks.push_back(kDefaultMask);
}

void BoxColumns::add(uint32_t inId, const double inMin[3], const double inMax[3], uint32_t inGroup,
                     uint32_t inMask) {
  addFilters(*this, inGroup, inMask);
  ids.push_back(inId);
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].push_back(inMin[axis]);
    hi[axis].push_back(inMax[axis]);
  }
}

void copyFrame(const BoxFrame& inFrame, BoxColumns& outBoxes) {
  outBoxes.resize(inFrame.size(), inFrame.hasFilters());
  const bool filtered = inFrame.hasFilters();
  std::size_t first_box = 0;
  for (std::size_t s = 0; s < inFrame.spanCount(); ++s) {
    const BoxSpan& span = inFrame.span(s);
    // A 2^20-box frame is 50 MB: copied in work units on the threads (one unit inline).
    runOverItems(WorkUnits{span.count}, [&](std::size_t inBegin, std::size_t inEnd) {
      for (std::size_t i = inBegin; i < inEnd; ++i) {
        const double* box = span.bounds + kBoundsPerBox * i;
        const std::size_t k = first_box + i;
        for (int axis = 0; axis < 3; ++axis) {
          outBoxes.lo[axis][k] = box[axis];
          outBoxes.hi[axis][k] = box[3 + axis];
        }
        outBoxes.ids[k] = static_cast<uint32_t>(span.idOf(i));
        if (filtered) {
          outBoxes.groups[k] = span.groupOf(i);
          outBoxes.masks[k] = span.maskOf(i);
        }
      }
    });
    first_box += span.count;
  }
}

BoxColumns columnsOf(const BoxFrame& inFrame) {
  BoxColumns boxes;
  copyFrame(inFrame, boxes);
  return boxes;
}
std::optional<ValidationError> checkColumns(const BoxColumns& inBoxes, const BoxFrame& inFrame) {
  const std::size_t n = inBoxes.size();
  if (n > kMaxBoxes)
    return shapeError(std::to_string(n) + " boxes exceed the engine's limit of " +
                      std::to_string(kMaxBoxes));
  std::optional<ValidationError> problem = findBadCoordinate(inBoxes);
  for (auto id_problem : {findIdOverflow(inFrame), findDuplicateId(inBoxes)}) {
    if (id_problem && (!problem || id_problem->index < problem->index)) problem = id_problem;
  }
  if (problem) {
    problem->span = spanOf(inFrame, problem->index);
    if (problem->problem == BoxProblem::kDuplicateId)
      problem->earlier_span = spanOf(inFrame, problem->earlier);
  }
  return problem;
}

std::optional<ValidationError> validate(const BoxFrame& inFrame) {
  return checkColumns(columnsOf(inFrame), inFrame);
}

}  // namespace sap_broadphase
