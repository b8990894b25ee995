// Tests of io/discrete_model_file.h: discrete_model.yaml and discrete_model.json read back to
// exactly the matrices, names and σ written (every double bit for bit, including ones that
// need 17 digits, subnormals and extreme exponents), the files written from what was read
// are the same bytes, and malformed files fail with the key that is wrong.
#include "io/discrete_model_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using test::error_of;
using ::testing::HasSubstr;

/// Bit-for-bit equality of two matrices (so −0 ≠ +0 and every last bit counts).
void expect_same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const char* what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  for (Eigen::Index r = 0; r < a.rows(); ++r)
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a(r, c)), std::bit_cast<std::uint64_t>(b(r, c)))
          << what << "(" << r << ", " << c << "): " << a(r, c) << " vs " << b(r, c);
}

void expect_same_content(const DiscreteModelFile& a, const DiscreteModelFile& b) {
  EXPECT_EQ(a.source_model, b.source_model);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.discrete.dt_s),
            std::bit_cast<std::uint64_t>(b.discrete.dt_s));
  EXPECT_EQ(a.discrete.state_names, b.discrete.state_names);
  EXPECT_EQ(a.continuous.state_names, b.discrete.state_names);
  EXPECT_EQ(a.continuous.noise_names, b.continuous.noise_names);
  expect_same_bits(a.discrete.Phi, b.discrete.Phi, "phi");
  expect_same_bits(a.discrete.Qd, b.discrete.Qd, "qd");
  expect_same_bits(a.continuous.initial_variance, b.continuous.initial_variance, "P0");
  expect_same_bits(a.continuous.F, b.continuous.F, "F");
  expect_same_bits(a.continuous.G, b.continuous.G, "G");
  expect_same_bits(a.continuous.Qc, b.continuous.Qc, "Qc");
  ASSERT_EQ(a.white_noise.size(), b.white_noise.size());
  for (std::size_t i = 0; i < a.white_noise.size(); ++i) {
    EXPECT_EQ(a.white_noise[i].axis, b.white_noise[i].axis);
    EXPECT_EQ(a.white_noise[i].kind, b.white_noise[i].kind);
    EXPECT_EQ(a.white_noise[i].density, b.white_noise[i].density);
    EXPECT_EQ(a.white_noise[i].rate_sigma, b.white_noise[i].rate_sigma);
    EXPECT_EQ(a.white_noise[i].increment_sigma, b.white_noise[i].increment_sigma);
  }
}

/// A file of N states and P noises whose numbers are the awkward ones a shortest-text writer
/// must get right (first, so they land in phi), then random doubles of every magnitude (fixed
/// seed).
DiscreteModelFile awkward_file(int n, int p) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  std::vector<double> special{0.1,
                              1.0 / 3.0,
                              -0.0,
                              5e-324,  // the smallest subnormal
                              std::numeric_limits<double>::min(),
                              std::numeric_limits<double>::max(),
                              -std::numeric_limits<double>::max(),
                              1e23,
                              9007199254740993.0,
                              2.2250738585072011e-308};
  std::size_t next_special = 0;
  const auto value = [&] {
    if (next_special < special.size()) return special[next_special++];
    return std::ldexp(mantissa(rng), exponent(rng));
  };
  const auto matrix = [&](int rows, int cols) {
    Eigen::MatrixXd m(rows, cols);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) m(r, c) = value();
    return m;
  };
  DiscreteModelFile f;
  f.source_model = "out/model.yaml";
  f.description = "per-axis sensor error states (theory.md §6.1); white noise is an input";
  f.notes = {"gyro_x: a note", "accel_z: another"};
  f.conservative = true;
  f.bias_model = "both";
  f.gm_convention = "peak_match";
  for (int i = 0; i < n; ++i) f.discrete.state_names.push_back("s" + std::to_string(i) + "_rad");
  for (int i = 0; i < p; ++i) f.continuous.noise_names.push_back("w" + std::to_string(i));
  f.continuous.state_names = f.discrete.state_names;
  f.discrete.dt_s = 0.005;
  f.discrete.method = "van loan, 2^3 substeps";
  f.discrete.Phi = matrix(n, n);
  f.discrete.Qd = matrix(n, n);
  f.continuous.F = matrix(n, n);
  f.continuous.G = matrix(n, p);
  f.continuous.Qc = matrix(p, p);
  f.continuous.initial_variance = matrix(n, 1).col(0);
  f.white_noise.push_back({"gyro_x", SensorKind::gyro, value(), value(), value()});
  f.white_noise.push_back({"accel_x", SensorKind::accel, value(), value(), value()});
  return f;
}

/// What a real discretize run writes: the 21-state INS model would do as well; the sensor
/// states of one gyro axis with RW, GM and ramp keep the test short.
DiscreteModelFile real_file() {
  models::NoiseModel model;
  model.sample_rate_hz = 200.0;
  models::AxisModel a;
  a.name = "gyro_x";
  a.terms[NoiseTerm::white_noise].value = 1.16355e-4;
  a.terms[NoiseTerm::bias_instability].value = 1.22173e-4;
  a.terms[NoiseTerm::random_walk].value = 6.80678e-6;
  a.terms[NoiseTerm::ramp].value = 1e-7;
  a.tau_min_adev_s = 29.6;
  model.axes.push_back(a);
  models::FilterParameterOptions options;
  options.axis = models::AxisChoice::each;
  options.filter_rate_hz = 200.0;
  pipeline::SensorStates states =
      pipeline::sensor_states(model, ins::BiasModel::both, options, 0.005);
  DiscreteModelFile f;
  f.discrete = models::discretize(states.continuous, 0.005);
  f.continuous = std::move(states.continuous);
  f.white_noise = std::move(states.white_noise);
  f.source_model = "model.yaml";
  f.description = states.description;
  f.bias_model = "both";
  f.gm_convention = "peak_match";
  return f;
}

/// FILE as read back from TEXT, with the parts the reader does not fill copied from FILE, so
/// that writing it again must give TEXT.
DiscreteModelFile with_unread_parts(DiscreteModelFile read, const DiscreteModelFile& file) {
  read.description = file.description;
  read.notes = file.notes;
  read.discrete.method = file.discrete.method;
  read.conservative = file.conservative;
  read.bias_model = file.bias_model;
  read.gm_convention = file.gm_convention;
  return read;
}

TEST(DiscreteModelFile, YamlReadsBackEveryNumberExactly) {
  for (const DiscreteModelFile& f : {awkward_file(7, 5), real_file()}) {
    const std::string text = format_discrete_model_yaml(f);
    const DiscreteModelFile back = parse_discrete_model_yaml(text, "d.yaml");
    expect_same_content(f, back);
    EXPECT_EQ(format_discrete_model_yaml(with_unread_parts(back, f)), text);
  }
}

TEST(DiscreteModelFile, JsonReadsBackEveryNumberExactly) {
  for (const DiscreteModelFile& f : {awkward_file(7, 5), real_file()}) {
    const std::string text = format_discrete_model_json(f);
    const DiscreteModelFile back = parse_discrete_model_json(text, "d.json");
    expect_same_content(f, back);
    EXPECT_EQ(back.description, f.description);
    EXPECT_EQ(back.notes, f.notes);
    EXPECT_EQ(back.discrete.method, f.discrete.method);
    EXPECT_EQ(format_discrete_model_json(with_unread_parts(back, f)), text);
  }
}

TEST(DiscreteModelFile, WrittenFilesLoadBackAndAgree) {
  const auto dir = test::make_temp_dir("discrete_model_file");
  const DiscreteModelFile f = real_file();
  const std::string base = write_discrete_model(f, (dir / "out").string());
  EXPECT_EQ(base, (dir / "out" / "discrete_model").string());
  const DiscreteModelFile yaml = load_discrete_model(base + ".yaml");
  const DiscreteModelFile json = load_discrete_model(base + ".json");
  expect_same_content(f, yaml);
  expect_same_content(f, json);
  expect_same_content(yaml, json);
}

TEST(DiscreteModelFile, SourceModelPathOfAnyCharactersReadsBack) {
  // Paths that break a YAML scalar written as is: a colon followed by a space, '#', quotes,
  // backslashes (a Windows path, and an escape sequence inside double quotes), leading and
  // trailing spaces, YAML indicators, "null", controls, UTF-8, and nothing at all.
  const std::vector<std::string> paths{
      "C:\\models\\imu: \"best\" #1.yaml",
      " leading space.yaml",
      "trailing space.yaml ",
      "runs/a: b # c/model.yaml",
      "it's 'quoted'.yaml",
      "- [dash]: {flow}, &anchor *alias !tag %directive @at `tick` |pipe >fold",
      "null",
      "line\nbreak\tand\r\x01\x7f controls.yaml",
      "ünïcode/模型.yaml",
      "",
  };
  const auto dir = test::make_temp_dir("discrete_model_file_paths");
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    DiscreteModelFile f = real_file();
    f.source_model = path;
    const std::string text = format_discrete_model_yaml(f);
    const DiscreteModelFile back = parse_discrete_model_yaml(text, "d.yaml");
    expect_same_content(f, back);
    EXPECT_EQ(format_discrete_model_yaml(with_unread_parts(back, f)), text);
    // The header comment stays one line: the next line is the description's comment.
    const std::size_t first_end = text.find('\n');
    ASSERT_NE(first_end, std::string::npos);
    EXPECT_EQ(text.compare(first_end + 1, 2 + f.description.size(), "# " + f.description), 0);
    expect_same_content(f, parse_discrete_model_json(format_discrete_model_json(f), "d.json"));
    const std::string base = write_discrete_model(f, (dir / "out").string());
    expect_same_content(f, load_discrete_model(base + ".yaml"));
  }
}

TEST(DiscreteModelFile, OrdinarySourceModelPathIsWrittenAsIs) {
  DiscreteModelFile f = real_file();
  f.source_model = "out/demo/model.yaml";
  const std::string text = format_discrete_model_yaml(f);
  EXPECT_EQ(text.rfind("# imunoise discrete state model from out/demo/model.yaml\n", 0), 0u);
  EXPECT_THAT(text, HasSubstr("\nsource_model: \"out/demo/model.yaml\"\n"));
}

TEST(DiscreteModelFile, ZeroStatesRoundTrip) {
  DiscreteModelFile f;
  f.source_model = "m.yaml";
  f.discrete.dt_s = 1.0;
  f.continuous = models::block_diagonal({});
  f.discrete = models::discretize(f.continuous, 1.0);
  expect_same_content(f, parse_discrete_model_yaml(format_discrete_model_yaml(f), "d.yaml"));
  expect_same_content(f, parse_discrete_model_json(format_discrete_model_json(f), "d.json"));
}

TEST(DiscreteModelFile, MalformedFilesNameTheKey) {
  const std::string good = format_discrete_model_yaml(real_file());
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const auto parse = [](const std::string& text) {
    return error_of([&] { parse_discrete_model_yaml(text, "d.yaml"); });
  };
  EXPECT_THAT(parse(replaced("format: imunoise-discrete-model", "format: other")),
              HasSubstr("format: expected 'imunoise-discrete-model', got 'other'"));
  EXPECT_THAT(parse(replaced("format_version: 1", "format_version: 2")),
              HasSubstr("format_version: version 2 is not supported"));
  EXPECT_THAT(parse(replaced("dt_s: 0.005\n", "")), HasSubstr("missing required key 'dt_s'"));
  EXPECT_THAT(parse(replaced("phi:\n  - [1, ", "phi:\n  - [x, ")),
              HasSubstr("phi[0][0]: expected a finite number, got 'x'"));
  EXPECT_THAT(parse(replaced("phi:\n  - [1, ", "phi:\n  - [")), HasSubstr("phi[0]: "));
  EXPECT_THAT(parse(replaced("noises: [", "noises: [extra, ")), HasSubstr("continuous.G[0]: "));
  EXPECT_THAT(parse("phi: [[1]\n"), HasSubstr("d.yaml:"));
  EXPECT_THAT(error_of([] { parse_discrete_model_json("{\"format\": 3}", "d.json"); }),
              HasSubstr("d.json: format: expected a text"));
  EXPECT_THAT(error_of([] { load_discrete_model("/nonexistent/discrete_model.json"); }),
              HasSubstr("cannot open the discrete model"));
}

}  // namespace
}  // namespace imunoise::io
