// The one way the engine's passes over the boxes run on several threads: the items are cut into
// units, and the units are claimed one at a time, from one shared counter, by whichever worker
// of the runner is free, the calling thread among them.
//
// Why units claimed from a counter, and why the caller waits only for claimed units: a worker
// that the operating system has descheduled (another process holds its core) claims nothing
// while it is away, so the others do its share, and the caller returns as soon as every unit
// is done, without waiting for that worker to come back. An OpenMP region cannot give this: its
// closing barrier waits for every team thread, even one that claimed nothing, and under
// OMP_WAIT_POLICY=passive or on a busy machine that thread may not run for a scheduler tick.
// So the runner opens one OpenMP region for its whole life (OpenMP stays the thread provider,
// a long-lived team parked between passes) and hands passes to its threads itself: a pass is
// published in one atomic word (units, workers allowed, next unit to claim), a worker claims
// with a compare-and-swap on that word, and the caller counts finished units. A worker that
// wakes after the last unit was claimed finds nothing to claim and parks again; a worker that
// wakes during a later pass claims that pass's units, which is as good.
//
// Why one runner rather than a schedule clause at each loop: every pass has the same unit rule,
// the same one-unit shortcut (a pass of one unit, or on one thread, runs inline) and a results
// order that does not depend on the threads (per-unit results, combined in unit order); and the
// passes handed to workers can be counted (parallelRegionsOpened) so tests can check that a
// small frame hands none out.
//
// Which runner a pass uses: the engine installs its own for the duration of its calls
// (RunnerScope); a pass started elsewhere (a test calling a kernel, a tool) uses a runner
// shared by the process, one per thread count. A runner serves one caller at a time: a second
// caller that finds it busy runs its pass inline, on its own thread.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
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

/// Workers a pass of inUnits units may use when inThreads are allowed: never more than units.
int teamForUnits(std::size_t inUnits, int inThreads);

/// Units of a pass cut by its thread count: kUnitsPerThread a thread, one on one thread.
int unitsForThreads(int inThreads);

/// Passes the runners of this process have handed to their workers (tests: a small frame
/// hands out none).
uint64_t parallelRegionsOpened();

/// A team of worker threads, parked between passes, that runs passes of units. Worker 0 is the
/// caller of run(); workers 1..threads()-1 are the threads of one OpenMP region held open by a
/// thread the runner owns (their omp_get_thread_num() is their worker index). The threads start
/// with the first pass handed out, so a runner that only ever runs inline costs no thread.
class WorkRunner {
 public:
  /// A runner of inThreads workers in all, the caller included (1: every pass inline).
  explicit WorkRunner(int inThreads);
  ~WorkRunner();
  WorkRunner(const WorkRunner&) = delete;
  WorkRunner& operator=(const WorkRunner&) = delete;

  int threads() const { return threads_; }

  /// Runs inBody(unit, worker) for every unit in [0, inUnits) on up to inTeam workers (worker
  /// in [0, min(inTeam, threads()))), each unit exactly once; returns when every unit has run.
  /// inBody must only write what its unit, or its worker, owns. An exception thrown by a unit
  /// is rethrown here once every claimed unit has finished (the remaining units still run).
  template <class Body>
  void run(std::size_t inUnits, int inTeam, Body&& inBody) {
    using Function = std::remove_reference_t<Body>;
    auto call = [](void* inContext, std::size_t inUnit, int inWorker) {
      (*static_cast<Function*>(inContext))(inUnit, inWorker);
    };
    runErased(inUnits, inTeam, call, const_cast<void*>(static_cast<const void*>(&inBody)));
  }

 private:
  using UnitFunction = void (*)(void*, std::size_t, int);
  void runErased(std::size_t inUnits, int inTeam, UnitFunction inFunction, void* inContext);
  void runPass(std::size_t inUnits, int inTeam, UnitFunction inFunction, void* inContext);
  void startTeam();
  void workerLoop(int inWorker);
  uint64_t claimAndRun(int inWorker);
  bool waitForNewPass(uint64_t inSeen);

  const int threads_;
  // The pass: epoch (16 bits) | workers allowed (8) | units (20) | next unit to claim (20).
  std::atomic<uint64_t> pass_{0};
  std::atomic<UnitFunction> function_{nullptr};  // the pass's unit, stable while it has units
  std::atomic<void*> context_{nullptr};
  std::atomic<std::size_t> finished_{0};  // units of the pass that have run
  std::atomic<bool> stopping_{false};
  std::atomic<int> sleepers_{0};
  std::mutex park_mutex_;
  std::condition_variable park_;
  std::mutex error_mutex_;
  std::exception_ptr error_;
  std::atomic<bool> busy_{false};  // one caller at a time; a second runs its pass inline
  std::thread host_;               // holds the OpenMP region of workers 1..threads_-1
};

namespace detail {
/// True on a thread running a unit of a pass: a pass it starts runs inline.
bool runningAUnit();
}  // namespace detail

/// The worker index of the calling thread in the pass whose unit it runs (its scratch row),
/// 0 outside a pass and on a pass run inline.
int currentWorker();

/// The runner a pass started on this thread uses: the one a RunnerScope installed, else the
/// process's shared runner of inThreads workers.
WorkRunner& currentRunner(int inThreads);

/// The process's runner of inThreads workers, for passes started outside an engine's call.
WorkRunner& sharedRunner(int inThreads);

/// The threads a pass started on this thread may use: the team of the innermost RunnerScope
/// (the frame's threads, decided once by the plan), 1 outside any scope. Passes ask here
/// instead of taking a thread count through their signatures, so nothing between the plan and
/// the runner can decide the threads again.
int passThreads();

/// Installs inRunner as this thread's runner, and inTeam as the threads its passes may use, for
/// the scope's life (the engine, for each call, with the plan's count; inTeam is cut to the
/// runner's workers).
class RunnerScope {
 public:
  explicit RunnerScope(WorkRunner& inRunner) : RunnerScope(inRunner, inRunner.threads()) {}
  RunnerScope(WorkRunner& inRunner, int inTeam);
  ~RunnerScope();
  RunnerScope(const RunnerScope&) = delete;
  RunnerScope& operator=(const RunnerScope&) = delete;

 private:
  WorkRunner* previous_;
  int previous_team_;
};

/// A RunnerScope on the process's shared runner of inThreads workers (tests and tools that call
/// a pass directly, outside an engine).
class ThreadsScope {
 public:
  explicit ThreadsScope(int inThreads) : scope_(sharedRunner(inThreads), inThreads) {}

 private:
  RunnerScope scope_;
};

/// The scope's runner with at most inAtMost of the scope's threads, for the scope's life: a part
/// of the frame's work that uses fewer threads than the frame (a sequential sweep on one, a scan
/// too short to share) narrows the scope instead of taking a count.
class NarrowedScope {
 public:
  explicit NarrowedScope(int inAtMost)
      : scope_(currentRunner(passThreads()), std::max(1, std::min(inAtMost, passThreads()))) {}

 private:
  RunnerScope scope_;
};

/// Runs inBody(unit, worker) for every unit in [0, inUnits) on up to passThreads() workers of
/// this thread's runner (worker < passThreads()); one unit or one thread runs inline, as the
/// calling thread's worker (currentWorker(): 0 unless inside a unit). No pass takes a thread
/// count: the scope holds the one the plan decided.
template <class Body>
void runUnitsOnWorkers(std::size_t inUnits, Body&& inBody) {
  const int threads = passThreads();
  const int team = teamForUnits(inUnits, threads);
  if (team <= 1 || detail::runningAUnit()) {
    const int worker = currentWorker();
    for (std::size_t unit = 0; unit < inUnits; ++unit) inBody(unit, worker);
    return;
  }
  currentRunner(threads).run(inUnits, team, inBody);
}

/// runUnitsOnWorkers for bodies that do not need their worker: inBody(unit).
template <class Body>
void runUnits(std::size_t inUnits, Body&& inBody) {
  runUnitsOnWorkers(inUnits, [&](std::size_t inUnit, int) { inBody(inUnit); });
}

/// runUnits over the units of inUnits, inBody(begin, end) on each unit's item range.
template <class Body>
void runOverItems(const WorkUnits& inUnits, Body&& inBody) {
  runUnits(inUnits.count(),
           [&](std::size_t unit) { inBody(inUnits.begin(unit), inUnits.end(unit)); });
}

/// runOverItems whose units each return a T (inBody(begin, end)), folded in unit order into
/// inInitial by inCombine(T&, const T&): the result does not depend on the thread count, even
/// where the fold is a floating-point sum.
template <class T, class Body, class Combine>
T reduceOverItems(const WorkUnits& inUnits, T inInitial, Body&& inBody, Combine&& inCombine) {
  std::vector<T> partial(inUnits.count(), inInitial);
  runUnits(inUnits.count(), [&](std::size_t unit) {
    partial[unit] = inBody(inUnits.begin(unit), inUnits.end(unit));
  });
  for (const T& part : partial) inCombine(inInitial, part);
  return inInitial;
}

}  // namespace sap_broadphase
