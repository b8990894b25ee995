// Tests of io/results_directory.h: a directory made by the writers of the io modules (model.yaml,
// allan.csv, psd.csv, sampling_report.json, the drift files, commands.txt) loads back into the
// typed struct with the file list the report describes; a drift directory of its own loads the
// model its summary names; a renamed key or column is a located error naming the file; a path
// that is no directory or holds no results is an InputError.
#include "io/results_directory.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/errors.h"
#include "io/atomic_output.h"
#include "io/drift_files.h"
#include "io/noise_model_yaml.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

namespace fs = std::filesystem;
using test::error_of;

models::NoiseModel example_model() {
  models::NoiseModel m;
  m.sensor_name = "bench IMU";
  m.source = "rec.csv";
  m.sample_rate_hz = 100.0;
  m.duration_s = 3600.0;
  m.samples = 360000;
  m.confidence = 0.9;
  m.data_quality = {"2 gaps"};
  models::AxisModel gyro;
  gyro.name = "gyro_x";
  gyro.kind = SensorKind::gyro;
  gyro.terms[NoiseTerm::white_noise] = {1e-4, 9e-5, 1.1e-4, true, "wnnls-oavar", ""};
  models::AxisModel accel;
  accel.name = "accel_z";
  accel.kind = SensorKind::accel;
  accel.terms[NoiseTerm::random_walk] = {2e-5, 1e-5, 3e-5, true, "wnnls-oavar", ""};
  m.axes = {gyro, accel};
  return m;
}

AllanTable example_allan() {
  AllanTable t;
  t.m = {1, 2};
  t.tau_s = {0.01, 0.02};
  AllanAxis a{"gyro_x", {}, {}, {1e-3, 7e-4}};
  for (std::int64_t m : t.m) {
    analysis::DeviationPoint p;
    p.m = m;
    p.tau_s = 0.01 * static_cast<double>(m);
    p.value = 1e-3 / static_cast<double>(m);
    p.ci_low = 0.9 * p.value;
    p.ci_high = 1.1 * p.value;
    p.edf = 100.0;
    a.oadev.points.push_back(p);
    a.ohdev.points.push_back(p);
  }
  t.axes = {a};
  return t;
}

PsdTable example_psd() {
  PsdTable t;
  t.frequency_hz = {0.1, 1.0};
  PsdAxis a;
  a.name = "accel_z";
  a.psd.frequency_hz = t.frequency_hz;
  a.psd.density = {4e-6, 3e-6};
  a.psd.dof = {2.0, 20.0};
  a.model_density = {4.1e-6, 2.9e-6};
  t.axes = {a};
  return t;
}

/// 10 s at 100 Hz with one 0.5 s gap after 2 s.
pipeline::SamplingReport example_sampling() {
  std::vector<double> stamps;
  for (int i = 0; i < 1000; ++i) stamps.push_back(0.01 * i + (i > 200 ? 0.5 : 0.0));
  pipeline::SamplingReport r;
  r.samples = static_cast<std::int64_t>(stamps.size());
  r.timing = pipeline::analyze_timing(stamps);
  return r;
}

pipeline::DriftSummary example_drift_summary(const std::string& model_path) {
  pipeline::DriftSummary s;
  s.recording = "rec.csv";
  s.model = model_path;
  s.protocol = {60.0, 600.0, 5.0, 3, "height hold", "removed", "given heading", "peak_match"};
  pipeline::DriftConsistency c;
  c.time_s = 60.0;
  c.mean_nees = 2.5;
  c.nees_inside = false;
  s.consistency = {c};
  return s;
}

pipeline::DriftSeries example_envelope() {
  pipeline::DriftSeries s;
  s.time_s = {1.0, 2.0};
  s.predicted_north_sigma_m = {0.1, 0.2};
  s.predicted_east_sigma_m = {0.1, 0.2};
  s.predicted_drms_m = {0.15, 0.3};
  s.predicted_velocity_drms_m_per_s = {1e-3, 2e-3};
  s.predicted_roll_sigma_rad = {1e-5, 2e-5};
  s.predicted_pitch_sigma_rad = {1e-5, 2e-5};
  s.predicted_heading_sigma_rad = {1e-3, 2e-3};
  s.predicted_attitude_sigma_rad = {1e-3, 2e-3};
  return s;
}

/// An analysis directory with a drift run in DIR/drift, as analyze and drift write it.
fs::path analysis_directory(const std::string& tag) {
  const fs::path dir = test::make_temp_dir(tag);
  write_model_yaml(example_model(), (dir / "model.yaml").string());
  write_allan_csv((dir / "allan.csv").string(), example_allan());
  write_psd_csv((dir / "psd.csv").string(), example_psd());
  write_sampling_report_json((dir / "sampling_report.json").string(), example_sampling(),
                             "rec.csv");
  write_command_file(dir.string(), {"/home/me", {"analyze", "rec.csv", "-o", "out"}});
  create_output_directory((dir / "drift").string());
  write_drift_summary_json((dir / "drift" / "drift_summary.json").string(),
                           example_drift_summary((dir / "model.yaml").string()));
  write_drift_envelope_csv((dir / "drift" / "drift_envelope.csv").string(), example_envelope());
  pipeline::DriftSegment segment;
  segment.start_s = 0.0;
  segment.time_s = {1.0, 2.0};
  segment.position_error_ne_m = {{0.1, 0.0}, {0.2, 0.1}};
  segment.velocity_error_horizontal_m_per_s = {1e-3, 2e-3};
  segment.attitude_error_ned_rad = {{1e-5, 1e-5, 1e-4}, {2e-5, 2e-5, 2e-4}};
  write_drift_segments_csv((dir / "drift" / "drift_segments.csv").string(), {segment});
  write_command_file((dir / "drift").string(), {"", {"drift", "rec.csv"}});
  // Not results: the report's own files, a temporary file, another tool's commands.txt.
  create_output_directory((dir / "plots").string());
  test::write_text(dir / "plots" / "allan-gyro.svg", "<svg/>");
  test::write_text(dir / "report.html", "<html/>");
  test::write_text(dir / "model.yaml.tmp.1", "x");
  create_output_directory((dir / "configs").string());
  test::write_text(dir / "configs" / "commands.txt", "make all\n");
  test::write_text(dir / "configs" / "openvins.yaml", "imu: 1\n");
  return dir;
}

TEST(ResultsDirectory, LoadsEveryFileItsWritersWrote) {
  const fs::path dir = analysis_directory("results-directory");
  const ResultsDirectory r = load_results_directory(dir.string());
  EXPECT_EQ(r.dir, dir.string());
  ASSERT_TRUE(r.model);
  EXPECT_EQ(r.model->sensor_name, "bench IMU");
  ASSERT_EQ(r.model->axes.size(), 2u);
  EXPECT_EQ(r.model->axes[1].terms[NoiseTerm::random_walk].value, 2e-5);
  ASSERT_TRUE(r.allan);
  ASSERT_EQ(r.allan->axes.size(), 1u);
  EXPECT_EQ(r.allan->axes[0].oadev.points[1].value, 5e-4);
  EXPECT_EQ(r.allan->axes[0].oadev.confidence, 0.9);  // the model's level
  ASSERT_TRUE(r.psd);
  EXPECT_EQ(r.psd->axes[0].model_density, (std::vector<double>{4.1e-6, 2.9e-6}));
  ASSERT_TRUE(r.sampling);
  EXPECT_EQ(r.sampling->source_path, "rec.csv");
  EXPECT_EQ(r.sampling->report.samples, 1000);
  EXPECT_EQ(r.sampling->report.timing.gap_count, 1);
  EXPECT_EQ(r.sampling->report.timing.gaps.size(), 1u);
  EXPECT_EQ(fs::path(r.drift_dir), dir / "drift");
  ASSERT_TRUE(r.drift_summary);
  EXPECT_EQ(r.drift_summary->protocol.segments, 3);
  ASSERT_TRUE(r.drift_envelope);
  EXPECT_EQ(r.drift_envelope->predicted_drms_m, (std::vector<double>{0.15, 0.3}));
  ASSERT_EQ(r.drift_segments.size(), 1u);
  EXPECT_EQ(r.drift_segments[0].time_s, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(r.drift_segments[0].position_error_ne_m[1].y(), 0.1);
  // commands.txt of DIR, then of the subdirectories by name; configs/'s is another tool's.
  ASSERT_EQ(r.commands.size(), 2u);
  EXPECT_EQ(r.commands[0].relative_path, "commands.txt");
  EXPECT_EQ(r.commands[0].record.working_directory, "/home/me");
  EXPECT_EQ(r.commands[0].record.arguments,
            (std::vector<std::string>{"analyze", "rec.csv", "-o", "out"}));
  EXPECT_EQ(r.commands[1].relative_path, "drift/commands.txt");
  EXPECT_EQ(r.commands[1].record.arguments, (std::vector<std::string>{"drift", "rec.csv"}));
  // The files the report lists: sorted, without its own files, temporaries and commands.txt.
  std::vector<std::string> listed;
  for (const ResultFileEntry& f : r.files) {
    listed.push_back(f.relative_path);
    EXPECT_EQ(f.size_bytes, fs::file_size(dir / f.relative_path)) << f.relative_path;
  }
  EXPECT_EQ(listed, (std::vector<std::string>{
                        "allan.csv", "configs/openvins.yaml", "drift/drift_envelope.csv",
                        "drift/drift_segments.csv", "drift/drift_summary.json", "model.yaml",
                        "psd.csv", "sampling_report.json"}));
}

TEST(ResultsDirectory, ADriftDirectoryOfItsOwnLoadsTheModelItsSummaryNames) {
  const fs::path analysis = analysis_directory("results-directory-drift");
  const ResultsDirectory r = load_results_directory((analysis / "drift").string());
  EXPECT_EQ(fs::path(r.drift_dir), analysis / "drift");
  ASSERT_TRUE(r.model);  // analysis/model.yaml, named by drift_summary.json
  EXPECT_EQ(r.model->sensor_name, "bench IMU");
  EXPECT_FALSE(r.allan);  // read only from DIR itself
  EXPECT_FALSE(r.psd);
  EXPECT_FALSE(r.sampling);
  ASSERT_EQ(r.commands.size(), 1u);
  EXPECT_EQ(r.commands[0].relative_path, "commands.txt");
  // Without its model the drift results alone are still results.
  fs::remove(analysis / "model.yaml");
  EXPECT_FALSE(load_results_directory((analysis / "drift").string()).model);
}

TEST(ResultsDirectory, ARenamedKeyOrColumnIsALocatedErrorNamingTheFile) {
  {
    const fs::path dir = analysis_directory("results-directory-sampling-key");
    std::string text = test::read_file_bytes(dir / "sampling_report.json");
    text.replace(text.find("\"rate_hz\""), 9, "\"rate__hz\"");
    test::write_text(dir / "sampling_report.json", text);
    const std::string error = error_of([&] { load_results_directory(dir.string()); });
    EXPECT_NE(error.find((dir / "sampling_report.json").string() + ": key 'rate_hz' missing"),
              std::string::npos)
        << error;
  }
  {
    const fs::path dir = analysis_directory("results-directory-drift-key");
    const fs::path path = dir / "drift" / "drift_summary.json";
    std::string text = test::read_file_bytes(path);
    text.replace(text.find("\"mean_nees\""), 11, "\"mean_nee\"");
    test::write_text(path, text);
    const std::string error = error_of([&] { load_results_directory(dir.string()); });
    EXPECT_NE(error.find(path.string() + ": consistency[0].mean_nees: missing"), std::string::npos)
        << error;
  }
  {
    const fs::path dir = analysis_directory("results-directory-allan-column");
    std::string text = test::read_file_bytes(dir / "allan.csv");
    text.replace(text.find("gyro_x_oadev_edf"), 16, "gyro_x_oadev_dof");
    test::write_text(dir / "allan.csv", text);
    const std::string error = error_of([&] { load_results_directory(dir.string()); });
    EXPECT_NE(error.find((dir / "allan.csv").string() + ":1: no column 'gyro_x_oadev_edf'"),
              std::string::npos)
        << error;
  }
}

TEST(ResultsDirectory, NoDirectoryOrNoResultsIsAnInputError) {
  const fs::path dir = test::make_temp_dir("results-directory-empty");
  test::expect_throw_containing<InputError>(
      [&] { load_results_directory(dir.string()); },
      dir.string() + ": no imunoise results here (expected model.yaml");
  test::expect_throw_containing<InputError>(
      [&] { load_results_directory((dir / "missing").string()); },
      (dir / "missing").string() + ": not a directory");
}

}  // namespace
}  // namespace imunoise::io
