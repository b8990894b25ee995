/// @file
/// @brief Verification of the battery's generator against closed-form AVAR, before any
/// scoring (issue 20: "verified against closed-form AVAR first"). For each term alone, each
/// phenomenon and a sum, R independent short realizations are generated and the mean of the
/// battery's own overlapping-AVAR estimates at several m is compared with the expected AVAR of
/// expected_avar.h: |mean − expected| ≤ 4·SE, SE = the empirical standard deviation over the
/// realizations / √R (deterministic terms: 1e-9 relative). Fixed seeds: the result is
/// deterministic; the 4σ band decides what counts as a defect (≈ 120 comparisons → a
/// false alarm of under 1 % for a correct generator). The table of ratios is printed at the
/// end (docs/validation.md quotes it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include "battery/battery_cases.h"
#include "battery/expected_avar.h"
#include "battery/generator.h"

namespace imunoise::battery {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTau0 = 0.01;           // 100 Hz [s]
constexpr std::size_t kSamples = 32768;  // per realization
constexpr int kRealizations = 256;
const std::vector<std::size_t> kMs = {1, 2, 4, 16, 64, 256, 1024, 4096};

struct Row {
  std::string name;
  std::size_t m;
  double expected, mean, tolerance;  // tolerance: 4·SE (or 1e-9·expected)
};
std::vector<Row>& rows() {
  static std::vector<Row> r;
  return r;
}

/// One-channel spec at 100 Hz with kSamples samples; CHANNEL 0 is filled by the caller.
RecordingSpec one_channel_spec(std::uint64_t seed, std::size_t samples = kSamples) {
  RecordingSpec s;
  s.rate_hz = 1.0 / kTau0;
  s.samples = samples;
  s.seed = seed;
  return s;
}

/// Generates R realizations with MAKE(seed) → spec (channel 0 used) and checks the mean
/// OAVAR at every m against EXPECTED(m).
void check_statistical(const std::string& name, const std::function<RecordingSpec(int)>& make,
                       const std::function<double(std::size_t)>& expected,
                       int realizations = kRealizations) {
  std::vector<std::vector<double>> values(kMs.size());
  for (int r = 0; r < realizations; ++r) {
    const RecordingSpec spec = make(r);
    const std::vector<double> y = generate_channel(spec, 0);
    const std::vector<double> avar = overlapping_avars(y, kMs);
    for (std::size_t i = 0; i < kMs.size(); ++i) values[i].push_back(avar[i]);
  }
  for (std::size_t i = 0; i < kMs.size(); ++i) {
    const std::vector<double>& v = values[i];
    double mean = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double var = 0.0;
    for (double x : v) var += (x - mean) * (x - mean);
    var /= static_cast<double>(v.size() - 1);
    const double se = std::sqrt(var / static_cast<double>(v.size()));
    const double e = expected(kMs[i]);
    rows().push_back({name, kMs[i], e, mean, 4.0 * se});
    EXPECT_NEAR(mean, e, 4.0 * se) << name << " at m = " << kMs[i] << ": mean/expected " << mean / e
                                   << ", 4 SE/expected " << 4.0 * se / e;
  }
}

void check_deterministic(const std::string& name, const std::vector<double>& y,
                         const std::function<double(std::size_t)>& expected) {
  const std::vector<double> avar = overlapping_avars(y, kMs);
  for (std::size_t i = 0; i < kMs.size(); ++i) {
    const double e = expected(kMs[i]);
    rows().push_back({name, kMs[i], e, avar[i], 1e-9 * e});
    EXPECT_NEAR(avar[i], e, 1e-9 * e) << name << " at m = " << kMs[i];
  }
}

double tau(std::size_t m, double tau0 = kTau0) { return static_cast<double>(m) * tau0; }

TEST(BatteryGenerator, WhiteNoiseMatchesNSquaredOverTau) {
  const double n = 1e-3;
  check_statistical(
      "white N",
      [&](int r) {
        RecordingSpec s = one_channel_spec(100 + r);
        s.channels[0].white = n;
        return s;
      },
      [&](std::size_t m) { return white_avar(n, tau(m)); });
}

TEST(BatteryGenerator, AngleCounterRoundingIsQuantizationNoise) {
  // Plain rounding of the cumulative angle with per-sample angle σ = Δ: the error is white
  // uniform to e^{−2π²} (docs/validation.md); a large constant rate is carried along.
  const double n = 1e-3, step = n * std::sqrt(kTau0), q = step / std::sqrt(12.0);
  check_statistical(
      "Q plain rounding + N",
      [&](int r) {
        RecordingSpec s = one_channel_spec(200 + r);
        s.channels[0].white = n;
        s.channels[0].constant = 0.37;
        s.channels[0].angle_step = step;
        return s;
      },
      [&](std::size_t m) { return quantization_avar(q, tau(m)) + white_avar(n, tau(m)); });
}

TEST(BatteryGenerator, DitheredAngleCounterIsExactQuantizationNoise) {
  const double q = 1e-5, n = 1e-5;  // Q dominates up to τ = 3Q²/N² = 3 s
  check_statistical(
      "Q dithered (Q-dominated)",
      [&](int r) {
        RecordingSpec s = one_channel_spec(300 + r);
        s.channels[0].white = n;
        s.channels[0].angle_step = q * std::sqrt(12.0);
        s.channels[0].angle_dither = true;
        return s;
      },
      [&](std::size_t m) { return quantization_avar(q, tau(m)) + white_avar(n, tau(m)); });
}

TEST(BatteryGenerator, FftFlickerMatchesItsSynthesizedSpectrum) {
  const double b = 1e-4;
  const std::size_t length = flicker_fft_length(one_channel_spec(0));
  ASSERT_GE(length, 4 * kSamples);
  check_statistical(
      "flicker B (FFT over >= 4x)",
      [&](int r) {
        RecordingSpec s = one_channel_spec(400 + r);
        s.channels[0].flicker = b;
        return s;
      },
      [&](std::size_t m) { return flicker_avar(b, length, m); });
  // The synthesized spectrum is the IEEE-952 1/f law: between the ends the AVAR is close to
  // the continuous (2 ln2/π)B² (within 3 % from m = 4 to n/32).
  for (std::size_t m : {4, 64, 1024}) {
    EXPECT_NEAR(flicker_avar(b, length, m) / (2.0 * std::numbers::ln2 / kPi * b * b), 1.0, 0.03)
        << "m = " << m;
  }
}

TEST(BatteryGenerator, DiscreteRandomWalkMatchesZhang2008) {
  const double k = 1e-4;
  check_statistical(
      "random walk K",
      [&](int r) {
        RecordingSpec s = one_channel_spec(500 + r);
        s.channels[0].random_walk = k;
        return s;
      },
      [&](std::size_t m) { return random_walk_avar(k, kTau0, m); });
}

TEST(BatteryGenerator, RampIsExactlyRSquaredTauSquaredOverTwo) {
  RecordingSpec s = one_channel_spec(1);
  s.channels[0].ramp = 1e-3;
  s.channels[0].constant = 2.0;
  check_deterministic("ramp R", generate_channel(s, 0),
                      [](std::size_t m) { return ramp_avar(1e-3, tau(m)); });
}

TEST(BatteryGenerator, GaussMarkovMatchesDiscreteAr1) {
  for (double tc_samples : {10.0, 1000.0}) {
    const double sigma = 1e-3, tc = tc_samples * kTau0;
    // Two independent forms of the same AVAR: the closed form and the lag sum over σ²φ^l.
    const double phi = std::exp(-kTau0 / tc);
    std::vector<double> autocov(2 * kMs.back() + 1);
    for (std::size_t l = 0; l < autocov.size(); ++l) autocov[l] = sigma * sigma * std::pow(phi, l);
    for (std::size_t m : kMs) {
      EXPECT_NEAR(gauss_markov_avar(sigma, tc, kTau0, m), stationary_avar(autocov, m),
                  1e-9 * stationary_avar(autocov, m));
    }
    check_statistical(
        "GM T_c = " + std::to_string(static_cast<int>(tc_samples)) + " tau0",
        [&](int r) {
          RecordingSpec s = one_channel_spec(600 + r + static_cast<int>(tc_samples));
          s.channels[0].gauss_markov.push_back({sigma, tc});
          return s;
        },
        [&](std::size_t m) { return gauss_markov_avar(sigma, tc, kTau0, m); });
  }
}

TEST(BatteryGenerator, SinusoidMatchesTheDiscreteAllanTransferFunction) {
  const double a = 1e-3, f = 1.3;
  std::vector<double> autocov(2 * kMs.back() + 1);
  for (std::size_t l = 0; l < autocov.size(); ++l) {
    autocov[l] = a * a / 2.0 * std::cos(2.0 * kPi * f * kTau0 * static_cast<double>(l));
  }
  for (std::size_t m : kMs) {
    EXPECT_NEAR(sinusoid_avar(a, f, kTau0, m), stationary_avar(autocov, m),
                1e-9 * a * a + 1e-12 * a * a);
  }
  check_statistical(
      "sinusoid (random phase)",
      [&](int r) {
        RecordingSpec s = one_channel_spec(700 + r);
        NormalStream u(static_cast<std::uint64_t>(9000 + r));
        s.channels[0].sinusoids.push_back({a, f, 2.0 * kPi * u.uniform()});
        return s;
      },
      [&](std::size_t m) { return sinusoid_avar(a, f, kTau0, m); });
}

TEST(BatteryGenerator, WarmupMatchesItsGeometricSum) {
  RecordingSpec s = one_channel_spec(1);
  s.channels[0].warmup_amplitude = 1e-3;
  s.channels[0].warmup_tau_s = 50.0;
  check_deterministic("warm-up a e^(-t/tau_w)", generate_channel(s, 0),
                      [](std::size_t m) { return warmup_oavar(1e-3, 50.0, kTau0, kSamples, m); });
}

TEST(BatteryGenerator, ButterworthLowPassOfWhiteMatchesItsAutocovariance) {
  const double n = 1e-3;
  const std::array<double, 5> c = butterworth2(25.0, 100.0);
  EXPECT_NEAR((c[0] + c[1] + c[2]) / (1.0 + c[3] + c[4]), 1.0, 1e-14);  // DC gain 1
  const std::vector<double> autocov = filtered_white_autocov(c);
  check_statistical(
      "low-pass fs/4 on N",
      [&](int r) {
        RecordingSpec s = one_channel_spec(800 + r);
        s.channels[0].white = n;
        s.channels[0].constant = 9.80665;
        s.low_pass_hz = 25.0;
        return s;
      },
      [&](std::size_t m) { return n * n / kTau0 * stationary_avar(autocov, m); });
  // N at long τ is unchanged: the lag sum tends to N²/τ (DC gain 1).
  EXPECT_NEAR(n * n / kTau0 * stationary_avar(autocov, 4096) / white_avar(n, tau(4096)), 1.0, 1e-3);
}

TEST(BatteryGenerator, OutputRoundingAddsDeltaSquaredOverTwelve) {
  const double n = 1e-3, sigma = n / std::sqrt(kTau0);
  for (double fraction : {1.0 / 7.0, 1.0}) {
    const double lsb = fraction * sigma;
    check_statistical(
        fraction < 0.5 ? "LSB sigma/7" : "LSB 1 sigma",
        [&](int r) {
          RecordingSpec s = one_channel_spec(900 + r + static_cast<int>(7 * fraction));
          s.channels[0].white = n;
          s.channels[0].constant = -9.80665;
          s.channels[0].lsb = lsb;
          return s;
        },
        [&](std::size_t m) { return (sigma * sigma + lsb * lsb / 12.0) / static_cast<double>(m); });
  }
}

TEST(BatteryGenerator, OutliersAddPTimesKSquaredSigmaSquared) {
  const double n = 1e-3, sigma = n / std::sqrt(kTau0), p = 0.05, k = 8.0;
  check_statistical(
      "outliers 5 % x 8 sigma",
      [&](int r) {
        RecordingSpec s = one_channel_spec(1000 + r);
        s.channels[0].white = n;
        s.channels[0].outlier_fraction = p;
        s.channels[0].outlier_size = k * sigma;
        return s;
      },
      [&](std::size_t m) { return sigma * sigma * (1.0 + p * k * k) / static_cast<double>(m); });
}

TEST(BatteryGenerator, DecimationWithoutAveraging) {
  const double n = 1e-3, b = 1e-4, k = 1e-4;
  const auto decimated = [](int seed) {
    RecordingSpec s = one_channel_spec(static_cast<std::uint64_t>(seed));
    s.decimation = 4;
    return s;
  };
  check_statistical(
      "decimated x4: N",
      [&](int r) {
        RecordingSpec s = decimated(1100 + r);
        s.channels[0].white = n;
        return s;
      },
      [&](std::size_t m) { return 4.0 * white_avar(n, tau(m)); });
  const std::size_t length = flicker_fft_length(decimated(0));
  check_statistical(
      "decimated x4: B",
      [&](int r) {
        RecordingSpec s = decimated(1200 + r);
        s.channels[0].flicker = b;
        return s;
      },
      [&](std::size_t m) { return flicker_avar(b, length, m, 4); });
  check_statistical(
      "decimated x4: K",
      [&](int r) {
        RecordingSpec s = decimated(1300 + r);
        s.channels[0].random_walk = k;
        return s;
      },
      [&](std::size_t m) { return random_walk_avar(k, kTau0, m); });
  // Low-pass at the internal fs/4, then every 4th sample: R_z(j) = σ_i²·R(4j).
  const std::vector<double> autocov = filtered_white_autocov(butterworth2(100.0, 400.0));
  std::vector<double> subsampled;
  for (std::size_t l = 0; l < autocov.size(); l += 4) subsampled.push_back(autocov[l]);
  check_statistical(
      "low-pass + decimated x4: N",
      [&](int r) {
        RecordingSpec s = decimated(1400 + r);
        s.channels[0].white = n;
        s.low_pass_hz = 100.0;
        return s;
      },
      [&](std::size_t m) { return n * n / (kTau0 / 4.0) * stationary_avar(subsampled, m); });
}

TEST(BatteryGenerator, SumOfTermsIsTheSumOfTheirAvars) {
  const double n = 1e-3, b = 2e-4, k = 2e-5, r_ramp = 1e-5, sigma = 5e-4, tc = 2.0, a = 3e-4;
  const std::size_t length = flicker_fft_length(one_channel_spec(0));
  check_statistical(
      "sum N+B+K+R+GM+sine",
      [&](int r) {
        RecordingSpec s = one_channel_spec(1500 + r);
        ChannelSpec& c = s.channels[0];
        c.white = n;
        c.flicker = b;
        c.random_walk = k;
        c.ramp = r_ramp;
        c.gauss_markov.push_back({sigma, tc});
        NormalStream u(static_cast<std::uint64_t>(19000 + r));
        c.sinusoids.push_back({a, 0.7, 2.0 * kPi * u.uniform()});
        return s;
      },
      [&](std::size_t m) {
        return white_avar(n, tau(m)) + flicker_avar(b, length, m) + random_walk_avar(k, kTau0, m) +
               ramp_avar(r_ramp, tau(m)) + gauss_markov_avar(sigma, tc, kTau0, m) +
               sinusoid_avar(a, 0.7, kTau0, m);
      });
}

TEST(BatteryGenerator, QuantizedStampsKeepTheTrueMeanInterval) {
  RecordingSpec s = one_channel_spec(1, 100000);
  s.rate_hz = 98.6;
  s.stamp_resolution_s = 1e-3;
  s.channels[0].white = 1e-3;
  const GeneratedRecording rec = generate(s);
  std::vector<double> dt;
  for (std::size_t k = 1; k < rec.time_s.size(); ++k)
    dt.push_back(rec.time_s[k] - rec.time_s[k - 1]);
  for (double v : dt) EXPECT_TRUE(std::abs(v - 0.010) < 1e-9 || std::abs(v - 0.011) < 1e-9) << v;
  const double mean = (rec.time_s.back() - rec.time_s.front()) / static_cast<double>(dt.size());
  EXPECT_NEAR(mean, 1.0 / 98.6, 1e-3 / static_cast<double>(dt.size()));
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  EXPECT_NEAR(dt[dt.size() / 2], 0.010, 1e-12);  // the median a reader would take
}

TEST(BatteryGenerator, TemperatureColumnFollowsTheWarmup) {
  RecordingSpec s = one_channel_spec(1, 200000);
  s.temperature = {true, 25.0, 8.0, 300.0, 0.02, 1.0 / 256.0};
  const GeneratedRecording rec = generate(s);
  ASSERT_EQ(rec.temperature_degc.size(), s.samples);
  // Residual about the noise-free law: mean 0, variance σ² + δ²/12 (rounding), 4 SE.
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t k = 0; k < s.samples; ++k) {
    const double t = static_cast<double>(k) * kTau0;
    const double e = rec.temperature_degc[k] - (25.0 + 8.0 * (1.0 - std::exp(-t / 300.0)));
    sum += e;
    sum2 += e * e;
  }
  const double n = static_cast<double>(s.samples);
  const double expected_var = 0.02 * 0.02 + std::pow(1.0 / 256.0, 2) / 12.0;
  EXPECT_NEAR(sum / n, 0.0, 4.0 * std::sqrt(expected_var / n));
  EXPECT_NEAR(sum2 / n / expected_var, 1.0, 4.0 * std::sqrt(2.0 / n));
}

TEST(BatteryGenerator, StreamsAreDeterministicAndIndependentPerTerm) {
  RecordingSpec a = one_channel_spec(42, 4096);
  a.channels[0].white = 1e-3;
  a.channels[1].white = 1e-3;
  RecordingSpec b = a;
  b.channels[0].random_walk = 1e-4;
  RecordingSpec c = one_channel_spec(42, 4096);
  c.channels[0].random_walk = 1e-4;
  const std::vector<double> ya = generate_channel(a, 0), yb = generate_channel(b, 0);
  const std::vector<double> yc = generate_channel(c, 0);
  EXPECT_EQ(ya, generate_channel(a, 0));
  EXPECT_NE(ya, generate_channel(a, 1));  // each channel its own stream
  for (std::size_t k = 0; k < ya.size(); ++k) EXPECT_NEAR(yb[k] - ya[k], yc[k], 1e-15);
  EXPECT_EQ(generate(a).channels[0], ya);  // the threaded whole recording gives the same
}

TEST(BatteryGenerator, SharesNoCodeWithImunoise) {
  // The generator, its expected AVARs and the cases include only the standard library, FFTW
  // and each other: no imunoise layer (models/, analysis/, pipeline/, common/, io/, …).
  const std::filesystem::path dir =
      std::filesystem::path(IMUNOISE_SOURCE_DIR) / "tests" / "validation" / "battery";
  static const std::regex quoted(R"re(^\s*#\s*include\s+"([^"]+)")re");
  for (const char* file : {"generator.h", "generator.cpp", "expected_avar.h", "expected_avar.cpp",
                           "battery_cases.h", "battery_cases.cpp"}) {
    std::ifstream in(dir / file);
    ASSERT_TRUE(in) << file;
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, quoted)) {
        EXPECT_EQ(m[1].str().rfind("battery/", 0), 0u) << file << ": " << line;
      }
    }
  }
}

TEST(BatteryCases, EveryClassBuildsAndItsTruthIsConsistent) {
  for (const std::string& name : battery_classes()) {
    for (BatterySize size : {BatterySize::full, BatterySize::reduced, BatterySize::long_record}) {
      const BatteryCase c = make_case(name, size, 1);
      EXPECT_GE(c.spec.samples, 100000u) << name;
      const double length = static_cast<double>(c.spec.samples) / c.spec.rate_hz;
      for (const ChannelTruth& t : c.truth) {
        EXPECT_GT(t.white_noise, 0.0) << name;
        EXPECT_GT(truth_avar(t, length / 10.0), 0.0) << name;
      }
    }
  }
  EXPECT_THROW(make_case("nonsense", BatterySize::full, 1), std::invalid_argument);
}

}  // namespace
}  // namespace imunoise::battery

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  using imunoise::battery::rows;
  std::printf(
      "\n| case | m | expected AVAR | mean OAVAR / expected | tolerance (4 SE) / expected |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const auto& r : rows()) {
    std::printf("| %s | %zu | %.4e | %.6f | %.3e |\n", r.name.c_str(), r.m, r.expected,
                r.mean / r.expected, r.tolerance / r.expected);
  }
  return result;
}
