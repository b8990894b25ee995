/// @file
/// @brief End-to-end tests of `imunoise fftw-wisdom` (tools/cmd_fftw_wisdom.cpp) and of
/// `analyze --fftw-wisdom` / IMUNOISE_FFTW_WISDOM: the wisdom file is written, analyze plans
/// its PSD from it (said with -v) and writes the same psd.csv up to rounding; a bad file is
/// exit 2 naming it. Records of 10 000 samples (200 s at 50 Hz): automatic L = 1024.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "test_support.h"

namespace imunoise::test {
namespace {

constexpr const char* kEnv = "IMUNOISE_FFTW_WISDOM";

/// Every test runs with IMUNOISE_FFTW_WISDOM unset (the user's value is put back after), so a
/// wisdom file in the developer's environment changes no expectation.
class FftwWisdomCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* value = std::getenv(kEnv)) saved_ = value;
    ::unsetenv(kEnv);
  }
  void TearDown() override {
    if (saved_) {
      ::setenv(kEnv, saved_->c_str(), 1);
    } else {
      ::unsetenv(kEnv);
    }
  }

  /// 200 s of the reference IMU at 50 Hz in DIR/rec.csv.
  static std::filesystem::path simulate_record(const std::filesystem::path& dir) {
    const auto rec = dir / "rec.csv";
    const auto model =
        std::filesystem::path(IMUNOISE_SOURCE_DIR) / "configs" / "reference-imu.yaml";
    const CommandResult sim =
        run_imunoise("simulate " + quoted_for_shell(model) +
                     " --duration 200s --rate 50 --seed 4 -o " + quoted_for_shell(rec));
    EXPECT_EQ(sim.exit_code, 0) << sim.err;
    return rec;
  }

  static CommandResult analyze(const std::filesystem::path& rec, const std::filesystem::path& out,
                               const std::string& extra) {
    return run_imunoise("analyze " + quoted_for_shell(rec) + " -o " + quoted_for_shell(out) +
                        " --bootstrap 0 -v " + extra);
  }

  std::optional<std::string> saved_;
};

TEST_F(FftwWisdomCli, WritesTheWisdomFileAndPrintsTheTimes) {
  const auto dir = make_temp_dir("wisdom_cli");
  const auto wisdom = dir / "plans.wisdom";
  const CommandResult r =
      run_imunoise("fftw-wisdom --length 1024 --samples 10000 -o " + quoted_for_shell(wisdom));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file_bytes(wisdom).rfind("(fftw-", 0), 0u);
  // --samples 10000 resolves to the same L = 1024: planned once.
  EXPECT_NE(r.out.find("L = 1024"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("L = 1024", r.out.find("L = 1024") + 1), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("measure planning"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("with FFTW_ESTIMATE"), std::string::npos) << r.out;

  // --merge keeps what the file holds: 1024 is not measured again.
  const CommandResult merged =
      run_imunoise("fftw-wisdom --length 1024,64 --merge -o " + quoted_for_shell(wisdom));
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.out.find("L = 1024 (--length): already in the merged wisdom"), std::string::npos)
      << merged.out;
  EXPECT_NE(merged.out.find("L = 64 (--length): measure planning"), std::string::npos)
      << merged.out;

  // Nothing to plan, or a length FFTW cannot take: bad input.
  EXPECT_EQ(run_imunoise("fftw-wisdom -o " + quoted_for_shell(wisdom)).exit_code, 2);
  EXPECT_EQ(run_imunoise("fftw-wisdom --samples 8 -o " + quoted_for_shell(wisdom)).exit_code, 2);
}

TEST_F(FftwWisdomCli, AnalyzeWithWisdomSaysSoAndWritesTheSamePsd) {
  const auto dir = make_temp_dir("wisdom_analyze");
  const auto rec = simulate_record(dir);
  const auto wisdom = dir / "plans.wisdom";
  ASSERT_EQ(run_imunoise("fftw-wisdom --length 1024 -o " + quoted_for_shell(wisdom)).exit_code, 0);

  const CommandResult plain = analyze(rec, dir / "plain", "");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.err.find("PSD FFT plan (L = 1024): FFTW_ESTIMATE"), std::string::npos)
      << plain.err;
  const CommandResult wise =
      analyze(rec, dir / "wise", "--fftw-wisdom " + quoted_for_shell(wisdom));
  ASSERT_EQ(wise.exit_code, 0) << wise.err;
  EXPECT_NE(wise.err.find("PSD FFT plan (L = 1024): from FFTW wisdom"), std::string::npos)
      << wise.err;

  const auto a = read_csv_rows(dir / "plain" / "psd.csv");
  const auto b = read_csv_rows(dir / "wise" / "psd.csv");
  ASSERT_GT(a.size(), 10u);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a[0], b[0]);
  for (std::size_t row = 1; row < a.size(); ++row) {
    ASSERT_EQ(a[row].size(), b[row].size()) << "row " << row;
    for (std::size_t col = 0; col < a[row].size(); ++col) {
      if (a[row][col].empty() || b[row][col].empty()) {
        EXPECT_EQ(a[row][col], b[row][col]);
        continue;
      }
      const double x = std::stod(a[row][col]);
      const double y = std::stod(b[row][col]);
      EXPECT_LE(std::abs(x - y), 1e-9 * std::max(std::abs(x), std::abs(y)))
          << a[0][col] << " at row " << row << ": " << a[row][col] << " vs " << b[row][col];
    }
  }
}

TEST_F(FftwWisdomCli, AnalyzeTakesTheWisdomFileFromTheEnvironment) {
  const auto dir = make_temp_dir("wisdom_env");
  const auto rec = simulate_record(dir);
  const auto wisdom = dir / "plans.wisdom";
  ASSERT_EQ(run_imunoise("fftw-wisdom --samples 10000 -o " + quoted_for_shell(wisdom)).exit_code,
            0);
  ::setenv(kEnv, wisdom.c_str(), 1);
  const CommandResult r = analyze(rec, dir / "out", "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("PSD FFT plan (L = 1024): from FFTW wisdom"), std::string::npos) << r.err;
  // An empty option switches the environment's file off.
  const CommandResult off = analyze(rec, dir / "off", "--fftw-wisdom ''");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_NE(off.err.find("PSD FFT plan (L = 1024): FFTW_ESTIMATE"), std::string::npos) << off.err;
  // The option wins over the environment: a bad file named there is what fails.
  const auto garbage = dir / "garbage.wisdom";
  write_text(garbage, "not wisdom\n");
  const CommandResult bad = analyze(rec, dir / "bad", "--fftw-wisdom " + quoted_for_shell(garbage));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find(garbage.string()), std::string::npos) << bad.err;
}

TEST_F(FftwWisdomCli, BadWisdomFileIsExit2WithOneLineNamingIt) {
  const auto dir = make_temp_dir("wisdom_bad");
  const auto rec = dir / "rec.csv";  // never read: the wisdom file fails first
  write_text(rec, "time_s,gyro_x_rad_per_s\n0,0\n");
  const auto garbage = dir / "garbage.wisdom";
  write_text(garbage, "(this is not fftw wisdom)\n");
  const CommandResult r = analyze(rec, dir / "out", "--fftw-wisdom " + quoted_for_shell(garbage));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "imunoise: error: " + garbage.string() +
                       ": not an FFTW wisdom file, or wisdom of another FFTW version or precision "
                       "(make it with 'imunoise fftw-wisdom')\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));

  ::setenv(kEnv, (dir / "missing.wisdom").c_str(), 1);
  const CommandResult missing = analyze(rec, dir / "out", "");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(
      missing.err.find((dir / "missing.wisdom").string() + ": cannot open the FFTW wisdom file"),
      std::string::npos)
      << missing.err;
}

}  // namespace
}  // namespace imunoise::test
