#include "sap_broadphase/core/box_set.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/radix_sort.h"

namespace sap_broadphase {
namespace {

constexpr const char* kAxisNames[3] = {"x", "y", "z"};

std::string formatNumber(double inValue) {
  std::ostringstream text;
  text.precision(17);
  text << inValue;
  return text.str();
}

// First box with an unusable coordinate: NaN anywhere, or min > max on some axis.
std::optional<ValidationError> findBadCoordinate(const BoxSet& inBoxes) {
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double low = inBoxes.lo[axis][i];
      const double high = inBoxes.hi[axis][i];
      std::string reason;
      if (std::isnan(low))
        reason = std::string("min_") + kAxisNames[axis] + " is NaN";
      else if (std::isnan(high))
        reason = std::string("max_") + kAxisNames[axis] + " is NaN";
      else if (low > high)
        reason = std::string("min_") + kAxisNames[axis] + " (" + formatNumber(low) + ") > max_" +
                 kAxisNames[axis] + " (" + formatNumber(high) + ")";
      if (!reason.empty()) return ValidationError{i, inBoxes.ids[i], reason};
    }
  }
  return std::nullopt;
}

// First repeated id, found in O(n) passes by radix-sorting the ids.
std::optional<ValidationError> findDuplicateId(const BoxSet& inBoxes) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  std::vector<uint32_t> order(n);
  radixIndexSort(inBoxes.ids.data(), n, order.data());
  std::optional<ValidationError> first;
  for (uint32_t k = 1; k < n; ++k) {
    if (inBoxes.ids[order[k]] != inBoxes.ids[order[k - 1]]) continue;
    // The stable sort keeps index order among equal ids: order[k] is a later repeat.
    const std::size_t index = order[k];
    if (!first || index < first->index)
      first = ValidationError{index, inBoxes.ids[index],
                              "duplicate id (also box " + std::to_string(order[k - 1]) + ")"};
  }
  return first;
}

}  // namespace

void BoxSet::clear() {
  ids.clear();
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].clear();
    hi[axis].clear();
  }
  groups.clear();
  masks.clear();
}

void BoxSet::reserve(std::size_t inCount) {
  ids.reserve(inCount);
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].reserve(inCount);
    hi[axis].reserve(inCount);
  }
}

void BoxSet::add(uint32_t inId, const double inMin[3], const double inMax[3]) {
  ids.push_back(inId);
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].push_back(inMin[axis]);
    hi[axis].push_back(inMax[axis]);
  }
  if (!groups.empty()) groups.push_back(kDefaultGroup);
  if (!masks.empty()) masks.push_back(kDefaultMask);
}

void BoxSet::add(uint32_t inId, const double inMin[3], const double inMax[3], uint32_t inGroup,
                 uint32_t inMask) {
  const std::size_t before = size();
  if (groups.empty()) groups.assign(before, kDefaultGroup);
  if (masks.empty()) masks.assign(before, kDefaultMask);
  ids.push_back(inId);
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis].push_back(inMin[axis]);
    hi[axis].push_back(inMax[axis]);
  }
  groups.push_back(inGroup);
  masks.push_back(inMask);
}

std::string ValidationError::message() const {
  return "box " + std::to_string(index) + " (id " + std::to_string(id) + "): " + reason;
}

std::optional<ValidationError> validate(const BoxSet& inBoxes) {
  const std::size_t n = inBoxes.size();
  for (int axis = 0; axis < 3; ++axis) {
    if (inBoxes.lo[axis].size() != n || inBoxes.hi[axis].size() != n)
      return ValidationError{0, 0,
                             std::string("bounds on axis ") + kAxisNames[axis] + " have " +
                                 std::to_string(inBoxes.lo[axis].size()) + " mins and " +
                                 std::to_string(inBoxes.hi[axis].size()) + " maxes for " +
                                 std::to_string(n) + " ids"};
  }
  if (!inBoxes.groups.empty() && inBoxes.groups.size() != n)
    return ValidationError{0, 0,
                           "groups has " + std::to_string(inBoxes.groups.size()) + " entries for " +
                               std::to_string(n) + " boxes"};
  if (!inBoxes.masks.empty() && inBoxes.masks.size() != n)
    return ValidationError{0, 0,
                           "masks has " + std::to_string(inBoxes.masks.size()) + " entries for " +
                               std::to_string(n) + " boxes"};
  if (n > kMaxBoxes)
    return ValidationError{
        0, 0,
        std::to_string(n) + " boxes exceed the engine's limit of " + std::to_string(kMaxBoxes)};
  if (auto bad = findBadCoordinate(inBoxes)) return bad;
  return findDuplicateId(inBoxes);
}

}  // namespace sap_broadphase
