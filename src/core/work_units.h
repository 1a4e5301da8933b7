// The one way the engine's passes over the boxes run on several threads: the items are cut into
// units of a fixed size, more units than threads on large frames, and the units are claimed one
// at a time by whichever thread of the team is free, the calling thread among them.
//
// Why units rather than one slice per thread: a thread the operating system has descheduled
// (another process holds its core) claims nothing while it is away, so the others do its share
// instead of waiting for it to come back and do it; a static slice would stall the whole frame
// for that long. The region's closing barrier still waits for every team thread to arrive, so
// what bounds such a stall is the time until a descheduled thread runs at all (to find no unit
// left), not the work it was given: hence the second rule, that a pass of one unit opens no
// parallel region. A frame of up to kUnitBoxes boxes never waits for another core, whatever
// the configured thread count and OMP_WAIT_POLICY.
//
// Why one runner over OpenMP rather than tasks or a schedule clause at each loop: every pass
// then has the same unit rule, the same one-unit shortcut and a results order that does not
// depend on the threads (per-unit results, combined in unit order), and the regions it opens
// can be counted (parallelRegionsOpened) so tests can check that a small frame opens none.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sap_broadphase {

/// Boxes of one unit of a pass over the boxes (a few tens of microseconds of streaming work per
/// unit on one core: large enough that handing a unit out costs little against it, small
/// enough that a 2^17-box frame has 8 units a thread on 2 cores and a 2^20 one 64).
constexpr std::size_t kUnitBoxes = std::size_t{1} << 14;

/// inItems items cut into units of inUnitItems (the last one shorter).
struct WorkUnits {
  std::size_t items = 0;
  std::size_t unit_items = kUnitBoxes;

  std::size_t count() const { return (items + unit_items - 1) / unit_items; }
  std::size_t begin(std::size_t inUnit) const { return inUnit * unit_items; }
  std::size_t end(std::size_t inUnit) const { return std::min(items, begin(inUnit) + unit_items); }
};

/// Units a thread of a pass cut by its thread count rather than by size (the sweep's slices of
/// the order, whose seams cost a little each): enough that the others can take a descheduled
/// thread's share.
constexpr int kUnitsPerThread = 4;

/// Threads a pass of inUnits units runs on when inThreads are allowed: never more than units.
int teamForUnits(std::size_t inUnits, int inThreads);

/// Units of a pass cut by its thread count: kUnitsPerThread a thread, one on one thread.
int unitsForThreads(int inThreads);

/// The team of a region of several phases (barriers between them) whose loops hand out inUnits
/// units with `omp for schedule(dynamic, 1)`; counted as opened when above one thread.
int openTeam(std::size_t inUnits, int inThreads);

/// Multi-thread parallel regions the runner has opened in this process (tests: a small frame
/// opens none).
uint64_t parallelRegionsOpened();

namespace detail {
void countParallelRegion();
}  // namespace detail

/// Runs inBody(unit) for every unit in [0, inUnits), claimed dynamically by up to inThreads
/// threads, the calling thread among them; one unit or one thread runs inline (no region).
/// inBody must only write what its unit owns.
template <class Body>
void runUnits(std::size_t inUnits, int inThreads, Body&& inBody) {
  const int team = teamForUnits(inUnits, inThreads);
  if (team <= 1) {
    for (std::size_t unit = 0; unit < inUnits; ++unit) inBody(unit);
    return;
  }
  detail::countParallelRegion();
  const auto units = static_cast<std::ptrdiff_t>(inUnits);
#pragma omp parallel for num_threads(team) schedule(dynamic, 1)
  for (std::ptrdiff_t unit = 0; unit < units; ++unit) inBody(static_cast<std::size_t>(unit));
}

/// runUnits over the units of inUnits, inBody(begin, end) on each unit's item range.
template <class Body>
void runOverItems(const WorkUnits& inUnits, int inThreads, Body&& inBody) {
  runUnits(inUnits.count(), inThreads,
           [&](std::size_t unit) { inBody(inUnits.begin(unit), inUnits.end(unit)); });
}

/// runOverItems whose units each return a T (inBody(begin, end)), folded in unit order into
/// inInitial by inCombine(T&, const T&): the result does not depend on the thread count, even
/// where the fold is a floating-point sum.
template <class T, class Body, class Combine>
T reduceOverItems(const WorkUnits& inUnits, int inThreads, T inInitial, Body&& inBody,
                  Combine&& inCombine) {
  std::vector<T> partial(inUnits.count(), inInitial);
  runUnits(inUnits.count(), inThreads, [&](std::size_t unit) {
    partial[unit] = inBody(inUnits.begin(unit), inUnits.end(unit));
  });
  for (const T& part : partial) inCombine(inInitial, part);
  return inInitial;
}

}  // namespace sap_broadphase
