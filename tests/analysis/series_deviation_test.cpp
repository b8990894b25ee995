// Tests of analysis/series_deviation.h: a rate series and its phase give the same curve, the
// SP 1065 9-point set gives its published OADEV, the grid's factors are those of
// averaging_factors, and a series too short for the grid is an AnalysisError led by WHERE.
#include "analysis/series_deviation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::analysis {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

/// NIST SP 1065 §12.1, the 9-point fractional-frequency data set (NBS 9).
const std::vector<double> kNbs9{892, 809, 823, 798, 671, 644, 883, 903, 677};

TEST(SeriesDeviation, Nbs9RateGivesThePublishedOadev) {
  DeviationOptions options;
  options.type = DeviationType::oadev;
  TauGridSpec grid;
  grid.kind = TauGridSpec::Kind::explicit_list;
  grid.factors = {1, 2};
  const DeviationCurve curve = series_deviation(kNbs9, SeriesKind::kRate, 1.0, grid, options, "f");
  ASSERT_EQ(curve.points.size(), 2u);
  // SP 1065 Table 31: OADEV 91.22945 (m = 1), 85.95287 (m = 2).
  EXPECT_NEAR(curve.points[0].value, 91.22945, 91.22945 * 4e-7);
  EXPECT_NEAR(curve.points[1].value, 85.95287, 85.95287 * 4e-7);
  EXPECT_EQ(curve.n_phase, 10);
  EXPECT_EQ(curve.tau0_s, 1.0);
}

TEST(SeriesDeviation, PhaseOfTheRateGivesTheSameCurve) {
  const double tau0 = 0.5;
  const std::vector<double> phase = phase_from_rate(kNbs9, tau0);
  DeviationOptions options;
  options.type = DeviationType::mdev;
  const TauGridSpec grid = parse_tau_grid("octave");
  const DeviationCurve from_rate =
      series_deviation(kNbs9, SeriesKind::kRate, tau0, grid, options, "f");
  const DeviationCurve from_phase =
      series_deviation(phase, SeriesKind::kPhase, tau0, grid, options, "f");
  ASSERT_EQ(from_rate.points.size(), from_phase.points.size());
  ASSERT_FALSE(from_rate.points.empty());
  for (std::size_t i = 0; i < from_rate.points.size(); ++i) {
    EXPECT_EQ(from_rate.points[i].m, from_phase.points[i].m);
    EXPECT_NEAR(from_phase.points[i].value / from_rate.points[i].value, 1.0, 1e-12);
  }
  const std::vector<std::int64_t> factors = averaging_factors(grid, DeviationType::mdev, 10);
  ASSERT_EQ(from_rate.points.size(), factors.size());
  for (std::size_t i = 0; i < factors.size(); ++i) EXPECT_EQ(from_rate.points[i].m, factors[i]);
}

TEST(SeriesDeviation, TooShortForTheGridIsAnAnalysisErrorLedByWhere) {
  TauGridSpec grid;
  grid.kind = TauGridSpec::Kind::explicit_list;
  grid.factors = {100};
  try {
    series_deviation(kNbs9, SeriesKind::kRate, 1.0, grid, DeviationOptions{}, "nbs9.txt");
    ADD_FAILURE() << "no AnalysisError";
  } catch (const AnalysisError& e) {
    EXPECT_THAT(e.what(), StartsWith("nbs9.txt: "));
    EXPECT_THAT(e.what(), HasSubstr("too few samples for the requested tau"));
  }
}

TEST(SeriesDeviation, FewerValuesThanTheKindNeedsIsAContractViolation) {
  EXPECT_EQ(min_series_values(SeriesKind::kRate), 1u);
  EXPECT_EQ(min_series_values(SeriesKind::kPhase), 2u);
  const std::vector<double> one{1.0};
  EXPECT_THROW(series_deviation(one, SeriesKind::kPhase, 1.0, parse_tau_grid("octave"),
                                DeviationOptions{}, "f"),
               ContractViolation);
  EXPECT_THROW(series_deviation({}, SeriesKind::kRate, 1.0, parse_tau_grid("octave"),
                                DeviationOptions{}, "f"),
               ContractViolation);
}

}  // namespace
}  // namespace imunoise::analysis
