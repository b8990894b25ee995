/// @file
/// @brief End-to-end behaviour of `imunoise analyze` / `allan` on bad or awkward inputs
/// (issue 9): time-stamp gaps under --gaps refuse|split|interpolate, one- and two-sample
/// records, identical and irregular time stamps, NaN/Inf in any column, values near the
/// float limits, tau grids beyond the record. Every case ends in a correct result or one
/// clear line on stderr with exit 2 (input) or 3 (analysis) — never a crash, exit 4, or
/// NaN/Inf in an output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "common/version.h"
#include "io/noise_model_yaml.h"
#include "models/noise_model.h"
#include "test_support.h"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr double kPeriod = 0.01;  // 100 Hz
constexpr double kArw = 2e-3;     // white rate noise N of every gyro axis [rad/s/√Hz]

/// One row of a three-gyro CSV.
struct Row {
  std::string time;
  std::string gyro[3];
};

/// N rows of white gyro noise at 100 Hz (σ = N/√τ0); the rows in [begin, end) of each of
/// CUT are left out (time-stamp gaps). Returns the rows kept.
std::vector<Row> white_rows(std::size_t n,
                            const std::vector<std::pair<std::size_t, std::size_t>>& cut,
                            std::uint32_t seed = 5) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, kArw / std::sqrt(kPeriod));
  std::vector<Row> rows;
  char buffer[64];
  for (std::size_t i = 0; i < n; ++i) {
    Row r;
    std::snprintf(buffer, sizeof buffer, "%.2f", static_cast<double>(i) * kPeriod);
    r.time = buffer;
    for (auto& v : r.gyro) {
      std::snprintf(buffer, sizeof buffer, "%.17g", g(rng));
      v = buffer;
    }
    bool removed = false;
    for (const auto& [b, e] : cut) removed = removed || (i >= b && i < e);
    if (!removed) rows.push_back(r);
  }
  return rows;
}

void write_rows(const fs::path& path, const std::vector<Row>& rows) {
  std::ofstream out(path);
  out << "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\n";
  for (const Row& r : rows)
    out << r.time << "," << r.gyro[0] << "," << r.gyro[1] << "," << r.gyro[2] << "\n";
}

std::string read_all(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// True when TEXT reads as a non-finite number (nan, inf, YAML's .nan/.inf, any sign/case).
bool non_finite_token(std::string text) {
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
  while (!text.empty() && (text.front() == ' ' || text.front() == '-' || text.front() == '+' ||
                           text.front() == '.')) {
    text.erase(0, 1);
  }
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text == "nan" || text == "inf" || text == "infinity";
}

/// No NaN/Inf among the numbers of an analysis directory: every CSV field, every YAML value
/// (quoted strings — file names, notes — are text, not numbers).
void expect_no_non_finite_outputs(const fs::path& out) {
  for (const char* name : {"allan.csv", "psd.csv"}) {
    const auto rows = read_csv_rows(out / name);
    ASSERT_GT(rows.size(), 1u) << name;
    for (std::size_t r = 1; r < rows.size(); ++r) {
      for (const std::string& field : rows[r]) {
        EXPECT_FALSE(non_finite_token(field)) << name << " row " << r << ": " << field;
      }
    }
  }
  std::istringstream yaml(read_all(out / "model.yaml"));
  for (std::string line; std::getline(yaml, line);) {
    const std::size_t colon = line.find(": ");
    std::string value = colon == std::string::npos ? line : line.substr(colon + 2);
    if (value.find('"') != std::string::npos) continue;
    if (value.rfind("- ", 0) == 0) value.erase(0, 2);
    for (std::size_t at = 0; at <= value.size();) {  // flow lists: [a, b, c]
      const std::size_t end = std::min(value.find_first_of(",[]", at), value.size());
      EXPECT_FALSE(non_finite_token(value.substr(at, end - at))) << "model.yaml: " << line;
      at = end + 1;
    }
  }
}

/// A clear failure: the expected exit code, one line on stderr naming the file, no outputs.
void expect_clear_error(const CommandResult& r, int code, const fs::path& file,
                        const std::string& fragment) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_THAT(r.err, HasSubstr(fragment));
  EXPECT_THAT(r.err, HasSubstr(file.filename().string()));
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
}

/// 20000 samples with two gaps: 50 samples missing before sample 5000 (file line 5002) and
/// 3 before sample 11950.
const std::vector<std::pair<std::size_t, std::size_t>> kTwoGaps{{5000, 5050}, {12000, 12003}};

TEST(EdgeCasesCli, GapsAreRefusedByDefaultWithWhereAndTheWayOut) {
  const fs::path dir = make_temp_dir("edge_gaps_refuse");
  const fs::path rec = dir / "gappy.csv";
  write_rows(rec, white_rows(20000, kTwoGaps));
  const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "out").string());
  expect_clear_error(r, 2, rec, "2 time-stamp gap(s)");
  EXPECT_THAT(r.err, HasSubstr("gappy.csv:5002: "));
  EXPECT_THAT(r.err, HasSubstr("the first before sample 5000 (t = 49.99 s, 0.51 s long)"));
  EXPECT_THAT(r.err, HasSubstr("the longest 0.51 s, about 53 samples missing"));
  EXPECT_THAT(r.err, HasSubstr("use --gaps split (pool the gap-free pieces) or --gaps "
                               "interpolate (fill linearly), or fix the recording"));
  EXPECT_FALSE(fs::exists(dir / "out" / "model.yaml"));
  // A bad policy name is an input error before the file is even read.
  const CommandResult bad =
      run_imunoise("analyze " + rec.string() + " --gaps fill -o " + (dir / "out").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_THAT(bad.err, HasSubstr("--gaps: expected refuse, split or interpolate, got 'fill'"));
}

TEST(EdgeCasesCli, SplitPoolsTheGapFreePiecesAndRecoversTheNoise) {
  const fs::path dir = make_temp_dir("edge_gaps_split");
  const fs::path rec = dir / "gappy.csv";
  // A third gap isolates 60 samples (too short a piece: dropped and counted).
  std::vector<std::pair<std::size_t, std::size_t>> cut = kTwoGaps;
  cut.push_back({15000, 15010});
  cut.push_back({15070, 15100});
  write_rows(rec, white_rows(20000, cut));
  const fs::path out = dir / "out";
  const CommandResult r =
      run_imunoise("analyze " + rec.string() + " --gaps split --bootstrap 0 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("--gaps split: 4 time-stamp gap(s); the curves and the PSD are "
                               "pooled over 4 gap-free piece(s) (19847 samples); 1 piece(s) "
                               "shorter than 100 samples dropped (60 samples)"));
  const models::NoiseModel model = io::load_model_yaml((out / "model.yaml").string());
  EXPECT_EQ(model.samples, 20000 - 53 - 40 - 60);
  for (const models::AxisModel& axis : model.axes) {
    const auto& n = axis.terms[static_cast<std::size_t>(NoiseTerm::white_noise)];
    ASSERT_TRUE(n.identified) << axis.name;
    // ~19800 samples: σ̂ at m = 1 has relative SD 1/√(2ν), ν ≈ 0.78·19800 → 0.57 %; 4× that.
    EXPECT_NEAR(n.value / kArw, 1.0, 0.025) << axis.name;
    EXPECT_THAT(axis.fit_note, HasSubstr("pooled over 4 gap-free pieces"));
  }
  expect_no_non_finite_outputs(out);
}

TEST(EdgeCasesCli, InterpolateFillsExactlyTheMissingSamples) {
  const fs::path dir = make_temp_dir("edge_gaps_interp");
  const fs::path rec = dir / "gappy.csv";
  write_rows(rec, white_rows(20000, kTwoGaps));
  const fs::path out = dir / "out";
  const CommandResult r = run_imunoise("analyze " + rec.string() +
                                       " --gaps interpolate --bootstrap 0 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const models::NoiseModel model = io::load_model_yaml((out / "model.yaml").string());
  EXPECT_EQ(model.samples, 20000);  // 19947 read + 53 filled
  bool said = false;
  for (const std::string& line : model.data_quality) {
    said = said || line.find(
                       "--gaps interpolate: 2 time-stamp gap(s) filled with 53 linearly "
                       "interpolated sample(s)") != std::string::npos;
  }
  EXPECT_TRUE(said) << r.out;
  expect_no_non_finite_outputs(out);
  // A gap longer than 1 % of the record (here 500 samples of 20000, limit 199): refused.
  const fs::path long_gap = dir / "long_gap.csv";
  write_rows(long_gap, white_rows(20000, {{8000, 8500}}));
  const CommandResult refused = run_imunoise("analyze " + long_gap.string() +
                                             " --gaps interpolate -o " + (dir / "o2").string());
  expect_clear_error(refused, 2, long_gap, "lacks 500 samples, more than interpolation may fill");
  EXPECT_THAT(refused.err, HasSubstr("use --gaps split"));
  EXPECT_THAT(refused.err, HasSubstr("line 8002"));
}

TEST(EdgeCasesCli, OneAndTwoSampleRecordsAreTooShort) {
  const fs::path dir = make_temp_dir("edge_short");
  for (std::size_t n : {1, 2}) {
    const fs::path rec = dir / ("rec" + std::to_string(n) + ".csv");
    write_rows(rec, white_rows(n, {}));
    const CommandResult a = run_imunoise("analyze " + rec.string() + " -o " + (dir / "o").string());
    EXPECT_TRUE(a.exit_code == 2 || a.exit_code == 3) << a.exit_code << " " << a.err;
    EXPECT_THAT(a.err, HasSubstr("too few samples"));
    EXPECT_THAT(a.err, HasSubstr(rec.filename().string()));
    const CommandResult b = run_imunoise("allan " + rec.string() + " --column gyro_x_rad_per_s");
    EXPECT_TRUE(b.exit_code == 2 || b.exit_code == 3) << b.exit_code << " " << b.err;
    EXPECT_THAT(b.err, HasSubstr("too few samples"));
  }
}

TEST(EdgeCasesCli, IdenticalTimeStampsGiveNoRate) {
  const fs::path dir = make_temp_dir("edge_same_time");
  const fs::path rec = dir / "rec.csv";
  std::vector<Row> rows = white_rows(3000, {});
  for (Row& r : rows) r.time = "12.5";
  write_rows(rec, rows);
  const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "o").string());
  expect_clear_error(r, 2, rec, "cannot estimate the sample rate: the time stamps never increase");
}

TEST(EdgeCasesCli, IrregularSamplingIsAnalysedAtTheMedianIntervalWithAJitterFinding) {
  // Intervals uniform in ±30 % of 10 ms: never a gap (limit 1.5×), so the analysis runs on the
  // median interval and names the jitter; nothing non-finite comes out.
  const fs::path dir = make_temp_dir("edge_irregular");
  const fs::path rec = dir / "rec.csv";
  std::vector<Row> rows = white_rows(20000, {});
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.7 * kPeriod, 1.3 * kPeriod);
  double t = 0.0;
  char buffer[64];
  for (Row& r : rows) {
    std::snprintf(buffer, sizeof buffer, "%.9f", t);
    r.time = buffer;
    t += u(rng);
  }
  write_rows(rec, rows);
  const fs::path out = dir / "out";
  const CommandResult r =
      run_imunoise("analyze " + rec.string() + " --bootstrap 0 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("time-stamp jitter"));
  expect_no_non_finite_outputs(out);
}

TEST(EdgeCasesCli, NanOrInfInAnyColumnIsRefusedWithItsLineOrDroppedAndCounted) {
  const fs::path dir = make_temp_dir("edge_nan");
  const std::vector<Row> clean = white_rows(5000, {});
  const char* spellings[] = {"nan", "inf", "-inf", "NaN"};
  for (int column = 0; column < 4; ++column) {  // time, gyro_x, gyro_y, gyro_z
    std::vector<Row> rows = clean;
    Row& bad = rows[1000];  // file line 1002
    (column == 0 ? bad.time : bad.gyro[column - 1]) = spellings[column];
    const fs::path rec = dir / ("rec" + std::to_string(column) + ".csv");
    write_rows(rec, rows);
    // Default: a located input error naming the column and the way to drop the row.
    const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "o").string());
    expect_clear_error(r, 2, rec, rec.filename().string() + ":1002:");
    EXPECT_THAT(r.err, HasSubstr("non-finite value"));
    EXPECT_THAT(r.err, HasSubstr("--drop-non-finite"));
    // --drop-non-finite: the row goes, which leaves a one-sample hole in the time stamps —
    // a gap, so the gap policy applies; interpolate fills it back.
    const CommandResult refused =
        run_imunoise("analyze " + rec.string() + " --drop-non-finite -o " + (dir / "o").string());
    expect_clear_error(refused, 2, rec, "1 time-stamp gap(s)");
    const fs::path out = dir / ("out" + std::to_string(column));
    const CommandResult filled =
        run_imunoise("analyze " + rec.string() +
                     " --drop-non-finite --gaps interpolate --bootstrap 0 -o " + out.string());
    ASSERT_EQ(filled.exit_code, 0) << filled.err;
    EXPECT_THAT(filled.out, HasSubstr("1 row(s) with NaN/Inf dropped"));
    EXPECT_THAT(filled.out, HasSubstr("filled with 1 linearly interpolated sample(s)"));
    EXPECT_EQ(io::load_model_yaml((out / "model.yaml").string()).samples, 5000);
    expect_no_non_finite_outputs(out);
  }
}

TEST(EdgeCasesCli, ValuesNearTheFloatLimitsAreAClearAnalysisError) {
  const fs::path dir = make_temp_dir("edge_float_limits");
  for (const char* scale : {"e300", "e-300", "e-320"}) {
    std::vector<Row> rows = white_rows(3000, {});
    for (Row& r : rows) {
      for (auto& v : r.gyro) v = v.substr(0, v.find('e')) + scale;  // mantissa × 10^scale
    }
    const fs::path rec = dir / (std::string("rec") + scale + ".csv");
    write_rows(rec, rows);
    const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "o").string());
    expect_clear_error(r, 3, rec, "outside what the analysis can square in double precision");
    EXPECT_FALSE(fs::exists(dir / "o" / "model.yaml"));
  }
  // 1e400 does not parse to a finite double: the reader's non-finite error, with its line.
  std::vector<Row> rows = white_rows(3000, {});
  rows[10].gyro[1] = "1e400";
  const fs::path rec = dir / "overflow.csv";
  write_rows(rec, rows);
  const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "o").string());
  EXPECT_TRUE(r.exit_code == 2) << r.exit_code << " " << r.err;
  EXPECT_THAT(r.err, HasSubstr("overflow.csv:12:"));
}

TEST(EdgeCasesCli, TausBeyondTheRecordAreAClearErrorNotAGarbagePoint) {
  const fs::path dir = make_temp_dir("edge_taus");
  const fs::path rec = dir / "rec.csv";
  write_rows(rec, white_rows(1000, {}));
  // 1000 samples → M = 1001 phase samples; OADEV allows m ≤ 250. m = 600 > N/2.
  const CommandResult a =
      run_imunoise("allan " + rec.string() + " --column gyro_x_rad_per_s --taus 1,10,600");
  EXPECT_EQ(a.exit_code, 3) << a.err;
  EXPECT_THAT(a.err, HasSubstr("m = 600"));
  EXPECT_THAT(a.err, HasSubstr("the largest usable m is 250"));
  const CommandResult huge = run_imunoise("allan " + rec.string() +
                                          " --column gyro_x_rad_per_s --taus 9000000000000000000");
  EXPECT_EQ(huge.exit_code, 3) << huge.err;
  EXPECT_THAT(huge.err, HasSubstr("more than 2^63"));
  const CommandResult b =
      run_imunoise("analyze " + rec.string() + " --taus 1,2,600 -o " + (dir / "o").string());
  EXPECT_EQ(b.exit_code, 3) << b.err;
  EXPECT_THAT(b.err, HasSubstr("the largest usable m is 250"));
  // In range, the explicit list is used as given.
  const CommandResult c =
      run_imunoise("allan " + rec.string() + " --column gyro_x_rad_per_s --taus 1,7,250 --json");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_THAT(c.out, HasSubstr("\"m\":250"));
  EXPECT_EQ(c.out.find("nan"), std::string::npos);
}

TEST(EdgeCasesCli, ConstantColumnInAllanIsZeroNotNan) {
  const fs::path dir = make_temp_dir("edge_constant_allan");
  const fs::path rec = dir / "rec.csv";
  std::vector<Row> rows = white_rows(2000, {});
  for (Row& r : rows) r.gyro[0] = "0.25";
  write_rows(rec, rows);
  const CommandResult r =
      run_imunoise("allan " + rec.string() + " --column gyro_x_rad_per_s --taus octave --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
  EXPECT_THAT(r.out, HasSubstr("\"value\":0"));
}

TEST(EdgeCasesCli, CommandLineMistakesExitTwoAndHelpExitsZero) {
  // Unknown flag, a value outside a set, a missing required argument: bad input, exit 2.
  for (const std::string args : {"analyze --no-such-flag x.csv -o out", "allan x.csv --type bogus",
                                 "analyze", "export model.yaml --to all --axis sideways"}) {
    const CommandResult r = run_imunoise(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_EQ(run_imunoise("analyze --help").exit_code, 0);
  // The version printed is the project's (CMakeLists.txt).
  const CommandResult version = run_imunoise("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, std::string(kSoftwareVersion) + "\n");
  EXPECT_THAT(version.out, ::testing::MatchesRegex("imunoise [0-9]+\\.[0-9]+\\.[0-9]+\n"));
}

}  // namespace
}  // namespace imunoise::test
