#include <gtest/gtest.h>

#include <numeric>

#include "tacs_graphs/odometry/parallel.h"

namespace tacs {
namespace {

struct Sum {
  double value = 0.0;
  Sum& operator+=(const Sum& o) {
    value += o.value;
    return *this;
  }
};

TEST(Parallel, ItemsPerThreadDecidesHowManyThreadsALoopWakes) {
  const int64_t before = minItemsPerThread();
  EXPECT_EQ(before, 2048);  // the default: the node suite shares the cores
  EXPECT_EQ(threadsFor(2800, 2), 1);
  setMinItemsPerThread(512);  // tacs_offline's, alone on the cores
  EXPECT_EQ(threadsFor(2800, 2), 2);
  EXPECT_EQ(threadsFor(400, 2), 1);
  setMinItemsPerThread(0);  // clamped: every item may get a thread
  EXPECT_EQ(minItemsPerThread(), 1);
  setMinItemsPerThread(before);
}

TEST(Parallel, AReductionIsTheSameBitForBitWhateverTheThreads) {
  auto run = [](int threads) {
    return parallelReduce<Sum>(
               100000, threads,
               [](int64_t i, Sum& s) { s.value += 1.0 / (1.0 + static_cast<double>(i)); })
        .value;
  };
  const int64_t before = minItemsPerThread();
  setMinItemsPerThread(512);
  const double two = run(2);
  setMinItemsPerThread(before);
  EXPECT_EQ(run(1), two);
}

}  // namespace
}  // namespace tacs
