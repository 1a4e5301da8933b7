// Round trip of one cache line between two threads pinned to CPUs 0 and 1: tells whether the
// two vCPUs of a VM sit close (a shared cache, ~80-110 ns on the 2-core VM) or far apart
// (~320-380 ns there), which decides what the passes that share cache lines between threads
// cost. Print it next to every two-thread measurement.
//
//   g++ -O2 -pthread bench/micro/ab/pingpong.cpp -o build/ab/pingpong && build/ab/pingpong
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

namespace {

alignas(64) std::atomic<int> g_turn{0};

void pinTo(int inCpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(inCpu, &set);
  pthread_setaffinity_np(pthread_self(), sizeof set, &set);
}

}  // namespace

int main() {
  constexpr int kRoundTrips = 200000;
  std::thread partner([] {
    pinTo(1);
    for (int k = 0; k < kRoundTrips; ++k) {
      while (g_turn.load(std::memory_order_acquire) != 1) {
      }
      g_turn.store(0, std::memory_order_release);
    }
  });
  pinTo(0);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < kRoundTrips; ++k) {
    g_turn.store(1, std::memory_order_release);
    while (g_turn.load(std::memory_order_acquire) != 0) {
    }
  }
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
  partner.join();
  std::printf("round trip %.0f ns\n", ns / kRoundTrips);
  return 0;
}
