#include "core/static_split.h"

#include <algorithm>
#include <cstring>

#include "core/tuning.h"

namespace sap_broadphase {

void StaticSplit::clear() {
  active_ = false;
  built_size_ = 0;
  left_ = 0;
}

bool StaticSplit::prepare(const BoxSet& inBoxes, const std::vector<uint8_t>& inUnchanged,
                          int inThreads) {
  const std::size_t n = inBoxes.size();
  if (n < kMinIndexedBoxes || inUnchanged.size() != n) {
    clear();
    return false;
  }
  if (active_ && indexed_.size() != n) clear();
  if (active_) {
    for (std::size_t i = 0; i < n; ++i) {
      if (indexed_[i] && !inUnchanged[i]) {
        index_.remove(inBoxes.ids[i]);
        indexed_[i] = 0;
        ++left_;
      }
    }
  }
  std::size_t resting = 0;  // unchanged boxes of indexable classes not in the index yet
  if (active_)
    for (std::size_t i = 0; i < n; ++i)
      resting += inUnchanged[i] && !indexed_[i] && inChosenClass(inBoxes, i);
  const std::size_t quarter = built_size_ / 4;
  if (!active_ || left_ > quarter || resting > std::max(kMinIndexedBoxes, quarter)) {
    if (!rebuild(inBoxes, inUnchanged, inThreads)) {
      clear();
      return false;
    }
  }
  collectMoving(inBoxes);
  return true;
}

// Picks group/mask classes of unchanged boxes, largest first, such that no box of a chosen
// class can pair with a box of the same or another chosen class.
bool StaticSplit::chooseClasses(const BoxSet& inBoxes, const std::vector<uint8_t>& inUnchanged) {
  std::vector<FilterClass> classes;
  std::size_t last = 0;
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    if (!inUnchanged[i]) continue;
    const uint32_t group = inBoxes.group(i), mask = inBoxes.mask(i);
    if (last >= classes.size() || classes[last].group != group || classes[last].mask != mask) {
      last = 0;
      while (last < classes.size() && (classes[last].group != group || classes[last].mask != mask))
        ++last;
      if (last == classes.size()) {
        if (classes.size() == tuning::kMaxFilterClasses) return false;
        classes.push_back({group, mask, 0});
      }
    }
    ++classes[last].boxes;
  }
  std::sort(classes.begin(), classes.end(),
            [](const FilterClass& inA, const FilterClass& inB) { return inA.boxes > inB.boxes; });
  const auto cannotPair = [](const FilterClass& inA, const FilterClass& inB) {
    return !groupsMayPair(inA.group, inA.mask, inB.group, inB.mask);
  };
  chosen_classes_.clear();
  for (const FilterClass& candidate : classes) {
    bool compatible = cannotPair(candidate, candidate);
    for (const FilterClass& chosen : chosen_classes_)
      compatible = compatible && cannotPair(candidate, chosen);
    if (compatible) chosen_classes_.push_back(candidate);
  }
  return !chosen_classes_.empty();
}

bool StaticSplit::inChosenClass(const BoxSet& inBoxes, std::size_t inBox) const {
  for (const FilterClass& chosen : chosen_classes_)
    if (chosen.group == inBoxes.group(inBox) && chosen.mask == inBoxes.mask(inBox)) return true;
  return false;
}

bool StaticSplit::rebuild(const BoxSet& inBoxes, const std::vector<uint8_t>& inUnchanged,
                          int inThreads) {
  if (!chooseClasses(inBoxes, inUnchanged)) return false;
  const std::size_t n = inBoxes.size();
  members_.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (inUnchanged[i] && inChosenClass(inBoxes, i)) members_.push_back(static_cast<uint32_t>(i));
  if (members_.size() < std::max(kMinIndexedBoxes, n / 4)) return false;
  index_.build(inBoxes, members_, inThreads);
  indexed_.assign(n, 0);
  for (uint32_t i : members_) indexed_[i] = 1;
  built_size_ = members_.size();
  left_ = 0;
  active_ = true;
  return true;
}

void StaticSplit::collectMoving(const BoxSet& inBoxes) {
  moving_indexes_.clear();
  for (std::size_t i = 0; i < inBoxes.size(); ++i)
    if (!indexed_[i]) moving_indexes_.push_back(static_cast<uint32_t>(i));
  moving_.clear();
  moving_.reserve(moving_indexes_.size());
  const bool filtered = inBoxes.hasFilters();
  for (uint32_t i : moving_indexes_) {
    const double low[3] = {inBoxes.lo[0][i], inBoxes.lo[1][i], inBoxes.lo[2][i]};
    const double high[3] = {inBoxes.hi[0][i], inBoxes.hi[1][i], inBoxes.hi[2][i]};
    if (filtered)
      moving_.add(inBoxes.ids[i], low, high, inBoxes.group(i), inBoxes.mask(i));
    else
      moving_.add(inBoxes.ids[i], low, high);
  }
}

void StaticSplit::crossPairs(const BoxSet& inBoxes, int inThreads, PairList& ioPairs) const {
  index_.queryAll(inBoxes, moving_indexes_, inThreads, ioPairs);
}

}  // namespace sap_broadphase
