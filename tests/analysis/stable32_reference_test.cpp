// Stable32 result tables (allantools test suite copies, ../shared/data/allantools-stable32):
// every row of the seven basic statistics, values at 1e-4 relative (5 printed digits), the
// number of terms exactly, and the 68.3 % bounds at 1e-3 relative with the table's alpha.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "analysis/deviation.h"
#include "analysis/tau_grid.h"
#include "stable32_tables.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

using test::Stable32Row;

/// Checks every row of a data set. VALUE_TOL: relative tolerance on sigma; BOUNDS: whether to
/// check the confidence bounds (at 1e-3 relative, the table's alpha forced).
struct CheckResult {
  int rows = 0;
  int bound_rows = 0;
  double max_value_error = 0.0;
  double max_bound_error = 0.0;
};

CheckResult check_table(const std::vector<Stable32Row>& rows, std::span<const double> series,
                        bool series_is_phase, double value_tol, bool check_bounds,
                        const std::set<std::string>& only_files = {}) {
  CheckResult result;
  std::map<double, std::vector<double>> phase_by_tau0;
  for (const auto& row : rows) {
    if (!only_files.empty() && !only_files.count(row.source_file)) continue;
    const double tau0 = row.tau_s / static_cast<double>(row.m);
    auto& phase = phase_by_tau0[tau0];
    if (phase.empty()) {
      phase = series_is_phase ? std::vector<double>(series.begin(), series.end())
                              : phase_from_rate(series, tau0);
    }
    const auto M = static_cast<std::int64_t>(phase.size());
    const auto v = allan_family_variance(row.type, phase, row.m, tau0);
    const double value = std::sqrt(v.variance);
    const double err = std::abs(value / row.sigma - 1.0);
    result.max_value_error = std::max(result.max_value_error, err);
    EXPECT_LE(err, value_tol) << row.source_file << " m=" << row.m << " value " << value
                              << " table " << row.sigma;
    EXPECT_EQ(v.n_terms, row.n_terms) << row.source_file << " m=" << row.m;
    ++result.rows;
    if (check_bounds && row.ci_given) {
      DeviationOptions options;
      options.type = row.type;
      options.alpha = row.alpha;
      options.threads = 1;
      const std::int64_t factors[] = {row.m};
      if (row.m > max_averaging_factor(row.type, M)) {
        ADD_FAILURE() << row.source_file << " m=" << row.m << " beyond the stop ratio";
        continue;
      }
      const auto curve = compute_deviation(phase, tau0, factors, options);
      const auto& p = curve.points.at(0);
      const double lo_err = std::abs(p.ci_low / row.sigma_min - 1.0);
      const double hi_err = std::abs(p.ci_high / row.sigma_max - 1.0);
      result.max_bound_error = std::max({result.max_bound_error, lo_err, hi_err});
      EXPECT_LE(lo_err, 1e-3) << row.source_file << " m=" << row.m << " alpha=" << row.alpha
                              << " ci_low " << p.ci_low << " table " << row.sigma_min << " edf "
                              << p.edf;
      EXPECT_LE(hi_err, 1e-3) << row.source_file << " m=" << row.m << " alpha=" << row.alpha
                              << " ci_high " << p.ci_high << " table " << row.sigma_max << " edf "
                              << p.edf;
      ++result.bound_rows;
    }
  }
  return result;
}

TEST(Stable32, MatchesPhasedatTables) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto dir = data / "allantools-stable32" / "phasedat";
  const auto phase = test::read_number_lines(dir / "PHASE.DAT");
  ASSERT_EQ(phase.size(), 1001u);
  const auto result =
      check_table(test::load_stable32_rows(dir / "expected_stable32.csv"), phase, true, 1e-4, true);
  EXPECT_GT(result.rows, 900);
  EXPECT_GT(result.bound_rows, 50);
  RecordProperty("max_value_error", std::to_string(result.max_value_error));
  RecordProperty("max_bound_error", std::to_string(result.max_bound_error));
}

TEST(Stable32, MatchesPinkFrequencyTables) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto dir = data / "allantools-stable32" / "pink_frequency";
  const auto y = test::read_number_lines(dir / "pink_frequency.txt");
  ASSERT_EQ(y.size(), 10000u);
  const auto result =
      check_table(test::load_stable32_rows(dir / "expected_stable32.csv"), y, false, 1e-4, true);
  EXPECT_GT(result.rows, 1400);
  EXPECT_GT(result.bound_rows, 10);
}

TEST(Stable32, MatchesKeysightTimeIntervalNoiseFloorTables) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto dir = data / "allantools-stable32" / "Keysight53230A_ti_noise_floor";
  const auto phase = test::read_number_lines(dir / "tic_phase.txt");
  ASSERT_EQ(phase.size(), 55688u);
  const auto result =
      check_table(test::load_stable32_rows(dir / "expected_stable32.csv"), phase, true, 1e-4, true);
  EXPECT_GT(result.rows, 340);
}

std::vector<double> ocxo_fractional_frequency(const std::filesystem::path& dir) {
  // Absolute frequency in Hz around 10 MHz → y = (f − 1e7)/1e7 (PROVENANCE.md pitfall):
  // subtracting first keeps the 15 printed digits.
  auto f = test::read_number_lines(dir / "ocxo_frequency.txt");
  for (double& v : f) v = (v - 1e7) / 1e7;
  return f;
}

TEST(Stable32, MatchesOcxoAllTauTables) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto dir = data / "allantools-stable32" / "ocxo";
  const auto y = ocxo_fractional_frequency(dir);
  ASSERT_EQ(y.size(), 19982u);
  const std::set<std::string> all_tau = {"stable32_adev_alltau.txt",  "stable32_oadev_alltau.txt",
                                         "stable32_mdev_alltau.txt",  "stable32_tdev_alltau.txt",
                                         "stable32_hdev_alltau.txt",  "stable32_ohdev_alltau.txt",
                                         "stable32_totdev_alltau.txt"};
  const auto result = check_table(test::load_stable32_rows(dir / "expected_stable32.csv"), y, false,
                                  1e-4, false, all_tau);
  EXPECT_GT(result.rows, 1900);
}

// The OCXO octave tables were computed by Stable32 on data normalised to 1.0 (f/1e7), so
// their last digits carry that run's round-off (PROVENANCE.md: up to 1.8e-3, TOTDEV up to
// 1.2e-2 at m ≥ 256). The values are checked at the 2e-3 the provenance documents for the
// non-TOTDEV tables; the strict check of these statistics is the all-tau test above.
TEST(Stable32, MatchesOcxoOctaveTablesWithinTheirDocumentedRoundOff) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto dir = data / "allantools-stable32" / "ocxo";
  const auto y = ocxo_fractional_frequency(dir);
  const std::set<std::string> octave = {"adev_octave.txt", "oadev_octave.txt", "mdev_octave.txt",
                                        "tdev_octave.txt", "hdev_octave.txt",  "ohdev_octave.txt"};
  const auto result = check_table(test::load_stable32_rows(dir / "expected_stable32.csv"), y, false,
                                  2e-3, false, octave);
  EXPECT_GT(result.rows, 70);
}

}  // namespace
}  // namespace imunoise::analysis
