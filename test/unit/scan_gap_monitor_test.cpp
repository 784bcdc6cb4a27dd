#include "tacs_graphs/pipeline/scan_gap_monitor.h"

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

TEST(OverloadMonitor, ReportsAWindowWithDropsOnceAndQuietWindowsNever) {
  OverloadMonitor monitor(10.0);
  // 10 s of a 10 Hz sensor, every scan handled: no report.
  for (int i = 0; i < 100; ++i) monitor.arrived(0.1 * i, 0);
  EXPECT_FALSE(monitor.poll(9.9));
  EXPECT_FALSE(monitor.poll(10.0));
  // The next 10 s: 40 scans handled, 60 missing before them.
  for (int i = 0; i < 40; ++i) monitor.arrived(10.0 + 0.25 * i, i % 2 == 0 ? 1 : 2);
  EXPECT_FALSE(monitor.poll(19.0));  // the window is still open
  const auto report = monitor.poll(20.0);
  ASSERT_TRUE(report);
  EXPECT_NE(report->find("60 of 100 scans of the last 10 s dropped (60 %)"), std::string::npos)
      << *report;
  EXPECT_NE(report->find("4.0 scans/s handled of 10.0 produced (0.40x real time)"),
            std::string::npos)
      << *report;
  EXPECT_FALSE(monitor.poll(20.5));  // reported once
  EXPECT_EQ(monitor.arrivedTotal(), 140u);
}

}  // namespace
}  // namespace tacs
