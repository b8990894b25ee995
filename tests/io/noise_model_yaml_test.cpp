// Tests of io/noise_model_yaml.h: bit-exact round trip of every NoiseModel field, the atomic
// write, the loading rules of docs/model-yaml.md (defaults of a minimal file) and each kind of
// located, key-naming error.
#include "io/noise_model_yaml.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using models::AxisModel;
using models::BiasInstabilityGm;
using models::Estimate;
using models::GaussMarkovEstimate;
using models::NoiseModel;
using models::ReadoffValues;
using models::SinusoidEstimate;
using test::expect_throw_containing;
using namespace std::string_literals;

// ---------------------------------------------------------------------------------------------
// Field-by-field comparison. Each function unpacks its struct with a structured binding, so it
// stops compiling when a field is added to models/noise_model.h: extend the schema, the
// writer, the reader and these checks together.
// ---------------------------------------------------------------------------------------------

/// Same bits (so -0.0 ≠ 0.0 and every last ulp counts).
void expect_bits(double expected, double actual, const std::string& what) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(expected), std::bit_cast<std::uint64_t>(actual))
      << what << ": expected " << expected << ", got " << actual;
}

void expect_same(const GaussMarkov& a, const GaussMarkov& b, const std::string& at) {
  const auto& [sigma, tau_c_s] = a;
  expect_bits(sigma, b.sigma, at + ".sigma");
  expect_bits(tau_c_s, b.tau_c_s, at + ".tau_c_s");
}

void expect_same(const Sinusoid& a, const Sinusoid& b, const std::string& at) {
  const auto& [amplitude, frequency_hz, phase_rad] = a;
  expect_bits(amplitude, b.amplitude, at + ".amplitude");
  expect_bits(frequency_hz, b.frequency_hz, at + ".frequency_hz");
  expect_bits(phase_rad, b.phase_rad, at + ".phase_rad");
}

void expect_same(const SinusoidEstimate& a, const SinusoidEstimate& b, const std::string& at) {
  const auto& [value, amplitude_ci_low, amplitude_ci_high] = a;
  expect_same(value, b.value, at);
  expect_bits(amplitude_ci_low, b.amplitude_ci_low, at + ".amplitude_ci_low");
  expect_bits(amplitude_ci_high, b.amplitude_ci_high, at + ".amplitude_ci_high");
}

void expect_same(const Estimate& a, const Estimate& b, const std::string& at) {
  const auto& [value, ci_low, ci_high, identified, method, interval_method] = a;
  expect_bits(value, b.value, at + ".value");
  expect_bits(ci_low, b.ci_low, at + ".ci_low");
  expect_bits(ci_high, b.ci_high, at + ".ci_high");
  EXPECT_EQ(identified, b.identified) << at;
  EXPECT_EQ(method, b.method) << at;
  EXPECT_EQ(interval_method, b.interval_method) << at;
}

void expect_same(const GaussMarkovEstimate& a, const GaussMarkovEstimate& b,
                 const std::string& at) {
  const auto& [value, sigma_ci_low, sigma_ci_high, tau_c_ci_low_s, tau_c_ci_high_s] = a;
  expect_same(value, b.value, at);
  expect_bits(sigma_ci_low, b.sigma_ci_low, at + ".sigma_ci_low");
  expect_bits(sigma_ci_high, b.sigma_ci_high, at + ".sigma_ci_high");
  expect_bits(tau_c_ci_low_s, b.tau_c_ci_low_s, at + ".tau_c_ci_low_s");
  expect_bits(tau_c_ci_high_s, b.tau_c_ci_high_s, at + ".tau_c_ci_high_s");
}

void expect_same(const GaussMarkovBound& a, const GaussMarkovBound& b, const std::string& at) {
  const auto& [tau_c_s, sigma_max] = a;
  expect_bits(tau_c_s, b.tau_c_s, at + ".tau_c_s");
  expect_bits(sigma_max, b.sigma_max, at + ".sigma_max");
}

void expect_same(const BiasInstabilityGm& a, const BiasInstabilityGm& b, const std::string& at) {
  const auto& [convention, value] = a;
  EXPECT_EQ(convention, b.convention) << at;
  expect_same(value, b.value, at);
}

template <class T>
void expect_same_list(const std::vector<T>& a, const std::vector<T>& b, const std::string& at) {
  ASSERT_EQ(a.size(), b.size()) << at;
  for (std::size_t i = 0; i < a.size(); ++i) expect_same(a[i], b[i], at + std::to_string(i));
}

void expect_same(const ReadoffValues& a, const ReadoffValues& b, const std::string& at) {
  const auto& [slope, psd] = a;
  for (std::size_t t = 0; t < slope.size(); ++t) {
    expect_bits(slope[t], b.slope[t], at + ".slope" + std::to_string(t));
    expect_bits(psd[t], b.psd[t], at + ".psd" + std::to_string(t));
  }
}

void expect_same(const AxisModel& a, const AxisModel& b) {
  const auto& [name, kind, terms, gauss_markov, gauss_markov_bounds, sinusoids, bias_instability_gm,
               multi_gm, multi_gm_fraction_inside_ci, tau_min_adev_s, fit_tau_min_s, fit_tau_max_s,
               fit_note, readoff, psd_check_pass, psd_check_note] = a;
  const std::string at = "axis '" + name + "'";
  EXPECT_EQ(name, b.name);
  EXPECT_EQ(kind, b.kind) << at;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    expect_same(terms[t], b.terms[t], at + ".terms" + std::to_string(t));
  }
  expect_same_list(gauss_markov, b.gauss_markov, at + ".gauss_markov");
  expect_same_list(gauss_markov_bounds, b.gauss_markov_bounds, at + ".gauss_markov_bounds");
  expect_same_list(sinusoids, b.sinusoids, at + ".sinusoids");
  expect_same_list(bias_instability_gm, b.bias_instability_gm, at + ".bias_instability_gm");
  expect_same_list(multi_gm, b.multi_gm, at + ".multi_gm");
  expect_bits(multi_gm_fraction_inside_ci, b.multi_gm_fraction_inside_ci, at + ".fraction");
  expect_bits(tau_min_adev_s, b.tau_min_adev_s, at + ".tau_min_adev_s");
  expect_bits(fit_tau_min_s, b.fit_tau_min_s, at + ".fit_tau_min_s");
  expect_bits(fit_tau_max_s, b.fit_tau_max_s, at + ".fit_tau_max_s");
  EXPECT_EQ(fit_note, b.fit_note) << at;
  expect_same(readoff, b.readoff, at + ".readoff");
  EXPECT_EQ(psd_check_pass, b.psd_check_pass) << at;
  EXPECT_EQ(psd_check_note, b.psd_check_note) << at;
}

void expect_same(const NoiseModel& a, const NoiseModel& b) {
  const auto& [sensor_name, source, sample_rate_hz, duration_s, samples, confidence, axes,
               data_quality, software] = a;
  EXPECT_EQ(sensor_name, b.sensor_name);
  EXPECT_EQ(source, b.source);
  expect_bits(sample_rate_hz, b.sample_rate_hz, "sample_rate_hz");
  expect_bits(duration_s, b.duration_s, "duration_s");
  EXPECT_EQ(samples, b.samples);
  expect_bits(confidence, b.confidence, "confidence");
  ASSERT_EQ(axes.size(), b.axes.size());
  for (std::size_t i = 0; i < axes.size(); ++i) expect_same(axes[i], b.axes[i]);
  EXPECT_EQ(data_quality, b.data_quality);
  EXPECT_EQ(software, b.software);
}

// ---------------------------------------------------------------------------------------------
// Fixtures
// ---------------------------------------------------------------------------------------------

/// Strings YAML could misread if they were not quoted and escaped.
std::vector<std::string> awkward_strings() {
  return {"",
          "say \"hi\"",
          "key: value, {braces} [brackets]",
          "# not a comment",
          "line one\nline two\r\nline three",
          "tab\there, back\\slash, \\n literally",
          "µrad/√h, σ ≈ 1e-5 °/h",
          "  leading and trailing spaces  ",
          "null",
          "~",
          "true",
          "123",
          "'single quotes'",
          "- not a list",
          "&anchor *alias !tag %directive @reserved `backtick`",
          "nul\0byte, bell\a, del\x7f"s,
          "\xc2\x85 NEL, \xe2\x80\xa8 LS, \xef\xbb\xbf BOM"};
}

Estimate estimate(double value, double ci_low, double ci_high, bool identified,
                  const std::string& method, const std::string& interval_method) {
  return {value, ci_low, ci_high, identified, method, interval_method};
}

/// A model with every field set to a value that is hard to write and read back exactly.
NoiseModel awkward_model() {
  const std::vector<std::string> s = awkward_strings();
  constexpr double kThird = 1.0 / 3.0;
  constexpr double kSum = 0.1 + 0.2;  // 0.30000000000000004
  constexpr double kTiny = std::numeric_limits<double>::denorm_min();
  constexpr double kHuge = std::numeric_limits<double>::max();

  NoiseModel model;
  model.sensor_name = "ADIS \"16465\": µ-rad # not a comment\nsecond line";
  model.source = "C:\\data\\rec 1.csv";
  model.sample_rate_hz = kThird;
  model.duration_s = 28800.000000000004;
  model.samples = std::numeric_limits<std::int64_t>::max();
  model.confidence = kSum;
  model.data_quality = s;
  model.software = "imunoise 0.1.0 \"dev\"";

  AxisModel gyro;
  gyro.name = "gyro_x";
  gyro.kind = SensorKind::gyro;
  gyro.terms = {estimate(0.0, -0.0, 1.2e-07, false, s[1], s[4]),
                estimate(kThird, 1e-300, kSum, true, "wnnls-oavar", "parametric bootstrap, 50"),
                estimate(1e-300, kTiny, kHuge, true, s[6], s[3]),
                estimate(4.9e-7, 1e-7, 5e-7, false, s[15], s[16]),  // identified ≠ (value > 0)
                estimate(0.0, 0.0, 0.0, true, "", "")};
  gyro.gauss_markov = {{{kThird, 100.0}, 0.0, 1.0, kTiny, kHuge},
                       {{2.5e-5, 1e-300}, 2.5e-5, 2.5e-5, 1e-300, 1e-299}};
  gyro.gauss_markov_bounds = {{0.01, kHuge}, {0.0178, kThird}, {1e300, 0.0}, {kTiny, 1e-300}};
  gyro.sinusoids = {{{-1e-3, 0.5, -0.0}, -2e-3, 0.0},
                    {{kSum, 1e-300, -3.141592653589793}, kTiny, kHuge}};
  gyro.bias_instability_gm = {{"min_adev_at_tau_min", {1e-5, 29.6}},
                              {"peak_match", {kThird, 15.638}},
                              {s[2], {0.0, kHuge}}};
  gyro.multi_gm = {{1e-5, 10.0}, {2e-5, 100.0}, {kTiny, 1000.0}};
  gyro.multi_gm_fraction_inside_ci = 0.97;
  gyro.tau_min_adev_s = 29.6;
  gyro.fit_tau_min_s = 0.02;
  gyro.fit_tau_max_s = 2880.0;
  gyro.fit_note = s[4] + s[5];
  gyro.readoff.slope = {0.0, kThird, 1e-300, kTiny, -0.0};
  gyro.readoff.psd = {1.0, 2.0, kSum, 4.0, kHuge};
  gyro.psd_check_pass = true;
  gyro.psd_check_note = "model within 3 dB: " + s[7];

  AxisModel accel;
  accel.name = "accel x: \"weird\" µ";
  accel.kind = SensorKind::accel;
  for (std::size_t t = 0; t < accel.terms.size(); ++t) {
    accel.terms[t] = estimate(kThird * static_cast<double>(t), 0.0, 1.0 + static_cast<double>(t),
                              t % 2 == 0, s[8 + t], s[13 - t]);
  }
  accel.gauss_markov = {{{9.80665e-6, 3600.0}, 1e-6, 2e-5, 1800.0, 7200.0}};
  accel.gauss_markov_bounds = {{1780.0, 2.5e-4}};
  accel.sinusoids = {{{kThird, 49.99, 1.0}, 0.0, 1.0}};
  accel.bias_instability_gm = {{"sigma_equals_b", {kSum, kThird}}};
  accel.multi_gm = {};
  accel.multi_gm_fraction_inside_ci = 0.5;  // written even though multi_gm is empty
  accel.psd_check_pass = std::nullopt;
  accel.psd_check_note = "not run: " + s[9];  // a note without a verdict

  AxisModel failed = gyro;
  failed.name = "null";  // a YAML null spelling as a key
  failed.psd_check_pass = false;
  failed.psd_check_note = "";

  AxisModel bare;  // every optional block at its default: psd_check is omitted
  bare.name = "9lives";
  bare.kind = SensorKind::accel;

  AxisModel unnamed = bare;
  unnamed.name = "";

  model.axes = {gyro, accel, failed, bare, unnamed};
  return model;
}

/// A hand-written file with only the required keys; line numbers are used by the error tests.
const std::vector<std::string> kMinimalLines{
    "format: imunoise-noise-model",                      // 1
    "format_version: 1",                                 // 2
    "sample_rate_hz: 100",                               // 3
    "axes:",                                             // 4
    "  gyro_x:",                                         // 5
    "    sensor: gyro",                                  // 6
    "    quantization_rad: {value: 0}",                  // 7
    "    white_noise_rad_per_sqrt_s: {value: 2.9e-05}",  // 8
    "    bias_instability_rad_per_s: {value: 1e-05}",    // 9
    "    random_walk_rad_per_s_sqrt_s: {value: 0}",      // 10
    "    ramp_rad_per_s2: {value: 0}",                   // 11
    "  accel_x:",                                        // 12
    "    sensor: accel",                                 // 13
    "    quantization_m_per_s: {value: 0}",              // 14
    "    white_noise_m_per_s_sqrt_s: {value: 6e-04}",    // 15
    "    bias_instability_m_per_s2: {value: 3e-04}",     // 16
    "    random_walk_m_per_s2_sqrt_s: {value: 0}",       // 17
    "    ramp_m_per_s3: {value: 0}",                     // 18
};

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

std::string minimal() { return joined(kMinimalLines); }

/// The minimal file with line LINE (1-based) replaced by TEXT ("" deletes it).
std::string minimal_with(std::size_t line, const std::string& text) {
  std::vector<std::string> lines = kMinimalLines;
  if (text.empty()) {
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(line - 1));
  } else {
    lines[line - 1] = text;
  }
  return joined(lines);
}

/// The minimal file with TEXT inserted after line LINE.
std::string minimal_plus(std::size_t line, const std::string& text) {
  std::vector<std::string> lines = kMinimalLines;
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(line), text);
  return joined(lines);
}

/// Expects parse_model_yaml(TEXT, "model.yaml") to throw an InputError containing FRAGMENT.
void expect_rejected(const std::string& text, const std::string& fragment) {
  expect_throw_containing<InputError>([&] { parse_model_yaml(text, "model.yaml"); }, fragment);
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  return names;
}

// ---------------------------------------------------------------------------------------------
// Round trip and layout
// ---------------------------------------------------------------------------------------------

TEST(NoiseModelYaml, RoundTripIsBitExactForEveryField) {
  const NoiseModel model = awkward_model();
  const std::string text = format_model_yaml(model);
  const NoiseModel back = parse_model_yaml(text, "round-trip.yaml");
  expect_same(model, back);
  // Writing what was read gives the same text: the format is a fixed point.
  EXPECT_EQ(format_model_yaml(back), text);
}

TEST(NoiseModelYaml, FormatIsDeterministicCommentedAndNamesUnits) {
  const NoiseModel model = awkward_model();
  const std::string text = format_model_yaml(model);
  EXPECT_EQ(format_model_yaml(model), text);
  EXPECT_EQ(text.rfind("# imunoise noise model (native schema v1). SI units, named in every key.\n"
                       "# Coefficients per theory.md §1.3: AVAR = 3Q²/τ² + N²/τ + (2 ln2/π)B² + "
                       "K²τ/3 + R²τ²/2.\n",
                       0),
            0U);
  EXPECT_NE(text.find("\nformat: imunoise-noise-model\nformat_version: 1\n"), std::string::npos);
  EXPECT_NE(text.find("\nsample_rate_hz: 0.3333333333333333\n"), std::string::npos);
  EXPECT_NE(text.find("\nsamples: 9223372036854775807\n"), std::string::npos);
  // Term keys carry their unit and a comment naming the symbol.
  EXPECT_NE(text.find("    white_noise_rad_per_sqrt_s: {value: 0.3333333333333333, ci_low: "
                      "1e-300, ci_high: 0.30000000000000004, identified: true, method: "
                      "\"wnnls-oavar\", interval_method: \"parametric bootstrap, 50\"}  # N (ARW)"),
            std::string::npos);
  EXPECT_NE(text.find("random_walk_rad_per_s_sqrt_s: {"), std::string::npos);
  EXPECT_NE(text.find("# K (RRW)\n"), std::string::npos);
  EXPECT_NE(text.find("    white_noise_m_per_s_sqrt_s: {"), std::string::npos);
  EXPECT_NE(text.find("# N (VRW)\n"), std::string::npos);
  EXPECT_NE(text.find("{sigma_m_per_s2: 9.80665e-06, tau_c_s: 3600, "), std::string::npos);
  EXPECT_NE(text.find("{amplitude_rad_per_s: -0.001, frequency_hz: 0.5, phase_rad: -0, "
                      "amplitude_ci_low_rad_per_s: -0.002, amplitude_ci_high_rad_per_s: 0}"),
            std::string::npos);
  // Names that are not simple identifiers are quoted; "null" would otherwise be a null key.
  EXPECT_NE(text.find("\n  gyro_x:\n"), std::string::npos);
  EXPECT_NE(text.find("\n  \"null\":\n"), std::string::npos);
  EXPECT_NE(text.find("\n  \"9lives\":\n"), std::string::npos);
  EXPECT_NE(text.find("\n  \"accel x: \\\"weird\\\" µ\":\n"), std::string::npos);
  // psd_check: a verdict, a note without a verdict, and omitted when neither exists.
  EXPECT_NE(text.find("psd_check: {pass: true, note: \"model within 3 dB"), std::string::npos);
  EXPECT_NE(text.find("psd_check: {pass: false, note: \"\"}"), std::string::npos);
  EXPECT_NE(text.find("psd_check: {note: \"not run: "), std::string::npos);
  const std::size_t bare = text.find("\n  \"9lives\":\n");
  const std::size_t next = text.find("\n  \"\":\n", bare);
  ASSERT_NE(next, std::string::npos);
  EXPECT_EQ(text.substr(bare, next - bare).find("psd_check"), std::string::npos);
  // Every string stays on its line: escapes, not raw line breaks.
  EXPECT_NE(text.find("\"line one\\nline two\\r\\nline three\""), std::string::npos);
  EXPECT_NE(text.find("\"nul\\x00byte, bell\\x07, del\\x7f\""), std::string::npos);
}

TEST(NoiseModelYaml, WriteIsAtomicAndKeepsOldContentOnFailure) {
  const auto dir = test::make_temp_dir("model-yaml");
  const std::string path = (dir / "model.yaml").string();
  const NoiseModel model = awkward_model();

  write_model_yaml(model, path);
  EXPECT_EQ(read_all(path), format_model_yaml(model));
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"model.yaml"});  // no temporary left
  expect_same(model, load_model_yaml(path));

  // A model the loader would reject is refused before the file is touched.
  NoiseModel broken = model;
  broken.axes[0].terms[1].value = std::nan("");
  const std::string before = read_all(path);
  expect_throw_containing<ContractViolation>(
      [&] { write_model_yaml(broken, path); },
      "axes.gyro_x.white_noise_rad_per_sqrt_s.value: expected a finite number, got 'nan'");
  EXPECT_EQ(read_all(path), before);
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"model.yaml"});

  // A valid model replaces the old content.
  NoiseModel other = model;
  other.sensor_name = "second write";
  write_model_yaml(other, path);
  EXPECT_EQ(load_model_yaml(path).sensor_name, "second write");
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"model.yaml"});
  std::filesystem::remove_all(dir);
}

TEST(NoiseModelYaml, WriteIntoMissingDirectoryNamesThePath) {
  const auto dir = test::make_temp_dir("model-yaml-missing");
  const std::string path = (dir / "no-such-dir" / "model.yaml").string();
  expect_throw_containing<InputError>([&] { write_model_yaml(awkward_model(), path); }, path);
  std::filesystem::remove_all(dir);
}

TEST(NoiseModelYaml, WriterRefusesModelsTheLoaderWouldReject) {
  NoiseModel negative = awkward_model();
  negative.axes[1].terms[2].ci_high = -1.0;
  expect_throw_containing<ContractViolation>([&] { format_model_yaml(negative); },
                                             "ci_high: must be >= 0, got -1");

  NoiseModel duplicate = awkward_model();
  duplicate.axes[1].name = "gyro_x";
  expect_throw_containing<ContractViolation>([&] { format_model_yaml(duplicate); },
                                             "axes.gyro_x: duplicate key");

  NoiseModel no_axes = awkward_model();
  no_axes.axes.clear();
  expect_throw_containing<ContractViolation>([&] { format_model_yaml(no_axes); }, "axes: expected");

  NoiseModel zero_tau = awkward_model();
  zero_tau.axes[0].multi_gm[1].tau_c_s = 0.0;
  expect_throw_containing<ContractViolation>(
      [&] { format_model_yaml(zero_tau); },
      "axes.gyro_x.bias_instability_multi_gm.terms[1].tau_c_s: must be > 0, got 0");
}

// ---------------------------------------------------------------------------------------------
// Loading rules
// ---------------------------------------------------------------------------------------------

TEST(NoiseModelYaml, MinimalFileLoadsWithDefaults) {
  const NoiseModel model = parse_model_yaml(minimal(), "model.yaml");
  EXPECT_EQ(model.sample_rate_hz, 100.0);
  EXPECT_EQ(model.software, "imunoise");
  EXPECT_EQ(model.sensor_name, "");
  EXPECT_EQ(model.source, "");
  EXPECT_EQ(model.duration_s, 0.0);
  EXPECT_EQ(model.samples, 0);
  EXPECT_EQ(model.confidence, 0.95);
  EXPECT_TRUE(model.data_quality.empty());
  ASSERT_EQ(model.axes.size(), 2U);

  const AxisModel& gyro = model.axes[0];
  EXPECT_EQ(gyro.name, "gyro_x");
  EXPECT_EQ(gyro.kind, SensorKind::gyro);
  const Estimate& arw = gyro.terms[static_cast<std::size_t>(NoiseTerm::white_noise)];
  EXPECT_EQ(arw.value, 2.9e-05);
  EXPECT_EQ(arw.ci_low, 2.9e-05);  // interval defaults to the value
  EXPECT_EQ(arw.ci_high, 2.9e-05);
  EXPECT_TRUE(arw.identified);  // defaults to value > 0
  EXPECT_EQ(arw.method, "");
  EXPECT_EQ(arw.interval_method, "");
  EXPECT_FALSE(gyro.terms[static_cast<std::size_t>(NoiseTerm::quantization)].identified);
  EXPECT_TRUE(gyro.gauss_markov.empty());
  EXPECT_TRUE(gyro.sinusoids.empty());
  EXPECT_TRUE(gyro.bias_instability_gm.empty());
  EXPECT_TRUE(gyro.multi_gm.empty());
  EXPECT_EQ(gyro.multi_gm_fraction_inside_ci, 0.0);
  EXPECT_EQ(gyro.tau_min_adev_s, 0.0);
  EXPECT_EQ(gyro.fit_tau_min_s, 0.0);
  EXPECT_EQ(gyro.fit_tau_max_s, 0.0);
  EXPECT_EQ(gyro.fit_note, "");
  EXPECT_EQ(gyro.readoff.slope, (std::array<double, 5>{}));
  EXPECT_EQ(gyro.readoff.psd, (std::array<double, 5>{}));
  EXPECT_FALSE(gyro.psd_check_pass.has_value());
  EXPECT_EQ(gyro.psd_check_note, "");

  const AxisModel& accel = model.axes[1];
  EXPECT_EQ(accel.name, "accel_x");
  EXPECT_EQ(accel.kind, SensorKind::accel);
  EXPECT_EQ(accel.terms[static_cast<std::size_t>(NoiseTerm::bias_instability)].value, 3e-4);
}

TEST(NoiseModelYaml, PartialEntriesTakeTheirDefaults) {
  const NoiseModel model = parse_model_yaml(
      minimal_plus(11,
                   "    gauss_markov:\n"
                   "      - {sigma_rad_per_s: 2e-5, tau_c_s: 100, sigma_ci_high_rad_per_s: 3e-5}\n"
                   "    sinusoids: [{amplitude_rad_per_s: 1e-4, frequency_hz: 12.5}]\n"
                   "    bias_instability_multi_gm: {terms: [{sigma_rad_per_s: 1e-5, tau_c_s: 9}]}\n"
                   "    readoff: {psd: {white_noise_rad_per_sqrt_s: 3e-5}}\n"
                   "    psd_check: {pass: false}"),
      "model.yaml");
  const AxisModel& gyro = model.axes[0];
  ASSERT_EQ(gyro.gauss_markov.size(), 1U);
  EXPECT_EQ(gyro.gauss_markov[0].sigma_ci_low, 2e-5);
  EXPECT_EQ(gyro.gauss_markov[0].sigma_ci_high, 3e-5);
  EXPECT_EQ(gyro.gauss_markov[0].tau_c_ci_low_s, 100.0);
  EXPECT_EQ(gyro.gauss_markov[0].tau_c_ci_high_s, 100.0);
  ASSERT_EQ(gyro.sinusoids.size(), 1U);
  EXPECT_EQ(gyro.sinusoids[0].value.phase_rad, 0.0);
  // Files written before the amplitude interval: an empty interval at the amplitude.
  EXPECT_EQ(gyro.sinusoids[0].amplitude_ci_low, 1e-4);
  EXPECT_EQ(gyro.sinusoids[0].amplitude_ci_high, 1e-4);
  ASSERT_EQ(gyro.multi_gm.size(), 1U);
  EXPECT_EQ(gyro.multi_gm[0].tau_c_s, 9.0);
  EXPECT_EQ(gyro.multi_gm_fraction_inside_ci, 0.0);
  EXPECT_EQ(gyro.readoff.psd, (std::array<double, 5>{0.0, 3e-5, 0.0, 0.0, 0.0}));
  EXPECT_EQ(gyro.psd_check_pass, false);
  EXPECT_EQ(gyro.psd_check_note, "");
}

TEST(NoiseModelYaml, AcceptsHandWrittenSpellingsAndKeepsAxisOrder) {
  const std::string text =
      "# written by hand\n"
      "format: \"imunoise-noise-model\"\n"
      "format_version: 1\n"
      "sensor_name: ADIS16465 unit 7   # plain string, trailing comment dropped\n"
      "sample_rate_hz: +2.0e+3\n"
      "axes:\n"
      "  accel_z:\n"
      "    sensor: accel\n"
      "    quantization_m_per_s:\n"
      "      value: 0\n"
      "    white_noise_m_per_s_sqrt_s: {value: .5e-3, identified: True}\n"
      "    bias_instability_m_per_s2: {value: 0, ci_high: 1e-4, identified: FALSE}\n"
      "    random_walk_m_per_s2_sqrt_s: {value: 0}\n"
      "    ramp_m_per_s3: {value: 0}\n"
      "  gyro_z:\n"
      "    sensor: \"gyro\"\n"
      "    quantization_rad: {value: 0}\n"
      "    white_noise_rad_per_sqrt_s: {value: 1}\n"
      "    bias_instability_rad_per_s: {value: 0}\n"
      "    random_walk_rad_per_s_sqrt_s: {value: 0}\n"
      "    ramp_rad_per_s2: {value: 0}\n";
  const NoiseModel model = parse_model_yaml(text, "model.yaml");
  EXPECT_EQ(model.sensor_name, "ADIS16465 unit 7");
  EXPECT_EQ(model.sample_rate_hz, 2000.0);
  ASSERT_EQ(model.axes.size(), 2U);
  EXPECT_EQ(model.axes[0].name, "accel_z");  // file order, not sorted
  EXPECT_EQ(model.axes[1].name, "gyro_z");
  EXPECT_EQ(model.axes[0].terms[1].value, 0.5e-3);
  EXPECT_TRUE(model.axes[0].terms[1].identified);
  EXPECT_EQ(model.axes[0].terms[2].ci_low, 0.0);
  EXPECT_EQ(model.axes[0].terms[2].ci_high, 1e-4);
  EXPECT_FALSE(model.axes[0].terms[2].identified);
}

// ---------------------------------------------------------------------------------------------
// Errors: each names the source, line, column and key path
// ---------------------------------------------------------------------------------------------

TEST(NoiseModelYaml, RejectsNonNumbersAtTheirLine) {
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: abc}"),
                  "model.yaml:8:41: axes.gyro_x.white_noise_rad_per_sqrt_s.value: expected a "
                  "finite number, got 'abc'");
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: .nan}"),
                  "model.yaml:8:41: axes.gyro_x.white_noise_rad_per_sqrt_s.value: expected a "
                  "finite number, got '.nan'");
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: inf}"), "got 'inf'");
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: 1e400}"), "got '1e400'");
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: 1.5x}"), "got '1.5x'");
  expect_rejected(minimal_with(3, "sample_rate_hz: \"100\""),
                  "model.yaml:3:17: sample_rate_hz: expected a finite number, got the quoted "
                  "string \"100\"");
  expect_rejected(minimal_with(3, "sample_rate_hz:"),
                  "sample_rate_hz: expected a finite number, got nothing");
}

TEST(NoiseModelYaml, UnknownKeyIsNamedWithTheAcceptedOnes) {
  expect_rejected(
      minimal_plus(6, "    colour: blue"),
      "model.yaml:7:5: axes.gyro_x.colour: unknown key for a gyro axis (accepted: "
      "sensor, quantization_rad, white_noise_rad_per_sqrt_s, "
      "bias_instability_rad_per_s, random_walk_rad_per_s_sqrt_s, ramp_rad_per_s2, "
      "gauss_markov, gauss_markov_upper_bound, sinusoids, bias_instability_as_gauss_markov, "
      "bias_instability_multi_gm, fit, readoff, psd_check)");
  expect_rejected(minimal_with(7, "    quantization_rad: {value: 0, ci_lo: 0}"),
                  "model.yaml:7:34: axes.gyro_x.quantization_rad.ci_lo: unknown key (accepted: "
                  "value, ci_low, ci_high, identified, method, interval_method)");
  expect_rejected(minimal_plus(3, "sample_rate: 100"),
                  "model.yaml:4:1: sample_rate: unknown key (accepted: format, format_version, "
                  "software, sensor_name, source, sample_rate_hz, duration_s, samples, "
                  "confidence, data_quality, axes)");
  // A gyro unit on an accelerometer axis: the message says which sensor the axis is.
  expect_rejected(minimal_with(15, "    white_noise_rad_per_sqrt_s: {value: 6e-04}"),
                  "model.yaml:15:5: axes.accel_x.white_noise_rad_per_sqrt_s: unknown key for an "
                  "accel axis (accepted: sensor, quantization_m_per_s, white_noise_m_per_s_sqrt_s");
  expect_rejected(minimal_plus(11, "    fit: {tau_min_s: 1, tau_max: 10}"),
                  "axes.gyro_x.fit.tau_max: unknown key (accepted: tau_min_s, tau_max_s, "
                  "tau_of_min_adev_s, note)");
}

TEST(NoiseModelYaml, MissingRequiredKeyIsNamed) {
  expect_rejected(minimal_with(11, ""),
                  "model.yaml:6:5: axes.gyro_x: missing required key 'ramp_rad_per_s2'");
  expect_rejected(minimal_with(6, ""),
                  "model.yaml:6:5: axes.gyro_x: missing required key 'sensor'");
  expect_rejected(minimal_with(9, "    bias_instability_rad_per_s: {ci_low: 0}"),
                  "model.yaml:9:33: axes.gyro_x.bias_instability_rad_per_s: missing required "
                  "key 'value'");
  expect_rejected(minimal_with(3, ""), "model.yaml:1:1: missing required key 'sample_rate_hz'");
  expect_rejected(minimal_with(1, ""), "model.yaml:1:1: missing required key 'format'");
  expect_rejected(minimal_plus(11, "    gauss_markov: [{sigma_rad_per_s: 1e-5}]"),
                  "model.yaml:12:20: axes.gyro_x.gauss_markov[0]: missing required key 'tau_c_s'");
  expect_rejected(joined({kMinimalLines.begin(), kMinimalLines.begin() + 3}),
                  "missing required key 'axes'");
}

TEST(NoiseModelYaml, WrongTypesAreNamed) {
  expect_rejected(joined({kMinimalLines.begin(), kMinimalLines.begin() + 3}) + "axes: [gyro_x]\n",
                  "model.yaml:4:7: axes: expected a mapping, got a list");
  expect_rejected(joined({kMinimalLines.begin(), kMinimalLines.begin() + 3}) + "axes: {}\n",
                  "model.yaml:4:7: axes: expected at least one axis");
  expect_rejected(minimal_with(7, "    quantization_rad: 0"),
                  "model.yaml:7:23: axes.gyro_x.quantization_rad: expected a mapping, got '0'");
  expect_rejected(minimal_with(7, "    quantization_rad: {value: 0, identified: maybe}"),
                  "model.yaml:7:46: axes.gyro_x.quantization_rad.identified: expected true or "
                  "false, got 'maybe'");
  expect_rejected(minimal_plus(11, "    gauss_markov: {sigma_rad_per_s: 1, tau_c_s: 1}"),
                  "model.yaml:12:19: axes.gyro_x.gauss_markov: expected a list ([] for none), got "
                  "a mapping");
  expect_rejected(minimal_plus(3, "samples: 1.5e6"),
                  "model.yaml:4:10: samples: expected an integer, got '1.5e6'");
  expect_rejected(minimal_plus(3, "sensor_name: {model: x}"),
                  "model.yaml:4:14: sensor_name: expected a string, got a mapping");
  expect_rejected(minimal_plus(3, "source:"),
                  "source: expected a string, got nothing (write \"\" for an empty string)");
  expect_rejected(minimal_plus(3, "data_quality: [ok, [nested]]"),
                  "model.yaml:4:20: data_quality[1]: expected a string, got a list");
  expect_rejected("", "model.yaml: expected a mapping of keys");
  expect_rejected("- just\n- a list\n", "model.yaml:1:1: expected a mapping of keys");
}

TEST(NoiseModelYaml, NegativeOrOutOfRangeValuesAreRejected) {
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: -2.9e-05}"),
                  "model.yaml:8:41: axes.gyro_x.white_noise_rad_per_sqrt_s.value: must be >= 0, "
                  "got -2.9e-05");
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: 1, ci_low: -1}"),
                  "axes.gyro_x.white_noise_rad_per_sqrt_s.ci_low: must be >= 0, got -1");
  expect_rejected(minimal_with(3, "sample_rate_hz: 0"),
                  "model.yaml:3:17: sample_rate_hz: must be > 0, got 0");
  expect_rejected(minimal_plus(3, "confidence: 1"), "confidence: must be in (0, 1), got 1");
  expect_rejected(minimal_plus(3, "samples: -5"), "model.yaml:4:10: samples: must be >= 0");
  expect_rejected(minimal_plus(11, "    gauss_markov: [{sigma_rad_per_s: 1e-5, tau_c_s: 0}]"),
                  "model.yaml:12:53: axes.gyro_x.gauss_markov[0].tau_c_s: must be > 0, got 0");
  expect_rejected(
      minimal_plus(11, "    gauss_markov_upper_bound: [{tau_c_s: 10, sigma_max_rad_per_s: -1}]"),
      "axes.gyro_x.gauss_markov_upper_bound[0].sigma_max_rad_per_s: must be >= 0, got -1");
  expect_rejected(minimal_plus(11, "    gauss_markov_upper_bound: [{sigma_max_rad_per_s: 1}]"),
                  "axes.gyro_x.gauss_markov_upper_bound[0]: missing required key 'tau_c_s'");
  expect_rejected(minimal_plus(11, "    readoff: {psd: {ramp_rad_per_s2: -1}}"),
                  "axes.gyro_x.readoff.psd.ramp_rad_per_s2: must be >= 0, got -1");
  expect_rejected(minimal_plus(11, "    bias_instability_multi_gm: {fraction_inside_ci: 1.5}"),
                  "axes.gyro_x.bias_instability_multi_gm.fraction_inside_ci: must be in [0, 1], "
                  "got 1.5");
  expect_rejected(minimal_plus(11, "    fit: {tau_min_s: 10, tau_max_s: 1}"),
                  "axes.gyro_x.fit: tau_min_s (10) is greater than tau_max_s (1)");
}

TEST(NoiseModelYaml, CiLowAboveCiHighIsRejected) {
  expect_rejected(
      minimal_with(
          9, "    bias_instability_rad_per_s: {value: 1e-05, ci_low: 2e-05, ci_high: 1.5e-05}"),
      "model.yaml:9:72: axes.gyro_x.bias_instability_rad_per_s: ci_low (2e-05) is greater than "
      "ci_high (1.5e-05)");
  // ci_high defaults to the value, so a lone ci_low above the value is caught too.
  expect_rejected(minimal_with(9, "    bias_instability_rad_per_s: {value: 1e-05, ci_low: 2e-05}"),
                  "axes.gyro_x.bias_instability_rad_per_s: ci_low (2e-05) is greater than "
                  "ci_high (1e-05)");
  expect_rejected(
      minimal_plus(11, "    gauss_markov: [{sigma_rad_per_s: 1, tau_c_s: 5, tau_c_ci_low_s: 6}]"),
      "axes.gyro_x.gauss_markov[0]: tau_c_ci_low_s (6) is greater than tau_c_ci_high_s (5)");
}

TEST(NoiseModelYaml, UnknownSensorIsRejected) {
  expect_rejected(minimal_with(6, "    sensor: magnetometer"),
                  "model.yaml:6:13: axes.gyro_x.sensor: unknown sensor 'magnetometer' (expected "
                  "gyro or accel)");
}

TEST(NoiseModelYaml, FormatAndVersionMustMatch) {
  expect_rejected(minimal_with(1, "format: kalibr-imu"),
                  "model.yaml:1:9: format: expected 'imunoise-noise-model', got 'kalibr-imu' (not "
                  "an imunoise noise model)");
  expect_rejected(minimal_with(2, "format_version: 2"),
                  "model.yaml:2:17: format_version: unsupported version 2 (this build reads 1)");
  expect_rejected(minimal_with(2, "format_version: 1.0"),
                  "format_version: expected an integer, got '1.0'");
  // A foreign file (a Kalibr imu.yaml) is told apart before its keys are judged.
  expect_rejected("gyroscope_noise_density: 1.0e-4\nupdate_rate: 200\n",
                  "model.yaml:1:1: missing required key 'format'");
}

TEST(NoiseModelYaml, DuplicateKeysAreRejected) {
  std::vector<std::string> lines = kMinimalLines;
  lines.insert(lines.end(), kMinimalLines.begin() + 4, kMinimalLines.begin() + 11);  // gyro_x again
  expect_rejected(joined(lines), "model.yaml:19:3: axes.gyro_x: duplicate key (first at line 5)");
  expect_rejected(minimal_with(7, "    quantization_rad: {value: 0, value: 1}"),
                  "model.yaml:7:34: axes.gyro_x.quantization_rad.value: duplicate key (first at "
                  "line 7)");
}

TEST(NoiseModelYaml, SyntaxErrorsAreLocated) {
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: 1"), "model.yaml:9:");
  expect_rejected(minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: 1"), "YAML syntax");
}

TEST(NoiseModelYaml, LoadNamesTheFile) {
  const auto dir = test::make_temp_dir("model-yaml-load");
  const auto path = dir / "bad.yaml";
  test::write_text(path, minimal_with(8, "    white_noise_rad_per_sqrt_s: {value: abc}"));
  expect_throw_containing<InputError>([&] { load_model_yaml(path.string()); },
                                      path.string() + ":8:41: axes.gyro_x.white_noise");
  const std::string missing = (dir / "missing.yaml").string();
  expect_throw_containing<InputError>([&] { load_model_yaml(missing); },
                                      missing + ": cannot open the model file");
  expect_throw_containing<InputError>([&] { load_model_yaml(dir.string()); }, "a directory");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace imunoise::io
