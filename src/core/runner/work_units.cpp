#include "core/runner/work_units.h"

#include <omp.h>

#include <chrono>
#include <map>
#include <memory>

#include "core/assert.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace sap_broadphase {
namespace {

std::atomic<uint64_t> regions_opened{0};

// The pass word's fields (work_units.h, WorkRunner::pass_).
constexpr int kNextBits = 20;
constexpr int kUnitsBits = 20;
constexpr int kTeamBits = 8;
constexpr uint64_t kNextMask = (uint64_t{1} << kNextBits) - 1;
constexpr uint64_t kUnitsMask = (uint64_t{1} << kUnitsBits) - 1;
constexpr uint64_t kTeamMask = (uint64_t{1} << kTeamBits) - 1;
constexpr int kUnitsShift = kNextBits;
constexpr int kTeamShift = kUnitsShift + kUnitsBits;
constexpr int kEpochShift = kTeamShift + kTeamBits;
/// The most units one published pass holds: a larger pass is published in parts.
constexpr std::size_t kMaxPassUnits = kUnitsMask;
/// The most workers a runner has (the team field's range).
constexpr int kMaxWorkers = static_cast<int>(kTeamMask);

uint64_t nextOf(uint64_t inPass) {
  return inPass & kNextMask;
}
uint64_t unitsOf(uint64_t inPass) {
  return (inPass >> kUnitsShift) & kUnitsMask;
}
int teamOf(uint64_t inPass) {
  return static_cast<int>((inPass >> kTeamShift) & kTeamMask);
}
uint64_t epochOf(uint64_t inPass) {
  return inPass >> kEpochShift;
}

// How long a worker that has run out of units keeps looking for the next pass before it
// parks: a frame's passes follow each other within microseconds, and waking a parked thread
// costs tens of microseconds; a worker spinning longer would only take a core from others.
constexpr auto kSpinBeforeParking = std::chrono::microseconds(50);

inline void relaxCpu() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

thread_local WorkRunner* installed_runner = nullptr;
thread_local int installed_team = 1;       // the threads of the innermost RunnerScope
thread_local bool running_a_unit = false;  // a pass started inside a unit runs inline
thread_local int current_worker = 0;

// Marks the calling thread as worker inWorker running a unit, for the guard's life.
struct UnitGuard {
  explicit UnitGuard(int inWorker) {
    running_a_unit = true;
    current_worker = inWorker;
  }
  ~UnitGuard() {
    running_a_unit = false;
    current_worker = 0;
  }
};

}  // namespace

int teamForUnits(std::size_t inUnits, int inThreads) {
  if (inUnits <= 1 || inThreads <= 1) return 1;
  return static_cast<int>(std::min<std::size_t>(inUnits, static_cast<std::size_t>(inThreads)));
}

int unitsForThreads(int inThreads) {
  return inThreads <= 1 ? 1 : kUnitsPerThread * inThreads;
}

namespace detail {
bool runningAUnit() {
  return running_a_unit;
}
}  // namespace detail

int currentWorker() {
  return current_worker;
}

uint64_t parallelRegionsOpened() {
  return regions_opened.load(std::memory_order_relaxed);
}

WorkRunner::WorkRunner(int inThreads) : threads_(std::clamp(inThreads, 1, kMaxWorkers)) {}

WorkRunner::~WorkRunner() {
  if (!host_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(park_mutex_);
    stopping_.store(true, std::memory_order_seq_cst);
  }
  park_.notify_all();
  host_.join();
}

// The host thread opens the region and parks as its thread 0 (the caller of run() is worker
// 0); its threads 1..threads_-1 are the workers. OpenMP may give fewer threads than asked: the
// missing workers' units are claimed by the others.
void WorkRunner::startTeam() {
  host_ = std::thread([this] {
#pragma omp parallel num_threads(threads_)
    {
      const int worker = omp_get_thread_num();
      if (worker > 0) {
        workerLoop(worker);
      } else {
        std::unique_lock<std::mutex> lock(park_mutex_);
        park_.wait(lock, [this] { return stopping_.load(std::memory_order_seq_cst); });
      }
    }
  });
}

void WorkRunner::runErased(std::size_t inUnits, int inTeam, UnitFunction inFunction,
                           void* inContext) {
  const int team = std::min(inTeam, threads_);
  if (team <= 1 || inUnits <= 1 || running_a_unit || busy_.exchange(true)) {
    for (std::size_t unit = 0; unit < inUnits; ++unit) inFunction(inContext, unit, current_worker);
    return;
  }
  struct Release {
    std::atomic<bool>& busy;
    ~Release() { busy.store(false, std::memory_order_release); }
  } release{busy_};
  if (!host_.joinable()) startTeam();
  for (std::size_t first = 0; first < inUnits; first += kMaxPassUnits) {
    const std::size_t units = std::min(kMaxPassUnits, inUnits - first);
    if (first == 0) {
      runPass(units, team, inFunction, inContext);
      continue;
    }
    struct Offset {
      UnitFunction function;
      void* context;
      std::size_t first;
    } offset{inFunction, inContext, first};
    runPass(
        units, team,
        [](void* inOffset, std::size_t inUnit, int inWorker) {
          const Offset& part = *static_cast<Offset*>(inOffset);
          part.function(part.context, part.first + inUnit, inWorker);
        },
        &offset);
  }
  std::exception_ptr error;
  {
    std::lock_guard<std::mutex> lock(error_mutex_);
    std::swap(error, error_);
  }
  if (error) std::rethrow_exception(error);
}

// Publishes the pass, claims units as worker 0 until none is left, then waits for the units
// other workers claimed: never for a worker that claimed nothing.
void WorkRunner::runPass(std::size_t inUnits, int inTeam, UnitFunction inFunction,
                         void* inContext) {
  SAP_ASSERT(inUnits <= kMaxPassUnits && inTeam <= kMaxWorkers, "a pass beyond its word");
  regions_opened.fetch_add(1, std::memory_order_relaxed);
  function_.store(inFunction, std::memory_order_relaxed);
  context_.store(inContext, std::memory_order_relaxed);
  finished_.store(0, std::memory_order_relaxed);
  const uint64_t epoch = epochOf(pass_.load(std::memory_order_relaxed)) + 1;
  const uint64_t pass = (epoch << kEpochShift) | (uint64_t(inTeam) << kTeamShift) |
                        (uint64_t(inUnits) << kUnitsShift);
  pass_.store(pass, std::memory_order_seq_cst);  // releases the fields above
  if (sleepers_.load(std::memory_order_seq_cst) > 0) {
    std::lock_guard<std::mutex> lock(park_mutex_);
    park_.notify_all();
  }
  claimAndRun(0);
  int spins = 0;
  while (finished_.load(std::memory_order_acquire) < inUnits) {
    // Only workers that claimed a unit are waited for, and they are running it.
    if (++spins < 1024)
      relaxCpu();
    else
      std::this_thread::yield();
  }
}

// Claims units of the pass in force while there are any this worker may take. A claim is a
// compare-and-swap of the whole pass word, so a claim that succeeds took an unclaimed unit of
// the pass now published (whatever pass this worker last saw), whose unit function stays in
// place until that unit has run.
uint64_t WorkRunner::claimAndRun(int inWorker) {
  uint64_t pass = pass_.load(std::memory_order_acquire);
  for (;;) {
    if (inWorker >= teamOf(pass) || nextOf(pass) >= unitsOf(pass)) return pass;
    if (!pass_.compare_exchange_weak(pass, pass + 1, std::memory_order_acq_rel,
                                     std::memory_order_acquire))
      continue;
    const std::size_t unit = nextOf(pass);
    try {
      const UnitGuard guard(inWorker);
      function_.load(std::memory_order_relaxed)(context_.load(std::memory_order_relaxed), unit,
                                                inWorker);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex_);
      if (!error_) error_ = std::current_exception();
    }
    finished_.fetch_add(1, std::memory_order_acq_rel);
    pass = pass_.load(std::memory_order_acquire);
  }
}

void WorkRunner::workerLoop(int inWorker) {
  // Waits for a pass other than the one whose units ran out (or that this worker may not
  // join): one published meanwhile is joined at once.
  for (;;) {
    if (!waitForNewPass(claimAndRun(inWorker))) return;
  }
}

// Waits until a pass other than inSeen is published (true) or the runner stops (false):
// spinning a moment, then parked.
bool WorkRunner::waitForNewPass(uint64_t inSeen) {
  auto newPass = [&] { return epochOf(pass_.load(std::memory_order_seq_cst)) != epochOf(inSeen); };
  const auto give_up = std::chrono::steady_clock::now() + kSpinBeforeParking;
  for (int spin = 1;; ++spin) {
    if (newPass()) return true;
    if (stopping_.load(std::memory_order_relaxed)) return false;
    if (spin % 64 == 0 && std::chrono::steady_clock::now() > give_up) break;
    relaxCpu();
  }
  std::unique_lock<std::mutex> lock(park_mutex_);
  sleepers_.fetch_add(1, std::memory_order_seq_cst);
  park_.wait(lock, [&] { return newPass() || stopping_.load(std::memory_order_seq_cst); });
  sleepers_.fetch_sub(1, std::memory_order_seq_cst);
  return !stopping_.load(std::memory_order_seq_cst);
}

WorkRunner& currentRunner(int inThreads) {
  if (installed_runner != nullptr) return *installed_runner;
  return sharedRunner(inThreads);
}

WorkRunner& sharedRunner(int inThreads) {
  // One runner a thread count, for passes started outside an engine's call; never destroyed
  // (its parked threads end with the process).
  static std::mutex shared_mutex;
  static auto* shared = new std::map<int, std::unique_ptr<WorkRunner>>();
  std::lock_guard<std::mutex> lock(shared_mutex);
  std::unique_ptr<WorkRunner>& runner = (*shared)[inThreads];
  if (!runner) runner = std::make_unique<WorkRunner>(inThreads);
  return *runner;
}

int passThreads() {
  return installed_team;
}

RunnerScope::RunnerScope(WorkRunner& inRunner, int inTeam)
    : previous_(installed_runner), previous_team_(installed_team) {
  SAP_ASSERT(inTeam >= 1, "a scope's team has at least one thread");
  installed_runner = &inRunner;
  installed_team = std::max(1, std::min(inTeam, inRunner.threads()));
}

RunnerScope::~RunnerScope() {
  installed_runner = previous_;
  installed_team = previous_team_;
}

}  // namespace sap_broadphase
