// The work-unit runner (work_units.h): every unit runs exactly once at any thread count, folds
// do not depend on the threads, a pass of one unit opens no parallel region, and a frame small
// enough for one unit per pass never waits for a second thread, whatever the configured count.
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <time.h>

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/runner/work_units.h"
#include "core/sweep/axis_spread.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

TEST(WorkUnits, EveryItemRunsOnceAtAnyThreadCountAndUnitSize) {
  for (std::size_t items : {0u, 1u, 7u, 64u, 1000u}) {
    for (std::size_t unit_items : {1u, 3u, 64u, 4096u}) {
      for (int threads = 1; threads <= 4; ++threads) {
        std::vector<std::atomic<int>> runs(items);
        const ThreadsScope scope(threads);
        runOverItems(WorkUnits{items, unit_items}, [&](std::size_t inBegin, std::size_t inEnd) {
          for (std::size_t i = inBegin; i < inEnd; ++i) runs[i].fetch_add(1);
        });
        for (std::size_t i = 0; i < items; ++i)
          ASSERT_EQ(runs[i].load(), 1) << "item " << i << " of " << items << ", units of "
                                       << unit_items << ", " << threads << " threads";
      }
    }
  }
}

TEST(WorkUnits, FoldsInUnitOrderWhateverTheThreads) {
  // A floating-point sum whose value depends on how its additions are grouped: per-unit sums
  // folded in unit order give one value for every thread count.
  std::vector<double> values(10000);
  test_support::TestRandom random(7);
  for (double& value : values) value = random.between(-1.0, 1.0) * 1e10 + random.unit();
  const WorkUnits units{values.size(), 97};
  auto sumOf = [&](int inThreads) {
    const ThreadsScope scope(inThreads);
    return reduceOverItems(
        units, 0.0,
        [&](std::size_t inBegin, std::size_t inEnd) {
          double sum = 0.0;
          for (std::size_t i = inBegin; i < inEnd; ++i) sum += values[i];
          return sum;
        },
        [](double& ioTotal, double inUnit) { ioTotal += inUnit; });
  };
  const double one_thread = sumOf(1);
  for (int threads = 2; threads <= 4; ++threads)
    for (int repeat = 0; repeat < 20; ++repeat) ASSERT_EQ(sumOf(threads), one_thread) << threads;
}

TEST(WorkUnits, OneUnitOrOneThreadOpensNoRegion) {
  const uint64_t before = parallelRegionsOpened();
  int ran = 0;
  {
    const ThreadsScope four_threads(4);
    runUnits(1, [&](std::size_t) { ++ran; });
  }
  runUnits(5, [&](std::size_t) { ++ran; });  // outside any scope: one thread
  EXPECT_EQ(ran, 6);
  EXPECT_EQ(parallelRegionsOpened(), before);
  std::atomic<int> parallel_ran{0};
  const ThreadsScope two_threads(2);
  runUnits(8, [&](std::size_t) { parallel_ran.fetch_add(1); });
  EXPECT_EQ(parallel_ran.load(), 8);
  EXPECT_EQ(parallelRegionsOpened(), before + 1);
}

TEST(WorkUnits, TheSpreadIsTheSameOnAnyThreadCount) {
  const BoxColumns boxes =
      columnsOf(test_support::randomBoxes(5 * kUnitBoxes + 123, 1000.0, 3.0, 11));
  for (int axis = 0; axis < 3; ++axis) {
    const AxisSpread one = measureAxisSpread(boxes, axis);
    for (int threads = 2; threads <= 4; ++threads) {
      const ThreadsScope scope(threads);
      const AxisSpread many = measureAxisSpread(boxes, axis);
      EXPECT_EQ(many.lowest, one.lowest);
      EXPECT_EQ(many.highest, one.highest);
      EXPECT_EQ(many.extent_sum, one.extent_sum) << "axis " << axis << ", " << threads;
      EXPECT_EQ(many.finite_boxes, one.finite_boxes);
    }
  }
}

// A small frame on an engine allowed four threads (and on the default, all cores): its plan
// runs on one thread, the kernel's or its kept candidates', and no pass of the frame (history,
// spread, copies) opens a parallel region, so no other core's availability can delay it. A large
// frame does open regions (the count is not stuck at zero).
TEST(WorkUnits, SmallFramesOpenNoParallelRegion) {
  for (int threads : {0, 2, 4}) {
    SceneConfig scene = test_support::movingScene(SceneKind::kUniform, 5, 4096, 0.35, 12);
    scene.speed = 0.01;
    SceneSimulator simulator(scene);
    BroadphaseConfig config;
    config.threads = threads;
    Broadphase engine(config);
    for (int frame = 0; frame < 12; ++frame) {
      if (frame > 0) simulator.step();
      const std::string label =
          "threads " + std::to_string(threads) + ", frame " + std::to_string(frame);
      const uint64_t before = parallelRegionsOpened();
      const PairList& pairs = engine.update(simulator.boxes());
      EXPECT_EQ(parallelRegionsOpened(), before) << label;
      EXPECT_TRUE(engine.stats().path == FramePath::kSmallFrame ||
                  engine.stats().path == FramePath::kSkin)
          << label << ": " << framePathName(engine.stats().path);
      EXPECT_EQ(engine.stats().threads, 1) << label;
      EXPECT_TRUE(test_support::samePairs(bruteForcePairs(simulator.boxes()), pairs)) << label;
    }
  }
  BroadphaseConfig config;
  config.threads = 4;
  config.method = Method::kParallel;
  Broadphase engine(config);
  const uint64_t before = parallelRegionsOpened();
  engine.update(test_support::randomBoxes(8 * kUnitBoxes, 1000.0, 3.0, 3));
  EXPECT_GT(parallelRegionsOpened(), before);
}

// Simulates a worker that another process's thread has taken the core from: a signal handler
// that holds the thread it interrupts until released (only lock-free atomics and nanosleep,
// which are async-signal-safe, inside it).
std::atomic<bool> held_thread_entered{false};
std::atomic<bool> release_held_thread{false};

void holdThread(int) {
  held_thread_entered.store(true);
  const timespec pause{0, 100000};
  while (!release_held_thread.load()) nanosleep(&pause, nullptr);
}

// The caller of a pass waits for the units claimed, never for a worker that claimed none: with
// worker 1 held (as if descheduled), a pass of many units completes on the caller alone. An
// OpenMP region's closing barrier would wait for the held thread: this test would hang.
TEST(WorkRunner, NeverWaitsForAWorkerThatClaimedNothing) {
  WorkRunner runner(2);
  // Rendezvous: unit 0 (whoever claims it first) waits until the other worker holds unit 1, so
  // worker 1 has surely run a unit and said which thread it is.
  std::atomic<int> claimed{0};
  std::atomic<bool> have_worker_thread{false};
  pthread_t worker_thread{};
  runner.run(2, 2, [&](std::size_t, int inWorker) {
    if (inWorker == 1) {
      worker_thread = pthread_self();
      have_worker_thread.store(true);
    }
    claimed.fetch_add(1);
    while (claimed.load() < 2) std::this_thread::yield();
  });
  ASSERT_TRUE(have_worker_thread.load());

  struct sigaction action {};
  action.sa_handler = holdThread;
  sigemptyset(&action.sa_mask);
  struct sigaction previous {};
  ASSERT_EQ(sigaction(SIGUSR1, &action, &previous), 0);
  release_held_thread.store(false);
  held_thread_entered.store(false);
  ASSERT_EQ(pthread_kill(worker_thread, SIGUSR1), 0);
  while (!held_thread_entered.load()) std::this_thread::yield();

  constexpr std::size_t kUnits = 1000;
  std::vector<std::atomic<int>> runs(kUnits);
  std::atomic<int> by_held_worker{0};
  runner.run(kUnits, 2, [&](std::size_t inUnit, int inWorker) {
    runs[inUnit].fetch_add(1);
    if (inWorker != 0) by_held_worker.fetch_add(1);
  });
  for (std::size_t unit = 0; unit < kUnits; ++unit) ASSERT_EQ(runs[unit].load(), 1) << unit;
  EXPECT_EQ(by_held_worker.load(), 0) << "a held worker ran a unit";

  release_held_thread.store(true);
  // Once back, the worker takes part in passes again and every unit still runs once.
  std::vector<std::atomic<int>> again(kUnits);
  runner.run(kUnits, 2, [&](std::size_t inUnit, int) { again[inUnit].fetch_add(1); });
  for (std::size_t unit = 0; unit < kUnits; ++unit) ASSERT_EQ(again[unit].load(), 1) << unit;
  ASSERT_EQ(sigaction(SIGUSR1, &previous, nullptr), 0);
}

TEST(WorkRunner, WorkersStayWithinTheTeamAndTheRunner) {
  WorkRunner runner(3);
  for (int team = 1; team <= 5; ++team) {
    std::atomic<int> highest{0};
    std::atomic<int> units_run{0};
    runner.run(64, team, [&](std::size_t, int inWorker) {
      int seen = highest.load();
      while (inWorker > seen && !highest.compare_exchange_weak(seen, inWorker)) {
      }
      units_run.fetch_add(1);
    });
    EXPECT_EQ(units_run.load(), 64) << "team " << team;
    EXPECT_LT(highest.load(), std::min(team, runner.threads())) << "team " << team;
  }
}

TEST(WorkRunner, AUnitsExceptionReachesTheCallerAfterEveryUnitRan) {
  WorkRunner runner(2);
  std::atomic<int> units_run{0};
  EXPECT_THROW(runner.run(16, 2,
                          [&](std::size_t inUnit, int) {
                            units_run.fetch_add(1);
                            if (inUnit == 5) throw std::runtime_error("unit 5");
                          }),
               std::runtime_error);
  EXPECT_EQ(units_run.load(), 16);
  std::atomic<int> after{0};
  runner.run(16, 2, [&](std::size_t, int) { after.fetch_add(1); });
  EXPECT_EQ(after.load(), 16);
}

// A pass started inside a unit runs inline on the unit's thread (no second team, no deadlock
// on the runner the outer pass holds).
TEST(WorkRunner, APassInsideAUnitRunsInline) {
  WorkRunner runner(2);
  const RunnerScope scope(runner);
  std::vector<std::atomic<int>> runs(8 * 8);
  runner.run(8, 2, [&](std::size_t inOuter, int) {
    const RunnerScope two(runner, 2);  // two threads allowed, and still inline
    runUnits(8, [&](std::size_t inInner) { runs[inOuter * 8 + inInner].fetch_add(1); });
  });
  for (std::size_t k = 0; k < runs.size(); ++k) ASSERT_EQ(runs[k].load(), 1) << k;
}

// The threads a pass may use come from the innermost scope, and are restored when it ends;
// outside every scope a pass runs on one thread.
TEST(WorkRunner, PassThreadsComeFromTheInnermostScope) {
  EXPECT_EQ(passThreads(), 1);
  WorkRunner runner(3);
  {
    const RunnerScope frame(runner, 2);
    EXPECT_EQ(passThreads(), 2);
    {
      const ThreadsScope tool(4);
      EXPECT_EQ(passThreads(), 4);
    }
    EXPECT_EQ(passThreads(), 2);
    const RunnerScope wider(runner, 8);
    EXPECT_EQ(passThreads(), 3) << "a scope's team is cut to its runner's workers";
  }
  EXPECT_EQ(passThreads(), 1);
  std::vector<std::atomic<int>> workers_seen(2);
  const ThreadsScope two(2);
  runUnitsOnWorkers(64, [&](std::size_t, int inWorker) { workers_seen[inWorker].fetch_add(1); });
  EXPECT_EQ(workers_seen[0].load() + workers_seen[1].load(), 64);
}

// Engines on several threads at once, each with its own runner (and its workers' own scratch):
// every one's pairs equal the oracle's.
TEST(WorkRunner, EnginesOnSeveralThreadsAtOnceStayExact) {
  const BoxSet boxes = test_support::randomBoxes(20000, 1000.0, 3.0, 21);
  const PairList expected = bruteForcePairs(boxes);
  std::vector<std::thread> callers;
  std::atomic<int> exact{0};
  for (int caller = 0; caller < 3; ++caller) {
    callers.emplace_back([&] {
      BroadphaseConfig config;
      config.threads = 2;
      config.method = Method::kParallel;
      Broadphase engine(config);
      if (test_support::samePairs(expected, engine.update(boxes))) exact.fetch_add(1);
    });
  }
  for (std::thread& caller : callers) caller.join();
  EXPECT_EQ(exact.load(), 3);
}

}  // namespace
}  // namespace sap_broadphase
