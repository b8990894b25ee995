// Lag-1 ACF noise identification [RG04] on simulated power-law noise of known type and on
// the Stable32 reference data, whose tables print the alpha Stable32 identified.
//
// Why the fixed seeds cannot fail by chance: the decision variable is 2δ (δ = r₁/(1+r₁) at
// the final difference order), rounded to the nearest integer. Over 40 seeds per case at
// n = 2^17 (scratch study) its mean and standard deviation were, for the cases used here:
//   white PM / white FM, any m ≤ 16: mean 0.00, sd ≤ 2/√N (N decimated points) → > 20 sd
//   flicker PM m = 1, 2, 4: −1.00, −1.18, −1.32, sd 0.011–0.024 → ≥ 7.5 sd from −1.5
//   flicker FM m = 1, 2, 4: −1.00, −0.74, −0.62, sd 0.011–0.015 → ≥ 8 sd from −0.5
//   RW FM m = 1, 4, 16: 0.00, 0.37, 0.40, sd 0.005–0.014 → ≥ 7 sd from 0.5
// so a misidentification needs a ≥ 7-sigma excursion (p < 1e-11 per case). Larger m is not
// used for the flicker types on purpose: decimating phase aliases flicker PM towards white
// PM (2δ → −1.5 by m ≈ 16), and flicker FM tends to the continuous-time value 2δ = −0.554
// (GR03 s_z with F = ∞), only 0.054 from the RW FM boundary — an inherent limit of [RG04].
#include "analysis/noise_id.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "common/errors.h"
#include "models/power_law_noise.h"
#include "test_support.h"

namespace imunoise::analysis {
namespace {

using ::testing::HasSubstr;

/// Phase x_0 = 0, x_{k+1} = x_k + y_k (τ0 = 1).
std::vector<double> phase_from_frequency(const std::vector<double>& y) {
  std::vector<double> x(y.size() + 1, 0.0);
  for (std::size_t k = 0; k < y.size(); ++k) x[k + 1] = x[k] + y[k];
  return x;
}

TEST(NoiseId, IdentifiesSimulatedPowerLawNoiseAtSeveralAveragingFactors) {
  struct Case {
    int alpha;
    std::vector<std::int64_t> factors;
  };
  const std::vector<Case> cases = {
      {2, {1, 4, 16}}, {1, {1, 2, 4}}, {0, {1, 4, 16}}, {-1, {1, 2, 4}}, {-2, {1, 4, 16}}};
  for (const Case& c : cases) {
    const auto phase = phase_from_frequency(
        models::power_law_noise(c.alpha, std::size_t{1} << 17, 7000 + 13 * (c.alpha + 2)));
    for (const std::int64_t m : c.factors) {
      EXPECT_EQ(lag1_noise_alpha(phase, m, 2), c.alpha) << "alpha=" << c.alpha << " m=" << m;
      // Hadamard depth changes nothing for alpha ≥ −2: δ < 0.25 is reached by d = 2.
      EXPECT_EQ(lag1_noise_alpha(phase, m, 3), c.alpha) << "alpha=" << c.alpha << " m=" << m;
      EXPECT_EQ(noise_alpha_for(DeviationType::oadev, phase, m), c.alpha);
    }
  }
}

TEST(NoiseId, SeparatesWhiteFmFromRandomWalkFmAtLargeM) {
  // ARW + rate random walk, the usual gyro pair: white FM h0 = 1 and RW FM with the AVAR
  // crossover h0/(2τ) = (2π)² h₋₂ τ/6 at τc = 16 samples. Short τ must read white FM (0),
  // long τ RW FM (−2). Scratch study (12 seeds, n = 2^21): 2δ = −1.98, −1.91, −1.68 at
  // m = 1, 2, 4 (sd ≤ 0.006, boundary −1.5/−2.5) and 0.385, 0.393 at m = 128, 256 (sd 0.007,
  // 0.009; boundary 0.5); at n = 2^20 the sd grow by √2, margins stay ≥ 8 sd.
  const std::size_t n = std::size_t{1} << 20;
  const double tau_c = 16.0;
  const double h_rw = 3.0 / (4.0 * std::numbers::pi * std::numbers::pi * tau_c * tau_c);
  const auto white = models::power_law_noise(0, n, 4242, 1.0);
  const auto walk = models::power_law_noise(-2, n, 4343, h_rw);
  std::vector<double> y(n);
  for (std::size_t k = 0; k < n; ++k) y[k] = white[k] + walk[k];
  const auto phase = phase_from_frequency(y);
  for (const std::int64_t m : {1, 2, 4}) {
    EXPECT_EQ(noise_alpha_for(DeviationType::oadev, phase, m), 0) << "m=" << m;
  }
  for (const std::int64_t m : {128, 256}) {
    EXPECT_EQ(noise_alpha_for(DeviationType::oadev, phase, m), -2) << "m=" << m;
    EXPECT_EQ(noise_alpha_for(DeviationType::hdev, phase, m), -2) << "m=" << m;
  }
}

TEST(NoiseId, MatchesStable32AlphasWhereThirtyPointsExist) {
  // Stable32 prints the alpha it identified (lag-1 ACF with ≥ 30 points [RG04]); ours must be
  // the same on the same data. OCXO: every m ≤ 512 of its ADEV/MDEV/HDEV/OHDEV octave tables
  // (19983 phase points); pink_frequency (tau0 = 1 run): m ≤ 256; PHASE.DAT: m ≤ 32 (all 0).
  IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
  const auto base = dir / "allantools-stable32";
  struct Set {
    const char* folder;
    const char* data_file;
    bool is_frequency;
    double offset_scale;  // y = (f − offset)/offset for absolute frequency, else 0
  };
  for (const Set& set : {Set{"ocxo", "ocxo_frequency.txt", true, 1e7},
                         Set{"pink_frequency", "pink_frequency.txt", true, 0.0},
                         Set{"phasedat", "PHASE.DAT", false, 0.0}}) {
    auto values = test::read_number_lines(base / set.folder / set.data_file);
    if (set.offset_scale > 0.0) {
      for (double& v : values) v = (v - set.offset_scale) / set.offset_scale;
    }
    const auto phase = set.is_frequency ? phase_from_frequency(values) : values;
    const auto rows = test::read_csv_rows(base / set.folder / "expected_stable32.csv");
    int checked = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const auto& r = rows[i];
      if (r[11] != "yes") continue;
      const std::string type = r[0];
      const bool hadamard = type == "Hadamard" || type == "Overlapping Hadamard";
      // The six GR03 statistics: TOTDEV repeats the same alphas, and the other PHASE.DAT
      // tables (HTOTDEV, MTOTDEV, …) were run on other input files.
      if (!hadamard && type != "Allan" && type != "Overlapping Allan" && type != "Modified Allan" &&
          type != "Time") {
        continue;
      }
      const std::int64_t m = std::stoll(r[4]);
      const auto alpha = lag1_noise_alpha(phase, m, hadamard ? 3 : 2);
      if (!alpha) continue;  // < 30 points: Stable32 uses other estimators there
      EXPECT_EQ(*alpha, std::stoi(r[7])) << set.folder << " " << r[1] << " m=" << m;
      ++checked;
    }
    EXPECT_GE(checked, 9) << set.folder;
  }
}

TEST(NoiseId, HadamardDepthIdentifiesRandomRunFm) {
  // Random-run FM (alpha = −4): y = running sum of RW FM. With d_max = 3 the third difference
  // is white (2δ ≈ 0 ± 0.01 at 65537 points); with d_max = 2 the second difference is a
  // random walk (r₁ → 1, 2δ → 1) and the estimate is −3, clamped to −2 for Allan types.
  const auto rw = models::power_law_noise(-2, std::size_t{1} << 16, 99);
  std::vector<double> run(rw.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < rw.size(); ++k) run[k] = (sum += rw[k]);
  const auto phase = phase_from_frequency(run);
  EXPECT_EQ(lag1_noise_alpha(phase, 1, 3), -4);
  EXPECT_EQ(lag1_noise_alpha(phase, 1, 2), -3);
  EXPECT_EQ(noise_alpha_for(DeviationType::ohdev, phase, 1), -4);
  EXPECT_EQ(noise_alpha_for(DeviationType::oadev, phase, 1), -2);
  EXPECT_EQ(noise_alpha_for(DeviationType::totdev, phase, 1), -2);
}

TEST(NoiseId, ClampsBluerThanWhitePmToTwo) {
  // Phase = first difference of white noise: r₁ = −1/2, δ = −1, estimate 4 → clamped to 2.
  const auto w = models::power_law_noise(0, 20001, 5);
  std::vector<double> phase(w.size() - 1);
  for (std::size_t k = 0; k + 1 < w.size(); ++k) phase[k] = w[k + 1] - w[k];
  EXPECT_EQ(lag1_noise_alpha(phase, 1, 2), 4);
  EXPECT_EQ(noise_alpha_for(DeviationType::mdev, phase, 1), 2);
}

TEST(NoiseId, ReturnsNulloptBelowThirtyPoints) {
  const auto phase = phase_from_frequency(models::power_law_noise(0, 58, 3));    // M = 59
  EXPECT_TRUE(lag1_noise_alpha(phase, 2, 2).has_value());                        // 30 points
  EXPECT_FALSE(lag1_noise_alpha(std::span(phase).first(58), 2, 2).has_value());  // 29
  EXPECT_FALSE(lag1_noise_alpha({}, 1, 2).has_value());
}

TEST(NoiseId, FallsBackToLargestFactorWithThirtyPoints) {
  // M = 4097: m = 1000 has 5 decimated points; the fallback factor is ⌊4096/29⌋ = 141 (30
  // points; 142 has 29).
  const auto phase = phase_from_frequency(models::power_law_noise(-2, 4096, 11));
  ASSERT_FALSE(lag1_noise_alpha(phase, 142, 2).has_value());
  const auto at_fallback = lag1_noise_alpha(phase, 141, 2);
  ASSERT_TRUE(at_fallback.has_value());
  EXPECT_EQ(noise_alpha_for(DeviationType::oadev, phase, 1000), std::clamp(*at_fallback, -2, 2));
  // Fewer than 30 points even at m = 1: white FM by convention.
  const auto tiny = phase_from_frequency(models::power_law_noise(-2, 20, 11));
  EXPECT_EQ(noise_alpha_for(DeviationType::oadev, tiny, 1), 0);
}

TEST(NoiseId, NoiselessQuadraticPhaseIsNotIdentified) {
  std::vector<double> phase(500);
  for (std::size_t k = 0; k < phase.size(); ++k) {
    const double t = static_cast<double>(k);
    phase[k] = 3.0 + 2e-3 * t + 5e-7 * t * t;  // frequency offset and drift only
  }
  EXPECT_FALSE(lag1_noise_alpha(phase, 1, 2).has_value());
  EXPECT_EQ(noise_alpha_for(DeviationType::adev, phase, 4), 0);
}

TEST(NoiseId, RejectsInvalidArguments) {
  const std::vector<double> phase(100, 0.0);
  try {
    lag1_noise_alpha(phase, 0, 2);
    ADD_FAILURE() << "no throw";
  } catch (const ContractViolation& e) {
    EXPECT_THAT(e.what(), HasSubstr("lag1_noise_alpha: m must be >= 1 (got 0)"));
  }
  try {
    lag1_noise_alpha(phase, 1, 4);
    ADD_FAILURE() << "no throw";
  } catch (const ContractViolation& e) {
    EXPECT_THAT(e.what(), HasSubstr("lag1_noise_alpha: d_max must be in 0..3 (got 4)"));
  }
  EXPECT_THROW(noise_alpha_for(DeviationType::oadev, phase, -1), ContractViolation);
}

}  // namespace
}  // namespace imunoise::analysis
