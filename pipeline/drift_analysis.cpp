#include "pipeline/drift_analysis.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "analysis/chi_square.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "ins/earth_model.h"
#include "ins/strapdown.h"

namespace imunoise::pipeline {
namespace {

constexpr double kConfidence = 0.95;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// Whole number of steps of STEP in T (within 1e-9 relative), or throw naming WHAT.
std::size_t whole_steps(double t, double step, const std::string& what) {
  const double n = t / step;
  const double rounded = std::round(n);
  if (!(rounded >= 1.0) || std::abs(n - rounded) > 1e-9 * std::max(1.0, n))
    throw InputError(what + " = " + shortest_number_text(t) + " s is not a whole number of " +
                     shortest_number_text(step) + " s steps");
  return static_cast<std::size_t>(rounded);
}

/// Stationary variance of every GM term of AXIS (bias_gm and gm_terms; independent, so they add).
double gm_variance(const ins::SensorAxisNoise& axis) {
  double v = axis.bias_gm.sigma * axis.bias_gm.sigma;
  for (const GaussMarkov& gm : axis.gm_terms) v += gm.sigma * gm.sigma;
  return v;
}

/// 1σ of the gyro-bias uncertainty over the alignment window (for the gyrocompass
/// decision): the σ of a window mean of white noise, RW and the GM terms (theory.md §7.6).
double gyro_bias_sigma(const ins::InsSensorNoise& noise, double align_s) {
  double worst = 0.0;
  for (const auto& a : noise.gyro) {
    const double v = a.white_noise * a.white_noise / align_s +
                     a.random_walk * a.random_walk * align_s / 3.0 + gm_variance(a);
    worst = std::max(worst, std::sqrt(v));
  }
  return worst;
}

/// One segment as run_segment() gives it: the navigation errors and the alignment.
struct SegmentRun {
  DriftSegment drift;
  ins::Alignment alignment;
};

/// Aligns and free-runs the segment that starts at sample FIRST; the navigation errors on
/// the output grid TIME_S (every STRIDE samples, COUNT points).
SegmentRun run_segment(const ImuSeries& s, std::size_t first, std::size_t n_align,
                       std::size_t stride, std::size_t count, const std::vector<double>& time_s,
                       const DriftOptions& o, double gyro_sigma) {
  SegmentRun run;
  DriftSegment& out = run.drift;
  out.start_s = static_cast<double>(first) * s.sample_period_s;
  out.time_s = time_s;
  Eigen::Vector3d mean_w = Eigen::Vector3d::Zero(), mean_f = Eigen::Vector3d::Zero();
  for (std::size_t k = first; k < first + n_align; ++k) {
    for (int i = 0; i < 3; ++i) {
      mean_w(i) += s.channels[i][k];
      mean_f(i) += s.channels[3 + i][k];
    }
  }
  mean_w /= static_cast<double>(n_align);
  mean_f /= static_cast<double>(n_align);
  ins::AlignmentInput input;
  input.mean_f_ib_b_m_per_s2 = mean_f;
  input.mean_w_ib_b_rad_per_s = mean_w;
  input.latitude_rad = o.latitude_rad;
  input.height_m = o.height_m;
  input.given_heading_rad = o.heading_rad;
  input.given_heading_sigma_rad = o.heading_sigma_rad;
  input.heading_setting = o.heading_setting;
  input.gyro_bias_sigma_rad_per_s = gyro_sigma;
  run.alignment = ins::coarse_alignment(input);

  ins::NavState start;
  start.latitude_rad = o.latitude_rad;
  start.longitude_rad = o.longitude_rad;
  start.height_m = o.height_m;
  start.q_bn = run.alignment.q_bn;
  ins::StrapdownNavigator navigator(start, ins::MechanizationOptions{});
  const Eigen::Vector3d bias = run.alignment.gyro_bias_estimate_rad_per_s;
  out.position_error_ne_m.reserve(count);
  out.velocity_error_horizontal_m_per_s.reserve(count);
  out.attitude_error_ned_rad.reserve(count);
  std::size_t k = first + n_align;
  for (std::size_t p = 0; p < count; ++p) {
    for (std::size_t j = 0; j < stride; ++j, ++k) {
      const Eigen::Vector3d w(s.channels[0][k], s.channels[1][k], s.channels[2][k]);
      const Eigen::Vector3d f(s.channels[3][k], s.channels[4][k], s.channels[5][k]);
      navigator.update(ins::increment_from_rates(w - bias, f, s.sample_period_s));
    }
    const auto& nav = navigator.state();
    out.position_error_ne_m.push_back(
        ins::horizontal_offset_m(nav, o.latitude_rad, o.longitude_rad));
    out.velocity_error_horizontal_m_per_s.push_back(nav.v_ned_m_per_s.head<2>().norm());
    // Ĉ_bn(t) = (I + [δψ×]) Ĉ_bn(0): the rotation q(t)·q(0)⁻¹ expressed in NED.
    const Eigen::AngleAxisd change(nav.q_bn * start.q_bn.conjugate());
    out.attitude_error_ned_rad.push_back(change.angle() * change.axis());
  }
  return run;
}

struct Grid {
  std::size_t n_align = 0, n_nav = 0, stride = 0, count = 0;
};

Grid make_grid(double dt, const DriftOptions& o) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw InputError("sample period must be > 0");
  for (double v : {o.align_s, o.navigation_s, o.output_step_s})
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError(
          "the alignment window, the segment length and the output step must be > 0 s");
  if (!(o.warmup_s >= 0.0)) throw InputError("the warm-up must be ≥ 0 s");
  Grid g;
  g.n_align = whole_steps(o.align_s, dt, "the alignment window");
  g.stride = whole_steps(o.output_step_s, dt, "the output step");
  g.count = whole_steps(o.navigation_s, o.output_step_s, "the segment length");
  g.n_nav = g.count * g.stride;
  for (double t : o.report_times_s)
    if (t > o.navigation_s * (1 + 1e-12)) {
      throw InputError("report time " + shortest_number_text(t) +
                       " s is beyond the segment length " + shortest_number_text(o.navigation_s) +
                       " s");
    } else {
      whole_steps(t, o.output_step_s, "report time");
    }
  return g;
}

}  // namespace

MotionCheck check_stationary(const ImuSeries& s, const ins::InsSensorNoise& noise) {
  MotionCheck out;
  const double dt = s.sample_period_s;
  const std::size_t window =
      std::max<std::size_t>(10, static_cast<std::size_t>(std::lround(1.0 / dt)));
  const std::size_t windows = s.size() / window;
  if (windows < 3) return out;  // too short to judge; the caller's length checks apply
  // Quantization Q of the integrated signal: a rate sample (e_{k+1} − e_k)/Δt of rounding
  // errors of variance Q² has variance 2Q²/Δt² (an angle counter's gyro is dominated by it).
  const auto per_sample_sigma = [dt](const ins::SensorAxisNoise& axis) {
    return std::sqrt(axis.white_noise * axis.white_noise / dt + gm_variance(axis) +
                     2.0 * axis.quantization * axis.quantization / (dt * dt));
  };
  std::array<double, 6> sigma{};
  for (int i = 0; i < 3; ++i) {
    sigma[i] = per_sample_sigma(noise.gyro[i]);
    sigma[3 + i] = per_sample_sigma(noise.accel[i]);
  }
  std::vector<Eigen::Vector3d> mean_f(windows), mean_w(windows);
  std::array<double, 6> worst_ratio{};
  for (std::size_t w = 0; w < windows; ++w) {
    for (int c = 0; c < 6; ++c) {
      const auto x = s.channels[c].subspan(w * window, window);
      const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(window);
      double ss = 0.0;
      for (double v : x) ss += (v - mean) * (v - mean);
      const double sd = std::sqrt(ss / static_cast<double>(window - 1));
      if (sigma[c] > 0.0) worst_ratio[c] = std::max(worst_ratio[c], sd / sigma[c]);
      (c < 3 ? mean_w[w] : mean_f[w])(c % 3) = mean;
    }
  }
  out.max_gyro_std_ratio = *std::max_element(worst_ratio.begin(), worst_ratio.begin() + 3);
  out.max_accel_std_ratio = *std::max_element(worst_ratio.begin() + 3, worst_ratio.end());
  std::vector<double> norms(windows);
  Eigen::Vector3d f_med, w_med;
  for (int i = 0; i < 3; ++i) {
    std::vector<double> fi(windows), wi(windows);
    for (std::size_t w = 0; w < windows; ++w) {
      fi[w] = mean_f[w](i);
      wi[w] = mean_w[w](i);
    }
    f_med(i) = median(fi);
    w_med(i) = median(wi);
  }
  for (std::size_t w = 0; w < windows; ++w) norms[w] = mean_f[w].norm();
  const double norm_med = median(norms);
  double window_gyro_sigma = 0.0;
  for (int i = 0; i < 3; ++i)
    window_gyro_sigma = std::max(window_gyro_sigma, sigma[i] / std::sqrt(double(window)));
  for (std::size_t w = 0; w < windows; ++w) {
    out.max_force_deviation_m_per_s2 =
        std::max(out.max_force_deviation_m_per_s2, std::abs(norms[w] - norm_med));
    const double cos_angle =
        std::clamp(mean_f[w].dot(f_med) / (mean_f[w].norm() * f_med.norm()), -1.0, 1.0);
    out.max_tilt_change_rad = std::max(out.max_tilt_change_rad, std::acos(cos_angle));
    out.max_rotation_rad_per_s = std::max(out.max_rotation_rad_per_s, (mean_w[w] - w_med).norm());
  }
  const double rotation_limit = 0.5 * units::kDeg + 10.0 * window_gyro_sigma;
  const std::string window_text = " (1-s windows)";
  if (out.max_gyro_std_ratio > 3.0) {
    out.stationary = false;
    out.reason = "gyro noise " + shortest_number_text(out.max_gyro_std_ratio) +
                 "x the model's per-sample sigma" + window_text;
  } else if (out.max_accel_std_ratio > 3.0) {
    out.stationary = false;
    out.reason = "accelerometer noise " + shortest_number_text(out.max_accel_std_ratio) +
                 "x the model's per-sample sigma" + window_text;
  } else if (out.max_force_deviation_m_per_s2 > 0.5) {
    out.stationary = false;
    out.reason = "specific-force magnitude changes by " +
                 shortest_number_text(out.max_force_deviation_m_per_s2) + " m/s^2" + window_text;
  } else if (out.max_tilt_change_rad > 2.0 * units::kDeg) {
    out.stationary = false;
    out.reason = "the IMU tilts by " + shortest_number_text(out.max_tilt_change_rad / units::kDeg) +
                 " deg" + window_text;
  } else if (out.max_rotation_rad_per_s > rotation_limit) {
    out.stationary = false;
    out.reason = "the IMU turns: rate changes by " +
                 shortest_number_text(out.max_rotation_rad_per_s / units::kDeg) + " deg/s" +
                 window_text;
  }
  return out;
}

DriftAnalysis analyze_drift(const ImuSeries& s, const ins::InsSensorNoise& noise,
                            const DriftOptions& o) {
  const double dt = s.sample_period_s;
  const Grid g = make_grid(dt, o);
  const std::size_t warmup = static_cast<std::size_t>(std::llround(o.warmup_s / dt));
  const std::size_t per_segment = g.n_align + g.n_nav;
  const std::size_t available = s.size() > warmup ? s.size() - warmup : 0;
  const std::size_t segments = available / per_segment;
  if (segments < 2)
    throw DriftRefused(DriftRefusal::too_few_segments,
                       "the recording holds " + std::to_string(segments) + " segment(s) of " +
                           shortest_number_text(o.align_s + o.navigation_s) +
                           " s (alignment + navigation); at least 2 are needed");
  const double gyro_sigma = gyro_bias_sigma(noise, o.align_s);

  DriftAnalysis out;
  for (std::size_t p = 1; p <= g.count; ++p)
    out.time_s.push_back(static_cast<double>(p) * o.output_step_s);
  const auto segment_count = static_cast<std::int64_t>(segments);
  report_progress(o.progress, "segments", 0, segment_count);
  for (std::size_t m = 0; m < segments; ++m) {
    SegmentRun run = run_segment(s, warmup + m * per_segment, g.n_align, g.stride, g.count,
                                 out.time_s, o, gyro_sigma);
    out.segments.push_back(std::move(run.drift));
    out.alignments.push_back(std::move(run.alignment));
    report_progress(o.progress, "segments", static_cast<std::int64_t>(m) + 1, segment_count);
  }
  const auto& first = out.alignments.front();
  out.heading_note = first.heading_note;

  ins::DriftPredictionOptions p;
  p.latitude_rad = o.latitude_rad;
  p.height_m = o.height_m;
  p.heading_rad = first.yaw_rad;
  p.step_s = o.output_step_s;
  p.times_s = out.time_s;
  p.alignment_time_s = o.align_s;
  p.heading_sigma_rad = first.heading_sigma_rad;
  p.budget = true;
  out.prediction = ins::predict_stationary_drift(noise, p);

  const double m = static_cast<double>(segments);
  const double band_low = analysis::chi_square_quantile((1 - kConfidence) / 2, 2 * m) / m;
  const double band_high = analysis::chi_square_quantile((1 + kConfidence) / 2, 2 * m) / m;
  const double joint_confidence = std::pow(
      kConfidence, 1.0 / static_cast<double>(std::max<std::size_t>(1, o.report_times_s.size())));
  const double joint_low = analysis::chi_square_quantile((1 - joint_confidence) / 2, 2 * m) / m;
  const double joint_high = analysis::chi_square_quantile((1 + joint_confidence) / 2, 2 * m) / m;
  for (double t : o.report_times_s) {
    const std::size_t i = whole_steps(t, o.output_step_s, "report time") - 1;
    DriftConsistency c;
    c.time_s = out.time_s[i];
    const double sn = out.prediction.north_sigma_m[i], se = out.prediction.east_sigma_m[i];
    c.predicted_north_sigma_m = sn;
    c.predicted_east_sigma_m = se;
    c.predicted_drms_m = out.prediction.horizontal_drms_m[i];
    double nees_sum = 0.0, square_sum = 0.0;
    std::array<int, 3> inside{};
    for (const auto& seg : out.segments) {
      const Eigen::Vector2d e = seg.position_error_ne_m[i];
      const double nees = e(0) * e(0) / (sn * sn) + e(1) * e(1) / (se * se);
      nees_sum += nees;
      square_sum += e.squaredNorm();
      for (int k = 0; k < 3; ++k)
        if (nees <= double((k + 1) * (k + 1))) ++inside[k];
    }
    c.mean_nees = nees_sum / m;
    c.nees_band_low = band_low;
    c.nees_band_high = band_high;
    c.nees_inside = c.mean_nees >= band_low && c.mean_nees <= band_high;
    c.nees_joint_band_low = joint_low;
    c.nees_joint_band_high = joint_high;
    c.nees_inside_joint_band = c.mean_nees >= joint_low && c.mean_nees <= joint_high;
    for (int k = 0; k < 3; ++k) c.coverage[k] = inside[k] / m;
    c.actual_rms_m = std::sqrt(square_sum / m);
    c.rms_ratio = c.actual_rms_m / c.predicted_drms_m;
    // For isotropic Gaussian errors mean |e|² = DRMS²·χ²_{2M}/(2M), i.e. ratio² is
    // χ²_{2M}/(2M) = (the NEES band)/2 at the tails; invert for the true ratio's interval.
    c.rms_ratio_ci_low = c.rms_ratio / std::sqrt(band_high / 2.0);
    c.rms_ratio_ci_high = c.rms_ratio / std::sqrt(band_low / 2.0);
    out.consistency.push_back(c);
  }
  return out;
}

MonteCarloEnvelope monte_carlo_drift(const models::ImuNoiseModel& simulation,
                                     const models::FlickerBand& flicker_band,
                                     const ins::InsSensorNoise& noise, double dt,
                                     const DriftOptions& o, int runs, std::uint64_t seed) {
  if (runs < 2) throw InputError("the Monte Carlo needs at least 2 runs");
  const Grid g = make_grid(dt, o);
  const std::size_t n = g.n_align + g.n_nav;
  // The true signal of a level IMU at rest with the heading used (theory.md §7.6 nominal).
  const auto nominal =
      ins::stationary_nominal(o.latitude_rad, o.height_m, o.heading_rad.value_or(0.0));
  models::ImuNoiseModel model = simulation;
  for (int i = 0; i < 3; ++i) {
    model.gyro[i].constant += nominal.w_ib_b_rad_per_s(i);
    model.accel[i].constant += nominal.f_ib_b_m_per_s2(i);
  }
  DriftOptions one = o;
  one.warmup_s = 0.0;
  const double gyro_sigma = gyro_bias_sigma(noise, o.align_s);
  std::vector<std::vector<double>> radial(g.count, std::vector<double>(runs));
  std::array<std::vector<double>, 6> data;
  for (auto& d : data) d.resize(n);
  report_progress(o.progress, "Monte Carlo", 0, runs);
  for (int r = 0; r < runs; ++r) {
    models::SimulationOptions so;
    so.sample_rate_hz = 1.0 / dt;
    so.seed = seed + static_cast<std::uint64_t>(r) * 0x9E3779B97F4A7C15ULL;
    so.flicker_band = flicker_band;
    models::ImuSimulator simulator(model, so);
    simulator.next_block({std::span<double>(data[0]), std::span<double>(data[1]),
                          std::span<double>(data[2]), std::span<double>(data[3]),
                          std::span<double>(data[4]), std::span<double>(data[5])});
    ImuSeries series;
    for (int c = 0; c < 6; ++c) series.channels[c] = data[c];
    series.sample_period_s = dt;
    // No time grid: only the radial errors are kept.
    const auto seg = run_segment(series, 0, g.n_align, g.stride, g.count, {}, one, gyro_sigma);
    for (std::size_t p = 0; p < g.count; ++p)
      radial[p][r] = seg.drift.position_error_ne_m[p].norm();
    report_progress(o.progress, "Monte Carlo", r + 1, runs);
  }
  MonteCarloEnvelope env;
  env.runs = runs;
  for (std::size_t p = 0; p < g.count; ++p) {
    env.time_s.push_back(static_cast<double>(p + 1) * o.output_step_s);
    auto v = radial[p];
    std::sort(v.begin(), v.end());
    const auto q = [&](double f) {
      const double x = f * (runs - 1);
      const auto lo = static_cast<std::size_t>(std::floor(x));
      const auto hi = std::min<std::size_t>(lo + 1, v.size() - 1);
      return v[lo] + (x - lo) * (v[hi] - v[lo]);
    };
    env.radial_p50_m.push_back(q(0.5));
    env.radial_p68_m.push_back(q(0.6827));
    env.radial_p95_m.push_back(q(0.95));
    double ss = 0.0;
    for (double x : v) ss += x * x;
    env.radial_rms_m.push_back(std::sqrt(ss / runs));
  }
  return env;
}

}  // namespace imunoise::pipeline
