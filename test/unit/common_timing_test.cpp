// ThreadCpuStopwatch counts the thread's own work, not the time it waits.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "tacs_graphs/common/timing.h"

namespace tacs {
namespace {

TEST(ThreadCpuStopwatch, SleepingCostsNoCpu) {
  const ThreadCpuStopwatch cpu;
  const Stopwatch wall;
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_GE(wall.elapsedMs(), 50.0);
  EXPECT_LT(cpu.elapsedMs(), 10.0);
}

TEST(ThreadCpuStopwatch, WorkCounts) {
  const ThreadCpuStopwatch cpu;
  const Stopwatch wall;
  volatile double sink = 0.0;
  // Spins until 5 ms of CPU are counted (on any load that takes a little wall time), or gives up.
  while (cpu.elapsedMs() < 5.0 && wall.elapsedMs() < 10000.0) {
    for (int i = 0; i < 10000; ++i) sink = sink + 1e-9 * i;
  }
  EXPECT_GE(cpu.elapsedMs(), 5.0);
  EXPECT_LE(cpu.elapsedMs(), wall.elapsedMs() + 1.0);
}

TEST(ThreadCpuStopwatch, AnotherThreadsWorkDoesNotCount) {
  const ThreadCpuStopwatch cpu;
  std::thread worker([] {
    const ThreadCpuStopwatch own;
    volatile double sink = 0.0;
    while (own.elapsedMs() < 20.0) sink = sink + 1.0;
  });
  worker.join();
  EXPECT_LT(cpu.elapsedMs(), 10.0);
}

}  // namespace
}  // namespace tacs
