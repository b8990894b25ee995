/// @file
/// @brief Tests of analysis/slope_readoff.h on exact closed-form ADEV curves (theory.md §4.1)
/// and on the worked example of §8, where the read-off's known bias (§4.2) must show.
#include "analysis/slope_readoff.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "analysis/noise_terms.h"
#include "common/errors.h"
#include "common/units.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

/// τ = 10^(k/10) s for k = −20 … 40: 0.01 s … 10⁴ s, 10 points per decade.
std::vector<double> log_grid() {
  std::vector<double> tau;
  for (int k = -20; k <= 40; ++k) tau.push_back(std::pow(10.0, k / 10.0));
  return tau;
}

std::vector<double> adev_of(const NoiseCoefficients& model, const std::vector<double>& tau) {
  std::vector<double> adev;
  for (double t : tau) adev.push_back(model_adev(model, t));
  return adev;
}

const SlopeReadoffTerm& term_of(const SlopeReadoff& r, NoiseTerm term) { return r[term]; }

TEST(SlopeReadoff, RecoversEachSingleTermExactly) {
  const std::vector<double> tau = log_grid();
  const std::array<double, 5> values = {3e-5, 2e-4, 5e-5, 7e-6, 4e-8};  // Q N B K R, SI
  for (NoiseTerm term : kNoiseTerms) {
    NoiseCoefficients model;
    const double value = values[static_cast<std::size_t>(term)];
    switch (term) {
      case NoiseTerm::quantization:
        model.quantization = value;
        break;
      case NoiseTerm::white_noise:
        model.white_noise = value;
        break;
      case NoiseTerm::bias_instability:
        model.bias_instability = value;
        break;
      case NoiseTerm::random_walk:
        model.random_walk = value;
        break;
      case NoiseTerm::ramp:
        model.ramp = value;
        break;
    }
    const SlopeReadoff r = slope_readoff(tau, adev_of(model, tau));
    for (NoiseTerm other : kNoiseTerms) {
      const SlopeReadoffTerm& t = term_of(r, other);
      if (other == term) {
        EXPECT_TRUE(t.found) << term_name(term);
        EXPECT_NEAR(t.value / value, 1.0, 1e-9) << term_name(term);
        EXPECT_EQ(t.points, tau.size()) << term_name(term);
        EXPECT_EQ(t.tau_low_s, tau.front());
        EXPECT_EQ(t.tau_high_s, tau.back());
      } else {
        EXPECT_FALSE(t.found) << term_name(other) << " in a pure " << term_name(term) << " curve";
        EXPECT_EQ(t.value, 0.0);
      }
    }
  }
}

TEST(SlopeReadoff, FloorReadoffOverestimatesBiasInstabilityInTheWorkedExample) {
  // theory.md §8.2 model; §4.2: "the flat floor is lifted by N and K (example §8: floor
  // 0.00496 vs 0.664B = 0.00465 deg/s)".
  NoiseCoefficients model;
  model.white_noise = 1.16355e-4;
  model.bias_instability = 1.22173e-4;
  model.random_walk = 6.80678e-6;
  const std::vector<double> tau = log_grid();
  const SlopeReadoff r = slope_readoff(tau, adev_of(model, tau));
  ASSERT_TRUE(r[NoiseTerm::bias_instability].found);
  const double floor_factor = std::sqrt(2.0 * std::log(2.0) / units::kPi);
  const double floor_deg = r[NoiseTerm::bias_instability].value * floor_factor / units::kDegPerS;
  EXPECT_NEAR(floor_deg, 0.00496, 0.000005);
  EXPECT_NEAR(model.bias_instability * floor_factor / units::kDegPerS, 0.00465, 0.000005);
  EXPECT_GT(r[NoiseTerm::bias_instability].value / model.bias_instability, 1.06);  // +6.7 % here
  // The zero-slope region brackets τ_min = 29.6 s.
  EXPECT_LT(r[NoiseTerm::bias_instability].tau_low_s, 29.6);
  EXPECT_GT(r[NoiseTerm::bias_instability].tau_high_s, 29.6);
  // N and K are found, each lifted by the floor in its own region (§4.2 inconsistency).
  ASSERT_TRUE(r[NoiseTerm::white_noise].found);
  ASSERT_TRUE(r[NoiseTerm::random_walk].found);
  EXPECT_GT(r[NoiseTerm::white_noise].value, model.white_noise);
  EXPECT_LT(r[NoiseTerm::white_noise].value, 1.1 * model.white_noise);
  EXPECT_GT(r[NoiseTerm::random_walk].value, model.random_walk);
  EXPECT_LT(r[NoiseTerm::random_walk].value, 1.3 * model.random_walk);
  EXPECT_FALSE(r[NoiseTerm::quantization].found);
  EXPECT_FALSE(r[NoiseTerm::ramp].found);
}

TEST(SlopeReadoff, RejectsBadInput) {
  const std::vector<double> tau = {1.0, 2.0, 4.0};
  test::expect_throw_containing<ContractViolation>(
      [&] {
        slope_readoff(tau, std::vector<double>{1.0, 2.0});
      },
      "3 tau values but 2");
  test::expect_throw_containing<AnalysisError>(
      [&] {
        slope_readoff(std::vector<double>{1.0, 2.0}, std::vector<double>{1.0, 2.0});
      },
      "at least 3 points");
  test::expect_throw_containing<ContractViolation>(
      [&] {
        slope_readoff(std::vector<double>{1.0, 4.0, 2.0}, std::vector<double>{1, 1, 1});
      },
      "strictly increasing");
  test::expect_throw_containing<AnalysisError>(
      [&] {
        slope_readoff(tau, std::vector<double>{1.0, 0.0, 1.0});
      },
      "deviation > 0");
}

}  // namespace
}  // namespace imunoise::analysis
