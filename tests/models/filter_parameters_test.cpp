// Tests of models/filter_parameters.h: the axis rules against hand-computed values, the
// conservative choice of interval ends, the B → GM scaling, and the overbound guarantee of
// fold_into_random_walk() checked against the closed-form AVAR of analysis/noise_terms.
#include "models/filter_parameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "analysis/noise_terms.h"
#include "common/errors.h"
#include "common/units.h"

namespace imunoise::models {
namespace {

Estimate estimate(double value, double low, double high) {
  Estimate e;
  e.value = value;
  e.ci_low = low;
  e.ci_high = high;
  e.identified = value > 0.0;
  return e;
}

/// An axis whose five terms are N, B, K (values ×SCALE) with intervals ±10 %/+20 %.
AxisModel axis(const std::string& name, SensorKind kind, double n, double b, double k) {
  AxisModel a;
  a.name = name;
  a.kind = kind;
  a.terms[static_cast<int>(NoiseTerm::white_noise)] = estimate(n, 0.9 * n, 1.1 * n);
  a.terms[static_cast<int>(NoiseTerm::bias_instability)] = estimate(b, 0.8 * b, 1.2 * b);
  a.terms[static_cast<int>(NoiseTerm::random_walk)] = estimate(k, 0.5 * k, 2.0 * k);
  a.terms[static_cast<int>(NoiseTerm::quantization)] = estimate(0.0, 0.0, 0.0);
  a.terms[static_cast<int>(NoiseTerm::ramp)] = estimate(0.0, 0.0, 0.0);
  a.tau_min_adev_s = 29.6;
  a.fit_tau_min_s = 0.01;
  a.fit_tau_max_s = 3000.0;
  return a;
}

/// The theory.md §8 gyro (N 0.4 deg/√h, B 25.2 deg/h, K 84.24 deg/h/√h) on x, and y, z
/// with other values so the axis rules give distinguishable answers.
NoiseModel example_model() {
  NoiseModel m;
  m.sample_rate_hz = 200.0;
  m.axes.push_back(axis("gyro_x", SensorKind::gyro, 1.16355e-4, 1.22173e-4, 6.80678e-6));
  m.axes.push_back(axis("gyro_y", SensorKind::gyro, 2.0e-4, 1.0e-4, 1.0e-6));
  m.axes.push_back(axis("gyro_z", SensorKind::gyro, 1.0e-4, 0.5e-4, 3.0e-6));
  m.axes.push_back(axis("accel_x", SensorKind::accel, 1.47e-3, 4.9e-4, 2.0e-5));
  m.axes.push_back(axis("accel_y", SensorKind::accel, 1.0e-3, 3.0e-4, 1.0e-5));
  m.axes.push_back(axis("accel_z", SensorKind::accel, 2.0e-3, 2.0e-4, 3.0e-5));
  m.axes[0].bias_instability_gm.push_back({"peak_match", {1.314e-4, 15.6}});  // §8.3 (b)
  return m;
}

FilterParameterOptions options(AxisChoice axis, bool conservative = false) {
  FilterParameterOptions o;
  o.axis = axis;
  o.conservative = conservative;
  o.filter_rate_hz = 200.0;
  return o;
}

TEST(FilterParameters, WorstTakesTheLargestOfEachCoefficient) {
  const auto p = select_filter_parameters(example_model(), options(AxisChoice::worst));
  ASSERT_TRUE(p.gyro && p.accel);
  const auto& g = p.gyro->one();
  EXPECT_DOUBLE_EQ(g.white_noise, 2.0e-4);           // y
  EXPECT_DOUBLE_EQ(g.bias_instability, 1.22173e-4);  // x
  EXPECT_DOUBLE_EQ(g.random_walk, 6.80678e-6);       // x
  EXPECT_DOUBLE_EQ(p.accel->one().white_noise, 2.0e-3);
  EXPECT_DOUBLE_EQ(p.accel->one().random_walk, 3.0e-5);
  // Best estimates: the RW-only pair is N, K unchanged.
  EXPECT_DOUBLE_EQ(g.rw_only_white_noise, 2.0e-4);
  EXPECT_DOUBLE_EQ(g.rw_only_random_walk, 6.80678e-6);
  // All three slots hold the same values.
  EXPECT_DOUBLE_EQ(p.gyro->axes[2].white_noise, 2.0e-4);
}

TEST(FilterParameters, MeanIsTheRootMeanSquare) {
  const auto p = select_filter_parameters(example_model(), options(AxisChoice::mean));
  const double n = std::sqrt((1.16355e-4 * 1.16355e-4 + 4e-8 + 1e-8) / 3.0);
  EXPECT_NEAR(p.gyro->one().white_noise, n, 1e-18);
  const double k = std::sqrt((6.80678e-6 * 6.80678e-6 + 1e-12 + 9e-12) / 3.0);
  EXPECT_NEAR(p.gyro->one().random_walk, k, 1e-20);
}

TEST(FilterParameters, SingleAxisAndEachAxis) {
  const auto y = select_filter_parameters(example_model(), options(AxisChoice::y));
  EXPECT_DOUBLE_EQ(y.gyro->one().white_noise, 2.0e-4);
  EXPECT_DOUBLE_EQ(y.accel->one().white_noise, 1.0e-3);
  EXPECT_EQ(y.gyro->one().from, "gyro_y");
  const auto each = select_filter_parameters(example_model(), options(AxisChoice::each));
  EXPECT_DOUBLE_EQ(each.gyro->axes[0].white_noise, 1.16355e-4);
  EXPECT_DOUBLE_EQ(each.gyro->axes[1].white_noise, 2.0e-4);
  EXPECT_DOUBLE_EQ(each.gyro->axes[2].white_noise, 1.0e-4);
  EXPECT_DOUBLE_EQ(each.accel->axes[2].random_walk, 3.0e-5);
}

TEST(FilterParameters, BiasAsGaussMarkovUsesTheStoredConversionOrComputesIt) {
  const auto x = select_filter_parameters(example_model(), options(AxisChoice::x));
  // gyro_x has the §8.3 (b) entry stored.
  EXPECT_DOUBLE_EQ(x.gyro->one().bias_gm.sigma, 1.314e-4);
  EXPECT_DOUBLE_EQ(x.gyro->one().bias_gm.tau_c_s, 15.6);
  // gyro_y has none: computed by convention (b), σ = B·0.664282/0.617364, T_c = 29.6/1.892618.
  const auto y = select_filter_parameters(example_model(), options(AxisChoice::y));
  EXPECT_NEAR(y.gyro->one().bias_gm.sigma, 1.0e-4 * 1.075996, 1.0e-4 * 1e-5);
  EXPECT_NEAR(y.gyro->one().bias_gm.tau_c_s, 29.6 / 1.892618, 1e-5);
  // Conservative: the upper B (1.2·B) scales the stored conversion.
  const auto xc = select_filter_parameters(example_model(), options(AxisChoice::x, true));
  EXPECT_NEAR(xc.gyro->one().bias_gm.sigma, 1.2 * 1.314e-4, 1e-18);
  EXPECT_DOUBLE_EQ(xc.gyro->one().bias_gm.tau_c_s, 15.6);
}

TEST(FilterParameters, ConservativeTakesUpperEndsAndFoldsByTheRule) {
  auto o = options(AxisChoice::x, true);
  o.correction_interval_s = 10.0;
  const auto p = select_filter_parameters(example_model(), o);
  const auto& g = p.gyro->one();
  EXPECT_DOUBLE_EQ(g.white_noise, 1.1 * 1.16355e-4);
  EXPECT_DOUBLE_EQ(g.bias_instability, 1.2 * 1.22173e-4);
  EXPECT_DOUBLE_EQ(g.random_walk, 2.0 * 6.80678e-6);
  // Hand computation of the rule: floor F = (2 ln2/π)·B_up², N'² = N_up² + F·T,
  // K'² = K_up² + 3F/T.
  const double floor = 2.0 * std::numbers::ln2 / std::numbers::pi * std::pow(1.2 * 1.22173e-4, 2);
  EXPECT_NEAR(g.rw_only_white_noise, std::sqrt(std::pow(1.1 * 1.16355e-4, 2) + floor * 10.0),
              1e-16);
  EXPECT_NEAR(g.rw_only_random_walk, std::sqrt(std::pow(2.0 * 6.80678e-6, 2) + 3.0 * floor / 10.0),
              1e-18);
  EXPECT_NE(p.rules.back().find("N'^2"), std::string::npos);
}

TEST(FilterParameters, GaussMarkovAvarIsBoundedByBothFoldLines) {
  // The two bounds the GM fold relies on: AVAR_GM ≤ 2σ²T_c/τ and ≤ (2/3)σ²τ/T_c.
  const double sigma = 2e-4, tc = 30.0;
  for (double tau = 1e-3; tau < 1e6; tau *= 1.3) {
    const double avar = analysis::gauss_markov_avar(sigma, tc, tau);
    EXPECT_LE(avar, 2.0 * sigma * sigma * tc / tau * (1 + 1e-12)) << tau;
    EXPECT_LE(avar, 2.0 / 3.0 * sigma * sigma * tau / tc * (1 + 1e-12)) << tau;
  }
}

TEST(FilterParameters, FoldOverboundsTheModelAvarEverywhereInItsRange) {
  NoiseCoefficients c;
  c.quantization = 2e-6;
  c.white_noise = 1.16355e-4;
  c.bias_instability = 1.22173e-4;
  c.random_walk = 6.80678e-6;
  c.ramp = 2e-8;
  c.gauss_markov = {{5e-5, 3.0}, {4e-5, 300.0}};  // one below, one above T
  const double rate = 200.0, t = 29.6, horizon = 5000.0;
  const auto fold = fold_into_random_walk(c, t, rate, horizon);
  double tightest = 1e300;
  for (double tau = 1.0 / rate; tau <= horizon; tau *= 1.05) {
    const double bound =
        fold.white_noise * fold.white_noise / tau + fold.random_walk * fold.random_walk * tau / 3.0;
    const double model = analysis::model_avar(c, tau);
    EXPECT_GE(bound, model) << "tau " << tau;
    tightest = std::min(tightest, bound / model);
  }
  // Not absurdly loose either: somewhere the bound is within a factor 3 of the model.
  EXPECT_LT(tightest, 3.0);
  // Without the optional terms the fold is the identity.
  NoiseCoefficients plain;
  plain.white_noise = 1e-4;
  plain.random_walk = 1e-6;
  const auto same = fold_into_random_walk(plain, t, rate, horizon);
  EXPECT_DOUBLE_EQ(same.white_noise, 1e-4);
  EXPECT_DOUBLE_EQ(same.random_walk, 1e-6);
}

TEST(FilterParameters, ErrorsNameTheProblem) {
  auto m = example_model();
  m.axes[1].name = "gyro_b";  // no gyro_y any more
  try {
    select_filter_parameters(m, options(AxisChoice::y));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no gyro axis named *_y"), std::string::npos);
  }
  m.axes.erase(m.axes.begin() + 2);
  EXPECT_THROW(select_filter_parameters(m, options(AxisChoice::each)), InputError);
  auto o = options(AxisChoice::worst);
  o.filter_rate_hz = 0.0;
  EXPECT_THROW(select_filter_parameters(example_model(), o), InputError);
  // A model without the τ of the ADEV minimum cannot convert B to a GM it has not stored.
  auto no_tau = example_model();
  no_tau.axes[1].tau_min_adev_s = 0.0;
  EXPECT_THROW(select_filter_parameters(no_tau, options(AxisChoice::y)), InputError);
}

TEST(FilterParameters, MissingSensorIsAbsentNotAnError) {
  auto m = example_model();
  m.axes.resize(3);  // gyro only
  const auto p = select_filter_parameters(m, options(AxisChoice::worst));
  EXPECT_TRUE(p.gyro.has_value());
  EXPECT_FALSE(p.accel.has_value());
}

TEST(FilterParameters, UpperBoundStandsInForATermNotIdentifiedWhenAsked) {
  auto m = example_model();
  // gyro_x: K and B not identified, bounded by 3e-6 and 2e-4; accel_x: B not identified with
  // a fitted GM, which stands for the bias instead of the bound.
  m.axes[0].terms[static_cast<int>(NoiseTerm::random_walk)] = estimate(0.0, 0.0, 3e-6);
  m.axes[0].terms[static_cast<int>(NoiseTerm::bias_instability)] = estimate(0.0, 0.0, 2e-4);
  m.axes[3].terms[static_cast<int>(NoiseTerm::bias_instability)] = estimate(0.0, 0.0, 1e-3);
  m.axes[3].gauss_markov.push_back({{2e-4, 50.0}, 1.5e-4, 2.5e-4, 40.0, 60.0});
  auto o = options(AxisChoice::x);
  const auto off = select_filter_parameters(m, o);  // default: 0 stays 0
  EXPECT_EQ(off.gyro->one().random_walk, 0.0);
  EXPECT_EQ(off.gyro->one().bias_instability, 0.0);
  ASSERT_EQ(off.gyro->one().unidentified.size(), 4u);  // Q, B, K, R
  for (const auto& u : off.gyro->one().unidentified) EXPECT_FALSE(u.substituted);
  o.upper_bound_when_not_identified = true;
  const auto on = select_filter_parameters(m, o);
  EXPECT_EQ(on.gyro->one().random_walk, 3e-6);
  EXPECT_EQ(on.gyro->one().rw_only_random_walk, 3e-6);
  EXPECT_EQ(on.gyro->one().bias_instability, 2e-4);
  // The GM form of the bound B: the stored (b) conversion scaled by 2e-4 / B (B = 0 here, so
  // computed afresh from τ of the ADEV minimum, 29.6 s): σ > 0 and T_c = 29.6/1.8926 s.
  EXPECT_GT(on.gyro->one().bias_gm.sigma, 0.0);
  EXPECT_NEAR(on.gyro->one().bias_gm.tau_c_s, 29.6 / 1.892618, 1e-3);
  int substituted = 0;
  for (const auto& u : on.gyro->one().unidentified) {
    EXPECT_EQ(u.axis, "gyro_x");
    if (u.substituted) ++substituted;
  }
  EXPECT_EQ(substituted, 2);                         // B and K (Q and R have no bound > 0 here)
  EXPECT_EQ(on.accel->one().bias_instability, 0.0);  // the GM stands for it
  EXPECT_EQ(on.accel->one().bias_gm.sigma, 2e-4);
  EXPECT_NE(on.rules[0].find("a term not identified: its upper bound"), std::string::npos);
}

}  // namespace
}  // namespace imunoise::models
