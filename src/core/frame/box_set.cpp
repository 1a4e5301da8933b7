#include "sap_broadphase/core/box_set.h"

#include <cstddef>
#include <optional>
#include <string>
#include <utility>

namespace sap_broadphase {
namespace {

// The filters of a box about to be added (before its id): earlier boxes get the defaults.
void addFilters(BoxSet& ioBoxes, uint32_t inGroup, uint32_t inMask) {
  ioBoxes.groups.resize(ioBoxes.size(), kDefaultGroup);
  ioBoxes.masks.resize(ioBoxes.size(), kDefaultMask);
  ioBoxes.groups.push_back(inGroup);
  ioBoxes.masks.push_back(inMask);
}

ValidationError shapeError(std::string inReason) {
  return ValidationError{0, 0, std::move(inReason)};
}

// "1 box", "2 boxes": inCount and the noun that agrees with it.
std::string countOf(std::size_t inCount, const char* inOne, const char* inMany) {
  return std::to_string(inCount) + " " + (inCount == 1 ? inOne : inMany);
}

// Why the arrays of inBoxes cannot form a span, if they cannot.
std::optional<ValidationError> shapeProblem(const BoxSet& inBoxes) {
  const std::size_t n = inBoxes.size();
  if (inBoxes.bounds.size() != kBoundsPerBox * n)
    return shapeError("bounds has " + countOf(inBoxes.bounds.size(), "value", "values") + " for " +
                      countOf(n, "id", "ids") + " (6 a box)");
  if (!inBoxes.groups.empty() && inBoxes.groups.size() != n)
    return shapeError("groups has " + countOf(inBoxes.groups.size(), "entry", "entries") + " for " +
                      countOf(n, "box", "boxes"));
  if (!inBoxes.masks.empty() && inBoxes.masks.size() != n)
    return shapeError("masks has " + countOf(inBoxes.masks.size(), "entry", "entries") + " for " +
                      countOf(n, "box", "boxes"));
  return std::nullopt;
}

}  // namespace

void BoxSet::clear() {
  ids.clear();
  bounds.clear();
  groups.clear();
  masks.clear();
}

void BoxSet::reserve(std::size_t inCount) {
  ids.reserve(inCount);
  bounds.reserve(kBoundsPerBox * inCount);
}

void BoxSet::add(uint32_t inId, const double inMin[3], const double inMax[3]) {
  ids.push_back(inId);
  bounds.insert(bounds.end(), inMin, inMin + 3);
  bounds.insert(bounds.end(), inMax, inMax + 3);
  if (!groups.empty()) groups.push_back(kDefaultGroup);
  if (!masks.empty()) masks.push_back(kDefaultMask);
}

void BoxSet::add(uint32_t inId, const double inMin[3], const double inMax[3], uint32_t inGroup,
                 uint32_t inMask) {
  addFilters(*this, inGroup, inMask);
  ids.push_back(inId);
  bounds.insert(bounds.end(), inMin, inMin + 3);
  bounds.insert(bounds.end(), inMax, inMax + 3);
}

BoxSpan BoxSet::span() const {
  if (auto problem = shapeProblem(*this)) throw InvalidBoxes(std::move(*problem));
  BoxSpan span;
  span.count = size();
  span.bounds = bounds.data();
  span.ids = ids.data();
  span.groups = groups.empty() ? nullptr : groups.data();
  span.masks = masks.empty() ? nullptr : masks.data();
  return span;
}

std::string ValidationError::message() const {
  return "box " + std::to_string(index) + " (id " + std::to_string(id) + "): " + reason;
}
std::optional<ValidationError> validate(const BoxSet& inBoxes) {
  if (auto problem = shapeProblem(inBoxes)) return problem;
  return validate(inBoxes.span());
}

}  // namespace sap_broadphase
