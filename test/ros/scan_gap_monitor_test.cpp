#include "tacs_graphs/ros/scan_gap_monitor.h"

#include <gtest/gtest.h>

namespace tacs {
namespace {

TEST(ScanGapMonitor, CountsScansMissingFromA10HzStream) {
  ScanGapMonitor monitor;
  double t = 100.0;
  for (int i = 0; i < 10; ++i, t += 0.1) EXPECT_EQ(monitor.observe(t), 0u);
  EXPECT_NEAR(monitor.period(), 0.1, 1e-9);
  // A full queue dropped three scans: the next stamp is four periods on.
  t += 0.3;
  EXPECT_EQ(monitor.observe(t), 3u);
  EXPECT_EQ(monitor.observe(t + 0.1), 0u);
  EXPECT_EQ(monitor.observe(t + 0.3), 1u);
  EXPECT_EQ(monitor.missingTotal(), 4u);
}

TEST(ScanGapMonitor, NoCountBeforeThePeriodIsKnownOrOnStampsGoingBack) {
  ScanGapMonitor monitor;
  EXPECT_EQ(monitor.observe(5.0), 0u);
  EXPECT_EQ(monitor.observe(6.0), 0u);  // one step: no period yet
  EXPECT_EQ(monitor.period(), 0.0);
  for (double t = 6.1; t < 6.65; t += 0.1) EXPECT_EQ(monitor.observe(t), 0u);
  EXPECT_NEAR(monitor.period(), 0.1, 1e-9);
  EXPECT_EQ(monitor.observe(1.0), 0u);  // a bag restarted
  EXPECT_EQ(monitor.observe(1.1), 0u);
  EXPECT_EQ(monitor.missingTotal(), 0u);
}

TEST(ScanGapMonitor, JitterBelowHalfAPeriodIsNoGap) {
  ScanGapMonitor monitor;
  const double stamps[] = {0.0, 0.1, 0.2, 0.3, 0.44, 0.5, 0.6, 0.72, 0.78, 0.9, 0.96, 1.1, 1.2};
  for (double s : stamps) EXPECT_EQ(monitor.observe(s), 0u) << s;
  EXPECT_NEAR(monitor.period(), 0.1, 1e-9);
}

TEST(ScanGapMonitor, KeepsCountingWhenTheNodeFallsBehindForGood) {
  // Consecutive scans first, then a node that only gets every third scan.
  ScanGapMonitor monitor;
  double t = 0.0;
  for (int i = 0; i < 8; ++i, t += 0.1) monitor.observe(t);
  size_t missing = 0;
  for (int i = 0; i < 20; ++i, t += 0.3) missing += monitor.observe(t);
  EXPECT_EQ(missing, 2u * 20u - 2u);  // the first of these came 0.1 s after the last consecutive
  EXPECT_NEAR(monitor.period(), 0.1, 1e-9);
}

}  // namespace
}  // namespace tacs
