#include "core/work_units.h"

#include <atomic>

namespace sap_broadphase {
namespace {

std::atomic<uint64_t> regions_opened{0};

}  // namespace

int teamForUnits(std::size_t inUnits, int inThreads) {
  if (inUnits <= 1 || inThreads <= 1) return 1;
  return static_cast<int>(std::min<std::size_t>(inUnits, static_cast<std::size_t>(inThreads)));
}

int unitsForThreads(int inThreads) {
  return inThreads <= 1 ? 1 : kUnitsPerThread * inThreads;
}

int openTeam(std::size_t inUnits, int inThreads) {
  const int team = teamForUnits(inUnits, inThreads);
  if (team > 1) detail::countParallelRegion();
  return team;
}

uint64_t parallelRegionsOpened() {
  return regions_opened.load(std::memory_order_relaxed);
}

namespace detail {
void countParallelRegion() {
  regions_opened.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace detail

}  // namespace sap_broadphase
