/// @file
/// @brief The drift job of `imunoise drift` (see drift_run.h).
#include "pipeline/drift_run.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/number_text.h"
#include "common/units.h"
#include "ins/noise_from_model.h"
#include "models/noise_simulator.h"

namespace imunoise::pipeline {
namespace {

/// The six channels of RECORDING as an ImuSeries (spans into RECORDING).
ImuSeries imu_series(const Recording& recording) {
  ImuSeries series;
  series.sample_period_s = recording.sample_period_s;
  for (int c = 0; c < 6; ++c) {
    const Channel* channel = recording.find_channel(kImuChannelNames[c]);
    if (channel == nullptr)
      throw DriftRefused(DriftRefusal::missing_channel, recording.source_path +
                                                            ": drift needs all six channels; " +
                                                            kImuChannelNames[c] + " is missing");
    series.channels[c] = channel->values;
  }
  return series;
}

DriftOptions drift_options(const DriftRunOptions& o, const ProgressCallback& progress) {
  DriftOptions d;
  d.latitude_rad = o.location.latitude_deg * units::kDeg;
  d.longitude_rad = o.location.longitude_deg * units::kDeg;
  d.height_m = o.location.height_m;
  d.heading_rad = o.heading_rad;
  d.heading_sigma_rad = o.heading_sigma_rad;
  d.heading_setting = o.heading_setting;
  d.align_s = o.align_s;
  d.navigation_s = o.navigation_s;
  d.warmup_s = o.warmup_s;
  d.output_step_s = o.output_step_s;
  d.report_times_s = o.report_times_s;
  d.progress = progress;
  return d;
}

/// MODEL's axes as simulator terms (flicker B included), gyro then accel, x, y, z.
models::ImuNoiseModel simulator_model(const models::NoiseModel& model) {
  models::ImuNoiseModel simulation;
  for (int i = 0; i < 3; ++i) {
    if (const auto* g = model.find_axis(kImuChannelNames[i]))
      simulation.gyro[i] = models::channel_model_from(g->coefficients());
    if (const auto* f = model.find_axis(kImuChannelNames[3 + i]))
      simulation.accel[i] = models::channel_model_from(f->coefficients());
  }
  return simulation;
}

/// The envelope: the prediction and the RMS of the segments on the grid of ANALYSIS.
DriftSeries envelope(const DriftAnalysis& analysis) {
  const ins::DriftPrediction& p = analysis.prediction;
  DriftSeries s;
  s.time_s = analysis.time_s;
  s.predicted_north_sigma_m = p.north_sigma_m;
  s.predicted_east_sigma_m = p.east_sigma_m;
  s.predicted_drms_m = p.horizontal_drms_m;
  s.predicted_velocity_drms_m_per_s = p.velocity_horizontal_drms_m_per_s;
  s.predicted_roll_sigma_rad = p.roll_sigma_rad;
  s.predicted_pitch_sigma_rad = p.pitch_sigma_rad;
  s.predicted_heading_sigma_rad = p.heading_sigma_rad;
  for (std::size_t i = 0; i < s.time_s.size(); ++i) {
    const double r = p.roll_sigma_rad[i], q = p.pitch_sigma_rad[i], h = p.heading_sigma_rad[i];
    s.predicted_attitude_sigma_rad.push_back(std::sqrt(r * r + q * q + h * h));
    double ss = 0.0;
    for (const DriftSegment& seg : analysis.segments)
      ss += seg.position_error_ne_m[i].squaredNorm();
    s.recorded_rms_m.push_back(std::sqrt(ss / analysis.segments.size()));
  }
  return s;
}

/// The budget of ANALYSIS's prediction at the report times of O and ~10 log-spaced times per
/// decade of its output grid (DriftBudget).
DriftBudget budget_on_grid(const DriftAnalysis& analysis, const DriftOptions& o) {
  const std::size_t n = analysis.time_s.size();
  std::vector<std::size_t> rows;  // indices into the output grid
  std::vector<std::size_t> reports;
  for (const double t : o.report_times_s)
    reports.push_back(static_cast<std::size_t>(std::llround(t / o.output_step_s)) - 1);
  for (int k = 0;; ++k) {
    const auto i = static_cast<std::size_t>(std::llround(std::pow(10.0, k / 10.0))) - 1;
    if (i >= n) break;
    rows.push_back(i);
  }
  if (n > 0) rows.push_back(n - 1);
  rows.insert(rows.end(), reports.begin(), reports.end());
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  DriftBudget b;
  for (const std::size_t i : rows) {
    const double drms = analysis.prediction.horizontal_drms_m[i];
    b.time_s.push_back(analysis.time_s[i]);
    b.variance_m2.push_back(analysis.prediction.horizontal_variance_budget_m2[i]);
    b.predicted_variance_m2.push_back(drms * drms);
    b.report_time.push_back(std::find(reports.begin(), reports.end(), i) != reports.end());
  }
  return b;
}

/// How the covariance carries B, the GM terms and R (drift_summary.json's protocol).
std::string bias_states_note(const models::NoiseModel& model, const ins::InsSensorNoise& noise,
                             models::GmConvention convention) {
  std::size_t terms = 0, ramps = 0;
  for (const auto* sensor : {&noise.gyro, &noise.accel})
    for (const ins::SensorAxisNoise& a : *sensor) {
      terms += a.gm_terms.size();
      ramps += a.ramp > 0.0 ? 1 : 0;
    }
  std::string note =
      "multi_gm: B as the model's Gauss-Markov terms (bias_instability_multi_gm) "
      "and every fitted GM term, each its own error state (" +
      std::to_string(terms) + " in all); R as a slope state on " + std::to_string(ramps) + " axes";
  const std::vector<std::string> fallback = ins::single_gm_fallback_axes(model);
  if (!fallback.empty()) {
    note += "; B as one GM (" + std::string(models::name_of(convention)) +
            ", the model has no multi_gm) on";
    for (const std::string& axis : fallback) note += " " + axis;
  }
  return note;
}

/// Samples [FIRST, FIRST + COUNT) of RECORDING as a recording of their own (time stamps
/// shifted to start at 0; the sampling report kept: it describes the whole read).
Recording part_of(const Recording& recording, std::size_t first, std::size_t count,
                  const std::string& label) {
  Recording part;
  part.source_path = recording.source_path + " (" + label + ")";
  part.sample_period_s = recording.sample_period_s;
  part.start_time_s = recording.start_time_s;
  part.report = recording.report;
  if (!recording.time_s.empty()) {
    const double t0 = recording.time_s[first];
    part.start_time_s += t0;
    for (std::size_t i = first; i < first + count; ++i)
      part.time_s.push_back(recording.time_s[i] - t0);
  }
  for (const Channel& c : recording.channels) {
    Channel copy = c;
    copy.values.assign(c.values.begin() + static_cast<std::ptrdiff_t>(first),
                       c.values.begin() + static_cast<std::ptrdiff_t>(first + count));
    part.channels.push_back(std::move(copy));
  }
  return part;
}

std::string sample_range_text(std::size_t first, std::size_t end, double dt) {
  return "samples " + std::to_string(first) + " ... " + std::to_string(end - 1) + " (" +
         significant_number_text(static_cast<double>(first) * dt) + " ... " +
         significant_number_text(static_cast<double>(end) * dt) + " s)";
}

/// The split-sample check (see DriftRunOptions::holdout_half).
DriftHoldout holdout_half(const Recording& recording, const DriftRunOptions& options,
                          const DriftOptions& o) {
  const std::size_t n = recording.sample_count();
  const std::size_t half = n / 2;
  const Recording first = part_of(recording, 0, half, "first half");
  const Recording second = part_of(recording, half, n - half, "second half");
  const RecordingAnalysis fit =
      analyze_recording(first, first.source_path, options.holdout_analysis);
  ins::InsNoiseOptions noise_options;
  noise_options.gm_convention = options.gm_convention;
  noise_options.model_terms_as_states = true;
  const ins::InsSensorNoise noise = ins::ins_sensor_noise(fit.model, noise_options);
  DriftOptions judged = o;
  judged.progress = {};
  // The warm-up belongs to the start of the recording, i.e. to the fitted half.
  judged.warmup_s = 0.0;
  DriftAnalysis analysis = analyze_drift(imu_series(second), noise, judged);
  DriftHoldout out;
  const double dt = recording.sample_period_s;
  out.fitted_on = "first half: " + sample_range_text(0, half, dt);
  out.judged_on = "second half: " + sample_range_text(half, n, dt);
  out.segments = analysis.segments.size();
  out.consistency = std::move(analysis.consistency);
  return out;
}

}  // namespace

DriftResult run_drift(const Recording& recording, const models::NoiseModel& model,
                      const DriftRunOptions& options, const ProgressCallback& progress) {
  ins::InsNoiseOptions noise_options;
  noise_options.gm_convention = options.gm_convention;
  noise_options.model_terms_as_states = true;
  const ins::InsSensorNoise noise = ins::ins_sensor_noise(model, noise_options);
  const DriftOptions o = drift_options(options, progress);

  const ImuSeries series = imu_series(recording);
  const std::int64_t gaps = recording.report.timing.gap_count;
  if (gaps > 0 && !options.force)
    throw DriftRefused(DriftRefusal::time_gaps,
                       recording.source_path + ": the recording has " + std::to_string(gaps) +
                           " time gap(s); segments across a gap would navigate through missing "
                           "data");
  const MotionCheck motion = check_stationary(series, noise);
  if (!motion.stationary && !options.force)
    throw DriftRefused(DriftRefusal::not_stationary,
                       recording.source_path + ": the IMU is not stationary (" + motion.reason +
                           "); drift analysis compares free-inertial drift at rest with the "
                           "noise model");

  DriftAnalysis analysis = analyze_drift(series, noise, o);
  DriftResult out;
  out.series = envelope(analysis);
  out.budget = budget_on_grid(analysis, o);
  DriftSummary& summary = out.summary;
  summary.consistency = std::move(analysis.consistency);
  if (options.monte_carlo_runs > 0) {
    models::FlickerBand band;
    band.tau_max_s = std::max(1e4, 10.0 * (o.align_s + o.navigation_s));
    MonteCarloEnvelope mc =
        monte_carlo_drift(simulator_model(model), band, noise, series.sample_period_s, o,
                          options.monte_carlo_runs, options.seed);
    for (DriftConsistency& c : summary.consistency) {
      const auto i = static_cast<std::size_t>(std::llround(c.time_s / o.output_step_s)) - 1;
      c.monte_carlo_radial_rms_m = mc.radial_rms_m[i];
      c.monte_carlo_radial_p95_m = mc.radial_p95_m[i];
    }
    out.series.mc_radial_p50_m = std::move(mc.radial_p50_m);
    out.series.mc_radial_p68_m = std::move(mc.radial_p68_m);
    out.series.mc_radial_p95_m = std::move(mc.radial_p95_m);
    out.series.mc_radial_rms_m = std::move(mc.radial_rms_m);
    summary.monte_carlo = DriftMonteCarlo{mc.runs, options.seed};
  }

  summary.recording = recording.source_path;
  summary.model = options.model_path;
  summary.location = options.location;
  summary.protocol.align_s = o.align_s;
  summary.protocol.navigation_s = o.navigation_s;
  summary.protocol.warmup_s = o.warmup_s;
  summary.protocol.segments = analysis.segments.size();
  summary.protocol.vertical_channel = "height hold (theory.md §7.2): horizontal errors only";
  summary.protocol.gyro_bias = "estimated over each alignment window and removed (§7.3)";
  summary.protocol.heading = analysis.heading_note;
  summary.protocol.bias_instability_as_gm = std::string(models::name_of(options.gm_convention));
  summary.protocol.bias_states = bias_states_note(model, noise, options.gm_convention);
  summary.motion = motion;
  summary.forced = options.force && !motion.stationary;
  if (options.holdout_half) summary.holdout = holdout_half(recording, options, o);
  out.segments = std::move(analysis.segments);
  return out;
}

}  // namespace imunoise::pipeline
