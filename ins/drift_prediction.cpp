/// @file
/// @brief Stationary INS drift by covariance propagation (see drift_prediction.h; theory.md
/// §7.3, §7.6, §8.4).
#include "ins/drift_prediction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "common/errors.h"
#include "common/number_text.h"
#include "ins/earth_model.h"
#include "ins/frames.h"
#include "models/state_space.h"

namespace imunoise::ins {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Layout = ErrorStateLayout;

constexpr double kMaxSteps = 1e8;  ///< guard against an output time of ~forever

void check_options(const DriftPredictionOptions& o) {
  IMUNOISE_CHECK(std::isfinite(o.step_s) && o.step_s > 0.0, InputError,
                 "predict_stationary_drift: step_s must be finite and > 0 s (got " +
                     shortest_number_text(o.step_s) + ")");
  IMUNOISE_CHECK(std::isfinite(o.alignment_time_s) && o.alignment_time_s >= 0.0, InputError,
                 "predict_stationary_drift: alignment_time_s must be finite and >= 0 s (got " +
                     shortest_number_text(o.alignment_time_s) + ")");
  IMUNOISE_CHECK(std::isfinite(o.heading_sigma_rad) && o.heading_sigma_rad >= 0.0, InputError,
                 "predict_stationary_drift: heading_sigma_rad must be finite and >= 0 (got " +
                     shortest_number_text(o.heading_sigma_rad) + ")");
  for (const double t : o.times_s) {
    IMUNOISE_CHECK(std::isfinite(t) && t > 0.0, InputError,
                   "predict_stationary_drift: every output time must be finite and > 0 s (got " +
                       shortest_number_text(t) + ")");
    const double steps = std::round(t / o.step_s);
    IMUNOISE_CHECK(steps <= kMaxSteps, InputError,
                   "predict_stationary_drift: output time " + shortest_number_text(t) +
                       " s needs more than 1e8 steps of " + shortest_number_text(o.step_s) + " s");
    IMUNOISE_CHECK(steps >= 1.0 && std::abs(steps * o.step_s - t) <= 1e-9 * t, InputError,
                   "predict_stationary_drift: output time " + shortest_number_text(t) +
                       " s is not a whole number of steps of " + shortest_number_text(o.step_s) +
                       " s (within 1e-9 relative)");
  }
  IMUNOISE_CHECK(std::is_sorted(o.times_s.begin(), o.times_s.end()), InputError,
                 "predict_stationary_drift: times_s must be sorted (non-decreasing)");
}

/// NOISE with the terms OPTION drops set to 0 (ErrorStateOptions::bias semantics), for the
/// model that always carries both an RW and a GM state per axis.
InsSensorNoise acting_terms(InsSensorNoise noise, BiasModel bias) {
  for (auto* sensor : {&noise.gyro, &noise.accel}) {
    for (SensorAxisNoise& axis : *sensor) {
      if (bias == BiasModel::random_walk) axis.bias_gm = {};
      if (bias == BiasModel::gauss_markov) {
        axis.random_walk = 0.0;
        axis.turn_on_bias_sigma = 0.0;
      }
    }
  }
  return noise;
}

/// Second-order statistics of the window mean m = (1/T)∫₀ᵀ b of a stationary GM b with
/// autocovariance σ²e^{−|τ|/T_c}, and its covariance with the end value b(T).
struct GmWindowMean {
  double mean_variance = 0.0;        ///< Var m = (2σ²/x)(1 − (1 − e^{−x})/x), x = T/T_c
  double mean_end_covariance = 0.0;  ///< Cov(m, b(T)) = σ²(1 − e^{−x})/x
  double end_variance = 0.0;         ///< Var b(T) = σ²
};

GmWindowMean gm_window_mean(const GaussMarkov& gm, double window_s) {
  GmWindowMean out;
  const double var = gm.sigma * gm.sigma;
  if (var == 0.0) return out;
  const double x = window_s / gm.tau_c_s;
  const double r = -std::expm1(-x) / x;  // (1 − e^{−x})/x
  // 1 − r = x/2 − x²/6 + x³/24 − …; the series avoids the cancellation for a short window.
  const double one_minus_r = x < 1e-3 ? x * (0.5 - x / 6.0 + x * x / 24.0) : 1.0 - r;
  out.mean_variance = 2.0 * var / x * one_minus_r;
  out.mean_end_covariance = var * r;
  out.end_variance = var;
  return out;
}

/// P₀ after a stationary alignment of T_a (see the header): P₀ = A Σ_z Aᵀ over independent
/// sources z = [u_a (3), m_a,GM (3), b_a,GM (3), u_g (3), m_g,GM (3), b_g,GM (3), δψ_D],
/// u = window mean of white noise + RW end-minus-mean (Var N²/T_a + K²T_a/3), m_GM the GM
/// window mean and b_GM its value at the end of the window (pairwise correlated).
MatrixXd aligned_initial_covariance(const NominalState& nominal, const InsSensorNoise& noise,
                                    const DriftPredictionOptions& o, const ErrorStateLayout& layout,
                                    int states) {
  constexpr int kUa = 0, kMa = 3, kBa = 6, kUg = 9, kMg = 12, kBg = 15, kHeading = 18,
                kSources = 19;
  const double T = o.alignment_time_s;
  MatrixXd Sz = MatrixXd::Zero(kSources, kSources);
  const auto fill_sensor = [&](const std::array<SensorAxisNoise, 3>& axes, int u, int m, int b) {
    for (int i = 0; i < 3; ++i) {
      const SensorAxisNoise& a = axes[i];
      Sz(u + i, u + i) =
          a.white_noise * a.white_noise / T + a.random_walk * a.random_walk * T / 3.0;
      const GmWindowMean w = gm_window_mean(a.bias_gm, T);
      Sz(m + i, m + i) = w.mean_variance;
      Sz(b + i, b + i) = w.end_variance;
      Sz(m + i, b + i) = Sz(b + i, m + i) = w.mean_end_covariance;
    }
  };
  fill_sensor(noise.accel, kUa, kMa, kBa);
  fill_sensor(noise.gyro, kUg, kMg, kBg);
  Sz(kHeading, kHeading) = o.heading_sigma_rad * o.heading_sigma_rad;

  // Leveling (theory.md §7.3): with e^n = C_bn(u_a + m_a) the tilt that zeroes the mean
  // horizontal specific force −f^n×δψ + e^n, f^n = [0, 0, −g]: δψ_N = −e_E/g, δψ_E = e_N/g.
  const Matrix3d& C = nominal.C_bn;
  const double g = -(C * nominal.f_ib_b_m_per_s2).z();
  Matrix3d level = Matrix3d::Zero();
  level(0, 1) = -1.0 / g;
  level(1, 0) = 1.0 / g;
  MatrixXd A_psi = MatrixXd::Zero(3, kSources);
  A_psi.middleCols<3>(kUa) = level * C;
  A_psi.middleCols<3>(kMa) = level * C;
  A_psi(2, kHeading) = 1.0;

  MatrixXd A = MatrixXd::Zero(states, kSources);
  A.middleRows<3>(Layout::kAttitude) = A_psi;
  // Accel RW state: 0 — taken relative to its value at the end of the window, which the
  // equivalent tilt above absorbs; Q_d grows it. (The vertical axis is not levelled, but the
  // vertical channel is held.) Accel GM state: b_a,GM(T_a).
  A.block<3, 3>(*layout.accel_bias_gm, kBa).setIdentity();
  // Gyro RW state: the residual of b̂_g = ω̄ − Ĉ_nb ω_ie^n: u_g − m_g,GM
  // + C_nb [ω_ie×] δψ₀ (the last only when Earth rate is in F; theory.md §7.3).
  A.block<3, 3>(Layout::kGyroBias, kUg).setIdentity();
  A.block<3, 3>(Layout::kGyroBias, kMg) = -Matrix3d::Identity();
  if (o.earth_rate_coupling)
    A.middleRows<3>(Layout::kGyroBias) +=
        C.transpose() * skew(earth_rate_ned(nominal.latitude_rad)) * A_psi;
  // Gyro GM state: b_g,GM(T_a).
  A.block<3, 3>(*layout.gyro_bias_gm, kBg).setIdentity();
  MatrixXd P0 = A * Sz * A.transpose();
  return 0.5 * (P0 + P0.transpose());
}

}  // namespace

DriftPrediction predict_stationary_drift(const InsSensorNoise& noise,
                                         const DriftPredictionOptions& options) {
  check_options(options);
  const NominalState nominal =
      stationary_nominal(options.latitude_rad, options.height_m, options.heading_rad);
  const InsSensorNoise acting = acting_terms(noise, options.bias);
  ErrorStateOptions model_options;
  model_options.bias = BiasModel::both;
  model_options.height_hold = true;
  model_options.earth_rate = options.earth_rate_coupling;
  const models::ContinuousStateModel model = ins_error_state_model(nominal, acting, model_options);
  const ErrorStateLayout layout = error_state_layout(model_options);
  const int n = model.states();

  MatrixXd P;
  if (options.alignment_time_s > 0.0) {
    P = aligned_initial_covariance(nominal, acting, options, layout, n);
  } else {
    P = model.initial_variance.asDiagonal();
    P(Layout::kAttitude + 2, Layout::kAttitude + 2) +=
        options.heading_sigma_rad * options.heading_sigma_rad;
  }

  DriftPrediction out;
  const std::size_t outputs = options.times_s.size();
  for (auto* v : {&out.time_s, &out.north_sigma_m, &out.east_sigma_m, &out.horizontal_drms_m,
                  &out.velocity_horizontal_drms_m_per_s, &out.roll_sigma_rad, &out.pitch_sigma_rad,
                  &out.heading_sigma_rad})
    v->reserve(outputs);
  if (outputs == 0) return out;

  // F is constant at rest: Φ and Q_d once (exact, Van Loan with substeps; theory.md §6.2).
  const models::DiscreteStateModel discrete = models::discretize(model, options.step_s);
  const MatrixXd& Phi = discrete.Phi;
  const Matrix3d C_nb = nominal.C_bn.transpose();
  MatrixXd PhiP(n, n);
  long long step = 0;
  for (const double t : options.times_s) {
    const auto target = static_cast<long long>(std::llround(t / options.step_s));
    for (; step < target; ++step) {
      PhiP.noalias() = Phi * P;
      P.noalias() = PhiP * Phi.transpose();
      P += discrete.Qd;
      P = 0.5 * (P + P.transpose()).eval();
    }
    // Variances that cancel exactly (e.g. an attitude error after a self-consistent bias
    // removal) can come out as −1e-20-sized rounding: read them as 0.
    const auto sigma = [](double variance) { return std::sqrt(std::max(variance, 0.0)); };
    const int r = Layout::kPosition, u = Layout::kVelocity;
    const double pn = P(r, r), pe = P(r + 1, r + 1);
    out.time_s.push_back(t);
    out.north_sigma_m.push_back(sigma(pn));
    out.east_sigma_m.push_back(sigma(pe));
    out.horizontal_drms_m.push_back(sigma(pn + pe));
    out.velocity_horizontal_drms_m_per_s.push_back(sigma(P(u, u) + P(u + 1, u + 1)));
    // Level IMU: (δφ, δθ, δψ) = C_nb δψ^n to first order.
    const Matrix3d attitude =
        C_nb * P.block<3, 3>(Layout::kAttitude, Layout::kAttitude) * C_nb.transpose();
    out.roll_sigma_rad.push_back(sigma(attitude(0, 0)));
    out.pitch_sigma_rad.push_back(sigma(attitude(1, 1)));
    out.heading_sigma_rad.push_back(sigma(attitude(2, 2)));
  }
  return out;
}

}  // namespace imunoise::ins
