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
      if (bias == BiasModel::random_walk) {
        axis.bias_gm = {};
        axis.gm_terms.clear();
      }
      if (bias == BiasModel::gauss_markov) {
        axis.random_walk = 0.0;
        axis.turn_on_bias_sigma = 0.0;
        axis.ramp = 0.0;
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

/// P₀ as a sum of parts of independent sources (the budget's start values): P₀ = Σ_g parts[g].
struct InitialCovariance {
  std::array<MatrixXd, kDriftBudgetTerms> parts;
  MatrixXd total() const {
    MatrixXd P = parts[0];
    for (std::size_t g = 1; g < parts.size(); ++g) P += parts[g];
    return P;
  }
};

/// P₀ after a stationary alignment of T_a (see the header): P₀ = A Σ_z Aᵀ over independent
/// sources z, listed per axis: the window mean of white noise (Var N²/T_a), the RW end minus
/// its window mean (K²T_a/3), for each GM term (bias_gm and gm_terms) its window mean m and
/// end value b (pairwise correlated, gm_window_mean()), the ramp slope s (R²); and δψ_D.
/// Sources are independent between groups, so A_g Σ_g A_gᵀ of each group g adds up to P₀.
InitialCovariance aligned_initial_covariance(const NominalState& nominal,
                                             const InsSensorNoise& noise,
                                             const DriftPredictionOptions& o,
                                             const ErrorStateLayout& layout, int states) {
  const double T = o.alignment_time_s;
  // Columns of A, with their variances (diagonal of Σ_z), a partner for the GM (m, b)
  // covariance and the budget group.
  struct Source {
    Eigen::VectorXd a;  // column of A (states)
    double variance = 0.0;
    int partner = -1;  // index of the correlated source (GM m ↔ b)
    double covariance = 0.0;
    DriftBudgetTerm group = DriftBudgetTerm::alignment;
  };
  std::vector<Source> z;
  const auto add = [&](double variance, DriftBudgetTerm group) {
    Source s;
    s.a = Eigen::VectorXd::Zero(states);
    s.variance = variance;
    s.group = group;
    z.push_back(std::move(s));
    return z.size() - 1;
  };
  // Leveling (theory.md §7.3): the tilt that zeroes the mean horizontal specific force
  // −f^n×δψ + e^n, f^n = [0, 0, −g], is δψ_N = −e_E/g, δψ_E = e_N/g with e^n = C_bn e^b the
  // accel error's window mean minus its end value for the RW and ramp parts (the accel RW
  // state is taken relative to its end value, so it starts at 0).
  const Matrix3d& C = nominal.C_bn;
  const double g = -(C * nominal.f_ib_b_m_per_s2).z();
  Matrix3d level = Matrix3d::Zero();
  level(0, 1) = -1.0 / g;
  level(1, 0) = 1.0 / g;
  const auto tilt_of = [&](int axis) -> Vector3d { return level * C.col(axis); };
  // The state of gm_terms[term] of an axis (σ > 0), or −1.
  const auto term_state = [&](bool gyro, int axis, int term) {
    for (const AxisState& x : layout.axis_states)
      if (x.kind == AxisState::Kind::gm_term && x.gyro == gyro && x.axis == axis && x.term == term)
        return x.state;
    return -1;
  };
  const auto ramp_state = [&](bool gyro, int axis) {
    for (const AxisState& x : layout.axis_states)
      if (x.kind == AxisState::Kind::ramp_slope && x.gyro == gyro && x.axis == axis) return x.state;
    return -1;
  };
  for (const bool gyro : {false, true}) {
    const auto& axes = gyro ? noise.gyro : noise.accel;
    for (int i = 0; i < 3; ++i) {
      const SensorAxisNoise& ax = axes[i];
      const int rw_state = (gyro ? Layout::kGyroBias : Layout::kAccelBias) + i;
      // The residual a source leaves: accel → equivalent tilt; gyro → the gyro RW state holds
      // b(T_a) − b̂_g (b̂_g = window mean), theory.md §7.3.
      const auto leave = [&](std::size_t k, double accel_factor, double gyro_factor) {
        if (gyro)
          z[k].a(rw_state) += gyro_factor;
        else
          z[k].a.segment<3>(Layout::kAttitude) += accel_factor * tilt_of(i);
      };
      leave(add(ax.white_noise * ax.white_noise / T, DriftBudgetTerm::alignment), 1.0, 1.0);
      leave(add(ax.random_walk * ax.random_walk * T / 3.0, DriftBudgetTerm::alignment), 1.0, 1.0);
      const auto add_gm = [&](const GaussMarkov& gm, int state) {
        if (gm.sigma == 0.0 || state < 0) return;
        const GmWindowMean w = gm_window_mean(gm, T);
        const std::size_t m = add(w.mean_variance, DriftBudgetTerm::alignment);
        const std::size_t b = add(w.end_variance, DriftBudgetTerm::alignment);
        z[m].partner = static_cast<int>(b);
        z[b].partner = static_cast<int>(m);
        z[m].covariance = z[b].covariance = w.mean_end_covariance;
        leave(m, 1.0, -1.0);  // leveling absorbs m; the gyro estimate takes it out
        z[b].a(state) = 1.0;  // the GM state starts at its end-of-window value
      };
      add_gm(ax.bias_gm, *(gyro ? layout.gyro_bias_gm : layout.accel_bias_gm) + i);
      for (std::size_t j = 0; j < ax.gm_terms.size(); ++j)
        add_gm(ax.gm_terms[j], term_state(gyro, i, static_cast<int>(j)));
      // Ramp slope s: the window mean minus the end value is −sT_a/2 (accel tilt), the gyro
      // residual b(T_a) − mean is +sT_a/2; the slope state holds s.
      if (const int rs = ramp_state(gyro, i); rs >= 0) {
        const std::size_t k = add(ax.ramp * ax.ramp, DriftBudgetTerm::ramp);
        leave(k, -T / 2.0, T / 2.0);
        z[k].a(rs) = 1.0;
      }
    }
  }
  const std::size_t heading =
      add(o.heading_sigma_rad * o.heading_sigma_rad, DriftBudgetTerm::heading);
  z[heading].a(Layout::kAttitude + 2) = 1.0;
  // With Earth-rate coupling the gyro-bias removal used the erroneous attitude, which adds
  // C_nb [ω_ie×] δψ₀ to the gyro RW state: the navigator is self-consistent and an attitude
  // error alone causes no drift at rest (theory.md §7.3).
  if (o.earth_rate_coupling) {
    const Matrix3d coupling = C.transpose() * skew(earth_rate_ned(nominal.latitude_rad));
    for (Source& s : z)
      s.a.segment<3>(Layout::kGyroBias) += coupling * s.a.segment<3>(Layout::kAttitude);
  }
  InitialCovariance out;
  for (MatrixXd& part : out.parts) part = MatrixXd::Zero(states, states);
  for (std::size_t k = 0; k < z.size(); ++k) {
    MatrixXd& part = out.parts[static_cast<std::size_t>(z[k].group)];
    part.noalias() += z[k].variance * z[k].a * z[k].a.transpose();
    if (z[k].partner >= 0)  // each (m, b) pair adds Cov·(a_m a_bᵀ + a_b a_mᵀ), once per side
      part.noalias() +=
          z[k].covariance * z[k].a * z[static_cast<std::size_t>(z[k].partner)].a.transpose();
  }
  for (MatrixXd& part : out.parts) part = 0.5 * (part + part.transpose()).eval();
  return out;
}

/// P₀ without alignment: the model's initial variance (turn-on σ², GM σ², ramp slope R²)
/// plus heading σ² on δψ_D, split by budget group.
InitialCovariance unaligned_initial_covariance(const models::ContinuousStateModel& model,
                                               const ErrorStateLayout& layout,
                                               double heading_sigma_rad) {
  InitialCovariance out;
  const int n = model.states();
  for (MatrixXd& part : out.parts) part = MatrixXd::Zero(n, n);
  Eigen::VectorXd ramp = Eigen::VectorXd::Zero(n);
  for (const AxisState& x : layout.axis_states)
    if (x.kind == AxisState::Kind::ramp_slope) ramp(x.state) = model.initial_variance(x.state);
  out.parts[static_cast<std::size_t>(DriftBudgetTerm::alignment)] =
      (model.initial_variance - ramp).asDiagonal();
  out.parts[static_cast<std::size_t>(DriftBudgetTerm::ramp)] = ramp.asDiagonal();
  out.parts[static_cast<std::size_t>(DriftBudgetTerm::heading)](
      Layout::kAttitude + 2, Layout::kAttitude + 2) = heading_sigma_rad * heading_sigma_rad;
  return out;
}

/// The budget group of each driving noise of the model of LAYOUT and NOISE.
std::vector<DriftBudgetTerm> noise_groups(const ErrorStateLayout& layout,
                                          const InsSensorNoise& noise) {
  std::vector<DriftBudgetTerm> groups(static_cast<std::size_t>(layout.noises),
                                      DriftBudgetTerm::bias_instability);
  for (int i = 0; i < 3; ++i) {
    groups[Layout::kGyroWhiteNoise + i] = DriftBudgetTerm::white_noise;
    groups[Layout::kAccelWhiteNoise + i] = DriftBudgetTerm::white_noise;
    groups[Layout::kGyroBiasNoise + i] = DriftBudgetTerm::random_walk;
    groups[Layout::kAccelBiasNoise + i] = DriftBudgetTerm::random_walk;
  }
  // bias_gm and B's multi-GM terms stay bias_instability, the fitted GM terms are
  // gauss_markov; a ramp slope has no driving noise.
  for (const AxisState& x : layout.axis_states) {
    const auto k = static_cast<std::size_t>(x.noise);
    if (x.kind == AxisState::Kind::ramp_slope) groups[k] = DriftBudgetTerm::ramp;
    const SensorAxisNoise& axis = (x.gyro ? noise.gyro : noise.accel)[x.axis];
    if (x.kind == AxisState::Kind::gm_term &&
        static_cast<std::size_t>(x.term) >= axis.bias_instability_terms)
      groups[k] = DriftBudgetTerm::gauss_markov;
  }
  return groups;
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
  const ErrorStateLayout layout = error_state_layout(model_options, acting);
  const int n = model.states();

  const InitialCovariance initial =
      options.alignment_time_s > 0.0
          ? aligned_initial_covariance(nominal, acting, options, layout, n)
          : unaligned_initial_covariance(model, layout, options.heading_sigma_rad);
  MatrixXd P = initial.total();

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

  // The budget: the system is linear and its sources independent, so each group propagates
  // alone, P_g ← ΦP_gΦᵀ + Q_d,g, with Q_d,g the Q_d of the group's driving noises alone (Q_d is
  // linear in Q_c, so Σ_g Q_d,g = Q_d) and P_g(0) its part of P₀; Σ_g P_g = P at every step.
  std::array<MatrixXd, kDriftBudgetTerms> P_group, Qd_group;
  if (options.budget) {
    const std::vector<DriftBudgetTerm> groups = noise_groups(layout, acting);
    for (std::size_t g = 0; g < kDriftBudgetTerms; ++g) {
      P_group[g] = initial.parts[g];
      models::ContinuousStateModel only = model;
      for (int k = 0; k < layout.noises; ++k)
        if (static_cast<std::size_t>(groups[static_cast<std::size_t>(k)]) != g) {
          only.Qc.row(k).setZero();
          only.Qc.col(k).setZero();
        }
      Qd_group[g] = models::discretize(only, options.step_s).Qd;
    }
  }
  const auto step_once = [&](MatrixXd& M, const MatrixXd& Qd) {
    PhiP.noalias() = Phi * M;
    M.noalias() = PhiP * Phi.transpose();
    M += Qd;
    M = 0.5 * (M + M.transpose()).eval();
  };

  long long step = 0;
  for (const double t : options.times_s) {
    const auto target = static_cast<long long>(std::llround(t / options.step_s));
    for (; step < target; ++step) {
      step_once(P, discrete.Qd);
      if (options.budget)
        for (std::size_t g = 0; g < kDriftBudgetTerms; ++g) step_once(P_group[g], Qd_group[g]);
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
    if (options.budget) {
      DriftBudgetRow row;
      for (std::size_t g = 0; g < kDriftBudgetTerms; ++g)
        row[g] = P_group[g](r, r) + P_group[g](r + 1, r + 1);
      out.horizontal_variance_budget_m2.push_back(row);
    }
  }
  return out;
}

}  // namespace imunoise::ins
