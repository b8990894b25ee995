/// @file
/// @brief End-to-end tests of `imunoise drift` (tools/cmd_drift.cpp): a simulated stationary
/// recording and the model it was simulated from give the three output files with units in
/// the column names and consistent statistics; a moving recording is refused unless forced.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/sensor_kind.h"
#include "test_support.h"

namespace imunoise::test {
namespace {

/// Simulator model: white + RW noise (what the fitted model below carries exactly), level
/// FRD at rest; EXTRA is appended to the gyro z block (e.g. a sinusoid = motion).
std::string simulation_model(const std::string& extra = "") {
  return "name: drift test IMU\nsample_rate_hz: 20\n"
         "gyro:\n  arw_rad_per_sqrt_s: 2.0e-5\n  rrw_rad_per_s_sqrt_s: 2.0e-7\n" +
         (extra.empty() ? std::string() : "  z: {" + extra + "}\n") +
         "accel:\n  vrw_m_per_s_sqrt_s: 5.0e-4\n  rw_m_per_s2_sqrt_s: 2.0e-5\n"
         "  z: {specific_force_m_per_s2: -9.80665}\n";
}

std::string fitted_axis(const std::string& name, SensorKind kind) {
  std::ostringstream s;
  s << "  " << name << ":\n    sensor: " << sensor_name(kind) << "\n";
  if (kind == SensorKind::gyro) {
    s << "    quantization_rad: {value: 0}\n    white_noise_rad_per_sqrt_s: {value: 2.0e-5}\n"
         "    bias_instability_rad_per_s: {value: 0}\n    random_walk_rad_per_s_sqrt_s: {value: "
         "2.0e-7}\n    ramp_rad_per_s2: {value: 0}\n";
  } else {
    s << "    quantization_m_per_s: {value: 0}\n    white_noise_m_per_s_sqrt_s: {value: 5.0e-4}\n"
         "    bias_instability_m_per_s2: {value: 0}\n    random_walk_m_per_s2_sqrt_s: {value: "
         "2.0e-5}\n    ramp_m_per_s3: {value: 0}\n";
  }
  return s.str();
}

std::string fitted_model() {
  std::string text = "format: imunoise-noise-model\nformat_version: 1\nsample_rate_hz: 20\naxes:\n";
  for (const char* a : {"x", "y", "z"})
    text += fitted_axis(std::string("gyro_") + a, SensorKind::gyro);
  for (const char* a : {"x", "y", "z"})
    text += fitted_axis(std::string("accel_") + a, SensorKind::accel);
  return text;
}

struct Files {
  std::filesystem::path dir, recording, model;
};

Files prepare(const std::string& tag, const std::string& extra, const std::string& duration) {
  Files f;
  f.dir = make_temp_dir(tag);
  const auto sim = f.dir / "sim.yaml";
  std::ofstream(sim) << simulation_model(extra);
  f.model = f.dir / "model.yaml";
  std::ofstream(f.model) << fitted_model();
  f.recording = f.dir / "rec.csv";
  const auto r = run_imunoise("simulate " + sim.string() + " --duration " + duration +
                              " --seed 3 -o " + f.recording.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return f;
}

std::string first_line(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(DriftCli, WritesSegmentsEnvelopeAndSummary) {
  const auto f = prepare("drift-ok", "", "40min");
  const auto out = f.dir / "drift";
  const auto r = run_imunoise("drift " + f.recording.string() + " --model " + f.model.string() +
                              " --heading 0 --align 30s --segment 90s --report-times 30,90 "
                              "--monte-carlo 20 -o " +
                              out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("20 segments of 30 s alignment + 90 s navigation"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("location not given: assumed 45 deg N"), std::string::npos);
  EXPECT_EQ(first_line(out / "drift_segments.csv"),
            "segment,start_s,time_s,north_error_m,east_error_m,horizontal_error_m,"
            "horizontal_velocity_error_m_per_s,attitude_error_north_deg,"
            "attitude_error_east_deg,attitude_error_down_deg");
  EXPECT_NE(first_line(out / "drift_envelope.csv").find("predicted_horizontal_drms_m"),
            std::string::npos);
  EXPECT_NE(first_line(out / "drift_envelope.csv").find("mc_radial_rms_m"), std::string::npos);
  std::ifstream in(out / "drift_summary.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["protocol"]["segments"], 20);
  ASSERT_EQ(j["consistency"].size(), 2u);
  for (const auto& c : j["consistency"]) {
    // The recording was simulated from this very model: the RMS ratio's 95 % interval
    // contains 1 (a 5 % chance of a false failure per time; the seed is fixed).
    EXPECT_LT(c["rms_ratio_ci_95"][0].get<double>(), 1.0) << c.dump();
    EXPECT_GT(c["rms_ratio_ci_95"][1].get<double>(), 1.0) << c.dump();
    EXPECT_GT(c["predicted_horizontal_drms_m"].get<double>(), 0.0);
    EXPECT_GT(c["monte_carlo_radial_rms_m"].get<double>(), 0.0);
  }
  EXPECT_TRUE(j["motion_check"]["stationary"].get<bool>());
}

TEST(DriftCli, LongSegmentsReportAtThirtyMinutesAndTheReportHasTheBudget) {
  // 65 min at 20 Hz hold two segments of 60 s + 30 min: the default report times within the
  // segment are 1, 5, 10 and 30 min (1 h needs segments that long). The report shows the
  // budget table and the stacked budget plot from drift_budget.csv.
  const auto f = prepare("drift-long", "", "65min");
  const auto out = f.dir / "drift";
  const auto r = run_imunoise("drift " + f.recording.string() + " --model " + f.model.string() +
                              " --heading 0 --segment 30min --monte-carlo 0 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out / "drift_summary.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["protocol"]["segments"], 2);
  std::vector<double> times;
  for (const auto& c : j["consistency"]) times.push_back(c["time_s"].get<double>());
  EXPECT_EQ(times, (std::vector<double>{60.0, 300.0, 600.0, 1800.0}));
  EXPECT_EQ(first_line(out / "drift_budget.csv").rfind("time_s,report_time,white_noise", 0), 0u);
  std::ifstream page(out / "report.html");
  const std::string html((std::istreambuf_iterator<char>(page)), {});
  EXPECT_NE(html.find("id=\"drift-budget-table\""), std::string::npos);
  EXPECT_NE(html.find("id=\"fig-drift-budget\""), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out / "plots" / "drift-budget.svg"));
}

TEST(DriftCli, RefusesAMovingRecordingUnlessForced) {
  // A 20 deg/s, 0.2 Hz oscillation about z: the IMU turns.
  const auto f =
      prepare("drift-moving", "sinusoids: [{amplitude_deg_per_s: 20, frequency_hz: 0.2}]", "10min");
  const auto out = f.dir / "drift";
  const std::string base = "drift " + f.recording.string() + " --model " + f.model.string() +
                           " --heading 0 --align 30s --segment 90s --monte-carlo 0 -o " +
                           out.string();
  auto r = run_imunoise(base);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the IMU is not stationary ("), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out / "drift_summary.json"));
  r = run_imunoise(base + " --force");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("WARNING: not stationary"), std::string::npos);
}

TEST(DriftCli, GyrocompassImpossibleWithoutHeadingSaysWhatToDo) {
  // This model's gyro (N 2e-5) could gyrocompass in 30 s only roughly; a MEMS-class model
  // cannot: raise N 100× in the fitted model and leave out --heading.
  auto f = prepare("drift-heading", "", "10min");
  std::string text = fitted_model();
  const std::string quiet = "white_noise_rad_per_sqrt_s: {value: 2.0e-5}";
  for (std::size_t p = 0; (p = text.find(quiet, p)) != std::string::npos;)
    text.replace(p, quiet.size(), "white_noise_rad_per_sqrt_s: {value: 2.0e-3}");
  std::ofstream(f.model) << text;
  const auto r = run_imunoise("drift " + f.recording.string() + " --model " + f.model.string() +
                              " --align 30s --segment 90s --monte-carlo 0 --force -o " +
                              (f.dir / "d").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--heading"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imunoise::test
