/// @file
/// @brief INS error-state model (see error_state_model.h; theory.md §6.3, §7.4).
#include "ins/error_state_model.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.h"
#include "ins/earth_model.h"
#include "ins/frames.h"

namespace imunoise::ins {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Layout = ErrorStateLayout;
using NavigationMatrix = Eigen::Matrix<double, 9, 9>;

/// The 9×9 navigation block of F in (δψ, δv^n, δr^n metres NED); see the header for the
/// equations. Position is handled as p = (L, λ, h) first (Groves 14.64–14.71 with the
/// radius and gravity latitude derivatives kept), then carried to metres.
/// EARTH_RATE false sets Ω_ie (and so its latitude derivative) to 0.
NavigationMatrix navigation_dynamics(const NominalState& nominal, bool earth_rate) {
  const double lat = nominal.latitude_rad, h = nominal.height_m;
  const double s = std::sin(lat), c = std::cos(lat), t = std::tan(lat);
  const double rn = meridian_radius(lat) + h;            // R_N + h
  const double re = transverse_radius(lat) + h;          // R_E + h
  const double drn = meridian_radius_d_latitude(lat);    // dR_N/dL
  const double dre = transverse_radius_d_latitude(lat);  // dR_E/dL
  const Vector3d& v = nominal.v_ned_m_per_s;
  const double vn = v.x(), ve = v.y(), vd = v.z();

  const Vector3d w_ie = earth_rate ? earth_rate_ned(lat) : Vector3d::Zero();
  const Vector3d w_en = transport_rate_ned(lat, h, v);
  const Vector3d f_n = nominal.C_bn * nominal.f_ib_b_m_per_s2;

  // ∂ω_en^n/∂v^n.
  Matrix3d den_dv;
  den_dv << 0.0, 1.0 / re, 0.0, -1.0 / rn, 0.0, 0.0, 0.0, -t / re, 0.0;
  // ∂ω_ie^n/∂p and ∂ω_en^n/∂p, columns (L, λ, h); nothing depends on λ.
  Matrix3d die_dp = Matrix3d::Zero();
  if (earth_rate) die_dp.col(0) = wgs84::kEarthRate * Vector3d(-s, 0.0, -c);
  Matrix3d den_dp = Matrix3d::Zero();
  den_dp.col(0) << -ve * dre / (re * re), vn * drn / (rn * rn),
      -ve * (1.0 / (re * c * c) - t * dre / (re * re));
  den_dp.col(2) << -ve / (re * re), vn / (rn * rn), ve * t / (re * re);
  const GravityGradient dg = gravity_ned_gradient(lat, h);
  Matrix3d dg_dp = Matrix3d::Zero();
  dg_dp.col(0) = dg.d_latitude;
  dg_dp.col(2) = dg.d_height;

  // Position kinematics ṗ = (v_N/(R_N+h), v_E/((R_E+h)cosL), −v_D): ∂ṗ/∂v and ∂ṗ/∂p.
  const Matrix3d dpdot_dv = Vector3d(1.0 / rn, 1.0 / (re * c), -1.0).asDiagonal();
  Matrix3d dpdot_dp = Matrix3d::Zero();
  dpdot_dp(0, 0) = -vn * drn / (rn * rn);
  dpdot_dp(0, 2) = -vn / (rn * rn);
  dpdot_dp(1, 0) = ve * (re * s - dre * c) / (re * re * c * c);
  dpdot_dp(1, 2) = -ve / (re * re * c);

  // δr = T δp with T = diag(R_N+h, (R_E+h)cosL, −1) along the nominal, so
  // δṙ = (Ṫ T⁻¹ + T ∂ṗ/∂p T⁻¹) δr + T ∂ṗ/∂v δv, and p-columns elsewhere pick up T⁻¹.
  const double lat_rate = vn / rn, h_rate = -vd;
  const Vector3d T(rn, re * c, -1.0);
  const Matrix3d T_inv = T.cwiseInverse().asDiagonal();
  const Matrix3d T_dot_T_inv =
      Vector3d((drn * lat_rate + h_rate) / rn,
               ((dre * lat_rate + h_rate) * c - re * s * lat_rate) / (re * c), 0.0)
          .asDiagonal();

  NavigationMatrix F = NavigationMatrix::Zero();
  const int a = Layout::kAttitude, u = Layout::kVelocity, r = Layout::kPosition;
  // δψ̇ = −ω_in × δψ − δω_in (Groves 14.64; F₁₂, F₁₃ are −∂ω_in/∂v, −∂ω_in/∂p).
  F.block<3, 3>(a, a) = -skew(w_ie + w_en);
  F.block<3, 3>(a, u) = -den_dv;
  F.block<3, 3>(a, r) = -(die_dp + den_dp) * T_inv;
  // δv̇ = −f^n × δψ − (2ω_ie + ω_en) × δv + v × δ(2ω_ie + ω_en) + δg (Groves 14.65–14.67).
  F.block<3, 3>(u, a) = -skew(f_n);
  F.block<3, 3>(u, u) = -skew(2.0 * w_ie + w_en) + skew(v) * den_dv;
  F.block<3, 3>(u, r) = (skew(v) * (2.0 * die_dp + den_dp) + dg_dp) * T_inv;
  // δṙ (Groves 14.68–14.70 carried to metres; T ∂ṗ/∂v = I).
  F.block<3, 3>(r, u) = T.asDiagonal() * dpdot_dv;
  F.block<3, 3>(r, r) = T.asDiagonal() * dpdot_dp * T_inv + T_dot_T_inv;
  return F;
}

void check_nominal(const NominalState& nominal) {
  const char* where = "ins_error_state_model";
  IMUNOISE_CHECK(std::isfinite(nominal.latitude_rad) &&
                     std::abs(nominal.latitude_rad) < std::numbers::pi / 2.0,
                 InputError,
                 std::string(where) +
                     ": nominal latitude must be finite and strictly within ±pi/2 rad (got " +
                     std::to_string(nominal.latitude_rad) + ")");
  IMUNOISE_CHECK(std::isfinite(nominal.height_m) &&
                     meridian_radius(nominal.latitude_rad) + nominal.height_m > 0.0,
                 InputError,
                 std::string(where) +
                     ": nominal height must be finite and above the centre of "
                     "curvature (got " +
                     std::to_string(nominal.height_m) + " m)");
  IMUNOISE_CHECK(nominal.v_ned_m_per_s.allFinite() && nominal.f_ib_b_m_per_s2.allFinite() &&
                     nominal.w_ib_b_rad_per_s.allFinite() && nominal.C_bn.allFinite(),
                 InputError,
                 std::string(where) +
                     ": nominal velocity, specific force, rate and C_bn must "
                     "be finite");
  const double orthogonality =
      (nominal.C_bn.transpose() * nominal.C_bn - Matrix3d::Identity()).cwiseAbs().maxCoeff();
  IMUNOISE_CHECK(orthogonality <= 1e-6 && nominal.C_bn.determinant() > 0.0, InputError,
                 std::string(where) + ": nominal C_bn must be a rotation (max |C^T C - I| = " +
                     std::to_string(orthogonality) + ", expected <= 1e-6; det = " +
                     std::to_string(nominal.C_bn.determinant()) + ", expected 1)");
}

void check_axis(const SensorAxisNoise& axis, const std::string& where) {
  const auto check_term = [&](double value, const char* field) {
    IMUNOISE_CHECK(std::isfinite(value) && value >= 0.0, InputError,
                   "ins_error_state_model: " + where + "." + field +
                       " must be finite and >= 0 (got " + std::to_string(value) + ")");
  };
  check_term(axis.white_noise, "white_noise");
  check_term(axis.random_walk, "random_walk");
  check_term(axis.bias_gm.sigma, "bias_gm.sigma");
  check_term(axis.turn_on_bias_sigma, "turn_on_bias_sigma");
  check_term(axis.scale_factor_sigma, "scale_factor_sigma");
  IMUNOISE_CHECK(axis.bias_gm.sigma == 0.0 ||
                     (std::isfinite(axis.bias_gm.tau_c_s) && axis.bias_gm.tau_c_s > 0.0),
                 InputError,
                 "ins_error_state_model: " + where +
                     ".bias_gm.tau_c_s must be finite and > 0 s when sigma > 0 (got " +
                     std::to_string(axis.bias_gm.tau_c_s) + ")");
  check_term(axis.ramp, "ramp");
  for (std::size_t j = 0; j < axis.gm_terms.size(); ++j) {
    const GaussMarkov& gm = axis.gm_terms[j];
    const std::string field = where + ".gm_terms[" + std::to_string(j) + "]";
    IMUNOISE_CHECK(std::isfinite(gm.sigma) && gm.sigma >= 0.0, InputError,
                   "ins_error_state_model: " + field + ".sigma must be finite and >= 0 (got " +
                       std::to_string(gm.sigma) + ")");
    IMUNOISE_CHECK(gm.sigma == 0.0 || (std::isfinite(gm.tau_c_s) && gm.tau_c_s > 0.0), InputError,
                   "ins_error_state_model: " + field +
                       ".tau_c_s must be finite and > 0 s when sigma > 0 (got " +
                       std::to_string(gm.tau_c_s) + ")");
  }
  IMUNOISE_CHECK(axis.scale_factor_tau_c_s > 0.0, InputError,
                 "ins_error_state_model: " + where +
                     ".scale_factor_tau_c_s must be > 0 s (infinity = random constant; got " +
                     std::to_string(axis.scale_factor_tau_c_s) + ")");
}

/// One per-axis stochastic state: its F diagonal, driving intensity Q_c and P₀.
struct ScalarState {
  double f = 0.0, qc = 0.0, p0 = 0.0;
};

/// RW bias: ḃ = K w, P₀ = turn-on σ² (theory.md §6.1 random walk + random constant).
ScalarState random_walk_bias(const SensorAxisNoise& axis) {
  return {0.0, axis.random_walk * axis.random_walk,
          axis.turn_on_bias_sigma * axis.turn_on_bias_sigma};
}

/// First-order GM (theory.md §6.1): F = −1/T_c, Q_c = 2σ²/T_c, P₀ = σ²; σ = 0 → inert state.
ScalarState gauss_markov(double sigma, double tau_c_s) {
  if (sigma == 0.0 || std::isinf(tau_c_s)) return {0.0, 0.0, sigma * sigma};
  return {-1.0 / tau_c_s, 2.0 * sigma * sigma / tau_c_s, sigma * sigma};
}

const char* const kNed[3] = {"n", "e", "d"};
const char* const kXyz[3] = {"x", "y", "z"};

}  // namespace

NominalState stationary_nominal(double latitude_rad, double height_m, double heading_rad) {
  IMUNOISE_CHECK(
      std::isfinite(heading_rad), InputError,
      "stationary_nominal: heading must be finite (got " + std::to_string(heading_rad) + ")");
  IMUNOISE_CHECK(std::isfinite(latitude_rad) && std::abs(latitude_rad) < std::numbers::pi / 2.0,
                 InputError,
                 "stationary_nominal: latitude must be finite and strictly within ±pi/2 rad "
                 "(got " +
                     std::to_string(latitude_rad) + ")");
  IMUNOISE_CHECK(
      std::isfinite(height_m), InputError,
      "stationary_nominal: height must be finite (got " + std::to_string(height_m) + ")");
  NominalState nominal;
  nominal.latitude_rad = latitude_rad;
  nominal.height_m = height_m;
  nominal.C_bn = Eigen::AngleAxisd(heading_rad, Vector3d::UnitZ()).toRotationMatrix();
  // At rest the accelerometers read minus the plumb-bob gravity and the gyros the Earth rate.
  nominal.f_ib_b_m_per_s2 = nominal.C_bn.transpose() * -gravity_ned(latitude_rad, height_m);
  nominal.w_ib_b_rad_per_s = nominal.C_bn.transpose() * earth_rate_ned(latitude_rad);
  return nominal;
}

ErrorStateLayout error_state_layout(const ErrorStateOptions& options) {
  ErrorStateLayout layout;
  int next_state = 15, next_noise = 12;
  if (options.bias == BiasModel::both) {
    layout.accel_bias_gm = next_state;
    layout.gyro_bias_gm = next_state + 3;
    layout.gyro_bias_gm_noise = next_noise;
    layout.accel_bias_gm_noise = next_noise + 3;
    next_state += 6;
    next_noise += 6;
  }
  if (options.scale_factors) {
    layout.accel_scale = next_state;
    layout.gyro_scale = next_state + 3;
    layout.gyro_scale_noise = next_noise;
    layout.accel_scale_noise = next_noise + 3;
    next_state += 6;
    next_noise += 6;
  }
  layout.states = next_state;
  layout.noises = next_noise;
  return layout;
}

ErrorStateLayout error_state_layout(const ErrorStateOptions& options, const InsSensorNoise& noise) {
  ErrorStateLayout layout = error_state_layout(options);
  const auto add = [&](AxisState::Kind kind, bool gyro, int axis, int term) {
    AxisState x;
    x.kind = kind;
    x.gyro = gyro;
    x.axis = axis;
    x.term = term;
    x.state = layout.states++;
    x.noise = layout.noises++;
    layout.axis_states.push_back(x);
  };
  for (const bool gyro : {true, false}) {
    const auto& axes = gyro ? noise.gyro : noise.accel;
    for (int i = 0; i < 3; ++i) {
      for (std::size_t j = 0; j < axes[i].gm_terms.size(); ++j)
        if (axes[i].gm_terms[j].sigma > 0.0)
          add(AxisState::Kind::gm_term, gyro, i, static_cast<int>(j));
      if (axes[i].ramp > 0.0 && options.bias != BiasModel::gauss_markov)
        add(AxisState::Kind::ramp_slope, gyro, i, 0);
    }
  }
  return layout;
}

models::ContinuousStateModel ins_error_state_model(const NominalState& nominal,
                                                   const InsSensorNoise& noise,
                                                   const ErrorStateOptions& options) {
  check_nominal(nominal);
  for (int i = 0; i < 3; ++i) {
    check_axis(noise.gyro[i], std::string("gyro[") + kXyz[i] + "]");
    check_axis(noise.accel[i], std::string("accel[") + kXyz[i] + "]");
  }
  const ErrorStateLayout layout = error_state_layout(options, noise);
  const int n = layout.states, p = layout.noises;
  const Matrix3d& C = nominal.C_bn;

  models::ContinuousStateModel model;
  model.F = Eigen::MatrixXd::Zero(n, n);
  model.G = Eigen::MatrixXd::Zero(n, p);
  model.Qc = Eigen::MatrixXd::Zero(p, p);
  model.initial_variance = Eigen::VectorXd::Zero(n);
  model.state_names.resize(static_cast<std::size_t>(n));
  model.noise_names.resize(static_cast<std::size_t>(p));

  model.F.topLeftCorner<9, 9>() = navigation_dynamics(nominal, options.earth_rate);
  const int a = Layout::kAttitude, u = Layout::kVelocity;
  for (int i = 0; i < 3; ++i) {
    model.state_names[a + i] = std::string("att_err_") + kNed[i] + "_rad";
    model.state_names[u + i] = std::string("vel_err_") + kNed[i] + "_m_per_s";
    model.state_names[Layout::kPosition + i] = std::string("pos_err_") + kNed[i] + "_m";
  }

  // White sensor noise enters like a sensor error: through C_bn (theory.md §6.3).
  model.G.block<3, 3>(a, Layout::kGyroWhiteNoise) = C;
  model.G.block<3, 3>(u, Layout::kAccelWhiteNoise) = C;
  for (int i = 0; i < 3; ++i) {
    model.Qc(Layout::kGyroWhiteNoise + i, Layout::kGyroWhiteNoise + i) =
        noise.gyro[i].white_noise * noise.gyro[i].white_noise;
    model.Qc(Layout::kAccelWhiteNoise + i, Layout::kAccelWhiteNoise + i) =
        noise.accel[i].white_noise * noise.accel[i].white_noise;
    model.noise_names[Layout::kGyroWhiteNoise + i] =
        std::string("gyro_white_") + kXyz[i] + "_rad_per_sqrt_s";
    model.noise_names[Layout::kAccelWhiteNoise + i] =
        std::string("accel_white_") + kXyz[i] + "_m_per_s_per_sqrt_s";
  }

  // A block of 3 per-axis sensor states at STATE driven by noises at NOISE, coupled into the
  // navigation rows NAV_ROW through COUPLING (C_bn, or C_bn·diag(ω or f) for scale factors).
  const auto add_sensor_block = [&](int state, int noise_index, int nav_row,
                                    const Matrix3d& coupling, const std::string& prefix,
                                    const std::string& unit, const std::string& noise_unit,
                                    const auto& scalar_of_axis) {
    model.F.block<3, 3>(nav_row, state) = coupling;
    for (int i = 0; i < 3; ++i) {
      const ScalarState x = scalar_of_axis(i);
      model.F(state + i, state + i) = x.f;
      model.G(state + i, noise_index + i) = 1.0;
      model.Qc(noise_index + i, noise_index + i) = x.qc;
      model.initial_variance(state + i) = x.p0;
      model.state_names[state + i] = prefix + "_" + kXyz[i] + unit;
      model.noise_names[noise_index + i] = prefix + "_driving_" + kXyz[i] + noise_unit;
    }
  };
  const auto gm_of = [](const SensorAxisNoise& axis) {
    return gauss_markov(axis.bias_gm.sigma, axis.bias_gm.tau_c_s);
  };
  const bool gm_only = options.bias == BiasModel::gauss_markov;
  const std::string bias_kind = gm_only ? "_bias_gm" : "_bias";
  add_sensor_block(Layout::kAccelBias, Layout::kAccelBiasNoise, u, C, "accel" + bias_kind,
                   "_m_per_s2", "_m_per_s2_per_sqrt_s", [&](int i) {
                     return gm_only ? gm_of(noise.accel[i]) : random_walk_bias(noise.accel[i]);
                   });
  add_sensor_block(Layout::kGyroBias, Layout::kGyroBiasNoise, a, C, "gyro" + bias_kind,
                   "_rad_per_s", "_rad_per_s_per_sqrt_s", [&](int i) {
                     return gm_only ? gm_of(noise.gyro[i]) : random_walk_bias(noise.gyro[i]);
                   });
  if (options.bias == BiasModel::both) {
    // b = b_RW + b_GM: both states feed the navigation errors the same way (theory.md §6.3).
    add_sensor_block(*layout.accel_bias_gm, *layout.accel_bias_gm_noise, u, C, "accel_bias_gm",
                     "_m_per_s2", "_m_per_s2_per_sqrt_s",
                     [&](int i) { return gm_of(noise.accel[i]); });
    add_sensor_block(*layout.gyro_bias_gm, *layout.gyro_bias_gm_noise, a, C, "gyro_bias_gm",
                     "_rad_per_s", "_rad_per_s_per_sqrt_s",
                     [&](int i) { return gm_of(noise.gyro[i]); });
  }
  if (options.scale_factors) {
    // δf = diag(f_ib^b) s_a, δω = diag(ω_ib^b) s_g (theory.md §6.3).
    const auto scale_of = [](const SensorAxisNoise& axis) {
      return gauss_markov(axis.scale_factor_sigma, axis.scale_factor_tau_c_s);
    };
    add_sensor_block(*layout.accel_scale, *layout.accel_scale_noise, u,
                     C * nominal.f_ib_b_m_per_s2.asDiagonal(), "accel_scale", "", "_per_sqrt_s",
                     [&](int i) { return scale_of(noise.accel[i]); });
    add_sensor_block(*layout.gyro_scale, *layout.gyro_scale_noise, a,
                     C * nominal.w_ib_b_rad_per_s.asDiagonal(), "gyro_scale", "", "_per_sqrt_s",
                     [&](int i) { return scale_of(noise.gyro[i]); });
  }

  // Further GM terms and ramp slopes, one scalar state each (theory.md §4.4, §6.1).
  for (const AxisState& x : layout.axis_states) {
    const SensorAxisNoise& axis = x.gyro ? noise.gyro[x.axis] : noise.accel[x.axis];
    const int nav_row = x.gyro ? a : u;
    const std::string sensor = x.gyro ? "gyro" : "accel";
    const std::string unit = x.gyro ? "_rad_per_s" : "_m_per_s2";
    model.G(x.state, x.noise) = 1.0;
    if (x.kind == AxisState::Kind::gm_term) {
      const GaussMarkov& gm = axis.gm_terms[static_cast<std::size_t>(x.term)];
      const ScalarState s = gauss_markov(gm.sigma, gm.tau_c_s);
      model.F.block<3, 1>(nav_row, x.state) = C.col(x.axis);
      model.F(x.state, x.state) = s.f;
      model.Qc(x.noise, x.noise) = s.qc;
      model.initial_variance(x.state) = s.p0;
      const std::string name =
          sensor + "_bias_gm" + std::to_string(x.term + 1) + "_" + kXyz[x.axis];
      model.state_names[x.state] = name + unit;
      model.noise_names[x.noise] = name + "_driving" + unit + "_per_sqrt_s";
    } else {
      // ḃ_RW = K w + s: the slope feeds the RW bias state of its axis; no driving noise.
      const int bias_state = (x.gyro ? Layout::kGyroBias : Layout::kAccelBias) + x.axis;
      model.F(bias_state, x.state) = 1.0;
      model.initial_variance(x.state) = axis.ramp * axis.ramp;
      const std::string name = sensor + "_ramp_slope_" + kXyz[x.axis];
      model.state_names[x.state] = name + unit + "_per_s";
      model.noise_names[x.noise] = name + "_driving_none";
    }
  }

  if (options.height_hold) {
    // Stationary-analysis convention (theory.md §7.2): δv_D and δr_D neither move nor are
    // driven, so with P₀ = 0 they stay 0 and the unstable vertical loop is cut.
    for (const int row : {u + 2, Layout::kPosition + 2}) {
      model.F.row(row).setZero();
      model.G.row(row).setZero();
    }
  }
  return model;
}

}  // namespace imunoise::ins
