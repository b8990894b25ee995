// Tests of report/result_tables.h: each table puts a fact of the results in its row and column
// (SI and datasheet values side by side, "—" and "< bound" for a term not identified, the
// Gauss–Markov forms, the sampling quantities with their units and the gap factor, the drift
// checkpoints with their intervals), and leaves out what is not finite.
#include "report/result_tables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/number_text.h"
#include "ins/drift_prediction.h"
#include "models/datasheet_units.h"

namespace imunoise::report {
namespace {

/// The row of T whose first cells are FIRST and SECOND, or an empty row.
std::vector<std::string> row_of(const Table& t, const std::string& first,
                                const std::string& second = "") {
  for (const auto& row : t.rows) {
    if (row.at(0) == first && (second.empty() || row.at(1) == second)) return row;
  }
  return {};
}

models::NoiseModel gyro_model() {
  models::NoiseModel m;
  m.confidence = 0.9;
  models::AxisModel a;
  a.name = "gyro_x";
  a.kind = SensorKind::gyro;
  a.terms[NoiseTerm::white_noise] = {1e-4, 9e-5, 1.1e-4, true, "wnnls-oavar", ""};
  a.terms[NoiseTerm::random_walk] = {0.0, 0.0, 3e-7, false, "", ""};
  a.readoff.slope[NoiseTerm::white_noise] = 1.05e-4;
  a.bias_instability_gm = {{"peak_match", {2e-5, 30.0}}};
  a.gauss_markov = {{{5e-6, 100.0}, 4e-6, 6e-6, 80.0, 120.0}};
  m.axes = {a};
  return m;
}

TEST(SummaryTable, SiAndDatasheetValuesSitInTheirColumns) {
  const Table t = summary_table(gyro_model());
  EXPECT_EQ(t.id, "summary-table");
  ASSERT_EQ(t.header.size(), 10u);
  EXPECT_EQ(t.header[3], "90 % interval (SI)");
  EXPECT_EQ(t.rows.size(), 5u);  // one per term
  const auto n = row_of(t, "gyro_x", "N angle random walk");
  ASSERT_EQ(n.size(), 10u);
  const models::DatasheetUnit unit =
      models::datasheet_unit(NoiseTerm::white_noise, SensorKind::gyro);
  EXPECT_EQ(n[2], "0.0001");
  EXPECT_EQ(n[3], "[9e-05, 0.00011]");
  EXPECT_EQ(n[4], "rad/s^0.5");
  EXPECT_EQ(n[5], significant_number_text(1e-4 * unit.factor, 4));
  EXPECT_EQ(n[7], std::string(unit.unicode));
  EXPECT_EQ(n[8], significant_number_text(1.05e-4 * unit.factor, 4));
  EXPECT_EQ(n[9], "wnnls-oavar");
  // Not identified: no value, the interval as an upper bound, no read-off.
  const auto k = row_of(t, "gyro_x", "K rate random walk");
  ASSERT_EQ(k.size(), 10u);
  EXPECT_EQ(k[2], "—");
  EXPECT_EQ(k[3], "< 3e-07");
  EXPECT_EQ(k[8], "—");
  EXPECT_EQ(k[9], "not identified");
  EXPECT_EQ(row_of(t, "gyro_x", "Q quantization").at(3), "—");  // not even a bound
}

TEST(GaussMarkovTable, OneRowPerConventionAndPerFittedTerm) {
  const Table t = gauss_markov_table(gyro_model());
  EXPECT_EQ(t.id, "gauss-markov-table");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"gyro_x", "peak_match", "2e-05", "rad/s", "30"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"gyro_x", "fitted GM term", "5e-06 [4e-06, 6e-06]",
                                                 "rad/s", "100 [80, 120]"}));
  EXPECT_TRUE(gauss_markov_table(models::NoiseModel{}).rows.empty());
}

TEST(SamplingTable, QuantitiesWithUnitsAndTheGapFactor) {
  pipeline::SamplingReport r;
  r.samples = 360000;
  r.rows_dropped = 2;
  r.timing.has_timestamps = true;
  r.timing.rate_hz = 100.0;
  r.timing.mean_rate_hz = 99.99;
  r.timing.duration_s = 3600.0;
  r.timing.gap_count = 3;
  r.timing.longest_gap_s = 0.25;
  r.timing.jitter_rms_s = std::nan("");  // not finite: left out
  const Table t = sampling_table(r);
  EXPECT_EQ(t.id, "sampling-table");
  EXPECT_EQ(row_of(t, "samples").at(1), "360000");
  EXPECT_EQ(row_of(t, "sample rate (1 / median interval)").at(1), "100 Hz");
  EXPECT_EQ(row_of(t, "mean rate").at(1), "99.99 Hz");
  EXPECT_EQ(row_of(t, "duration").at(1), "3600 s");
  EXPECT_EQ(row_of(t, "gaps (> " + shortest_number_text(kGapFactor) + " × median interval)").at(1),
            "3");
  EXPECT_EQ(row_of(t, "gaps (> 1.5 × median interval)").at(1), "3");  // the text as it reads
  EXPECT_EQ(row_of(t, "longest gap").at(1), "0.25 s");
  EXPECT_EQ(row_of(t, "rows dropped (NaN/Inf)").at(1), "2");
  EXPECT_TRUE(row_of(t, "interval jitter, RMS").empty());
  EXPECT_EQ(t.rows.size(), 11u);
}

TEST(DriftTable, OneRowPerCheckpointWithItsIntervals) {
  pipeline::DriftSummary s;
  pipeline::DriftConsistency c;
  c.time_s = 60.0;
  c.predicted_drms_m = 1.5;
  c.actual_rms_m = 2.0;
  c.rms_ratio = 4.0 / 3.0;
  c.rms_ratio_ci_low = 1.1;
  c.rms_ratio_ci_high = std::numeric_limits<double>::quiet_NaN();  // null in the file
  c.coverage = {0.25, 0.75, 1.0};
  c.mean_nees = 2.5;
  c.nees_band_low = 1.5;
  c.nees_band_high = 2.75;
  s.consistency = {c};
  const Table t = drift_table(s);
  EXPECT_EQ(t.id, "drift-table");
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"60", "1.5", "2", "1.33", "0.25 / 0.75 / 1",
                                                 "0.39 / 0.86 / 0.99", "2.5 [1.5, 2.75]"}));
}

/// A budget of a real prediction (every source acting, aligned, heading σ), rows at 30, 60,
/// 300 and 600 s with the last three flagged report times.
pipeline::DriftBudget predicted_budget() {
  ins::SensorAxisNoise gyro, accel;
  gyro.white_noise = 1e-4;
  gyro.random_walk = 3e-7;
  gyro.gm_terms = {{2e-5, 30.0}, {5e-6, 300.0}};
  gyro.bias_instability_terms = 1;
  gyro.ramp = 1e-8;
  accel.white_noise = 1e-3;
  accel.random_walk = 5e-5;
  accel.gm_terms = {{2e-4, 100.0}};
  ins::InsSensorNoise noise;
  noise.gyro = {gyro, gyro, gyro};
  noise.accel = {accel, accel, accel};
  ins::DriftPredictionOptions o;
  o.alignment_time_s = 60.0;
  o.heading_sigma_rad = 0.01;
  o.times_s = {30.0, 60.0, 300.0, 600.0};
  o.budget = true;
  const ins::DriftPrediction p = ins::predict_stationary_drift(noise, o);
  pipeline::DriftBudget b;
  b.time_s = p.time_s;
  b.variance_m2 = p.horizontal_variance_budget_m2;
  for (const double d : p.horizontal_drms_m) b.predicted_variance_m2.push_back(d * d);
  b.report_time = {false, true, true, true};
  return b;
}

TEST(DriftBudgetTable, ContributionsSumToThePredictedVariance) {
  const pipeline::DriftBudget b = predicted_budget();
  const Table t = drift_budget_table(b);
  EXPECT_EQ(t.id, "drift-budget-table");
  ASSERT_EQ(t.header.size(), 1u + 2u * 3u);  // source, then σ and share per report time
  EXPECT_EQ(t.header[1], "σ at 60 s [m]");
  EXPECT_EQ(t.header[6], "share at 600 s [%]");
  ASSERT_EQ(t.rows.size(), ins::kDriftBudgetTerms + 1);
  std::vector<std::string> sources;
  for (const auto& row : t.rows) sources.push_back(row.at(0));
  EXPECT_EQ(sources, (std::vector<std::string>{"N", "B", "K", "GM", "R", "alignment", "heading",
                                               "total (predicted DRMS)"}));
  for (std::size_t k = 0; k < 3; ++k) {
    // The cells as printed (4 significant digits): the σ add in quadrature to the DRMS the
    // prediction gives, the shares add to 100 %, each to the rounding of its cells.
    const double drms = std::sqrt(b.predicted_variance_m2[k + 1]);
    double variance = 0.0, share = 0.0;
    for (std::size_t g = 0; g < ins::kDriftBudgetTerms; ++g) {
      const double sigma = std::stod(t.rows[g].at(1 + 2 * k));
      variance += sigma * sigma;
      share += std::stod(t.rows[g].at(2 + 2 * k));
      EXPECT_GT(sigma, 0.0) << t.rows[g][0] << " at report time " << k;  // every source acts
    }
    EXPECT_NEAR(std::sqrt(variance) / drms, 1.0, 1e-3) << k;
    EXPECT_NEAR(share, 100.0, 7 * 0.05) << k;
    EXPECT_NEAR(std::stod(t.rows.back().at(1 + 2 * k)) / drms, 1.0, 1e-3);
    EXPECT_EQ(t.rows.back().at(2 + 2 * k), "100");
  }
  pipeline::DriftBudget none = b;
  none.report_time.assign(b.time_s.size(), false);
  EXPECT_TRUE(drift_budget_table(none).rows.empty());
}

TEST(NumberCell, SignificantDigitsOrADashWhenNotFinite) {
  EXPECT_EQ(number_cell(1.23456789), "1.235");
  EXPECT_EQ(number_cell(1.23456789, 6), "1.23457");
  EXPECT_EQ(number_cell(std::nan("")), "—");
  EXPECT_EQ(number_cell(std::numeric_limits<double>::infinity()), "—");
}

}  // namespace
}  // namespace imunoise::report
