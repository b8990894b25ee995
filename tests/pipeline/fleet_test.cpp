// Tests of pipeline/fleet.h: the spec rule on the interval (pass / fail / undecided, and a term
// not identified never fails), the distribution of a term over the units (median, range, MAD
// of log10 against hand-computed values), the robust outlier rule (far in the fleet's spread
// and beyond the unit's own interval), the unit verdicts and the errors.
#include "pipeline/fleet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::pipeline {
namespace {

models::Estimate identified(double value, double low, double high) {
  return {value, low, high, true, "wnnls-oavar", ""};
}

/// A unit with one gyro axis whose N is VALUE with a ±1 % interval.
FleetUnit unit(const std::string& name, double n) {
  FleetUnit u;
  u.name = name;
  models::AxisModel a;
  a.name = "gyro_x";
  a.kind = SensorKind::gyro;
  a.terms[NoiseTerm::white_noise] = identified(n, 0.99 * n, 1.01 * n);
  a.terms[NoiseTerm::random_walk] = {0.0, 0.0, 1e-6, false, "", ""};
  u.model.axes.push_back(a);
  return u;
}

/// "u0", "u1", … (appended: GCC 12 raises a false -Wstringop-overflow on `"u" + to_string`).
std::string unit_name(int i) {
  std::string name = "u";
  name.append(std::to_string(i));
  return name;
}

TEST(FleetSpecRule, PassFailAndUndecidedByTheInterval) {
  EXPECT_EQ(judge_against_spec(identified(1.0, 0.9, 1.1), 1.2), SpecVerdict::pass);
  EXPECT_EQ(judge_against_spec(identified(1.0, 0.9, 1.1), 1.1), SpecVerdict::pass);  // ≤
  EXPECT_EQ(judge_against_spec(identified(1.0, 0.9, 1.1), 0.8), SpecVerdict::fail);
  EXPECT_EQ(judge_against_spec(identified(1.0, 0.9, 1.1), 0.9), SpecVerdict::undecided);
  EXPECT_EQ(judge_against_spec(identified(1.0, 0.9, 1.1), 1.0), SpecVerdict::undecided);
  // Not identified: [0, bound] — pass when the bound is below the maximum, else undecided.
  EXPECT_EQ(judge_against_spec({0.0, 0.0, 0.5, false, "", ""}, 1.0), SpecVerdict::pass);
  EXPECT_EQ(judge_against_spec({0.0, 0.0, 2.0, false, "", ""}, 1.0), SpecVerdict::undecided);
  EXPECT_EQ(judge_against_spec({0.0, 0.0, 0.0, false, "", ""}, 1.0), SpecVerdict::undecided);
}

TEST(Fleet, DistributionMedianRangeAndMadOfTheLog) {
  // log10 values 0, 0.1, 0.2, 0.3, 1.0: median 0.2, |dev| 0.2, 0.1, 0, 0.1, 0.8 → MAD 0.1;
  // σ = 1.4826·0.1; the last unit's modified z = 0.6745·0.8/0.1 = 5.396 > 3.5.
  std::vector<FleetUnit> units;
  const double logs[] = {0.0, 0.1, 0.2, 0.3, 1.0};
  for (int i = 0; i < 5; ++i) units.push_back(unit(unit_name(i), std::pow(10.0, logs[i])));
  const FleetResult r = analyze_fleet(units, std::nullopt);
  ASSERT_EQ(r.units.size(), 5u);
  EXPECT_EQ(r.entries.size(), 5u * 5u);
  EXPECT_TRUE(r.unit_verdicts.empty());
  const TermDistribution* n = nullptr;
  const TermDistribution* k = nullptr;
  for (const TermDistribution& d : r.distributions) {
    if (d.term == NoiseTerm::white_noise) n = &d;
    if (d.term == NoiseTerm::random_walk) k = &d;
  }
  ASSERT_NE(n, nullptr);
  EXPECT_EQ(n->units, 5u);
  EXPECT_EQ(n->identified, 5u);
  EXPECT_DOUBLE_EQ(n->median_si, std::pow(10.0, 0.2));
  EXPECT_DOUBLE_EQ(n->min_si, 1.0);
  EXPECT_DOUBLE_EQ(n->max_si, 10.0);
  EXPECT_NEAR(n->log10_spread, 1.4826 * 0.1, 1e-12);
  EXPECT_EQ(n->outliers, (std::vector<std::size_t>{4}));
  for (const FleetEntry& e : r.entries) {
    if (e.term != NoiseTerm::white_noise) {
      EXPECT_TRUE(std::isnan(e.robust_z));  // not identified
      EXPECT_FALSE(e.outlier);
      continue;
    }
    EXPECT_NEAR(e.robust_z, 0.6745 * (logs[e.unit] - 0.2) / 0.1, 1e-9) << e.unit;
    EXPECT_EQ(e.outlier, e.unit == 4);
  }
  ASSERT_NE(k, nullptr);
  EXPECT_EQ(k->identified, 0u);
  EXPECT_TRUE(k->outliers.empty());
}

TEST(Fleet, AFarUnitWhoseIntervalHoldsTheMedianIsNotAnOutlier) {
  std::vector<FleetUnit> units;
  const double logs[] = {0.0, 0.1, 0.2, 0.3, 1.0};
  for (int i = 0; i < 5; ++i) units.push_back(unit(unit_name(i), std::pow(10.0, logs[i])));
  // The far unit's estimate is uncertain: its interval reaches down past the median.
  units[4].model.axes[0].terms[NoiseTerm::white_noise] = identified(10.0, 1.0, 30.0);
  const FleetResult r = analyze_fleet(units, std::nullopt);
  for (const FleetEntry& e : r.entries) EXPECT_FALSE(e.outlier) << e.unit;
}

TEST(Fleet, UnitVerdictsAgainstTheSpec) {
  std::vector<FleetUnit> units{unit("low", 1.0), unit("high", 3.0), unit("edge", 2.0)};
  FleetSpec spec{"sheet", {{SensorKind::gyro, NoiseTerm::white_noise, 2.0}}};
  const FleetResult r = analyze_fleet(units, spec);
  ASSERT_EQ(r.unit_verdicts.size(), 3u);
  EXPECT_EQ(r.unit_verdicts[0], SpecVerdict::pass);
  EXPECT_EQ(r.unit_verdicts[1], SpecVerdict::fail);
  EXPECT_EQ(r.unit_verdicts[2], SpecVerdict::undecided);  // [1.98, 2.02] straddles 2
  // Only the spec's terms carry a maximum.
  for (const FleetEntry& e : r.entries) {
    EXPECT_EQ(e.spec_max_si.has_value(), e.term == NoiseTerm::white_noise);
    EXPECT_EQ(e.spec_verdict.has_value(), e.term == NoiseTerm::white_noise);
  }
  // A failing term wins over an undecided one.
  spec.limits.push_back({SensorKind::gyro, NoiseTerm::random_walk, 1e-7});  // bound 1e-6 > max
  const FleetResult both = analyze_fleet(units, spec);
  EXPECT_EQ(both.unit_verdicts[0], SpecVerdict::undecided);
  EXPECT_EQ(both.unit_verdicts[1], SpecVerdict::fail);
}

TEST(Fleet, NoUnitOrAUnitWithoutAxesIsAnInputError) {
  EXPECT_THROW(analyze_fleet({}, std::nullopt), InputError);
  std::vector<FleetUnit> units{FleetUnit{"empty", {}}};
  try {
    analyze_fleet(units, std::nullopt);
    FAIL() << "no throw";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("empty: the model has no axis"), std::string::npos);
  }
}

}  // namespace
}  // namespace imunoise::pipeline
