/// @file
/// @brief End-to-end tests of `imunoise analyze` (tools/cmd_analyze.cpp): a simulated record
/// in, model.yaml / allan.csv / psd.csv out with the truth inside the intervals; bad records
/// stop with one clear line, a non-zero exit and no output files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/units.h"
#include "io/noise_model_yaml.h"
#include "models/noise_model.h"
#include "test_support.h"

namespace imunoise::test {
namespace {

/// Gyro: N = 0.4 deg/√h, K = 84.24 deg/h/√h (theory.md §8.2); accel: VRW only; at 50 Hz.
void write_white_and_walk_model(const std::filesystem::path& file) {
  write_text(file,
             "sample_rate_hz: 50\n"
             "gyro:\n  arw_rad_per_sqrt_s: 1.16355e-4\n  rrw_rad_per_s_sqrt_s: 6.80678e-6\n"
             "accel:\n  vrw_m_per_s_sqrt_s: 1.471e-3\n"
             "  z: {specific_force_m_per_s2: -9.80665}\n");
}

/// DIR/rec.csv: the white-and-walk model (written to DIR/truth.yaml) simulated for DURATION
/// with SEED; empty when simulate failed (the test then fails with its message).
std::filesystem::path simulated_white_and_walk(const std::filesystem::path& dir,
                                               const std::string& duration, int seed) {
  const auto model_file = dir / "truth.yaml";
  write_white_and_walk_model(model_file);
  const auto rec = dir / "rec.csv";
  const CommandResult sim =
      run_imunoise("simulate " + model_file.string() + " --duration " + duration + " --seed " +
                   std::to_string(seed) + " -o " + rec.string());
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  return sim.exit_code == 0 ? rec : std::filesystem::path();
}

TEST(AnalyzeCli, SimulatedRecordGivesModelYamlAndCsvFilesWithTheTruthInside) {
  const auto dir = make_temp_dir("analyze_cli");
  const auto model_file = dir / "truth.yaml";
  write_white_and_walk_model(model_file);
  const auto rec = dir / "rec.csv";
  ASSERT_EQ(
      run_imunoise("simulate " + model_file.string() + " --duration 1h --seed 3 -o " + rec.string())
          .exit_code,
      0);
  const auto out = dir / "out";
  const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + out.string() +
                                       " --bootstrap 20 --truth " + model_file.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("white_noise [deg/sqrt(h)]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("true 0.4"), std::string::npos) << r.out;
  ASSERT_TRUE(std::filesystem::exists(out / "model.yaml"));
  const models::NoiseModel model = io::load_model_yaml((out / "model.yaml").string());
  // The rate comes from the median time-stamp interval as printed in the CSV.
  EXPECT_NEAR(model.sample_rate_hz, 50.0, 1e-9);
  EXPECT_EQ(model.samples, 180000);
  ASSERT_EQ(model.axes.size(), 6u);
  const models::AxisModel* gx = model.find_axis("gyro_x");
  ASSERT_NE(gx, nullptr);
  const auto& n = gx->terms[static_cast<std::size_t>(NoiseTerm::white_noise)];
  EXPECT_TRUE(n.identified);
  EXPECT_LE(n.ci_low, 1.16355e-4);
  EXPECT_GE(n.ci_high, 1.16355e-4);
  const models::AxisModel* az = model.find_axis("accel_z");
  ASSERT_NE(az, nullptr);
  EXPECT_EQ(az->kind, SensorKind::accel);
  EXPECT_NEAR(az->terms[1].value / 1.471e-3, 1.0, 0.05);  // the gravity constant is not noise

  const auto allan = read_csv_rows(out / "allan.csv");
  ASSERT_GT(allan.size(), 10u);
  EXPECT_EQ(allan[0][0], "m");
  EXPECT_EQ(allan[0][2], "gyro_x_oadev_rad_per_s");
  bool accel_unit = false;
  for (const auto& column : allan[0]) accel_unit |= column == "accel_z_oadev_m_per_s2";
  EXPECT_TRUE(accel_unit);
  // The fitted model.yaml drives the simulator directly (noise only, the fitted terms).
  const CommandResult sim = run_imunoise("simulate " + (out / "model.yaml").string() +
                                         " --duration 60s -o " + (dir / "refit.csv").string());
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto refit = read_csv_rows(dir / "refit.csv");
  EXPECT_GT(refit.size(), 3000u);  // 60 s at the model's 50 Hz, plus the header
  const auto psd = read_csv_rows(out / "psd.csv");
  ASSERT_GT(psd.size(), 10u);
  EXPECT_EQ(psd[0][0], "frequency_hz");
  EXPECT_EQ(psd[0][1], "gyro_x_psd_rad2_per_s2_per_hz");
  bool accel_psd_unit = false;
  for (const auto& column : psd[0]) accel_psd_unit |= column == "accel_z_psd_m2_per_s4_per_hz";
  EXPECT_TRUE(accel_psd_unit);
}

TEST(AnalyzeCli, ConstantChannelStopsWithAClearMessageAndNoOutput) {
  const auto dir = make_temp_dir("analyze_constant");
  const auto rec = dir / "rec.csv";
  std::ofstream csv(rec);
  csv << "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\n";
  for (int i = 0; i < 2000; ++i) csv << i * 0.01 << ",0.001,0.001,0.001\n";
  csv.close();
  const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("constant"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "model.yaml"));
}

TEST(AnalyzeCli, ThreadCountDoesNotChangeAnyOutput) {
  // --threads splits the axes, the τ passes of the deviations and the bootstrap replicates;
  // every result must be the same bytes whatever the split (issue 8). 60 000 samples is above
  // the size where the deviations themselves go parallel.
  const auto dir = make_temp_dir("analyze_threads");
  const auto rec = dir / "rec.csv";
  const auto model = std::filesystem::path(IMUNOISE_SOURCE_DIR) / "configs" / "reference-imu.yaml";
  const CommandResult sim = run_imunoise("simulate " + model.string() +
                                         " --duration 20min --rate 50 --seed 8 -o " + rec.string());
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  // The default intervals (the interval draws of the OAVAR vector, issue 21) and the simulated
  // record bootstrap.
  for (const std::string intervals : {"", " --bootstrap 2"}) {
    std::string reference[3];
    for (const char* threads : {"1", "3", "2"}) {
      const auto out = dir / (std::string("out") + threads + (intervals.empty() ? "d" : "b"));
      const CommandResult r = run_imunoise("analyze " + rec.string() + intervals + " --threads " +
                                           threads + " -o " + out.string());
      ASSERT_EQ(r.exit_code, 0) << r.err;
      int k = 0;
      for (const char* name : {"model.yaml", "allan.csv", "psd.csv"}) {
        const std::string text = read_file_bytes(out / name);
        ASSERT_FALSE(text.empty()) << name;
        if (reference[k].empty()) {
          reference[k] = text;
        } else {
          EXPECT_TRUE(text == reference[k])
              << name << " differs with --threads " << threads << intervals;
        }
        ++k;
      }
    }
  }
}

TEST(AnalyzeCli, GeneralizedLeastSquaresEstimatorIsNamedAndKeepsTheTruthInside) {
  // `--estimator gls` re-estimates the selected model with the correlation across τ; the
  // estimate's method says so, and N stays inside its interval. A wrong name is refused.
  const auto dir = make_temp_dir("analyze_gls");
  const auto rec = simulated_white_and_walk(dir, "30min", 5);
  ASSERT_FALSE(rec.empty());
  const auto out = dir / "out";
  const CommandResult r =
      run_imunoise("analyze " + rec.string() + " --estimator gls -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const models::NoiseModel model = io::load_model_yaml((out / "model.yaml").string());
  const models::AxisModel* gx = model.find_axis("gyro_x");
  ASSERT_NE(gx, nullptr);
  const auto& n = gx->terms[static_cast<std::size_t>(NoiseTerm::white_noise)];
  EXPECT_EQ(n.method, "gls-oavar");
  EXPECT_LE(n.ci_low, 1.16355e-4);
  EXPECT_GE(n.ci_high, 1.16355e-4);

  const CommandResult bad =
      run_imunoise("analyze " + rec.string() + " --estimator ols -o " + (dir / "bad").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--estimator: expected wnnls or gls, got 'ols'"), std::string::npos)
      << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad" / "model.yaml"));
  const CommandResult edf =
      run_imunoise("analyze " + rec.string() + " --min-edf 0.5 -o " + (dir / "bad").string());
  EXPECT_NE(edf.exit_code, 0);
  EXPECT_NE(edf.err.find("--min-edf: expected an EDF in [1, 100], got 0.5"), std::string::npos)
      << edf.err;
}

TEST(AnalyzeCli, DatasheetSpecShowsAWhiteNoiseAboveItsDensityAsADecimation) {
  // The truth's gyro N is 0.4 deg/√h and its accel N 1.471e-3 m/s/√s = 150 µg/√Hz. Against a
  // datasheet of half the gyro density (what a decimation by 4 without averaging does to the
  // record) each gyro axis gets the finding and no accel axis; against the truth's own
  // densities none does; a spec file that does not exist stops with its path.
  const auto dir = make_temp_dir("analyze_spec");
  const auto rec = simulated_white_and_walk(dir, "20min", 6);
  ASSERT_FALSE(rec.empty());
  const auto findings_with = [&](const std::string& spec_text, const std::string& name) {
    const auto spec = dir / (name + ".yaml");
    write_text(spec, spec_text);
    const auto out = dir / name;
    const CommandResult r = run_imunoise("analyze " + rec.string() + " --spec " + spec.string() +
                                         " -o " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> lines;
    for (const std::string& line : io::load_model_yaml((out / "model.yaml").string()).data_quality)
      if (line.find("decimated without averaging") != std::string::npos) lines.push_back(line);
    return lines;
  };
  const std::vector<std::string> half = findings_with(
      "name: half density\ngyro:\n  arw_deg_per_sqrt_h: 0.2\naccel:\n  vrw_ug_per_sqrt_hz: "
      "150\n",
      "half");
  ASSERT_EQ(half.size(), 3u);
  for (std::size_t i = 0; i < half.size(); ++i) {
    EXPECT_EQ(half[i].rfind(std::string("gyro_") + "xyz"[i] + ": output likely decimated", 0), 0u)
        << half[i];
    EXPECT_NE(half[i].find("the datasheet's 0.2 deg/sqrt(h) (half density)"), std::string::npos)
        << half[i];
  }
  EXPECT_TRUE(
      findings_with("gyro:\n  arw_deg_per_sqrt_h: 0.4\naccel:\n  vrw_ug_per_sqrt_hz: 150\n", "same")
          .empty());

  const CommandResult missing =
      run_imunoise("analyze " + rec.string() + " --spec " + (dir / "nope.yaml").string() + " -o " +
                   (dir / "bad").string());
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("nope.yaml"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad" / "model.yaml"));
}

TEST(AnalyzeCli, TooShortRecordStopsWithAClearMessage) {
  const auto dir = make_temp_dir("analyze_short");
  const auto rec = dir / "rec.csv";
  std::ofstream csv(rec);
  csv << "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\n0,0.1,0.1,0.1\n"
         "0.01,0.2,0.1,0.1\n0.02,0.15,0.1,0.1\n0.03,0.3,0.1,0.1\n";
  csv.close();
  const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("too few samples"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "model.yaml"));
}

TEST(AnalyzeCli, AllNanChannelIsRefusedNotWrittenAsNan) {
  const auto dir = make_temp_dir("analyze_nan");
  const auto rec = dir / "rec.csv";
  std::ofstream csv(rec);
  csv << "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\n";
  for (int i = 0; i < 2000; ++i) csv << i * 0.01 << ",nan,nan,nan\n";
  csv.close();
  const CommandResult r = run_imunoise("analyze " + rec.string() + " -o " + (dir / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(r.err.empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "model.yaml"));
}

}  // namespace
}  // namespace imunoise::test
