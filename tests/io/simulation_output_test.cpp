// Tests of io/simulation_setup.h and io/simulation_output.h: the set-up from a fitted
// model.yaml, the flicker-band default, the sample period of a binary output against
// pipeline::analyze_timing of the CSV stamps, the CSV header, and the three outputs read back
// (CSV, binary, LCM log) holding exactly the samples a simulator of the same seed generates.
#include "io/simulation_output.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "io/binary_recording.h"
#include "io/csv_reader.h"
#include "io/lcm_log.h"
#include "io/simulation_setup.h"
#include "pipeline/sampling_checks.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace fs = std::filesystem;

const fs::path kSource = IMUNOISE_SOURCE_DIR;

/// The six channels of RUN.samples samples from a fresh simulator of SETUP for RUN, drawn in
/// blocks of 4096 as write_simulation draws them.
std::array<std::vector<double>, 6> generated(const SimulationModelFile& setup,
                                             const SimulationRun& run) {
  models::ImuSimulator simulator = make_simulator(setup, run);
  std::array<std::vector<double>, 6> values;
  for (auto& v : values) v.resize(static_cast<std::size_t>(run.samples));
  for (std::size_t done = 0; done < values[0].size(); done += 4096) {
    const std::size_t n = std::min<std::size_t>(4096, values[0].size() - done);
    std::array<std::span<double>, 6> spans;
    for (std::size_t c = 0; c < 6; ++c) spans[c] = std::span<double>(values[c]).subspan(done, n);
    simulator.next_block(spans);
  }
  return values;
}

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b,
                      const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i]))
        << what << " sample " << i;
  }
}

TEST(SimulationSetup, FittedModelYamlBecomesItsPointEstimates) {
  const std::string path = (kSource / "tests/io/golden/export_native.txt").string();
  ASSERT_TRUE(is_fitted_model_file(path));
  const SimulationModelFile setup = load_simulation_setup(path);
  EXPECT_EQ(setup.source, path);
  EXPECT_EQ(setup.name, "fitted model of worked-example.csv");
  ASSERT_TRUE(setup.sample_rate_hz);
  EXPECT_EQ(*setup.sample_rate_hz, 200.0);
  EXPECT_EQ(setup.gyro[0].coefficients.white_noise, 0.00011635528346628864);
  EXPECT_EQ(setup.gyro[0].coefficients.random_walk, 6.806784082777885e-06);
  EXPECT_EQ(setup.gyro[0].bias, 0.0);
  EXPECT_EQ(setup.accel[2].signal, 0.0);  // the noise only: no gravity
}

TEST(SimulationSetup, SimulatorModelFileIsReadAsSuch) {
  const std::string path = (kSource / "configs/demo_imu.yaml").string();
  EXPECT_FALSE(is_fitted_model_file(path));
  const SimulationModelFile setup = load_simulation_setup(path);
  EXPECT_EQ(setup.source, path);
  EXPECT_GT(setup.gyro[0].coefficients.white_noise, 0.0);
}

TEST(SimulationSetup, InvalidAxisModelNamesTheAxis) {
  SimulationModelFile setup;
  setup.accel[1].coefficients.white_noise = -1.0;
  try {
    imu_noise_model(setup);
    ADD_FAILURE() << "no exception";
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), HasSubstr("accel.y"));
  }
}

TEST(SimulationRun, FlickerBandDefaultsToOneSampleToTheDuration) {
  SimulationModelFile setup;
  const SimulationRun run = simulation_run(setup, 100.0, 600.0, 60000, 3);
  EXPECT_EQ(run.flicker_band.tau_min_s, 0.01);
  EXPECT_EQ(run.flicker_band.tau_max_s, 600.0);
  EXPECT_EQ(run.seed, 3u);
  // At least two sample periods, for a record of one sample.
  EXPECT_EQ(simulation_run(setup, 100.0, 0.001, 1, 1).flicker_band.tau_max_s, 0.02);
  setup.flicker_band = models::FlickerBand{0.5, 7200.0};
  EXPECT_EQ(simulation_run(setup, 100.0, 600.0, 60000, 1).flicker_band.tau_max_s, 7200.0);
}

TEST(SimulatedSamplePeriod, IsTheMedianIntervalAnalyzeTimingFindsInTheStamps) {
  for (const double rate : {3.0, 50.0, 100.0, 400.0, 1000.0 / 3.0}) {
    for (const std::int64_t samples : {2, 3, 4, 1001, 10000}) {
      std::vector<double> stamps;
      for (std::int64_t k = 0; k < samples; ++k) stamps.push_back(static_cast<double>(k) / rate);
      EXPECT_EQ(simulated_sample_period_s(rate, samples),
                pipeline::analyze_timing(stamps).median_interval_s)
          << rate << " Hz, " << samples << " samples";
    }
  }
  EXPECT_EQ(simulated_sample_period_s(400.0, 1), 1.0 / 400.0);
}

TEST(SimulationOutputFormat, FollowsTheExtension) {
  EXPECT_EQ(simulation_output_format("a.imnb"), SimulationOutputFormat::kBinary);
  EXPECT_EQ(simulation_output_format("a.lcmlog"), SimulationOutputFormat::kLcmLog);
  EXPECT_EQ(simulation_output_format("a.csv"), SimulationOutputFormat::kCsv);
  EXPECT_EQ(simulation_output_format("a.log"), SimulationOutputFormat::kCsv);
  EXPECT_EQ(simulation_output_format(".imnb"), SimulationOutputFormat::kCsv);
}

TEST(SimulationCsvHeader, NamesModelSeedRateBandAndTerms) {
  SimulationModelFile setup;
  setup.source = "m.yaml";
  setup.name = "demo";
  setup.gyro[2].bias = 0.002;
  const SimulationRun run = simulation_run(setup, 100.0, 60.0, 6000, 7);
  std::ostringstream out;
  write_simulation_csv_header(out, setup, run);
  EXPECT_THAT(out.str(), StartsWith("# imunoise simulate: synthetic stationary IMU recording, SI "
                                    "units\n# model: m.yaml (demo)\n# seed: 7\n"
                                    "# sample_rate_hz: 100\n# duration_s: 60\n# samples: 6000\n"
                                    "# flicker_band_s: [0.01, 60]\n# gyro_x: (no terms)\n"));
  EXPECT_THAT(out.str(), HasSubstr("# gyro_z: bias_rad_per_s=0.002\n"));
  EXPECT_THAT(out.str(), HasSubstr("\ntime_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,"
                                   "accel_x_m_per_s2,accel_y_m_per_s2,accel_z_m_per_s2\n"));
}

class WriteSimulation : public ::testing::Test {
 protected:
  void SetUp() override {
    setup_ = load_simulation_setup((kSource / "configs/reference-imu.yaml").string());
    run_ = simulation_run(setup_, 50.0, 200.0, 10000, 11);  // several 4096-sample blocks
    expected_ = generated(setup_, run_);
    dir_ = test::make_temp_dir("simulation_output");
  }
  /// Writes the run to DIR/NAME; the progress calls are counted.
  std::string write(const std::string& name) {
    const std::string path = (dir_ / name).string();
    models::ImuSimulator simulator = make_simulator(setup_, run_);
    write_simulation(simulator, setup_, run_, path, "SIM",
                     [this](std::string_view stage, std::int64_t done, std::int64_t total) {
                       EXPECT_EQ(stage, "generating");
                       EXPECT_EQ(total, run_.samples);
                       EXPECT_LT(done, total);
                       ++progress_calls_;
                     });
    return path;
  }
  void expect_samples(const pipeline::Recording& rec) {
    ASSERT_EQ(rec.channels.size(), 6u);
    for (std::size_t c = 0; c < 6; ++c) {
      EXPECT_EQ(rec.channels[c].name, pipeline::kImuChannelNames[c]);
      expect_same_bits(rec.channels[c].values, expected_[c], rec.channels[c].name);
    }
  }

  SimulationModelFile setup_;
  SimulationRun run_;
  std::array<std::vector<double>, 6> expected_;
  fs::path dir_;
  int progress_calls_ = 0;
};

TEST_F(WriteSimulation, CsvReadsBackAsTheGeneratedSamples) {
  const pipeline::Recording rec = read_recording(write("sim.csv"), InputConfig{});
  expect_samples(rec);
  EXPECT_EQ(progress_calls_, 3);  // one per block
  ASSERT_EQ(rec.time_s.size(), 10000u);
  EXPECT_EQ(rec.time_s[4097], 4097.0 / 50.0);
}

TEST_F(WriteSimulation, BinaryHoldsTheCsvsSamplesAndPeriod) {
  const std::string binary = write("sim.imnb");
  const pipeline::Recording rec = read_binary_recording(binary);
  expect_samples(rec);
  const pipeline::Recording csv = read_recording(write("sim.csv"), InputConfig{});
  EXPECT_EQ(rec.sample_period_s, csv.sample_period_s);
  expect_same_bits(rec.time_s, csv.time_s, "time_s");
  const BinaryRecordingHeader header = read_binary_header(binary);
  EXPECT_EQ(header.source_path, setup_.source);
  EXPECT_EQ(header.channels[3].source_column, "accel_x_m_per_s2");
}

TEST_F(WriteSimulation, LcmLogHoldsTheSamplesStampedInWholeMicroseconds) {
  const pipeline::Recording rec = read_lcm_imu_log(write("sim.lcmlog"), "SIM");
  expect_samples(rec);
  EXPECT_DOUBLE_EQ(rec.time_s[1], 0.02);
}

TEST_F(WriteSimulation, UnwritablePathLeavesNothing) {
  models::ImuSimulator simulator = make_simulator(setup_, run_);
  const fs::path path = dir_ / "missing" / "sim.csv";
  const std::string message =
      test::error_of([&] { write_simulation(simulator, setup_, run_, path.string(), "SIM"); });
  EXPECT_THAT(message, HasSubstr(path.string()));
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
}

}  // namespace
}  // namespace imunoise::io
