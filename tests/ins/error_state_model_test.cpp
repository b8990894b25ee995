/// @file
/// @brief Tests of ins/error_state_model.h: layout and labels, Q_c against the densities of
/// theory.md §6.1/§6.3, F against finite differences of the nonlinear NED mechanization of
/// §7.2, the Schuler period and vertical instability of §7.2/§7.4, and covariance propagation
/// (models::discretize) against the stationary closed forms of §7.5.
#include "ins/error_state_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/units.h"
#include "ins/earth_model.h"
#include "models/state_space.h"
#include "test_support.h"

namespace imunoise::ins {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Layout = ErrorStateLayout;
using units::kDeg;

constexpr double kLat45 = 45.0 * kDeg;  // latitude of the §7.5 checks [rad]

/// @name Options of the four sizes (theory.md §6.3)
/// @{
ErrorStateOptions options_of(BiasModel bias, bool scale_factors, bool height_hold = false) {
  ErrorStateOptions options;
  options.bias = bias;
  options.scale_factors = scale_factors;
  options.height_hold = height_hold;
  return options;
}
/// @}

/// Every axis of both sensors set to AXIS.
InsSensorNoise isotropic(const SensorAxisNoise& gyro, const SensorAxisNoise& accel) {
  InsSensorNoise noise;
  noise.gyro.fill(gyro);
  noise.accel.fill(accel);
  return noise;
}

/// P(t) from P₀ = diag(initial_variance) by P ← ΦPΦᵀ + Q_d, STEPS steps of DT.
MatrixXd propagate_covariance(const models::ContinuousStateModel& model, double dt_s, int steps) {
  const models::DiscreteStateModel discrete = models::discretize(model, dt_s);
  MatrixXd P = model.initial_variance.asDiagonal();
  for (int k = 0; k < steps; ++k) P = discrete.Phi * P * discrete.Phi.transpose() + discrete.Qd;
  return P;
}

TEST(InsErrorStateModel, StationaryNominalReadsGravityAndEarthRate) {
  // Heading ψ = 30°: body x is 30° east of north, body y 30° south of east, z down, so the
  // gyros read Ω[cosL cosψ, −cosL sinψ, −sinL] and the accelerometers [−g_N cosψ, g_N sinψ,
  // −g_D] (a level FRD accelerometer at rest reads minus gravity).
  const double psi = 30.0 * kDeg, h = 500.0;
  const NominalState rest = stationary_nominal(kLat45, h, psi);
  const double W = wgs84::kEarthRate, c = std::cos(kLat45), s = std::sin(kLat45);
  const Vector3d g = gravity_ned(kLat45, h);
  EXPECT_LT(
      (rest.w_ib_b_rad_per_s - W * Vector3d(c * std::cos(psi), -c * std::sin(psi), -s)).norm(),
      1e-20);
  EXPECT_LT((rest.f_ib_b_m_per_s2 - Vector3d(-g.x() * std::cos(psi), g.x() * std::sin(psi), -g.z()))
                .norm(),
            1e-14);
  EXPECT_EQ(rest.v_ned_m_per_s.norm(), 0.0);
  EXPECT_EQ(rest.latitude_rad, kLat45);
  EXPECT_EQ(rest.height_m, h);
}

TEST(InsErrorStateModel, DimensionsAndLabelsOfTheFourSizes) {
  struct Case {
    BiasModel bias;
    bool scale;
    int states;
    std::vector<std::pair<int, std::string>> states_at, noises_at;
  };
  const std::vector<Case> cases = {
      {BiasModel::random_walk,
       false,
       15,
       {{0, "att_err_n_rad"},
        {4, "vel_err_e_m_per_s"},
        {8, "pos_err_d_m"},
        {9, "accel_bias_x_m_per_s2"},
        {14, "gyro_bias_z_rad_per_s"}},
       {{0, "gyro_white_x_rad_per_sqrt_s"},
        {5, "accel_white_z_m_per_s_per_sqrt_s"},
        {6, "gyro_bias_driving_x_rad_per_s_per_sqrt_s"},
        {11, "accel_bias_driving_z_m_per_s2_per_sqrt_s"}}},
      {BiasModel::gauss_markov,
       false,
       15,
       {{9, "accel_bias_gm_x_m_per_s2"}, {14, "gyro_bias_gm_z_rad_per_s"}},
       {{7, "gyro_bias_gm_driving_y_rad_per_s_per_sqrt_s"}}},
      {BiasModel::both,
       false,
       21,
       {{9, "accel_bias_x_m_per_s2"},
        {12, "gyro_bias_x_rad_per_s"},
        {15, "accel_bias_gm_x_m_per_s2"},
        {20, "gyro_bias_gm_z_rad_per_s"}},
       {{12, "gyro_bias_gm_driving_x_rad_per_s_per_sqrt_s"},
        {17, "accel_bias_gm_driving_z_m_per_s2_per_sqrt_s"}}},
      {BiasModel::random_walk,
       true,
       21,
       {{15, "accel_scale_x"}, {19, "gyro_scale_y"}},
       {{12, "gyro_scale_driving_x_per_sqrt_s"}, {17, "accel_scale_driving_z_per_sqrt_s"}}},
      {BiasModel::both,
       true,
       27,
       {{20, "gyro_bias_gm_z_rad_per_s"}, {21, "accel_scale_x"}, {26, "gyro_scale_z"}},
       {{18, "gyro_scale_driving_x_per_sqrt_s"}, {23, "accel_scale_driving_z_per_sqrt_s"}}},
  };
  for (const Case& c : cases) {
    const auto model = ins_error_state_model(stationary_nominal(kLat45, 0.0, 0.0), InsSensorNoise{},
                                             options_of(c.bias, c.scale));
    const int n = c.states, p = c.states - 3;
    SCOPED_TRACE(n);
    EXPECT_EQ(model.states(), n);
    EXPECT_EQ(model.F.cols(), n);
    EXPECT_EQ(model.G.rows(), n);
    EXPECT_EQ(model.G.cols(), p);
    EXPECT_EQ(model.Qc.rows(), p);
    EXPECT_EQ(model.Qc.cols(), p);
    EXPECT_EQ(model.initial_variance.size(), n);
    ASSERT_EQ(model.state_names.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(model.noise_names.size(), static_cast<std::size_t>(p));
    for (const auto& [i, name] : c.states_at) EXPECT_EQ(model.state_names[i], name);
    for (const auto& [i, name] : c.noises_at) EXPECT_EQ(model.noise_names[i], name);
    const ErrorStateLayout layout = error_state_layout(options_of(c.bias, c.scale));
    EXPECT_EQ(layout.states, n);
    EXPECT_EQ(layout.noises, p);
  }
}

TEST(InsErrorStateModel, QcIsTheSquaredDensitiesAndP0TheVariances) {
  // Distinct values per axis and term so a misplaced entry cannot pass.
  InsSensorNoise noise;
  for (int i = 0; i < 3; ++i) {
    const double k = 1.0 + i;
    noise.gyro[i] = {.white_noise = 1e-4 * k,
                     .random_walk = 2e-6 * k,
                     .bias_gm = {3e-5 * k, 100.0 * k},
                     .turn_on_bias_sigma = 4e-4 * k,
                     .scale_factor_sigma = 5e-4 * k,
                     .scale_factor_tau_c_s = 3600.0 * k};
    noise.accel[i] = {.white_noise = 6e-3 * k,
                      .random_walk = 7e-5 * k,
                      .bias_gm = {8e-4 * k, 50.0 * k},
                      .turn_on_bias_sigma = 9e-3 * k,
                      .scale_factor_sigma = 1e-3 * k};  // T_s = ∞: random constant
  }
  const auto model = ins_error_state_model(stationary_nominal(kLat45, 0.0, 0.3), noise,
                                           options_of(BiasModel::both, true));
  const ErrorStateLayout L = error_state_layout(options_of(BiasModel::both, true));
  ASSERT_EQ(model.states(), 27);
  const auto sq = [](double x) { return x * x; };
  for (int i = 0; i < 3; ++i) {
    const SensorAxisNoise &g = noise.gyro[i], &a = noise.accel[i];
    EXPECT_DOUBLE_EQ(model.Qc(L.kGyroWhiteNoise + i, L.kGyroWhiteNoise + i), sq(g.white_noise));
    EXPECT_DOUBLE_EQ(model.Qc(L.kAccelWhiteNoise + i, L.kAccelWhiteNoise + i), sq(a.white_noise));
    EXPECT_DOUBLE_EQ(model.Qc(L.kGyroBiasNoise + i, L.kGyroBiasNoise + i), sq(g.random_walk));
    EXPECT_DOUBLE_EQ(model.Qc(L.kAccelBiasNoise + i, L.kAccelBiasNoise + i), sq(a.random_walk));
    const int gg = *L.gyro_bias_gm_noise + i, ga = *L.accel_bias_gm_noise + i;
    EXPECT_DOUBLE_EQ(model.Qc(gg, gg), 2.0 * sq(g.bias_gm.sigma) / g.bias_gm.tau_c_s);
    EXPECT_DOUBLE_EQ(model.Qc(ga, ga), 2.0 * sq(a.bias_gm.sigma) / a.bias_gm.tau_c_s);
    const int sg = *L.gyro_scale_noise + i, sa = *L.accel_scale_noise + i;
    EXPECT_DOUBLE_EQ(model.Qc(sg, sg), 2.0 * sq(g.scale_factor_sigma) / g.scale_factor_tau_c_s);
    EXPECT_EQ(model.Qc(sa, sa), 0.0);

    // F diagonal of the sensor states: RW 0, GM −1/T_c, random constant 0, GM scale −1/T_s.
    EXPECT_EQ(model.F(L.kGyroBias + i, L.kGyroBias + i), 0.0);
    EXPECT_EQ(model.F(L.kAccelBias + i, L.kAccelBias + i), 0.0);
    EXPECT_DOUBLE_EQ(model.F(*L.gyro_bias_gm + i, *L.gyro_bias_gm + i), -1.0 / g.bias_gm.tau_c_s);
    EXPECT_DOUBLE_EQ(model.F(*L.accel_bias_gm + i, *L.accel_bias_gm + i), -1.0 / a.bias_gm.tau_c_s);
    EXPECT_DOUBLE_EQ(model.F(*L.gyro_scale + i, *L.gyro_scale + i), -1.0 / g.scale_factor_tau_c_s);
    EXPECT_EQ(model.F(*L.accel_scale + i, *L.accel_scale + i), 0.0);

    // P₀: turn-on σ² for RW states, σ² for GM states, σ_s² for scale factors.
    EXPECT_DOUBLE_EQ(model.initial_variance(L.kGyroBias + i), sq(g.turn_on_bias_sigma));
    EXPECT_DOUBLE_EQ(model.initial_variance(L.kAccelBias + i), sq(a.turn_on_bias_sigma));
    EXPECT_DOUBLE_EQ(model.initial_variance(*L.gyro_bias_gm + i), sq(g.bias_gm.sigma));
    EXPECT_DOUBLE_EQ(model.initial_variance(*L.accel_bias_gm + i), sq(a.bias_gm.sigma));
    EXPECT_DOUBLE_EQ(model.initial_variance(*L.gyro_scale + i), sq(g.scale_factor_sigma));
    EXPECT_DOUBLE_EQ(model.initial_variance(*L.accel_scale + i), sq(a.scale_factor_sigma));
  }
  // Q_c is diagonal, P₀ of the navigation errors is 0, and each driving noise reaches only
  // its own state with gain 1.
  EXPECT_EQ((MatrixXd(model.Qc.diagonal().asDiagonal()) - model.Qc).norm(), 0.0);
  EXPECT_EQ(model.initial_variance.head(9).norm(), 0.0);
  const std::vector<std::pair<int, int>> driven = {
      {L.kGyroBias, L.kGyroBiasNoise},          {L.kAccelBias, L.kAccelBiasNoise},
      {*L.gyro_bias_gm, *L.gyro_bias_gm_noise}, {*L.accel_bias_gm, *L.accel_bias_gm_noise},
      {*L.gyro_scale, *L.gyro_scale_noise},     {*L.accel_scale, *L.accel_scale_noise}};
  MatrixXd expected_G = MatrixXd::Zero(18, 18);
  for (const auto& [state, input] : driven)
    expected_G.block(state - 9, input - 6, 3, 3).setIdentity();
  EXPECT_EQ(model.G.bottomRightCorner(18, 18), expected_G);
  EXPECT_EQ(model.G.bottomLeftCorner(18, 6).norm(), 0.0);
  EXPECT_EQ(model.G.topRightCorner(9, 18).norm(), 0.0);
}

TEST(InsErrorStateModel, SingleBiasModesDropTheOtherTerm) {
  SensorAxisNoise axis{.white_noise = 0.0,
                       .random_walk = 2e-6,
                       .bias_gm = {3e-5, 120.0},
                       .turn_on_bias_sigma = 4e-4};
  const InsSensorNoise noise = isotropic(axis, axis);
  const NominalState rest = stationary_nominal(kLat45, 0.0, 0.0);
  const auto rw = ins_error_state_model(rest, noise, options_of(BiasModel::random_walk, false));
  const auto gm = ins_error_state_model(rest, noise, options_of(BiasModel::gauss_markov, false));
  const int b = Layout::kGyroBias, w = Layout::kGyroBiasNoise;
  EXPECT_EQ(rw.F(b, b), 0.0);
  EXPECT_DOUBLE_EQ(rw.Qc(w, w), 4e-12);
  EXPECT_DOUBLE_EQ(rw.initial_variance(b), 1.6e-7);
  EXPECT_DOUBLE_EQ(gm.F(b, b), -1.0 / 120.0);
  EXPECT_DOUBLE_EQ(gm.Qc(w, w), 2.0 * 9e-10 / 120.0);
  EXPECT_DOUBLE_EQ(gm.initial_variance(b), 9e-10);
  // A GM term with σ = 0 (and the default T_c = 0) leaves an inert state.
  const auto none =
      ins_error_state_model(rest, InsSensorNoise{}, options_of(BiasModel::gauss_markov, false));
  EXPECT_EQ(none.F.bottomRightCorner(6, 6).norm(), 0.0);
  EXPECT_EQ(none.Qc.norm(), 0.0);
}

TEST(InsErrorStateModel, SensorErrorsEnterThroughCbn) {
  // Heading 30°: body x points 30° east of north. Independent truth: the NED image of the
  // body axes, and for a y-gyro bias at heading 0 (body y = east) δψ̇_E = +ε (§7.4 sign).
  const double psi = 30.0 * kDeg;
  const NominalState nominal = stationary_nominal(kLat45, 0.0, psi);
  const auto model =
      ins_error_state_model(nominal, InsSensorNoise{}, options_of(BiasModel::both, true));
  const ErrorStateLayout L = error_state_layout(options_of(BiasModel::both, true));
  Matrix3d body_axes_in_ned;
  body_axes_in_ned << std::cos(psi), -std::sin(psi), 0.0, std::sin(psi), std::cos(psi), 0.0, 0.0,
      0.0, 1.0;
  const auto block = [&](int row, int col) { return Matrix3d(model.F.block<3, 3>(row, col)); };
  EXPECT_LT((block(Layout::kAttitude, Layout::kGyroBias) - body_axes_in_ned).norm(), 1e-15);
  EXPECT_LT((block(Layout::kVelocity, Layout::kAccelBias) - body_axes_in_ned).norm(), 1e-15);
  EXPECT_LT((block(Layout::kAttitude, *L.gyro_bias_gm) - body_axes_in_ned).norm(), 1e-15);
  EXPECT_LT((block(Layout::kVelocity, *L.accel_bias_gm) - body_axes_in_ned).norm(), 1e-15);
  EXPECT_LT(
      (MatrixXd(model.G.block<3, 3>(Layout::kAttitude, Layout::kGyroWhiteNoise)) - body_axes_in_ned)
          .norm(),
      1e-15);
  // Scale factors: δω = diag(ω_ib^b) s_g, so C_bn·diag(ω) maps s_g into δψ̇; at rest the
  // NED image is the Earth rate per axis, f^n = −g^n for s_a.
  const Vector3d w_ie = earth_rate_ned(kLat45), g = gravity_ned(kLat45, 0.0);
  EXPECT_LT((block(Layout::kAttitude, *L.gyro_scale) * Vector3d::Ones() - w_ie).norm(), 1e-20);
  EXPECT_LT((block(Layout::kVelocity, *L.accel_scale) * Vector3d::Ones() + g).norm(), 1e-14);

  const auto north = ins_error_state_model(stationary_nominal(kLat45, 0.0, 0.0), InsSensorNoise{},
                                           options_of(BiasModel::random_walk, false));
  EXPECT_EQ(north.F(Layout::kAttitude + 1, Layout::kGyroBias + 1), 1.0);
  // ... and δψ_E drives δv_N = −g δψ_E (f^n = [0, 0, −g]).
  EXPECT_NEAR(north.F(Layout::kVelocity + 0, Layout::kAttitude + 1), -g.z(), 1e-12);
  EXPECT_NEAR(north.F(Layout::kVelocity + 1, Layout::kAttitude + 0), g.z(), 1e-12);
}

/// @name Nonlinear NED mechanization (theory.md §7.2) for the finite-difference check
/// @{
struct FullState {
  Matrix3d C_bn;
  Vector3d v;
  double lat, lon, h;
};
struct FullRate {
  Matrix3d C_dot;
  Vector3d v_dot;
  double lat_dot, lon_dot, h_dot;
};
Matrix3d skew(const Vector3d& a) {
  Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}
FullRate mechanization(const FullState& x, const Vector3d& f_b, const Vector3d& w_b) {
  const Vector3d w_ie = earth_rate_ned(x.lat), w_en = transport_rate_ned(x.lat, x.h, x.v);
  const double rn = meridian_radius(x.lat) + x.h, re = transverse_radius(x.lat) + x.h;
  return {x.C_bn * skew(w_b) - skew(w_ie + w_en) * x.C_bn,
          x.C_bn * f_b + gravity_ned(x.lat, x.h) - (2.0 * w_ie + w_en).cross(x.v), x.v.x() / rn,
          x.v.y() / (re * std::cos(x.lat)), -x.v.z()};
}
/// d/dt of the error state (δψ, δv, δr in metres, theory.md §7.6 definitions) when the
/// navigator sits at TRUTH ⊕ ERROR and is fed the sensor values F_HAT, W_HAT, while the
/// truth moves with F_B, W_B.
Eigen::Matrix<double, 9, 1> error_rate(const FullState& truth, const Eigen::Matrix<double, 9, 1>& e,
                                       const Vector3d& f_b, const Vector3d& w_b,
                                       const Vector3d& f_hat, const Vector3d& w_hat) {
  const auto radius_n = [](double lat) { return meridian_radius(lat); };
  const auto radius_e = [](double lat) { return transverse_radius(lat); };
  const auto d_dlat = [](const auto& fn, double lat) {
    return (fn(lat + 1e-6) - fn(lat - 1e-6)) / 2e-6;
  };
  const double rn = meridian_radius(truth.lat) + truth.h;
  const double re = transverse_radius(truth.lat) + truth.h;
  const double c = std::cos(truth.lat), s = std::sin(truth.lat);
  const Vector3d psi = e.segment<3>(0);
  const double dlat = e(6) / rn, dlon = e(7) / (re * c), dh = -e(8);
  FullState est = truth;
  est.C_bn = Eigen::AngleAxisd(psi.norm(), psi.normalized()).toRotationMatrix() * truth.C_bn;
  est.v = truth.v + e.segment<3>(3);
  est.lat += dlat;
  est.lon += dlon;
  est.h += dh;
  const FullRate rt = mechanization(truth, f_b, w_b), re_ = mechanization(est, f_hat, w_hat);
  Eigen::Matrix<double, 9, 1> out;
  // Ĉ Cᵀ = Exp(δψ): the skew part of its derivative is [δψ̇×] to second order.
  const Matrix3d E_dot = re_.C_dot * truth.C_bn.transpose() + est.C_bn * rt.C_dot.transpose();
  const Matrix3d A = 0.5 * (E_dot - E_dot.transpose());
  out.segment<3>(0) = Vector3d(A(2, 1), A(0, 2), A(1, 0));
  out.segment<3>(3) = re_.v_dot - rt.v_dot;
  // δr_N = (R_N(L)+h)δL and δr_E = (R_E(L)+h)cosL δλ along the moving truth: product rule.
  out(6) = (d_dlat(radius_n, truth.lat) * rt.lat_dot + rt.h_dot) * dlat +
           rn * (re_.lat_dot - rt.lat_dot);
  out(7) =
      ((d_dlat(radius_e, truth.lat) * rt.lat_dot + rt.h_dot) * c - re * s * rt.lat_dot) * dlon +
      re * c * (re_.lon_dot - rt.lon_dot);
  out(8) = -(re_.h_dot - rt.h_dot);
  return out;
}
/// @}

TEST(InsErrorStateModel, FMatchesFiniteDifferencesOfTheMechanization) {
  // A manoeuvring aircraft-like nominal so every velocity term is exercised.
  FullState truth{Matrix3d::Identity(), Vector3d(180.0, -95.0, 12.0), 40.0 * kDeg, 0.2, 1500.0};
  truth.C_bn = (Eigen::AngleAxisd(130.0 * kDeg, Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-5.0 * kDeg, Vector3d::UnitY()) *
                Eigen::AngleAxisd(10.0 * kDeg, Vector3d::UnitX()))
                   .toRotationMatrix();
  const Vector3d f_b =
      truth.C_bn.transpose() * (-gravity_ned(truth.lat, truth.h) + Vector3d(0.8, -0.5, 0.3));
  const Vector3d w_b(0.01, -0.02, 0.03);
  NominalState nominal;
  nominal.latitude_rad = truth.lat;
  nominal.height_m = truth.h;
  nominal.v_ned_m_per_s = truth.v;
  nominal.C_bn = truth.C_bn;
  nominal.f_ib_b_m_per_s2 = f_b;
  nominal.w_ib_b_rad_per_s = w_b;
  const ErrorStateOptions options = options_of(BiasModel::random_walk, true);
  const ErrorStateLayout L = error_state_layout(options);
  const auto model = ins_error_state_model(nominal, InsSensorNoise{}, options);

  // Column j of F by central differences; sensor columns perturb the measured f̃ or ω̃ by
  // measured − true = b (+ diag(·) s), the convention of the header.
  const auto column = [&](int j, double step) {
    Eigen::Matrix<double, 9, 1> plus = Eigen::Matrix<double, 9, 1>::Zero(), minus = plus;
    Vector3d fp = f_b, fm = f_b, wp = w_b, wm = w_b;
    if (j < 9) {
      plus(j) = step;
      minus(j) = -step;
    } else if (j < Layout::kGyroBias) {
      fp(j - Layout::kAccelBias) += step;
      fm(j - Layout::kAccelBias) -= step;
    } else if (j < *L.accel_scale) {
      wp(j - Layout::kGyroBias) += step;
      wm(j - Layout::kGyroBias) -= step;
    } else if (j < *L.gyro_scale) {
      const int i = j - *L.accel_scale;
      fp(i) += f_b(i) * step;
      fm(i) -= f_b(i) * step;
    } else {
      const int i = j - *L.gyro_scale;
      wp(i) += w_b(i) * step;
      wm(i) -= w_b(i) * step;
    }
    return Eigen::Matrix<double, 9, 1>(
        (error_rate(truth, plus, f_b, w_b, fp, wp) - error_rate(truth, minus, f_b, w_b, fm, wm)) /
        (2.0 * step));
  };
  double worst = 0.0;
  for (int j = 0; j < model.states(); ++j) {
    // Steps: 1e-4 rad, 1e-3 m/s, 1 m, 1e-4 m/s², 1e-6 rad/s, 1e-4 scale.
    const double step = j < 3    ? 1e-6
                        : j < 6  ? 1e-3
                        : j < 9  ? 1.0
                        : j < 12 ? 1e-4
                        : j < 15 ? 1e-6
                                 : 1e-4;
    const Eigen::Matrix<double, 9, 1> fd = column(j, step);
    const Eigen::Matrix<double, 9, 1> analytic = model.F.block<9, 1>(0, j);
    for (int i = 0; i < 9; ++i) {
      // Tolerance: 1e-5 relative, plus 1e-6 of the largest entry of the same 3-row block
      // (the rounding floor of the differences, which reaches 3e-12 rad/s on zero entries).
      const double block_max = fd.segment<3>(i / 3 * 3).cwiseAbs().maxCoeff();
      const double err = std::abs(analytic(i) - fd(i));
      EXPECT_LE(err, 1e-5 * std::abs(fd(i)) + 1e-6 * block_max)
          << model.state_names[i] << " / " << model.state_names[j] << ": F = " << analytic(i)
          << ", finite difference " << fd(i);
      if (std::abs(fd(i)) > 1e-6 * block_max) worst = std::max(worst, err / std::abs(fd(i)));
    }
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
}

/// Stationary F at 45° (height hold unless told), no noise.
models::ContinuousStateModel stationary_model(bool height_hold) {
  return ins_error_state_model(stationary_nominal(kLat45, 0.0, 0.0), InsSensorNoise{},
                               options_of(BiasModel::random_walk, false, height_hold));
}

TEST(InsErrorStateModel, SchulerPeriodAt45DegIs84_4Minutes) {
  const auto model = stationary_model(true);
  const Eigen::VectorXcd eig = Eigen::EigenSolver<MatrixXd>(model.F).eigenvalues();
  // The Schuler pair is split by the Foucault rate Ω sinL into ω_s ± Ω sinL (§7.4);
  // the remaining modes are the 24 h Earth-rate mode and zeros.
  std::vector<double> schuler;
  for (const auto& z : eig) {
    EXPECT_LT(std::abs(z.real()), 1e-9) << z;
    if (z.imag() > 1e-4) schuler.push_back(z.imag());
  }
  ASSERT_EQ(schuler.size(), 2u);
  const double mean = 0.5 * (schuler[0] + schuler[1]);
  const double split = 0.5 * std::abs(schuler[0] - schuler[1]);
  const double g = gravity_ned(kLat45, 0.0).z();
  const double R = std::sqrt(meridian_radius(kLat45) * transverse_radius(kLat45));
  const double omega_s = std::sqrt(g / R);
  const double period_min = 2.0 * std::numbers::pi / mean / 60.0;
  EXPECT_NEAR(mean / omega_s, 1.0, 0.005);
  EXPECT_NEAR(period_min, 84.4, 0.1);  // theory.md §7.4 (V)
  EXPECT_NEAR(split / (wgs84::kEarthRate * std::sin(kLat45)), 1.0, 0.05);
  RecordProperty("schuler_period_min", std::to_string(period_min));
  RecordProperty("schuler_expected_period_min",
                 std::to_string(2.0 * std::numbers::pi / omega_s / 60.0));
  RecordProperty("foucault_split_rad_per_s", std::to_string(split));
}

TEST(InsErrorStateModel, WithoutEarthRateOnlySchulerCouplingRemains) {
  // earth_rate = false (theory.md §8.4 "Earth-rate and Coriolis coupling neglected"): at rest
  // δψ̇ = F₁₂δv and δv̇ = −f^n×δψ + δg; the −[ω_ie×] attitude block, the −2[ω_ie×] Coriolis
  // block and ∂ω_ie/∂L are gone, the Foucault split vanishes and ±iω_s remains.
  auto options = options_of(BiasModel::random_walk, false, true);
  options.earth_rate = false;
  const NominalState rest = stationary_nominal(kLat45, 0.0, 0.0);
  const MatrixXd F_off = ins_error_state_model(rest, InsSensorNoise{}, options).F;
  options.earth_rate = true;
  const MatrixXd F_on = ins_error_state_model(rest, InsSensorNoise{}, options).F;
  const Vector3d w_ie = earth_rate_ned(kLat45);
  const auto skew = [](const Vector3d& a) {
    Matrix3d m;
    m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
    return m;
  };
  MatrixXd expected_difference = MatrixXd::Zero(F_on.rows(), F_on.cols());
  expected_difference.block<3, 3>(Layout::kAttitude, Layout::kAttitude) = -skew(w_ie);
  expected_difference.block<3, 3>(Layout::kVelocity, Layout::kVelocity) = -2.0 * skew(w_ie);
  expected_difference.row(Layout::kVelocity + 2).setZero();  // height hold
  // −∂ω_ie/∂L / (R_N + h) in the δψ/δr_N column.
  expected_difference.block<3, 1>(Layout::kAttitude, Layout::kPosition) =
      wgs84::kEarthRate * Vector3d(std::sin(kLat45), 0.0, std::cos(kLat45)) /
      meridian_radius(kLat45);
  EXPECT_LT((F_on - F_off - expected_difference).cwiseAbs().maxCoeff(), 1e-18);
  const Eigen::VectorXcd eig = Eigen::EigenSolver<MatrixXd>(F_off).eigenvalues();
  const double omega_s = std::sqrt(gravity_ned(kLat45, 0.0).z() /
                                   std::sqrt(meridian_radius(kLat45) * transverse_radius(kLat45)));
  int schuler = 0;
  for (const auto& z : eig) {
    EXPECT_LT(std::abs(z.real()), 1e-9) << z;
    if (z.imag() > 1e-4) {
      ++schuler;
      EXPECT_NEAR(z.imag() / omega_s, 1.0, 0.005) << z;
    }
  }
  EXPECT_EQ(schuler, 2);  // the N and E channels, now at the same frequency
}

TEST(InsErrorStateModel, VerticalChannelDivergesWithoutHeightHold) {
  // Free: one real eigenvalue ≈ +√(2g/R), e-folding ≈ 570 s (theory.md §7.2). Held: none.
  const Eigen::VectorXcd free =
      Eigen::EigenSolver<MatrixXd>(stationary_model(false).F).eigenvalues();
  const Eigen::VectorXcd held =
      Eigen::EigenSolver<MatrixXd>(stationary_model(true).F).eigenvalues();
  double largest_free = 0.0, largest_held = 0.0;
  for (const auto& z : free) largest_free = std::max(largest_free, z.real());
  for (const auto& z : held) largest_held = std::max(largest_held, z.real());
  const double R = std::sqrt(meridian_radius(kLat45) * transverse_radius(kLat45));
  EXPECT_NEAR(largest_free / std::sqrt(2.0 * gravity_ned(kLat45, 0.0).z() / R), 1.0, 0.005);
  EXPECT_NEAR(1.0 / largest_free, 570.0, 5.0);
  EXPECT_LT(largest_held, 1e-9);
  const auto held_model = stationary_model(true);
  for (const int row : {Layout::kVelocity + 2, Layout::kPosition + 2}) {
    EXPECT_EQ(held_model.F.row(row).norm(), 0.0);
    EXPECT_EQ(held_model.G.row(row).norm(), 0.0);
  }
}

/// @name Stationary closed forms, theory.md §7.5, short-time limits at t = 60 s
/// @{
struct ClosedFormCase {
  const char* name;
  std::function<void(SensorAxisNoise& gyro, SensorAxisNoise& accel)> set;
  std::function<double(double t, double g)> expected_north_sigma_m;
};

TEST(InsErrorStateModel, NorthPositionSigmaMatchesShortTimeClosedForms) {
  // One source at a time on all three axes (the north channel is driven by gyro y and
  // accel x at heading 0); height hold, L = 45°, 60 steps of 1 s.
  constexpr double kB = 1e-3;                           // accel bias σ [m/s²] (≈ 100 µg)
  constexpr double kEps = 10.0 * units::kDegPerHour;    // gyro bias σ [rad/s]
  constexpr double kNg = 0.2 * units::kDegPerSqrtHour;  // ARW [rad/√s]
  constexpr double kNa = 1e-3;                          // VRW [m/s/√s]
  constexpr double kKa = 1e-4;                          // accel RW [m/s^{5/2}]
  constexpr double kKg = 1e-5;                          // gyro RW [rad/s^{3/2}]
  const std::vector<ClosedFormCase> cases = {
      {"accel_bias", [](auto&, auto& a) { a.turn_on_bias_sigma = kB; },
       [](double t, double) { return kB * t * t / 2.0; }},
      {"gyro_bias", [](auto& g, auto&) { g.turn_on_bias_sigma = kEps; },
       [](double t, double g) { return g * kEps * t * t * t / 6.0; }},
      {"arw", [](auto& g, auto&) { g.white_noise = kNg; },
       [](double t, double g) { return g * kNg * std::pow(t, 2.5) / std::sqrt(20.0); }},
      {"vrw", [](auto&, auto& a) { a.white_noise = kNa; },
       [](double t, double) { return kNa * std::pow(t, 1.5) / std::sqrt(3.0); }},
      {"accel_rw", [](auto&, auto& a) { a.random_walk = kKa; },
       [](double t, double) { return kKa * std::pow(t, 2.5) / std::sqrt(20.0); }},
      {"gyro_rw", [](auto& g, auto&) { g.random_walk = kKg; },
       [](double t, double g) { return g * kKg * std::pow(t, 3.5) / std::sqrt(252.0); }},
  };
  const double t = 60.0, g = gravity_ned(kLat45, 0.0).z();
  const int north = Layout::kPosition;
  for (const ClosedFormCase& c : cases) {
    SensorAxisNoise gyro, accel;
    c.set(gyro, accel);
    const auto model =
        ins_error_state_model(stationary_nominal(kLat45, 0.0, 0.0), isotropic(gyro, accel),
                              options_of(BiasModel::random_walk, false, true));
    const MatrixXd P = propagate_covariance(model, 1.0, 60);
    const double sigma = std::sqrt(P(north, north)), expected = c.expected_north_sigma_m(t, g);
    EXPECT_NEAR(sigma / expected, 1.0, 0.01) << c.name << ": " << sigma << " m vs " << expected;
    EXPECT_NEAR(P(north, north), P(north + 1, north + 1), 0.01 * P(north, north)) << c.name;
    RecordProperty(std::string(c.name) + "_north_sigma_m", std::to_string(sigma));
    RecordProperty(std::string(c.name) + "_expected_m", std::to_string(expected));
    RecordProperty(std::string(c.name) + "_difference_percent",
                   std::to_string(100.0 * (sigma / expected - 1.0)));
  }
}
/// @}

TEST(InsErrorStateModel, BiasesFollowSchulerFormsAtHalfPeriod) {
  // At t = π/ω_s (≈ 42.2 min), theory.md §7.5: accel bias (b/ω_s²)(1 − cos ω_s t) = 2b/ω_s²;
  // gyro bias R ε (t − sin(ω_s t)/ω_s) = R ε t. Isotropic biases, so the Foucault rotation
  // (Ω sinL t ≈ 0.13 rad here) moves error between the channels without changing the sum.
  constexpr double kB = 1e-3;                         // accel bias σ [m/s²]
  constexpr double kEps = 10.0 * units::kDegPerHour;  // gyro bias σ [rad/s]
  const double g = gravity_ned(kLat45, 0.0).z();
  const double R = std::sqrt(meridian_radius(kLat45) * transverse_radius(kLat45));
  const double omega_s = std::sqrt(g / R), t = std::numbers::pi / omega_s;
  EXPECT_NEAR(t / 60.0, 42.2, 0.05);
  const int steps = 2532;  // ≈ 1 s steps
  SensorAxisNoise gyro, accel;
  gyro.turn_on_bias_sigma = kEps;
  accel.turn_on_bias_sigma = kB;
  const struct {
    const char* name;
    InsSensorNoise noise;
    double expected_m;
  } cases[] = {
      {"accel_bias", isotropic(SensorAxisNoise{}, accel),
       kB / (omega_s * omega_s) * (1.0 - std::cos(omega_s * t))},
      {"gyro_bias", isotropic(gyro, SensorAxisNoise{}),
       R * kEps * (t - std::sin(omega_s * t) / omega_s)},
  };
  for (const auto& c : cases) {
    const auto model = ins_error_state_model(stationary_nominal(kLat45, 0.0, 0.0), c.noise,
                                             options_of(BiasModel::random_walk, false, true));
    const MatrixXd P = propagate_covariance(model, t / steps, steps);
    const double sigma = std::sqrt(P(Layout::kPosition, Layout::kPosition));
    EXPECT_NEAR(sigma / c.expected_m, 1.0, 0.01)
        << c.name << ": " << sigma << " m vs " << c.expected_m << " m";
    const std::string key = std::string("half_period_") + c.name;
    RecordProperty(key + "_north_sigma_m", std::to_string(sigma));
    RecordProperty(key + "_expected_m", std::to_string(c.expected_m));
    RecordProperty(key + "_difference_percent",
                   std::to_string(100.0 * (sigma / c.expected_m - 1.0)));
  }
}

TEST(InsErrorStateModel, LevelImuAtRestWithoutNoiseStaysExact) {
  for (const bool scale : {false, true}) {
    const auto model = ins_error_state_model(stationary_nominal(kLat45, 120.0, 0.7),
                                             InsSensorNoise{}, options_of(BiasModel::both, scale));
    const models::DiscreteStateModel d = models::discretize(model, 1.0);
    EXPECT_EQ(d.Qd.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(propagate_covariance(model, 1.0, 600).cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(InsErrorStateModel, RejectsBadInput) {
  const NominalState rest = stationary_nominal(kLat45, 0.0, 0.0);
  const ErrorStateOptions options;
  NominalState skewed = rest;
  skewed.C_bn(0, 1) = 0.1;
  test::expect_throw_containing<InputError>(
      [&] { ins_error_state_model(skewed, InsSensorNoise{}, options); }, "must be a rotation");
  NominalState mirrored = rest;
  mirrored.C_bn(2, 2) = -1.0;
  test::expect_throw_containing<InputError>(
      [&] { ins_error_state_model(mirrored, InsSensorNoise{}, options); }, "det");
  NominalState polar = rest;
  polar.latitude_rad = std::numbers::pi / 2.0;
  test::expect_throw_containing<InputError>(
      [&] { ins_error_state_model(polar, InsSensorNoise{}, options); }, "nominal latitude");
  NominalState nan_velocity = rest;
  nan_velocity.v_ned_m_per_s.x() = std::numeric_limits<double>::quiet_NaN();
  test::expect_throw_containing<InputError>(
      [&] { ins_error_state_model(nan_velocity, InsSensorNoise{}, options); }, "must be finite");

  InsSensorNoise negative;
  negative.accel[1].white_noise = -1.0;
  test::expect_throw_containing<InputError>([&] { ins_error_state_model(rest, negative, options); },
                                            "accel[y].white_noise");
  InsSensorNoise no_tau;
  no_tau.gyro[2].bias_gm.sigma = 1e-5;
  test::expect_throw_containing<InputError>([&] { ins_error_state_model(rest, no_tau, options); },
                                            "gyro[z].bias_gm.tau_c_s");
  InsSensorNoise zero_scale_tau;
  zero_scale_tau.gyro[0].scale_factor_tau_c_s = 0.0;
  test::expect_throw_containing<InputError>(
      [&] { ins_error_state_model(rest, zero_scale_tau, options); },
      "gyro[x].scale_factor_tau_c_s");
  test::expect_throw_containing<InputError>(
      [] { stationary_nominal(0.1, 0.0, std::numeric_limits<double>::infinity()); }, "heading");
}

TEST(InsErrorStateModel, GmTermsAndRampsAreAppendedAxisStates) {
  // gyro y: two GM terms (one with σ = 0: no state) and a ramp; accel z: one GM term. The
  // blocks of the base layout keep their offsets; the new states follow, gyro before accel.
  InsSensorNoise noise;
  noise.gyro[1].gm_terms = {{3e-5, 20.0}, {0.0, 5.0}, {2e-5, 2000.0}};
  noise.gyro[1].ramp = 1e-8;
  noise.accel[2].gm_terms = {{4e-4, 60.0}};
  const ErrorStateOptions options = options_of(BiasModel::both, false);
  const ErrorStateLayout base = error_state_layout(options);
  const ErrorStateLayout L = error_state_layout(options, noise);
  EXPECT_EQ(L.accel_bias_gm, base.accel_bias_gm);
  EXPECT_EQ(L.gyro_bias_gm_noise, base.gyro_bias_gm_noise);
  ASSERT_EQ(L.axis_states.size(), 4u);
  EXPECT_EQ(L.states, base.states + 4);
  EXPECT_EQ(L.noises, L.states - 3);
  const NominalState nominal = stationary_nominal(kLat45, 0.0, 0.4);
  const auto model = ins_error_state_model(nominal, noise, options);
  ASSERT_EQ(model.states(), L.states);
  const std::array<std::pair<int, double>, 2> gyro_terms{{{0, 20.0}, {2, 2000.0}}};
  for (std::size_t k = 0; k < 2; ++k) {
    const AxisState& x = L.axis_states[k];
    EXPECT_EQ(x.kind, AxisState::Kind::gm_term);
    EXPECT_TRUE(x.gyro);
    EXPECT_EQ(x.axis, 1);
    EXPECT_EQ(x.term, gyro_terms[k].first);
    const double sigma = noise.gyro[1].gm_terms[static_cast<std::size_t>(x.term)].sigma;
    const double tc = gyro_terms[k].second;
    EXPECT_DOUBLE_EQ(model.F(x.state, x.state), -1.0 / tc);
    EXPECT_DOUBLE_EQ(model.Qc(x.noise, x.noise), 2.0 * sigma * sigma / tc);
    EXPECT_DOUBLE_EQ(model.initial_variance(x.state), sigma * sigma);
    EXPECT_EQ(model.G(x.state, x.noise), 1.0);
    // δψ̇ += C_bn b: the column of body y in NED.
    const Eigen::Vector3d coupling = model.F.block<3, 1>(ErrorStateLayout::kAttitude, x.state);
    EXPECT_TRUE(coupling.isApprox(nominal.C_bn.col(1), 1e-15));
  }
  const AxisState& ramp = L.axis_states[2];
  EXPECT_EQ(ramp.kind, AxisState::Kind::ramp_slope);
  EXPECT_EQ(model.F(ErrorStateLayout::kGyroBias + 1, ramp.state), 1.0);  // ḃ_RW += s
  EXPECT_EQ(model.F.col(ramp.state).sum(), 1.0);
  EXPECT_EQ(model.Qc(ramp.noise, ramp.noise), 0.0);
  EXPECT_DOUBLE_EQ(model.initial_variance(ramp.state), 1e-16);
  const AxisState& accel = L.axis_states[3];
  EXPECT_FALSE(accel.gyro);
  EXPECT_EQ(accel.axis, 2);
  const Eigen::Vector3d coupling = model.F.block<3, 1>(ErrorStateLayout::kVelocity, accel.state);
  EXPECT_TRUE(coupling.isApprox(nominal.C_bn.col(2), 1e-15));
  // gauss_markov mode: no RW state to integrate a slope, so no ramp state.
  EXPECT_EQ(
      error_state_layout(options_of(BiasModel::gauss_markov, false), noise).axis_states.size(), 3u);
  // A bad term names its field.
  InsSensorNoise bad;
  bad.accel[0].gm_terms = {{1e-4, 0.0}};
  test::expect_throw_containing<InputError>([&] { ins_error_state_model(nominal, bad, options); },
                                            "accel[x].gm_terms[0].tau_c_s");
}

}  // namespace
}  // namespace imunoise::ins
