// ThreadChoice: the thread count of a frame's work learnt from measured costs (thread_choice.h),
// driven here with made-up times so that every decision is deterministic.
#include <gtest/gtest.h>

#include <vector>

#include "core/thread_choice.h"

namespace sap_broadphase {
namespace {

constexpr int kPlanned = 4;
constexpr std::size_t kBoxes = 100000;

// Runs inFrames frames of inWork in which one thread costs inOneMs and the planned count
// inPlannedMs; returns the thread count of each frame.
std::vector<int> runFrames(ThreadChoice& ioChoice, int inFrames, double inOneMs, double inPlannedMs,
                           ThreadedWork inWork = ThreadedWork::kSweep,
                           std::size_t inBoxes = kBoxes) {
  std::vector<int> threads;
  for (int frame = 0; frame < inFrames; ++frame) {
    const int used = ioChoice.choose(inWork, kPlanned, inBoxes);
    ioChoice.record(inWork, used, used == 1 ? inOneMs : inPlannedMs);
    threads.push_back(used);
  }
  return threads;
}

// Frames (0-based) on which the count differs from the most frequent one.
std::vector<int> probesOf(const std::vector<int>& inThreads, int inUsual) {
  std::vector<int> probes;
  for (int frame = 0; frame < static_cast<int>(inThreads.size()); ++frame)
    if (inThreads[frame] != inUsual) probes.push_back(frame);
  return probes;
}

TEST(ThreadChoice, PlannedCountFirstThenAProbeOfOneThread) {
  ThreadChoice choice;
  const std::vector<int> threads = runFrames(choice, 20, 10.0, 6.0);
  EXPECT_EQ(probesOf(threads, kPlanned), std::vector<int>({15}));
}

TEST(ThreadChoice, ProbesThatLoseClearlyComeLessAndLessOften) {
  ThreadChoice choice;
  const std::vector<int> threads = runFrames(choice, 16 + 32 + 64 + 128 + 256 + 256 + 1, 10.0, 6.0);
  EXPECT_EQ(probesOf(threads, kPlanned),
            std::vector<int>({15, 47, 111, 239, 495, 751}));  // 16, then 32, 64, ... 256 apart
}

TEST(ThreadChoice, OneThreadWhenItCostsLessAndBackWhenItNoLongerDoes) {
  ThreadChoice choice;
  // A loaded machine: the second thread gets no core and only adds its hand-offs.
  std::vector<int> threads = runFrames(choice, 40, 10.0, 12.0);
  EXPECT_EQ(threads[15], 1);  // the probe
  // From then on one thread, but for a probe of the planned count every 16 frames (it still
  // loses, though not clearly: 1.2x).
  EXPECT_EQ(probesOf(std::vector<int>(threads.begin() + 16, threads.end()), 1),
            std::vector<int>({31 - 16}));
  // The load goes away: the next probe of the planned count (frame 47, 16 after the last)
  // finds it cheaper again; from then on one thread is the probe, and as it loses clearly
  // (1.67x) the one after it comes 32 frames later.
  threads = runFrames(choice, 40, 10.0, 6.0);
  EXPECT_EQ(probesOf(std::vector<int>(threads.begin(), threads.begin() + 7), 1),
            std::vector<int>());
  EXPECT_EQ(threads[7], kPlanned);
  EXPECT_EQ(probesOf(std::vector<int>(threads.begin() + 7, threads.end()), kPlanned),
            std::vector<int>({16}));
}

TEST(ThreadChoice, CloseCostsKeepProbingOften) {
  ThreadChoice choice;
  const std::vector<int> threads = runFrames(choice, 64, 10.0, 9.5);  // one costs 1.05x
  EXPECT_EQ(probesOf(threads, kPlanned), std::vector<int>({15, 31, 47, 63}));
}

TEST(ThreadChoice, EachWorkAndFrameSizeLearnsOnItsOwn) {
  ThreadChoice choice;
  runFrames(choice, 20, 10.0, 12.0, ThreadedWork::kSweep);  // one thread wins the sweep
  EXPECT_EQ(choice.preferred(ThreadedWork::kSweep, kPlanned), 1);
  EXPECT_EQ(choice.choose(ThreadedWork::kSweep, kPlanned, kBoxes), 1);
  choice.record(ThreadedWork::kSweep, 1, 10.0);
  // The kept-candidate pass has learnt nothing: the planned count.
  EXPECT_EQ(choice.preferred(ThreadedWork::kKeptCandidates, kPlanned), kPlanned);
  EXPECT_EQ(choice.choose(ThreadedWork::kKeptCandidates, kPlanned, kBoxes), kPlanned);
  choice.record(ThreadedWork::kKeptCandidates, kPlanned, 1.0);
  // A frame three times as large starts afresh, as does another planned count.
  EXPECT_EQ(choice.choose(ThreadedWork::kSweep, kPlanned, 3 * kBoxes), kPlanned);
  choice.record(ThreadedWork::kSweep, kPlanned, 30.0);
  EXPECT_EQ(choice.choose(ThreadedWork::kSweep, 2, 3 * kBoxes), 2);
  choice.record(ThreadedWork::kSweep, 2, 30.0);
  choice.forget();
  EXPECT_EQ(choice.choose(ThreadedWork::kSweep, 2, 3 * kBoxes), 2);
}

}  // namespace
}  // namespace sap_broadphase
