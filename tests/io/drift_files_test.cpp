// Round trips of the three result files of `imunoise drift` (io/drift_files.h): what the
// writer puts in drift_envelope.csv, drift_segments.csv and drift_summary.json the reader gives
// back — SI values exactly (shortest round-trip numbers), values the file holds in degrees to
// the last bit of the conversion — and a renamed column or key is an error that names it.
#include "io/drift_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/units.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using pipeline::DriftSegment;
using pipeline::DriftSeries;
using pipeline::DriftSummary;
using test::error_of;

/// Relative tolerance of a value the file holds in degrees: x / kDeg printed exactly, read
/// back and multiplied by kDeg is x within two roundings.
constexpr double kDegreeRoundTrip = 4 * std::numeric_limits<double>::epsilon();

void expect_close(const std::vector<double>& actual, const std::vector<double>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i], expected[i], kDegreeRoundTrip * std::abs(expected[i])) << "i = " << i;
  }
}

DriftSeries envelope(bool recorded, bool monte_carlo) {
  DriftSeries s;
  s.time_s = {1.0, 2.0, 3.0};
  s.predicted_north_sigma_m = {0.1, 0.4, 1.0 / 3.0};
  s.predicted_east_sigma_m = {0.2, 0.5, 2.0 / 3.0};
  s.predicted_drms_m = {0.25, 0.7, 0.9};
  s.predicted_velocity_drms_m_per_s = {1e-3, 2e-3, 3.5e-3};
  s.predicted_roll_sigma_rad = {1e-5, 2e-5, 3e-5};
  s.predicted_pitch_sigma_rad = {1.5e-5, 2.5e-5, 3.5e-5};
  s.predicted_heading_sigma_rad = {1e-2, 1.1e-2, 0.0};
  for (std::size_t i = 0; i < 3; ++i) {
    const double r = s.predicted_roll_sigma_rad[i], p = s.predicted_pitch_sigma_rad[i];
    const double h = s.predicted_heading_sigma_rad[i];
    s.predicted_attitude_sigma_rad.push_back(std::sqrt(r * r + p * p + h * h));
  }
  if (recorded) s.recorded_rms_m = {0.3, 0.6, 1.2};
  if (monte_carlo) {
    s.mc_radial_p50_m = {0.2, 0.5, 0.8};
    s.mc_radial_p68_m = {0.25, 0.6, 0.95};
    s.mc_radial_p95_m = {0.4, 1.0, 1.6};
    s.mc_radial_rms_m = {0.26, 0.71, 0.91};
  }
  return s;
}

TEST(DriftEnvelopeCsv, RoundTripsEveryColumn) {
  const auto dir = test::make_temp_dir("drift-envelope");
  const std::string path = (dir / "drift_envelope.csv").string();
  const DriftSeries s = envelope(true, true);
  write_drift_envelope_csv(path, s);
  EXPECT_EQ(test::read_file_bytes(path), format_drift_envelope_csv(s));
  const DriftSeries r = read_drift_envelope_csv(path);
  EXPECT_EQ(r.time_s, s.time_s);
  EXPECT_EQ(r.predicted_north_sigma_m, s.predicted_north_sigma_m);
  EXPECT_EQ(r.predicted_east_sigma_m, s.predicted_east_sigma_m);
  EXPECT_EQ(r.predicted_drms_m, s.predicted_drms_m);
  EXPECT_EQ(r.predicted_velocity_drms_m_per_s, s.predicted_velocity_drms_m_per_s);
  expect_close(r.predicted_roll_sigma_rad, s.predicted_roll_sigma_rad);
  expect_close(r.predicted_pitch_sigma_rad, s.predicted_pitch_sigma_rad);
  expect_close(r.predicted_heading_sigma_rad, s.predicted_heading_sigma_rad);
  expect_close(r.predicted_attitude_sigma_rad, s.predicted_attitude_sigma_rad);
  EXPECT_EQ(r.recorded_rms_m, s.recorded_rms_m);
  EXPECT_EQ(r.mc_radial_p50_m, s.mc_radial_p50_m);
  EXPECT_EQ(r.mc_radial_p68_m, s.mc_radial_p68_m);
  EXPECT_EQ(r.mc_radial_p95_m, s.mc_radial_p95_m);
  EXPECT_EQ(r.mc_radial_rms_m, s.mc_radial_rms_m);
}

TEST(DriftEnvelopeCsv, RecordedAndMonteCarloColumnsAreOptional) {
  const auto dir = test::make_temp_dir("drift-envelope-optional");
  const std::string path = (dir / "drift_envelope.csv").string();
  write_drift_envelope_csv(path, envelope(false, false));
  const std::string text = test::read_file_bytes(path);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "time_s,predicted_north_sigma_m,predicted_east_sigma_m,predicted_horizontal_drms_m,"
            "predicted_horizontal_velocity_drms_m_per_s,predicted_roll_sigma_deg,"
            "predicted_pitch_sigma_deg,predicted_heading_sigma_deg");
  const DriftSeries r = read_drift_envelope_csv(path);
  EXPECT_EQ(r.time_s.size(), 3u);
  EXPECT_TRUE(r.recorded_rms_m.empty());
  EXPECT_TRUE(r.mc_radial_rms_m.empty());
}

TEST(DriftEnvelopeCsv, AttitudeTotalIsComputedFromTheDegreesOfTheFile) {
  // √(0.3² + 0.4² + 1.2²) = 1.3 deg: kDeg · √(Σ deg²), as the LCM message has always carried it.
  const auto dir = test::make_temp_dir("drift-envelope-attitude");
  const auto path = dir / "drift_envelope.csv";
  test::write_text(path,
                   "time_s,predicted_north_sigma_m,predicted_east_sigma_m,"
                   "predicted_horizontal_drms_m,predicted_horizontal_velocity_drms_m_per_s,"
                   "predicted_roll_sigma_deg,predicted_pitch_sigma_deg,"
                   "predicted_heading_sigma_deg,actual_rms_horizontal_error_m\n"
                   "60,30,40,50,1,0.3,0.4,1.2,45\n");
  const DriftSeries r = read_drift_envelope_csv(path.string());
  ASSERT_EQ(r.predicted_attitude_sigma_rad.size(), 1u);
  EXPECT_EQ(r.predicted_attitude_sigma_rad[0],
            units::kDeg * std::sqrt(0.3 * 0.3 + 0.4 * 0.4 + 1.2 * 1.2));
  EXPECT_EQ(r.recorded_rms_m, std::vector<double>{45.0});
}

TEST(DriftEnvelopeCsv, ARenamedColumnIsAnErrorThatNamesIt) {
  const auto dir = test::make_temp_dir("drift-envelope-renamed");
  const auto path = dir / "drift_envelope.csv";
  std::string text = format_drift_envelope_csv(envelope(true, true));
  text.replace(text.find("mc_radial_p68_m"), 15, "mc_radial_p66_m");
  test::write_text(path, text);
  const std::string error = error_of([&] { read_drift_envelope_csv(path.string()); });
  EXPECT_NE(error.find("no column 'mc_radial_p68_m'"), std::string::npos) << error;
}

TEST(DriftEnvelopeCsv, UnequalLengthsAreACallerBug) {
  DriftSeries s = envelope(true, false);
  s.recorded_rms_m.pop_back();
  EXPECT_THROW(format_drift_envelope_csv(s), ContractViolation);
}

std::vector<DriftSegment> segments() {
  std::vector<DriftSegment> out(2);
  for (std::size_t k = 0; k < out.size(); ++k) {
    DriftSegment& s = out[k];
    s.start_s = 70.0 * static_cast<double>(k);
    s.time_s = {1.0, 2.0};
    s.position_error_ne_m = {{0.1 + k, -0.2}, {1.0 / 3.0, 0.75 * k}};
    s.velocity_error_horizontal_m_per_s = {0.01, 0.02 + k};
    s.attitude_error_ned_rad = {{1e-5, -2e-5, 3e-3}, {0.0, 4e-5 * k, -1e-3}};
  }
  return out;
}

TEST(DriftSegmentsCsv, RoundTripsEverySegment) {
  const auto dir = test::make_temp_dir("drift-segments");
  const std::string path = (dir / "drift_segments.csv").string();
  const auto written = segments();
  write_drift_segments_csv(path, written);
  EXPECT_EQ(test::read_file_bytes(path), format_drift_segments_csv(written));
  const auto read = read_drift_segments_csv(path);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t k = 0; k < read.size(); ++k) {
    EXPECT_EQ(read[k].start_s, written[k].start_s);
    EXPECT_EQ(read[k].time_s, written[k].time_s);
    EXPECT_EQ(read[k].position_error_ne_m, written[k].position_error_ne_m);
    EXPECT_EQ(read[k].horizontal_error_m(), written[k].horizontal_error_m());
    EXPECT_EQ(read[k].velocity_error_horizontal_m_per_s,
              written[k].velocity_error_horizontal_m_per_s);
    ASSERT_EQ(read[k].attitude_error_ned_rad.size(), written[k].attitude_error_ned_rad.size());
    for (std::size_t i = 0; i < read[k].attitude_error_ned_rad.size(); ++i) {
      for (int a = 0; a < 3; ++a) {
        const double expected = written[k].attitude_error_ned_rad[i](a);
        EXPECT_NEAR(read[k].attitude_error_ned_rad[i](a), expected,
                    kDegreeRoundTrip * std::abs(expected));
      }
    }
  }
}

TEST(DriftSegmentsCsv, TheHorizontalColumnIsTheNormOfNorthAndEast) {
  const auto rows = [] {
    const auto dir = test::make_temp_dir("drift-segments-norm");
    const auto path = dir / "drift_segments.csv";
    test::write_text(path, format_drift_segments_csv(segments()));
    return test::read_csv_rows(path);
  }();
  ASSERT_EQ(rows.size(), 1u + 2u * 2u);
  EXPECT_EQ(rows[0][5], "horizontal_error_m");
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const double north = std::stod(rows[r][3]), east = std::stod(rows[r][4]);
    EXPECT_EQ(std::stod(rows[r][5]), std::sqrt(north * north + east * east));
  }
}

TEST(DriftSegmentsCsv, AMissingColumnIsAnErrorThatNamesIt) {
  const auto dir = test::make_temp_dir("drift-segments-missing");
  const auto path = dir / "drift_segments.csv";
  test::write_text(path, "segment,time_s,horizontal_error_m\n0,1,0.5\n");
  const std::string error = error_of([&] { read_drift_segments_csv(path.string()); });
  EXPECT_NE(error.find("no column 'start_s'"), std::string::npos) << error;
}

DriftSummary summary(bool monte_carlo) {
  DriftSummary s;
  s.recording = "/data/rec.csv";
  s.model = "out/model.yaml";
  s.location = {45.5, 7.25, 300.0, true};
  s.protocol = {60.0, 600.0, 5.0, 43, "height hold", "removed", "given heading", "peak_match", ""};
  s.motion.stationary = false;
  s.motion.reason = "the IMU tilts by 3 deg";
  s.motion.max_gyro_std_ratio = 1.25;
  s.motion.max_accel_std_ratio = 0.875;
  s.motion.max_force_deviation_m_per_s2 = 0.01;
  s.motion.max_tilt_change_rad = 3.0 * units::kDeg;
  s.motion.max_rotation_rad_per_s = 1e-4;
  s.forced = true;
  for (double t : {60.0, 600.0}) {
    pipeline::DriftConsistency c;
    c.time_s = t;
    c.predicted_north_sigma_m = t / 10;
    c.predicted_east_sigma_m = t / 11;
    c.predicted_drms_m = t / 7;
    c.actual_rms_m = t / 6;
    c.mean_nees = 2.5;
    c.nees_band_low = 1.5;
    c.nees_band_high = 2.625;
    c.nees_inside = t < 100;
    c.nees_joint_band_low = 1.25;
    c.nees_joint_band_high = 2.875;
    c.nees_inside_joint_band = true;
    c.coverage = {0.375, 0.875, 1.0};
    c.rms_ratio = 7.0 / 6.0;
    c.rms_ratio_ci_low = 0.9;
    c.rms_ratio_ci_high = std::numeric_limits<double>::infinity();  // written as null
    if (monte_carlo) {
      c.monte_carlo_radial_rms_m = t / 7.5;
      c.monte_carlo_radial_p95_m = t / 4;
    }
    s.consistency.push_back(c);
  }
  s.protocol.bias_states = "multi_gm: 31 states";
  if (monte_carlo) {
    s.monte_carlo = pipeline::DriftMonteCarlo{100, 18446744073709551615ULL};
    pipeline::DriftHoldout h;
    h.fitted_on = "first half: samples 0 ... 9";
    h.judged_on = "second half: samples 10 ... 19";
    h.segments = 21;
    h.consistency = s.consistency;
    for (auto& c : h.consistency) {
      c.monte_carlo_radial_rms_m.reset();
      c.monte_carlo_radial_p95_m.reset();
      c.mean_nees *= 1.5;
    }
    s.holdout = h;
  }
  return s;
}

void expect_same_consistency(const std::vector<pipeline::DriftConsistency>& r,
                             const std::vector<pipeline::DriftConsistency>& s);

void expect_same_summary(const DriftSummary& r, const DriftSummary& s) {
  EXPECT_EQ(r.recording, s.recording);
  EXPECT_EQ(r.model, s.model);
  EXPECT_EQ(r.location.latitude_deg, s.location.latitude_deg);
  EXPECT_EQ(r.location.longitude_deg, s.location.longitude_deg);
  EXPECT_EQ(r.location.height_m, s.location.height_m);
  EXPECT_EQ(r.location.given, s.location.given);
  EXPECT_EQ(r.protocol.align_s, s.protocol.align_s);
  EXPECT_EQ(r.protocol.navigation_s, s.protocol.navigation_s);
  EXPECT_EQ(r.protocol.warmup_s, s.protocol.warmup_s);
  EXPECT_EQ(r.protocol.segments, s.protocol.segments);
  EXPECT_EQ(r.protocol.vertical_channel, s.protocol.vertical_channel);
  EXPECT_EQ(r.protocol.gyro_bias, s.protocol.gyro_bias);
  EXPECT_EQ(r.protocol.heading, s.protocol.heading);
  EXPECT_EQ(r.protocol.bias_instability_as_gm, s.protocol.bias_instability_as_gm);
  EXPECT_EQ(r.motion.stationary, s.motion.stationary);
  EXPECT_EQ(r.motion.reason, s.motion.reason);
  EXPECT_EQ(r.forced, s.forced);
  EXPECT_EQ(r.motion.max_gyro_std_ratio, s.motion.max_gyro_std_ratio);
  EXPECT_EQ(r.motion.max_accel_std_ratio, s.motion.max_accel_std_ratio);
  EXPECT_EQ(r.motion.max_force_deviation_m_per_s2, s.motion.max_force_deviation_m_per_s2);
  EXPECT_NEAR(r.motion.max_tilt_change_rad, s.motion.max_tilt_change_rad,
              kDegreeRoundTrip * s.motion.max_tilt_change_rad);
  EXPECT_NEAR(r.motion.max_rotation_rad_per_s, s.motion.max_rotation_rad_per_s,
              kDegreeRoundTrip * s.motion.max_rotation_rad_per_s);
  EXPECT_EQ(r.protocol.bias_states, s.protocol.bias_states);
  expect_same_consistency(r.consistency, s.consistency);
  ASSERT_EQ(r.holdout.has_value(), s.holdout.has_value());
  if (s.holdout) {
    EXPECT_EQ(r.holdout->fitted_on, s.holdout->fitted_on);
    EXPECT_EQ(r.holdout->judged_on, s.holdout->judged_on);
    EXPECT_EQ(r.holdout->segments, s.holdout->segments);
    expect_same_consistency(r.holdout->consistency, s.holdout->consistency);
  }
  ASSERT_EQ(r.monte_carlo.has_value(), s.monte_carlo.has_value());
  if (s.monte_carlo) {
    EXPECT_EQ(r.monte_carlo->runs, s.monte_carlo->runs);
    EXPECT_EQ(r.monte_carlo->seed, s.monte_carlo->seed);
  }
}

void expect_same_consistency(const std::vector<pipeline::DriftConsistency>& rc,
                             const std::vector<pipeline::DriftConsistency>& sc) {
  ASSERT_EQ(rc.size(), sc.size());
  for (std::size_t i = 0; i < rc.size(); ++i) {
    const auto& a = rc[i];
    const auto& b = sc[i];
    EXPECT_EQ(a.time_s, b.time_s);
    EXPECT_EQ(a.predicted_north_sigma_m, b.predicted_north_sigma_m);
    EXPECT_EQ(a.predicted_east_sigma_m, b.predicted_east_sigma_m);
    EXPECT_EQ(a.predicted_drms_m, b.predicted_drms_m);
    EXPECT_EQ(a.actual_rms_m, b.actual_rms_m);
    EXPECT_EQ(a.mean_nees, b.mean_nees);
    EXPECT_EQ(a.nees_band_low, b.nees_band_low);
    EXPECT_EQ(a.nees_band_high, b.nees_band_high);
    EXPECT_EQ(a.nees_inside, b.nees_inside);
    EXPECT_EQ(a.nees_joint_band_low, b.nees_joint_band_low);
    EXPECT_EQ(a.nees_joint_band_high, b.nees_joint_band_high);
    EXPECT_EQ(a.nees_inside_joint_band, b.nees_inside_joint_band);
    EXPECT_EQ(a.coverage, b.coverage);
    EXPECT_EQ(a.expected_coverage, b.expected_coverage);
    EXPECT_EQ(a.rms_ratio, b.rms_ratio);
    EXPECT_EQ(a.rms_ratio_ci_low, b.rms_ratio_ci_low);
    if (std::isfinite(b.rms_ratio_ci_high)) {
      EXPECT_EQ(a.rms_ratio_ci_high, b.rms_ratio_ci_high);
    } else {
      EXPECT_TRUE(std::isnan(a.rms_ratio_ci_high));  // JSON has no infinity: null
    }
    EXPECT_EQ(a.monte_carlo_radial_rms_m, b.monte_carlo_radial_rms_m);
    EXPECT_EQ(a.monte_carlo_radial_p95_m, b.monte_carlo_radial_p95_m);
  }
}

TEST(DriftSummaryJson, RoundTripsEveryKey) {
  for (bool monte_carlo : {true, false}) {
    SCOPED_TRACE(monte_carlo ? "with the Monte Carlo" : "without the Monte Carlo");
    const auto dir = test::make_temp_dir("drift-summary");
    const std::string path = (dir / "drift_summary.json").string();
    const DriftSummary s = summary(monte_carlo);
    write_drift_summary_json(path, s);
    EXPECT_EQ(test::read_file_bytes(path), format_drift_summary_json(s));
    expect_same_summary(read_drift_summary_json(path), s);
  }
}

TEST(DriftSummaryJson, ARenamedKeyIsAnErrorThatNamesIt) {
  const auto dir = test::make_temp_dir("drift-summary-renamed");
  const auto path = dir / "drift_summary.json";
  std::string text = format_drift_summary_json(summary(true));
  text.replace(text.find("\"rms_ratio\""), 11, "\"rms_ratio_\"");
  test::write_text(path, text);
  const std::string error = error_of([&] { read_drift_summary_json(path.string()); });
  EXPECT_NE(error.find("drift_summary.json: consistency[0].rms_ratio: missing"), std::string::npos)
      << error;
  test::write_text(path, "{\"recording\": 3}");
  EXPECT_NE(
      error_of([&] { read_drift_summary_json(path.string()); }).find("recording: is not a string"),
      std::string::npos);
  test::write_text(path, "{");
  EXPECT_NE(error_of([&] { read_drift_summary_json(path.string()); }).find("not valid JSON"),
            std::string::npos);
}

TEST(DriftBudgetCsv, RoundTripsEveryColumn) {
  pipeline::DriftBudget b;
  b.time_s = {60.0, 300.0};
  b.variance_m2 = {{1.0, 2.5, 3e-7, 0.25, 0.0, 1.0 / 3.0, 4e12},
                   {5.0, 6.0, 7.0, 7.5, 8.0, 9.0, 10.0}};
  b.predicted_variance_m2 = {4e12 + 6.75, 52.5};
  b.report_time = {true, false};
  const auto dir = test::make_temp_dir("drift-budget");
  const std::string path = (dir / "drift_budget.csv").string();
  write_drift_budget_csv(path, b);
  const std::string text = test::read_file_bytes(path);
  EXPECT_EQ(text, format_drift_budget_csv(b));
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "time_s,report_time,white_noise_variance_m2,bias_instability_variance_m2,"
            "random_walk_variance_m2,gauss_markov_variance_m2,ramp_variance_m2,"
            "alignment_variance_m2,heading_variance_m2,predicted_horizontal_variance_m2");
  const pipeline::DriftBudget r = read_drift_budget_csv(path);
  EXPECT_EQ(r.time_s, b.time_s);
  EXPECT_EQ(r.variance_m2, b.variance_m2);
  EXPECT_EQ(r.predicted_variance_m2, b.predicted_variance_m2);
  EXPECT_EQ(r.report_time, b.report_time);
  std::string flag = text;
  flag.replace(flag.find("\n60,1,") + 4, 1, "2");
  test::write_text(dir / "drift_budget.csv", flag);
  EXPECT_NE(error_of([&] { read_drift_budget_csv(path); }).find("report_time must be 0 or 1"),
            std::string::npos);
  std::string renamed = text;
  renamed.replace(renamed.find("ramp_variance_m2"), 4, "rmp_");
  test::write_text(dir / "drift_budget.csv", renamed);
  EXPECT_NE(error_of([&] { read_drift_budget_csv(path); }).find("ramp_variance_m2"),
            std::string::npos);
}

}  // namespace
}  // namespace imunoise::io
