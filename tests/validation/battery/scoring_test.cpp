/// @file
/// @brief Tests of the battery's scoring of Gauss–Markov terms (battery/scoring.h): a truth GM
/// the fit identifies is judged by its interval; one it does not identify by model.yaml's
/// `gauss_markov_upper_bound` curve, interpolated in (ln T_c, ln σ) between the curve's points
/// (docs/validation.md "Scoring"). The GM coverage of the closing notes rests on this rule.
#include "battery/scoring.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "battery/battery_cases.h"

namespace imunoise::battery {
namespace {

/// The gm class's gyro_y (one truth GM) and a model whose gyro_y holds AXIS.
struct GmCase {
  BatteryCase c = make_case("gm", BatterySize::reduced, 1);
  const ChannelTruth& truth() const { return c.truth[1]; }
  models::NoiseModel model_with(const models::AxisModel& axis) const {
    models::NoiseModel m;
    m.axes.push_back(axis);
    return m;
  }
};

models::AxisModel gyro_y() {
  models::AxisModel a;
  a.name = "gyro_y";
  a.kind = SensorKind::gyro;
  return a;
}

/// The gm_sigma and gm_tau_c rows of gyro_y.
std::pair<ScoreRow, ScoreRow> gm_rows(const BatteryCase& c, const models::NoiseModel& model) {
  std::vector<ChannelExtras> extras;
  ScoreRow sigma, tau;
  for (const ScoreRow& r : score_model(c, model, extras)) {
    if (r.channel != "gyro_y") continue;
    if (r.term == Coefficient::gm_sigma) sigma = r;
    if (r.term == Coefficient::gm_tau_c) tau = r;
  }
  return {sigma, tau};
}

TEST(BatteryScoring, AGaussMarkovNotIdentifiedIsJudgedOnTheBoundCurveAtItsCorrelationTime) {
  const GmCase g;
  ASSERT_EQ(g.truth().gauss_markov.size(), 1u);
  const double sigma = g.truth().gauss_markov[0].sigma;
  const double tau_c = g.truth().gauss_markov[0].tau_c_s;
  models::AxisModel axis = gyro_y();

  // No curve: not identified, no interval, not covered.
  auto [s0, t0] = gm_rows(g.c, g.model_with(axis));
  EXPECT_FALSE(s0.identified);
  EXPECT_FALSE(s0.has_interval);
  EXPECT_FALSE(s0.covered);
  EXPECT_FALSE(t0.covered);

  // A curve through (T_c/2, 2σ) and (2·T_c, 0.5σ): at T_c, halfway in ln T_c, the bound is σ
  // exactly (geometric mean), so a truth a hair below is covered and a hair above is not.
  axis.gauss_markov_bounds = {{tau_c / 2.0, 2.0 * sigma}, {2.0 * tau_c, 0.5 * sigma}};
  auto [s1, t1] = gm_rows(g.c, g.model_with(axis));
  EXPECT_FALSE(s1.identified);
  EXPECT_TRUE(s1.has_interval);
  EXPECT_NEAR(s1.ci_high / sigma, 1.0, 1e-12);
  EXPECT_EQ(s1.ci_low, 0.0);
  EXPECT_EQ(t1.ci_high, std::numeric_limits<double>::infinity());
  EXPECT_EQ(s1.covered, t1.covered);  // one joint statement, on both rows

  axis.gauss_markov_bounds = {{tau_c / 2.0, 2.02 * sigma}, {2.0 * tau_c, 0.505 * sigma}};
  auto [s2, t2] = gm_rows(g.c, g.model_with(axis));
  EXPECT_TRUE(s2.covered);
  EXPECT_TRUE(t2.covered);
  axis.gauss_markov_bounds = {{tau_c / 2.0, 1.98 * sigma}, {2.0 * tau_c, 0.495 * sigma}};
  auto [s3, t3] = gm_rows(g.c, g.model_with(axis));
  EXPECT_FALSE(s3.covered);
  EXPECT_FALSE(t3.covered);

  // A curve that does not reach the truth's T_c gives no bound.
  axis.gauss_markov_bounds = {{tau_c * 2.0, 10.0 * sigma}, {tau_c * 4.0, 10.0 * sigma}};
  EXPECT_FALSE(gm_rows(g.c, g.model_with(axis)).first.has_interval);
}

TEST(BatteryScoring, AnIdentifiedGaussMarkovIsJudgedByItsOwnIntervalNotTheCurve) {
  const GmCase g;
  const double sigma = g.truth().gauss_markov[0].sigma;
  const double tau_c = g.truth().gauss_markov[0].tau_c_s;
  models::AxisModel axis = gyro_y();
  // A fitted GM within ×3 of the truth's T_c whose σ interval misses the truth, beside a curve
  // that would cover it: the interval decides.
  models::GaussMarkovEstimate gm;
  gm.value = {2.0 * sigma, 1.5 * tau_c};
  gm.sigma_ci_low = 1.5 * sigma;
  gm.sigma_ci_high = 2.5 * sigma;
  gm.tau_c_ci_low_s = 0.5 * tau_c;
  gm.tau_c_ci_high_s = 2.0 * tau_c;
  axis.gauss_markov = {gm};
  axis.gauss_markov_bounds = {{tau_c / 2.0, 10.0 * sigma}, {2.0 * tau_c, 10.0 * sigma}};
  auto [s, t] = gm_rows(g.c, g.model_with(axis));
  EXPECT_TRUE(s.identified);
  EXPECT_FALSE(s.covered);
  EXPECT_TRUE(t.covered);
}

}  // namespace
}  // namespace imunoise::battery
