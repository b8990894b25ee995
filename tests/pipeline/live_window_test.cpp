// Tests of the rolling window of `imunoise live` (pipeline/live_window.h) on constructed
// sample streams whose counts are known by construction: out of order and duplicate stamps,
// gaps, switches between rates and increments, non-finite values, the restart after a run of
// rejections, the bounds by data time and by sample count, the analysis cadence, and the
// snapshot's columns and Recording.
#include "pipeline/live_window.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>

#include "common/errors.h"
#include "common/sampling_gap.h"
#include "pipeline/imu_samples.h"

namespace imunoise::pipeline {
namespace {

constexpr std::int64_t kPeriodUs = 10'000;  // 100 Hz
constexpr double kPeriodS = 0.01;

/// Rate sample at UTIME_US: gyro x = 0.001·k, accel z = −9.8 (k = utime / period).
ImuSample rate_sample(std::int64_t utime_us) {
  ImuSample s;
  s.utime_us = utime_us;
  s.values = {1e-3 * static_cast<double>(utime_us / kPeriodUs), 0, 0, 0, 0, -9.8};
  return s;
}

ImuSample increment_sample(std::int64_t utime_us) {
  ImuSample s = rate_sample(utime_us);
  s.increments = true;
  return s;
}

ImuSampleFields test_fields() {
  ImuSampleFields f;
  for (std::size_t c = 0; c < 6; ++c) {
    f.rate_fields[c] = "rate" + std::to_string(c);
    f.rate_units[c] = c < 3 ? "rad/s" : "m/s^2";
    f.increment_fields[c] = "inc" + std::to_string(c);
    f.increment_units[c] = c < 3 ? "rad" : "m/s";
  }
  f.temperature_field = "temp";
  return f;
}

/// A window that no bound limits: 1 h, 10⁶ samples, analysis every 1 s.
LiveWindow open_window() { return LiveWindow({3600.0, 1'000'000, 1.0}, test_fields()); }

/// Adds samples k = first … last − 1 at the nominal period.
void add_range(LiveWindow& w, std::int64_t first, std::int64_t last) {
  for (std::int64_t k = first; k < last; ++k) w.add(rate_sample(k * kPeriodUs));
}

TEST(LiveWindow, CountsOutOfOrderAndDuplicateStampsAndKeepsThemOut) {
  LiveWindow w = open_window();
  add_range(w, 0, 10);
  w.add(rate_sample(5 * kPeriodUs));  // before the last
  w.add(rate_sample(9 * kPeriodUs));  // duplicate of the last
  add_range(w, 10, 20);
  const LiveWindowCounts& c = w.counts();
  EXPECT_EQ(c.received, 22);
  EXPECT_EQ(c.accepted, 20);
  EXPECT_EQ(c.out_of_order, 2);
  EXPECT_EQ(c.mode_changes, 0);
  EXPECT_EQ(c.restarts, 0);
  EXPECT_EQ(w.size(), 20u);
  EXPECT_EQ(w.last_utime(), 19 * kPeriodUs);
}

TEST(LiveWindow, CountsAGapOnlyBeyondTheGapFactorOnceThePeriodIsKnown) {
  LiveWindow w = open_window();
  add_range(w, 0, 5);
  w.add(rate_sample(10 * kPeriodUs));  // no nominal period yet: not counted
  EXPECT_EQ(w.counts().gaps, 0);
  w.set_nominal_period_s(kPeriodS);
  // An interval of exactly kGapFactor × the period is not a gap; one µs more is.
  const auto at_factor = static_cast<std::int64_t>(kGapFactor * kPeriodUs);
  w.add(rate_sample(10 * kPeriodUs + at_factor));
  EXPECT_EQ(w.counts().gaps, 0);
  w.add(rate_sample(10 * kPeriodUs + 2 * at_factor + 1));
  EXPECT_EQ(w.counts().gaps, 1);
  w.add(rate_sample(100 * kPeriodUs));  // 88 samples missing: one gap
  EXPECT_EQ(w.counts().gaps, 2);
  EXPECT_EQ(w.counts().accepted, 9);  // gaps are accepted samples
}

TEST(LiveWindow, CountsASwitchBetweenRatesAndIncrementsAndKeepsItOut) {
  LiveWindow w = open_window();
  add_range(w, 0, 10);
  w.add(increment_sample(10 * kPeriodUs));
  add_range(w, 11, 20);
  EXPECT_EQ(w.counts().mode_changes, 1);
  EXPECT_EQ(w.counts().out_of_order, 0);
  EXPECT_EQ(w.counts().accepted, 19);
  EXPECT_FALSE(w.snapshot().increments);
}

TEST(LiveWindow, CountsNonFiniteValuesAndUndecodableMessages) {
  LiveWindow w = open_window();
  add_range(w, 0, 3);
  ImuSample nan = rate_sample(3 * kPeriodUs);
  nan.values[4] = std::numeric_limits<double>::quiet_NaN();
  w.add(nan);
  ImuSample hot = rate_sample(3 * kPeriodUs);
  hot.temperature_degc = std::numeric_limits<double>::infinity();
  w.add(hot);
  w.add_undecodable();
  add_range(w, 3, 5);
  const LiveWindowCounts& c = w.counts();
  EXPECT_EQ(c.received, 8);
  EXPECT_EQ(c.accepted, 5);
  EXPECT_EQ(c.non_finite, 2);
  EXPECT_EQ(c.undecodable, 1);
  EXPECT_EQ(c.out_of_order, 0);
}

TEST(LiveWindow, RestartsAfterARunOfRejectionsFromTheSampleThatEndsIt) {
  LiveWindow w = open_window();
  add_range(w, 1000, 1100);
  // The sender restarts with its clock at 0: the first kRestartAfterRejections − 1 samples
  // are rejected, the next one restarts the window.
  add_range(w, 0, 150);
  const LiveWindowCounts& c = w.counts();
  EXPECT_EQ(c.out_of_order, kRestartAfterRejections - 1);
  EXPECT_EQ(c.restarts, 1);
  EXPECT_EQ(c.accepted, 100 + 150 - (kRestartAfterRejections - 1));
  EXPECT_EQ(c.received, 250);
  EXPECT_EQ(static_cast<std::int64_t>(w.size()), 150 - (kRestartAfterRejections - 1));
  EXPECT_EQ(w.last_utime(), 149 * kPeriodUs);
}

TEST(LiveWindow, AcceptedSampleEndsTheRunOfRejections) {
  LiveWindow w = open_window();
  add_range(w, 0, 10);
  for (int round = 0; round < 3; ++round) {
    for (std::int64_t k = 0; k < kRestartAfterRejections - 1; ++k) w.add(rate_sample(0));
    add_range(w, 10 + round, 11 + round);  // one good sample: the count starts again
  }
  EXPECT_EQ(w.counts().restarts, 0);
  EXPECT_EQ(w.counts().out_of_order, 3 * (kRestartAfterRejections - 1));
  EXPECT_EQ(w.size(), 13u);
}

TEST(LiveWindow, IsBoundedByDataTime) {
  LiveWindow w({1.0, 1'000'000, 1.0}, test_fields());  // 1 s at 100 Hz: 101 samples
  add_range(w, 0, 300);
  EXPECT_EQ(w.size(), 101u);
  EXPECT_DOUBLE_EQ(w.span_s(), 1.0);
  EXPECT_EQ(w.counts().trimmed_by_cap, 0);  // dropped by time are not counted
  EXPECT_EQ(w.counts().accepted, 300);
  const ImuSampleColumns columns = w.snapshot();
  EXPECT_EQ(columns.utime_us.front(), 199 * kPeriodUs);
  EXPECT_EQ(columns.utime_us.back(), 299 * kPeriodUs);
}

TEST(LiveWindow, IsBoundedBySampleCountAndCountsWhatThatDrops) {
  LiveWindow w({3600.0, 50, 1.0}, test_fields());
  add_range(w, 0, 120);
  EXPECT_EQ(w.size(), 50u);
  EXPECT_EQ(w.counts().trimmed_by_cap, 70);
  EXPECT_EQ(w.counts().accepted, 120);
  EXPECT_DOUBLE_EQ(w.span_s(), 49 * kPeriodS);
}

TEST(LiveWindow, AnalysisIsDueEveryPeriodOfNewData) {
  LiveWindow w = open_window();  // every 1 s
  EXPECT_FALSE(w.analysis_due());
  EXPECT_FALSE(w.has_unanalysed_data());
  add_range(w, 0, 100);  // spans 0.99 s
  EXPECT_FALSE(w.analysis_due());
  EXPECT_TRUE(w.has_unanalysed_data());
  add_range(w, 100, 101);  // spans 1 s
  EXPECT_TRUE(w.analysis_due());
  EXPECT_EQ(w.snapshot().size(), 101u);
  EXPECT_EQ(w.new_samples(), 0);
  EXPECT_FALSE(w.analysis_due());
  EXPECT_FALSE(w.has_unanalysed_data());
  add_range(w, 101, 200);  // 0.99 s after the snapshot's data
  EXPECT_FALSE(w.analysis_due());
  EXPECT_TRUE(w.has_unanalysed_data());
  add_range(w, 200, 201);
  EXPECT_TRUE(w.analysis_due());
}

TEST(LiveWindow, AfterARestartBeforeTheLastAnalysisItIsDueWhenTheWindowSpansThePeriod) {
  LiveWindow w = open_window();
  add_range(w, 10'000, 10'200);
  (void)w.snapshot();
  add_range(w, 0, kRestartAfterRejections - 1);  // rejected
  add_range(w, 0, 100);                          // the first restarts the window: it spans 0.99 s
  EXPECT_EQ(w.counts().restarts, 1);
  EXPECT_FALSE(w.analysis_due());
  add_range(w, 100, 101);  // spans 1 s, stamps still before the last analysis
  EXPECT_DOUBLE_EQ(w.span_s(), 1.0);
  EXPECT_TRUE(w.analysis_due());
}

TEST(LiveWindow, SnapshotIsTheColumnsOfTheWindowWithTheFieldsOfItsKind) {
  LiveWindow w = open_window();
  for (std::int64_t k = 0; k < 4; ++k) {
    ImuSample s = increment_sample(1000 + k * kPeriodUs);
    s.values = {0.5 + k, 1.0, 1.5, 2.0, 2.5, 3.0 + k};
    s.temperature_degc = 20.0 + k;
    w.add(s);
  }
  const ImuSampleColumns columns = w.snapshot();
  EXPECT_TRUE(columns.increments);
  EXPECT_EQ(columns.source_fields[0], "inc0");
  EXPECT_EQ(columns.source_units[5], "m/s");
  EXPECT_EQ(columns.temperature_field, "temp");
  EXPECT_EQ(columns.utime_us, (std::vector<std::int64_t>{1000, 11'000, 21'000, 31'000}));
  EXPECT_EQ(columns.values[0], (std::vector<double>{0.5, 1.5, 2.5, 3.5}));
  EXPECT_EQ(columns.values[5], (std::vector<double>{3, 4, 5, 6}));
  EXPECT_EQ(columns.temperature_degc, (std::vector<double>{20, 21, 22, 23}));

  const Recording rec = recording_from_imu_samples(columns, "lcm:IMU", "IMU");
  EXPECT_EQ(rec.sample_count(), 4u);
  EXPECT_DOUBLE_EQ(rec.sample_period_s, kPeriodS);
  EXPECT_EQ(rec.find_channel("gyro_x")->source_column, "IMU.inc0");
  EXPECT_DOUBLE_EQ(rec.find_channel("accel_z")->values[1], 4.0 / kPeriodS);
  ASSERT_NE(rec.find_channel("temperature"), nullptr);
  EXPECT_EQ(rec.find_channel("temperature")->source_column, "IMU.temp");
}

TEST(LiveWindow, SnapshotHasATemperatureOnlyWhenEverySampleHasOne) {
  LiveWindow w = open_window();
  for (std::int64_t k = 0; k < 4; ++k) {
    ImuSample s = rate_sample(k * kPeriodUs);
    if (k != 2) s.temperature_degc = 20.0 + k;
    w.add(s);
  }
  const ImuSampleColumns columns = w.snapshot();
  EXPECT_EQ(columns.source_fields[3], "rate3");
  EXPECT_EQ(columns.temperature_degc, (std::vector<double>{20, 21}));
  EXPECT_EQ(recording_from_imu_samples(columns, "lcm:IMU", "IMU").find_channel("temperature"),
            nullptr);
}

TEST(LiveWindow, LimitsOutsideTheirRangeAreContractViolations) {
  EXPECT_THROW(LiveWindow({0.0, 100, 1.0}, test_fields()), ContractViolation);
  EXPECT_THROW(LiveWindow({std::numeric_limits<double>::infinity(), 100, 1.0}, test_fields()),
               ContractViolation);
  EXPECT_THROW(LiveWindow({1.0, 0, 1.0}, test_fields()), ContractViolation);
  EXPECT_THROW(LiveWindow({1.0, 100, -1.0}, test_fields()), ContractViolation);
}

}  // namespace
}  // namespace imunoise::pipeline
