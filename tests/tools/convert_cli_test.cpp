// Process-level tests of `imunoise convert` (tools/cmd_convert.cpp), `simulate -o FILE.imnb`
// and binary input to the analysis commands (tools/recording_input.cpp): a binary recording
// analyses to the same bytes as the CSV it came from, CSV ↔ binary round trips keep every
// sample bit for bit, and bad requests exit 2 with a message naming the problem.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/binary_recording.h"
#include "io/lcm_log.h"
#include "test_support.h"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// TEXT with every occurrence of FROM replaced by TO.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
  return text;
}

/// The data section of a binary recording (from the first 64-aligned offset after the JSON
/// header, per docs/binary-format.md; read here without io/).
std::string data_section(const fs::path& path) {
  const std::string bytes = read_file_bytes(path);
  if (bytes.size() < 24) return {};
  std::uint64_t json = 0;
  std::memcpy(&json, bytes.data() + 16, 8);
  return bytes.substr((24 + json + 63) / 64 * 64);
}

/// The lines of a text file that are not '#' comments.
std::vector<std::string> data_lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("#")) lines.push_back(line);
  }
  return lines;
}

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b,
                      const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i]))
        << what << " sample " << i;
  }
}

/// One simulated recording (60 s at 100 Hz, reference IMU), written by simulate as CSV and as
/// binary, and the CSV converted to binary, shared by the tests below.
class ConvertCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(make_temp_dir("convert_cli"));
    const std::string model =
        quoted_for_shell(fs::path(IMUNOISE_SOURCE_DIR) / "configs/reference-imu.yaml");
    for (const char* name : {"rec.csv", "sim.imnb"}) {
      const auto r = run_imunoise("simulate " + model + " --duration 60s --rate 100 --seed 5 -o " +
                                  quoted_for_shell(*dir_ / name));
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const auto r = run_imunoise("convert " + quoted_for_shell(*dir_ / "rec.csv") + " -q -o " +
                                quoted_for_shell(*dir_ / "conv.imnb"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("wrote 6000 samples"));
  }
  static void TearDownTestSuite() { delete dir_; }
  static const fs::path& dir() { return *dir_; }
  static inline const std::string kAnalysisFlags = " -q --bootstrap 4 --seed 9";

 private:
  static inline fs::path* dir_ = nullptr;
};

TEST_F(ConvertCli, AnalyzeOnBinaryGivesTheCsvResultsByteForByte) {
  for (const char* input : {"rec.csv", "conv.imnb"}) {
    const auto r = run_imunoise("analyze " + quoted_for_shell(dir() / input) + kAnalysisFlags +
                                " -o " + quoted_for_shell(dir() / (std::string("a_") + input)));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const fs::path csv = dir() / "a_rec.csv";
  const fs::path bin = dir() / "a_conv.imnb";
  // model.yaml names its source (path and file name); everything else must be the same bytes.
  std::string model_bin = read_file_bytes(bin / "model.yaml");
  model_bin = replaced(model_bin, (dir() / "conv.imnb").string(), (dir() / "rec.csv").string());
  model_bin = replaced(model_bin, "conv.imnb", "rec.csv");
  const std::string model_csv = read_file_bytes(csv / "model.yaml");
  ASSERT_FALSE(model_csv.empty());
  EXPECT_EQ(model_bin, model_csv);
  const std::string allan_csv = read_file_bytes(csv / "allan.csv");
  ASSERT_FALSE(allan_csv.empty());
  EXPECT_EQ(read_file_bytes(bin / "allan.csv"), allan_csv);
  EXPECT_EQ(read_file_bytes(bin / "psd.csv"), read_file_bytes(csv / "psd.csv"));
}

TEST_F(ConvertCli, BinaryToCsvToBinaryKeepsEveryByteOfData) {
  const auto r1 = run_imunoise("convert " + quoted_for_shell(dir() / "conv.imnb") + " -q -o " +
                               quoted_for_shell(dir() / "back.csv"));
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  // The same columns and numbers as simulate's own CSV (shortest round-trip text).
  const auto back_lines = data_lines(dir() / "back.csv");
  ASSERT_EQ(back_lines.size(), 6001U);
  EXPECT_EQ(back_lines, data_lines(dir() / "rec.csv"));
  const auto r2 = run_imunoise("convert " + quoted_for_shell(dir() / "back.csv") + " -q -o " +
                               quoted_for_shell(dir() / "back.imnb"));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const std::string data = data_section(dir() / "conv.imnb");
  EXPECT_EQ(data.size(), 7U * 48000U);  // 6000 × 8 bytes is a multiple of 64
  EXPECT_EQ(data_section(dir() / "back.imnb"), data);
}

TEST_F(ConvertCli, SimulateBinaryEqualsTheConvertedCsv) {
  EXPECT_EQ(data_section(dir() / "sim.imnb"), data_section(dir() / "conv.imnb"));
  const pipeline::Recording sim = io::read_binary_recording((dir() / "sim.imnb").string());
  const pipeline::Recording conv = io::read_binary_recording((dir() / "conv.imnb").string());
  EXPECT_EQ(std::bit_cast<std::uint64_t>(sim.sample_period_s),
            std::bit_cast<std::uint64_t>(conv.sample_period_s));
  EXPECT_EQ(sim.start_time_s, conv.start_time_s);
  expect_same_bits(sim.time_s, conv.time_s, "time_s");
  ASSERT_EQ(sim.channels.size(), 6U);
  ASSERT_EQ(conv.channels.size(), 6U);
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_EQ(sim.channels[c].name, conv.channels[c].name);
    EXPECT_EQ(sim.channels[c].unit(), conv.channels[c].unit());
    EXPECT_EQ(sim.channels[c].source_column, conv.channels[c].source_column);
    EXPECT_EQ(sim.channels[c].source_unit, conv.channels[c].source_unit);
    expect_same_bits(sim.channels[c].values, conv.channels[c].values, sim.channels[c].name);
  }
  const io::BinaryRecordingHeader header = io::read_binary_header((dir() / "sim.imnb").string());
  EXPECT_THAT(header.source_path, HasSubstr("reference-imu.yaml"));
  EXPECT_EQ(io::read_binary_header((dir() / "conv.imnb").string()).source_path,
            (dir() / "rec.csv").string());
}

TEST_F(ConvertCli, CsvToLcmLogReadsBackTheSameSamples) {
  const fs::path log = dir() / "rec.lcmlog";
  const auto r = run_imunoise("convert " + quoted_for_shell(dir() / "rec.csv") + " -q -o " +
                              quoted_for_shell(log) + " --lcm-channel IMU_A");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto check = run_imunoise("check " + quoted_for_shell(log) + " --json");
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("\"samples\": 6000"));
  const pipeline::Recording from_log = io::read_lcm_imu_log(log.string(), "IMU_A");
  const pipeline::Recording from_bin = io::read_binary_recording((dir() / "conv.imnb").string());
  ASSERT_EQ(from_log.channels.size(), 6U);
  for (std::size_t c = 0; c < 6; ++c) {
    expect_same_bits(from_log.channels[c].values, from_bin.channels[c].values,
                     from_bin.channels[c].name);
  }
  EXPECT_NEAR(from_log.sample_period_s, 0.01, 1e-15);  // whole µs stamps
}

TEST_F(ConvertCli, BinaryInputWorksForCheckAndDrift) {
  const auto check_bin = run_imunoise("check " + quoted_for_shell(dir() / "conv.imnb"));
  const auto check_csv = run_imunoise("check " + quoted_for_shell(dir() / "rec.csv"));
  ASSERT_EQ(check_bin.exit_code, 0) << check_bin.err;
  ASSERT_EQ(check_csv.exit_code, 0) << check_csv.err;
  EXPECT_EQ(replaced(check_bin.out, (dir() / "conv.imnb").string(), (dir() / "rec.csv").string()),
            check_csv.out);
}

TEST_F(ConvertCli, FixedRateCsvWithAnExtraColumnKeepsItInBinary) {
  const fs::path csv = dir() / "fixed.csv";
  write_text(csv, "gx,gy,gz,temp\n0.1,0.2,0.3,20.5\n0.4,0.5,0.6,20.25\n0.7,0.8,0.9,20\n");
  const fs::path config = dir() / "fixed.yaml";
  write_text(config,
             "rate_hz: 3\ngyro:\n  columns: [gx, gy, gz]\nextra_columns:\n  temperature: temp\n");
  const fs::path bin = dir() / "fixed.imnb";
  const auto r = run_imunoise("convert " + quoted_for_shell(csv) + " --config " +
                              quoted_for_shell(config) + " -q -o " + quoted_for_shell(bin));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const pipeline::Recording rec = io::read_binary_recording(bin.string());
  ASSERT_EQ(rec.channels.size(), 4U);
  EXPECT_EQ(rec.channels[3].name, "temperature");
  EXPECT_EQ(rec.channels[3].values, (std::vector<double>{20.5, 20.25, 20.0}));
  EXPECT_TRUE(rec.time_s.empty());
  EXPECT_EQ(rec.report.timing.rate_hz, 3.0);
  // To CSV: time_s = k / 3 and the extra column kept by name.
  const auto r2 = run_imunoise("convert " + quoted_for_shell(bin) + " -q --to csv -o " +
                               quoted_for_shell(dir() / "fixed.out"));
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const auto lines = data_lines(dir() / "fixed.out");
  ASSERT_EQ(lines.size(), 4U);
  EXPECT_EQ(lines[0], "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,temperature");
  EXPECT_EQ(lines[2], "0.3333333333333333,0.4,0.5,0.6,20.25");
}

/// Three samples of the three gyro axes, in the columns `simulate` writes.
constexpr const char* kGyroOnlyCsv =
    "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\n0,1,2,3\n0.01,2,3,4\n0.02,3,4,5\n";

TEST(ConvertCliErrors, UnknownExtensionExits2WithoutOutput) {
  const fs::path dir = make_temp_dir("convert_err");
  write_text(dir / "rec.csv", kGyroOnlyCsv);
  const auto r = run_imunoise("convert " + quoted_for_shell(dir / "rec.csv") + " -o " +
                              quoted_for_shell(dir / "x.dat"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("cannot tell the output format"));
  EXPECT_THAT(r.err, HasSubstr("--to csv|binary|lcm"));
  EXPECT_FALSE(fs::exists(dir / "x.dat"));
  const auto ok = run_imunoise("convert " + quoted_for_shell(dir / "rec.csv") +
                               " -q --to binary -o " + quoted_for_shell(dir / "x.dat"));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(io::is_binary_recording_file((dir / "x.dat").string()));
  const auto bad_to = run_imunoise("convert " + quoted_for_shell(dir / "rec.csv") +
                                   " --to parquet -o " + quoted_for_shell(dir / "y.csv"));
  EXPECT_EQ(bad_to.exit_code, 2);
  EXPECT_THAT(bad_to.err, HasSubstr("--to 'parquet'"));
}

TEST(ConvertCliErrors, MissingInputExits2) {
  const fs::path dir = make_temp_dir("convert_missing");
  const auto r = run_imunoise("convert " + quoted_for_shell(dir / "none.csv") + " -o " +
                              quoted_for_shell(dir / "out.imnb"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("none.csv"));
  EXPECT_FALSE(fs::exists(dir / "out.imnb"));
}

TEST(ConvertCliErrors, LcmOutputNeedsTheSixImuChannels) {
  const fs::path dir = make_temp_dir("convert_lcm6");
  write_text(dir / "rec.csv", kGyroOnlyCsv);
  const auto r = run_imunoise("convert " + quoted_for_shell(dir / "rec.csv") + " -o " +
                              quoted_for_shell(dir / "o.lcm"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("missing: accel_x, accel_y, accel_z"));
  EXPECT_FALSE(fs::exists(dir / "o.lcm"));
}

TEST(ConvertCliErrors, TableFlagsOnBinaryInputExit2NamingTheFlag) {
  const fs::path dir = make_temp_dir("convert_flags");
  write_text(dir / "rec.csv", kGyroOnlyCsv);
  ASSERT_EQ(run_imunoise("convert " + quoted_for_shell(dir / "rec.csv") + " -q -o " +
                         quoted_for_shell(dir / "r.imnb"))
                .exit_code,
            0);
  const std::string bin = quoted_for_shell(dir / "r.imnb");
  const auto rate =
      run_imunoise("convert " + bin + " --rate 100 -o " + quoted_for_shell(dir / "o.csv"));
  EXPECT_EQ(rate.exit_code, 2);
  EXPECT_THAT(rate.err, HasSubstr("--rate does not apply to an imunoise binary recording (the "
                                  "binary header carries rate and units)"));
  const auto cols =
      run_imunoise("analyze " + bin + " --gyro-cols 2 -o " + quoted_for_shell(dir / "out"));
  EXPECT_EQ(cols.exit_code, 2);
  EXPECT_THAT(cols.err, HasSubstr("--gyro-cols does not apply"));
  const auto channel = run_imunoise("check " + bin + " --channel IMU");
  EXPECT_EQ(channel.exit_code, 2);
  EXPECT_THAT(channel.err, HasSubstr("--channel does not apply"));
  EXPECT_FALSE(fs::exists(dir / "o.csv"));
}

TEST(ConvertCliErrors, CorruptBinaryInputExits2NamingTheFile) {
  const fs::path dir = make_temp_dir("convert_corrupt");
  write_text(dir / "rec.csv", kGyroOnlyCsv);
  ASSERT_EQ(run_imunoise("convert " + quoted_for_shell(dir / "rec.csv") + " -q -o " +
                         quoted_for_shell(dir / "r.imnb"))
                .exit_code,
            0);
  std::string bytes = read_file_bytes(dir / "r.imnb");
  bytes.pop_back();
  std::ofstream(dir / "r.imnb", std::ios::binary | std::ios::trunc) << bytes;
  const auto r = run_imunoise("check " + quoted_for_shell(dir / "r.imnb"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr((dir / "r.imnb").string() + ": file size"));
}

}  // namespace
}  // namespace imunoise::test
