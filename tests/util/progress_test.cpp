// The progress display's time-left estimate: exact for steady progress, and following the
// recent rate when the work slows down (as an adaptive render does once its cheap pixels
// have converged), where the average since the start would promise too early an end.
#include <gtest/gtest.h>

#include "pbrkit/util/eta_estimator.h"

namespace pbrkit {
namespace {

TEST(EtaEstimator, UnknownBeforeAnyProgressAndInTheFirstSecond) {
  EtaEstimator e;
  EXPECT_LT(e.eta(), 0.0);
  e.add(0.5, 0.0);
  e.add(1.0, 0.0);
  EXPECT_LT(e.eta(), 0.0);
  EtaEstimator early;
  early.add(0.1, 0.0001);  // 0.1 s in: a guess of 1000 s would be noise
  EXPECT_LT(early.eta(), 0.0);
}

TEST(EtaEstimator, SteadyProgressGivesTheExactTimeLeft) {
  EtaEstimator e;
  for (int k = 1; k <= 50; ++k) e.add(0.1 * k, 0.01 * k);  // 10% per second
  EXPECT_NEAR(e.eta(), 5.0, 1e-9);
  e.add(10.0, 1.0);
  EXPECT_EQ(e.eta(), 0.0);
}

TEST(EtaEstimator, FollowsTheRecentRateWhenWorkSlowsDown) {
  // Half the work in the first second, then 5% per second: at t = 6 s, 75% done, 5 s left.
  // The average since the start (12.5% per second) would say 2 s.
  EtaEstimator e;
  for (int k = 1; k <= 10; ++k) e.add(0.1 * k, 0.05 * k);
  for (int k = 1; k <= 50; ++k) e.add(1.0 + 0.1 * k, 0.5 + 0.005 * k);
  EXPECT_NEAR(e.eta(), 5.0, 1e-6);
}

TEST(EtaEstimator, ManyReportsKeepTheRateAndABoundedHistory) {
  // A million reports over 100 s at a steady 0.1% per second: the rate, and so the time
  // left, are exact whatever the thinning of the history.
  EtaEstimator e;
  for (int k = 1; k <= 1000000; ++k) e.add(1e-4 * k, 1e-7 * k);
  EXPECT_NEAR(e.eta(), 900.0, 1e-3);
  EXPECT_LE(e.history_size(), 100u);  // not a million
}

TEST(EtaEstimator, FallsBackToTheAverageWhenTheWindowSawNoProgress) {
  EtaEstimator e;
  e.add(1.0, 0.5);
  for (int k = 1; k <= 100; ++k) e.add(1.0 + 0.1 * k, 0.5);  // stalled for 10 s
  EXPECT_NEAR(e.eta(), 11.0, 1e-9);                          // 11 s for the first half: 11 s more
}

}  // namespace
}  // namespace pbrkit
