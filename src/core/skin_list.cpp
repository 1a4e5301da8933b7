#include "core/skin_list.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace sap_broadphase {
namespace {

template <typename T>
bool sameElements(const std::vector<T>& inA, const std::vector<T>& inB) {
  return inA.size() == inB.size() &&
         (inA.empty() || std::memcmp(inA.data(), inB.data(), inA.size() * sizeof(T)) == 0);
}

}  // namespace

bool SkinList::covers(const BoxSet& inBoxes, int inThreads) const {
  if (!valid_ || !sameElements(reference_.ids, inBoxes.ids) ||
      !sameElements(reference_.groups, inBoxes.groups) ||
      !sameElements(reference_.masks, inBoxes.masks))
    return false;
  const std::size_t n = inBoxes.size();
  bool inside = true;
#pragma omp parallel for num_threads(inThreads) reduction(&& : inside) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    for (int axis = 0; axis < 3; ++axis)
      inside = inside && inBoxes.lo[axis][i] >= reference_.lo[axis][i] &&
               inBoxes.hi[axis][i] <= reference_.hi[axis][i];
  }
  return inside;
}

void SkinList::inflate(const BoxSet& inBoxes, double inSkin, BoxSet& outInflated) {
  const double margin = inSkin / 2;
  const double infinity = std::numeric_limits<double>::infinity();
  outInflated.ids = inBoxes.ids;
  outInflated.groups = inBoxes.groups;
  outInflated.masks = inBoxes.masks;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t n = inBoxes.size();
    outInflated.lo[axis].resize(n);
    outInflated.hi[axis].resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      // One step further out than the rounded sum: the inflated box contains the exact one.
      outInflated.lo[axis][i] = std::nextafter(inBoxes.lo[axis][i] - margin, -infinity);
      outInflated.hi[axis][i] = std::nextafter(inBoxes.hi[axis][i] + margin, infinity);
    }
  }
  reference_ = outInflated;
  valid_ = false;  // until adopt() receives this sweep's candidates
}

void SkinList::adopt(const BoxSet& inBoxes, const PairList& inCandidates) {
  std::unordered_map<uint32_t, uint32_t> index_of_id;
  index_of_id.reserve(inBoxes.size());
  for (std::size_t i = 0; i < inBoxes.size(); ++i)
    index_of_id.emplace(inBoxes.ids[i], static_cast<uint32_t>(i));
  candidate_indexes_.resize(inCandidates.size());
  for (std::size_t k = 0; k < inCandidates.size(); ++k)
    candidate_indexes_[k] = {index_of_id[inCandidates[k].a], index_of_id[inCandidates[k].b]};
  valid_ = true;
}

void SkinList::collect(const BoxSet& inBoxes, int inThreads, PairList& outPairs) {
  const std::size_t count = candidate_indexes_.size();
  per_thread_.resize(std::max(1, inThreads));
  for (PairList& part : per_thread_) part.clear();  // a smaller team leaves lists untouched
    // Contiguous slices in canonical order, concatenated in order: the result stays canonical.
#pragma omp parallel num_threads(inThreads)
  {
    const int thread = omp_get_thread_num();
    const int team = omp_get_num_threads();
    PairList& mine = per_thread_[thread];
    for (std::size_t k = count * thread / team; k < count * (thread + 1) / team; ++k) {
      const auto [a, b] = candidate_indexes_[k];
      if (boxesOverlap(inBoxes, a, b)) mine.push_back(makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
    }
  }
  outPairs.clear();
  for (const PairList& part : per_thread_)
    outPairs.insert(outPairs.end(), part.begin(), part.end());
}

}  // namespace sap_broadphase
