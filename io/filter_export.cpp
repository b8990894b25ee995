#include "io/filter_export.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <sstream>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/sensor_kind.h"
#include "common/units.h"
#include "io/filter_export_internal.h"
#include "io/noise_model_yaml.h"

namespace imunoise::io {
namespace {

using detail::bracketed;
using detail::Config;
using detail::kMilliGal;
using detail::need;
using detail::per_sample;
using detail::real;
using detail::rw_only;
using detail::RwOnly;
using detail::Slot;
using detail::triple;
using models::FilterParameters;
using models::SensorAxisParameters;
using models::SensorParameters;

struct FormatInfo {
  ExportFormat format;
  const char* name;
  const char* file_name;
  const char* consumer;
};
constexpr std::array<FormatInfo, 18> kFormats{{
    {ExportFormat::native, "native", "model.yaml", "imunoise native model.yaml"},
    {ExportFormat::kalibr, "kalibr", "kalibr_imu.yaml", "Kalibr (imu.yaml)"},
    {ExportFormat::openvins, "openvins", "kalibr_imu_chain.yaml",
     "OpenVINS (kalibr_imu_chain.yaml)"},
    {ExportFormat::vins, "vins", "vins_imu.yaml", "VINS-Mono / VINS-Fusion (IMU keys)"},
    {ExportFormat::orbslam3, "orbslam3", "orbslam3_imu.yaml", "ORB-SLAM3 (settings, IMU keys)"},
    {ExportFormat::okvis, "okvis", "okvis_imu.yaml", "OKVIS (imu_params block)"},
    {ExportFormat::kf_gins, "kf-gins", "kf-gins_imunoise.yaml", "KF-GINS (imunoise block)"},
    {ExportFormat::gnss_ins_sim, "gnss-ins-sim", "gnss_ins_sim_imu.py",
     "gnss-ins-sim (imu_err dict)"},
    {ExportFormat::matlab, "matlab", "imu_params.m", "MATLAB imuSensor (gyroparams, accelparams)"},
    {ExportFormat::px4, "px4", "px4_ekf2.params", "PX4 EKF2 (QGroundControl parameter file)"},
    {ExportFormat::robot_localization, "robot_localization", "robot_localization_ekf.yaml",
     "robot_localization (ekf.yaml)"},
    {ExportFormat::lio_sam, "lio-sam", "lio_sam_params.yaml", "LIO-SAM (config/params.yaml)"},
    {ExportFormat::fast_lio, "fast-lio", "fast_lio_mapping.yaml",
     "FAST-LIO / FAST-LIO2 (config/*.yaml mapping block)"},
    {ExportFormat::basalt, "basalt", "basalt_imu_calib.json", "Basalt (calibration JSON)"},
    {ExportFormat::gtsam, "gtsam", "gtsam_preintegration.yaml",
     "GTSAM PreintegrationCombinedParams"},
    {ExportFormat::ardupilot, "ardupilot", "ardupilot_ekf3.parm", "ArduPilot EKF3 (.parm)"},
    {ExportFormat::kimera, "kimera", "kimera_ImuParams.yaml", "Kimera-VIO (ImuParams.yaml)"},
    {ExportFormat::imu_utils, "imu_utils", "imu_utils_imu_param.yaml",
     "imu_utils (<name>_imu_param.yaml)"},
}};

const FormatInfo& info(ExportFormat format) {
  for (const auto& f : kFormats)
    if (f.format == format) return f;
  return kFormats[0];
}

std::string kalibr_like(const models::NoiseModel& model, const ExportRequest& request,
                        const FilterParameters& p, double rate, bool openvins) {
  Config c("#", model, request, rate);
  c.rules(p);
  const auto v = rw_only(p, c, request.format, request.parameters.conservative);
  if (!openvins) {
    // Kalibr's ImuParameters rejects a zero density or random walk.
    for (const auto& [value, what] :
         {std::pair{v.n_a, "accelerometer_noise_density"},
          std::pair{v.k_a, "accelerometer_random_walk"},
          std::pair{v.n_g, "gyroscope_noise_density"}, std::pair{v.k_g, "gyroscope_random_walk"}})
      if (!(value > 0.0))
        throw InputError(
            std::string("kalibr: ") + what +
            " would be 0 (the model has neither a value nor an upper bound for it) and "
            "Kalibr requires > 0");
  }
  const std::string n = request.parameters.conservative ? "N'" : "N";
  const std::string k = request.parameters.conservative ? "K'" : "K";
  c.conversion("accelerometer_noise_density", n + "_a", v.n_a, "m/s^2/sqrt(Hz)");
  c.conversion("accelerometer_random_walk", k + "_a", v.k_a, "m/s^3/sqrt(Hz)");
  c.conversion("gyroscope_noise_density", n + "_g", v.n_g, "rad/s/sqrt(Hz)");
  c.conversion("gyroscope_random_walk", k + "_g", v.k_g, "rad/s^2/sqrt(Hz)");
  c.line("discrete equivalents at this rate (what Kalibr prints): sigma_d = N*sqrt(rate): gyro " +
         real(v.n_g * std::sqrt(rate)) + " rad/s, accel " + real(v.n_a * std::sqrt(rate)) +
         " m/s^2; sigma_bd = K/sqrt(rate): gyro " + real(v.k_g / std::sqrt(rate)) +
         " rad/s, accel " + real(v.k_a / std::sqrt(rate)) + " m/s^2");
  auto& b = c.body();
  const std::string indent = openvins ? "  " : "";
  if (openvins) {
    c.line("extrinsics and intrinsics below are identity: imunoise does not estimate them");
    b << "\nimu0:\n";
    b << "  T_i_b:\n";
    for (int r = 0; r < 4; ++r) {
      b << "    - [";
      for (int col = 0; col < 4; ++col) b << (col ? ", " : "") << (r == col ? "1.0" : "0.0");
      b << "]\n";
    }
  } else {
    b << "\n";
  }
  b << indent << "accelerometer_noise_density: " << real(v.n_a) << "  # [m/s^2/sqrt(Hz)]\n";
  b << indent << "accelerometer_random_walk: " << real(v.k_a) << "  # [m/s^3/sqrt(Hz)]\n";
  b << indent << "gyroscope_noise_density: " << real(v.n_g) << "  # [rad/s/sqrt(Hz)]\n";
  b << indent << "gyroscope_random_walk: " << real(v.k_g) << "  # [rad/s^2/sqrt(Hz)]\n";
  b << indent << "rostopic: /imu0\n";
  if (openvins) b << indent << "time_offset: 0.0\n";
  b << indent << "update_rate: " << real(rate) << "  # [Hz]\n";
  if (openvins) {
    b << indent << "model: \"kalibr\"\n";
    const auto matrix = [&](const char* key, bool identity) {
      b << indent << key << ":\n";
      for (int r = 0; r < 3; ++r) {
        b << indent << "  - [";
        for (int col = 0; col < 3; ++col)
          b << (col ? ", " : "") << (identity && r == col ? "1.0" : "0.0");
        b << "]\n";
      }
    };
    matrix("Tw", true);
    matrix("R_IMUtoGYRO", true);
    matrix("Ta", true);
    matrix("R_IMUtoACC", true);
    matrix("Tg", false);
  }
  return c.text(openvins ? "%YAML:1.0" : "");
}

std::string vins(const models::NoiseModel& model, const ExportRequest& request,
                 const FilterParameters& p, double rate) {
  Config c("#", model, request, rate);
  c.rules(p);
  const auto v = rw_only(p, c, request.format, request.parameters.conservative);
  c.line(
      "VINS uses these as discrete per-sample sigmas (integration_base.h multiplies the "
      "noise by dt): acc_n = N*sqrt(rate), acc_w = K*sqrt(rate)");
  const auto d = per_sample(
      c, v, rate,
      {{"acc_n", Slot::n_a}, {"gyr_n", Slot::n_g}, {"acc_w", Slot::k_a}, {"gyr_w", Slot::k_g}});
  c.line(
      "g_norm is standard gravity; put your local gravity there. VINS-Fusion reads these "
      "keys only with imu: 1, and a missing key silently becomes 0");
  auto& b = c.body();
  b << "\n";
  b << "acc_n: " << real(d.n_a) << "  # accelerometer measurement noise sigma [m/s^2]\n";
  b << "gyr_n: " << real(d.n_g) << "  # gyroscope measurement noise sigma [rad/s]\n";
  b << "acc_w: " << real(d.k_a) << "  # accelerometer bias random walk sigma [m/s^3]\n";
  b << "gyr_w: " << real(d.k_g) << "  # gyroscope bias random walk sigma [rad/s^2]\n";
  b << "g_norm: " << real(units::kStandardGravity) << "  # [m/s^2]\n";
  return c.text("%YAML:1.0");
}

std::string orbslam3(const models::NoiseModel& model, const ExportRequest& request,
                     const FilterParameters& p, double rate) {
  Config c("#", model, request, rate);
  c.rules(p);
  const auto v = rw_only(p, c, request.format, request.parameters.conservative);
  c.line("ORB-SLAM3 reads continuous densities and discretizes with sqrt(IMU.Frequency)");
  c.line(
      "IMU.Frequency is written as a real, as the v1.0 settings (File.version: \"1.0\") "
      "require; a legacy settings file without File.version needs an integer there");
  c.conversion("IMU.NoiseGyro", "N_g", v.n_g, "rad/s/sqrt(Hz)");
  c.conversion("IMU.NoiseAcc", "N_a", v.n_a, "m/s^2/sqrt(Hz)");
  c.conversion("IMU.GyroWalk", "K_g", v.k_g, "rad/s^2/sqrt(Hz)");
  c.conversion("IMU.AccWalk", "K_a", v.k_a, "m/s^3/sqrt(Hz)");
  auto& b = c.body();
  b << "\n";
  b << "IMU.NoiseGyro: " << real(v.n_g) << "  # [rad/s/sqrt(Hz)]\n";
  b << "IMU.NoiseAcc: " << real(v.n_a) << "  # [m/s^2/sqrt(Hz)]\n";
  b << "IMU.GyroWalk: " << real(v.k_g) << "  # [rad/s^2/sqrt(Hz)]\n";
  b << "IMU.AccWalk: " << real(v.k_a) << "  # [m/s^3/sqrt(Hz)]\n";
  b << "IMU.Frequency: " << real(rate) << "  # [Hz]\n";
  return c.text("%YAML:1.0");
}

std::string okvis(const models::NoiseModel& model, const ExportRequest& request,
                  const FilterParameters& p, double rate) {
  Config c("#", model, request, rate);
  c.rules(p);
  const auto v = rw_only(p, c, request.format, request.parameters.conservative);
  c.conversion("sigma_g_c", "N_g", v.n_g, "rad/s/sqrt(Hz)");
  c.conversion("sigma_a_c", "N_a", v.n_a, "m/s^2/sqrt(Hz)");
  c.conversion("sigma_gw_c", "K_g", v.k_g, "rad/s^2/sqrt(Hz)");
  c.conversion("sigma_aw_c", "K_a", v.k_a, "m/s^3/sqrt(Hz)");
  c.line(
      "a_max, g_max, sigma_bg, sigma_ba, tau, g, a0, T_BS are not noise-model values: they "
      "keep OKVIS's example values here; set them from your datasheet and calibration");
  auto& b = c.body();
  b << "\nimu_params:\n";
  b << "  a_max: 176.0  # acceleration saturation [m/s^2] (not from the noise model)\n";
  b << "  g_max: 7.8  # gyro saturation [rad/s] (not from the noise model)\n";
  b << "  sigma_g_c: " << real(v.n_g) << "  # gyro noise density [rad/s/sqrt(Hz)]\n";
  b << "  sigma_a_c: " << real(v.n_a) << "  # accelerometer noise density [m/s^2/sqrt(Hz)]\n";
  b << "  sigma_bg: 0.03  # gyro bias prior [rad/s] (turn-on bias: AVAR cannot see it)\n";
  b << "  sigma_ba: 0.1  # accelerometer bias prior [m/s^2] (turn-on bias: AVAR cannot see it)\n";
  b << "  sigma_gw_c: " << real(v.k_g) << "  # gyro drift noise density [rad/s^2/sqrt(Hz)]\n";
  b << "  sigma_aw_c: " << real(v.k_a)
    << "  # accelerometer drift noise density [m/s^3/sqrt(Hz)]\n";
  b << "  tau: 3600.0  # accelerometer bias reversion time [s] (not from the noise model)\n";
  b << "  g: " << real(units::kStandardGravity) << "  # gravity [m/s^2]: put your local value\n";
  b << "  a0: [ 0.0, 0.0, 0.0 ]  # accelerometer bias [m/s^2]\n";
  // VioParametersReader asserts imu_rate is an integer (and the others reals).
  b << "  imu_rate: " << static_cast<long long>(std::lround(rate)) << "  # [Hz], an integer\n";
  b << "  T_BS: [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, "
       "1.0]  # row-major 4x4, identity\n";
  return c.text("%YAML:1.0");
}

/// The GM-bias line shared by KF-GINS and gnss-ins-sim.
void gm_lines(Config& c, const SensorParameters& g, const SensorParameters& a, bool conservative) {
  c.line(
      "bias: one first-order Gauss-Markov term per axis (sigma, T_c); the random walk K and "
      "the ramp R have no slot in this format and are dropped");
  if (conservative)
    c.line(
        "  conservative: sigma from the upper bound of B; K is NOT overbounded (a GM cannot "
        "bound a random walk at long tau)");
  std::string previous;
  for (int i = 0; i < 3; ++i) {
    if (g.axes[i].random_walk > 0.0 || a.axes[i].random_walk > 0.0) {
      const std::string text = "  dropped K: gyro " + real(g.axes[i].random_walk) +
                               " rad/s^1.5, accel " + real(a.axes[i].random_walk) + " m/s^2.5";
      if (text != previous) c.line(text + (i > 0 ? " (axis " + std::to_string(i) + ")" : ""));
      previous = text;
    }
  }
}

std::string kf_gins(const models::NoiseModel& model, const ExportRequest& request,
                    const FilterParameters& p, double rate) {
  const auto& g = need(p.gyro, SensorKind::gyro, request.format);
  const auto& a = need(p.accel, SensorKind::accel, request.format);
  Config c("#", model, request, rate);
  c.rules(p);
  gm_lines(c, g, a, request.parameters.conservative);
  const double corr_s = g.one().bias_gm.tau_c_s;
  c.line(
      "KF-GINS has one corrtime for all bias and scale-factor states: the gyro's T_c (gyro "
      "terms dominate the drift, theory.md §8.5); accel T_c = " +
      real(a.one().bias_gm.tau_c_s) + " s");
  c.line(
      "gsstd/asstd (scale factors) are not observable from a stationary recording "
      "(theory.md §6.3): 0 here, set them from the datasheet");
  for (int i = 0; i < 3; ++i) {
    const std::string s = bracketed(i, '[', ']');
    c.conversion("arw" + s, "N_g*(180/pi)*60", g.axes[i].white_noise / units::kDegPerSqrtHour,
                 "deg/sqrt(h)");
    c.conversion("vrw" + s, "N_a*60", a.axes[i].white_noise / units::kMPerSPerSqrtHour,
                 "m/s/sqrt(h)");
    c.conversion("gbstd" + s, "sigma_GM,g*(180/pi)*3600",
                 g.axes[i].bias_gm.sigma / units::kDegPerHour, "deg/h");
    c.conversion("abstd" + s, "sigma_GM,a/1e-5", a.axes[i].bias_gm.sigma / kMilliGal, "mGal");
  }
  c.conversion("corrtime", "T_c,g/3600", corr_s / 3600.0, "h");
  auto& b = c.body();
  b << "\nimunoise:\n";
  b << "  arw: [" << triple(g, &SensorAxisParameters::white_noise, units::kDegPerSqrtHour)
    << "]  # [deg/sqrt(h)]\n";
  b << "  vrw: [" << triple(a, &SensorAxisParameters::white_noise, units::kMPerSPerSqrtHour)
    << "]  # [m/s/sqrt(h)]\n";
  b << "  gbstd: [" << real(g.axes[0].bias_gm.sigma / units::kDegPerHour) << ", "
    << real(g.axes[1].bias_gm.sigma / units::kDegPerHour) << ", "
    << real(g.axes[2].bias_gm.sigma / units::kDegPerHour) << "]  # [deg/h]\n";
  b << "  abstd: [" << real(a.axes[0].bias_gm.sigma / kMilliGal) << ", "
    << real(a.axes[1].bias_gm.sigma / kMilliGal) << ", "
    << real(a.axes[2].bias_gm.sigma / kMilliGal) << "]  # [mGal]\n";
  b << "  gsstd: [0.0, 0.0, 0.0]  # [ppm] not estimated\n";
  b << "  asstd: [0.0, 0.0, 0.0]  # [ppm] not estimated\n";
  b << "  corrtime: " << real(corr_s / 3600.0) << "  # [h]\n";
  return c.text();
}

std::string gnss_ins_sim(const models::NoiseModel& model, const ExportRequest& request,
                         const FilterParameters& p, double rate) {
  const auto& g = need(p.gyro, SensorKind::gyro, request.format);
  const auto& a = need(p.accel, SensorKind::accel, request.format);
  Config c("#", model, request, rate);
  c.rules(p);
  gm_lines(c, g, a, request.parameters.conservative);
  c.line("gyro_b / accel_b (turn-on bias) are 0: a noise analysis cannot see constant offsets");
  for (int i = 0; i < 3; ++i) {
    const std::string s = bracketed(i, '[', ']');
    c.conversion("gyro_arw" + s, "N_g*(180/pi)*60", g.axes[i].white_noise / units::kDegPerSqrtHour,
                 "deg/sqrt(h)");
    c.conversion("gyro_b_stability" + s, "sigma_GM,g*(180/pi)*3600",
                 g.axes[i].bias_gm.sigma / units::kDegPerHour, "deg/h");
    c.conversion("gyro_b_corr" + s, "T_c,g", g.axes[i].bias_gm.tau_c_s, "s");
    c.conversion("accel_vrw" + s, "N_a*60", a.axes[i].white_noise / units::kMPerSPerSqrtHour,
                 "m/s/sqrt(h)");
    c.conversion("accel_b_stability" + s, "sigma_GM,a", a.axes[i].bias_gm.sigma, "m/s^2");
    c.conversion("accel_b_corr" + s, "T_c,a", a.axes[i].bias_gm.tau_c_s, "s");
  }
  auto& b = c.body();
  const auto arr = [&](const std::string& inner) { return "np.array([" + inner + "])"; };
  const auto gm = [&](const SensorParameters& s, bool sigma, double scale) {
    std::string out;
    for (int i = 0; i < 3; ++i)
      out += (i ? ", " : "") +
             real((sigma ? s.axes[i].bias_gm.sigma : s.axes[i].bias_gm.tau_c_s) / scale);
    return out;
  };
  b << "\nimport numpy as np\n\n";
  b << "imu_err = {\n";
  b << "    'gyro_b': " << arr("0.0, 0.0, 0.0") << ",  # [deg/h]\n";
  b << "    'gyro_arw': "
    << arr(triple(g, &SensorAxisParameters::white_noise, units::kDegPerSqrtHour))
    << ",  # [deg/sqrt(h)]\n";
  b << "    'gyro_b_stability': " << arr(gm(g, true, units::kDegPerHour)) << ",  # [deg/h]\n";
  b << "    'gyro_b_corr': " << arr(gm(g, false, 1.0)) << ",  # [s]\n";
  b << "    'accel_b': " << arr("0.0, 0.0, 0.0") << ",  # [m/s^2]\n";
  b << "    'accel_vrw': "
    << arr(triple(a, &SensorAxisParameters::white_noise, units::kMPerSPerSqrtHour))
    << ",  # [m/s/sqrt(h)]\n";
  b << "    'accel_b_stability': " << arr(gm(a, true, 1.0)) << ",  # [m/s^2]\n";
  b << "    'accel_b_corr': " << arr(gm(a, false, 1.0)) << ",  # [s]\n";
  b << "}\n";
  return c.text();
}

std::string matlab(const models::NoiseModel& model, const ExportRequest& request,
                   const FilterParameters& p, double rate) {
  Config c("%", model, request, rate);
  c.rules(p);
  c.line(
      "NoiseDensity = N, BiasInstability = B, RandomWalk = K, all SI; imuSensor's default "
      "NoiseType 'double-sided' matches the two-sided N");
  c.line("Q (quantization), R (ramp) and GM terms are not carried by gyroparams/accelparams");
  const auto block = [&](const std::optional<SensorParameters>& s) {
    if (!s) return;
    const std::string var(sensor_name(s->kind));  // gyro, accel
    const std::string fn = var + "params";
    const std::string bu(si_rate_unit(s->kind));
    const std::string nu = "(" + bu + ")/sqrt(Hz)";
    const std::string ku = "(" + bu + ")*sqrt(Hz)";
    const std::string sub = s->kind == SensorKind::gyro ? "_g" : "_a";
    for (int i = 0; i < 3; ++i) {
      const std::string ix = bracketed(i + 1, '(', ')');
      c.conversion(var + ".NoiseDensity" + ix, "N" + sub, s->axes[i].white_noise, nu);
      c.conversion(var + ".BiasInstability" + ix, "B" + sub, s->axes[i].bias_instability, bu);
      c.conversion(var + ".RandomWalk" + ix, "K" + sub, s->axes[i].random_walk, ku);
    }
    auto& b = c.body();
    b << "\n" << var << " = " << fn << "( ...\n";
    b << "    'NoiseDensity', [" << triple(*s, &SensorAxisParameters::white_noise, 1.0, " ")
      << "], ...  % " << nu << "\n";
    b << "    'BiasInstability', [" << triple(*s, &SensorAxisParameters::bias_instability, 1.0, " ")
      << "], ...  % " << bu << "\n";
    b << "    'RandomWalk', [" << triple(*s, &SensorAxisParameters::random_walk, 1.0, " ")
      << "]);  % " << ku << "\n";
  };
  block(p.gyro);
  block(p.accel);
  if (!p.gyro && !p.accel) throw InputError("the model has no axes");
  return c.text();
}

std::string px4(const models::NoiseModel& model, const ExportRequest& request,
                const FilterParameters& p, double rate) {
  Config c("#", model, request, rate);
  c.rules(p);
  const auto v = rw_only(p, c, request.format, request.parameters.conservative);
  c.line(
      "EKF2 applies these per filter update of fixed period dt (delta-angle variance = "
      "(dt*EKF2_GYR_NOISE)^2, bias step std = dt^2*EKF2_GYR_B_NOISE): noise = N*sqrt(rate), "
      "bias noise = K*sqrt(rate), rate = the filter rate");
  const auto d = per_sample(c, v, rate,
                            {{"EKF2_GYR_NOISE", Slot::n_g},
                             {"EKF2_ACC_NOISE", Slot::n_a},
                             {"EKF2_GYR_B_NOISE", Slot::k_g},
                             {"EKF2_ACC_B_NOISE", Slot::k_a}});
  struct Bound {
    const char* name;
    double value, min, max;
  };
  // Allowed ranges of PX4-Autopilot's ekf2 parameter definitions (module.yaml).
  for (const Bound& bound :
       {Bound{"EKF2_GYR_NOISE", d.n_g, 1e-4, 0.1}, Bound{"EKF2_ACC_NOISE", d.n_a, 0.01, 1.0},
        Bound{"EKF2_GYR_B_NOISE", d.k_g, 0.0, 0.01}, Bound{"EKF2_ACC_B_NOISE", d.k_a, 0.0, 0.01}})
    if (bound.value < bound.min || bound.value > bound.max)
      c.line(std::string("WARNING: ") + bound.name + " = " + real(bound.value) +
             " is outside PX4's allowed range [" + real(bound.min) + ", " + real(bound.max) +
             "]; PX4 will not accept it as is");
  c.line(
      "Vehicle-Id Component-Id Name Value Type (9 = float); the Vehicle-Id must match your "
      "vehicle's system id");
  auto& b = c.body();
  const auto param = [&](const char* name, double value) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "1\t1\t%s\t%.9g\t9\n", name, value);
    b << buffer;
  };
  param("EKF2_ACC_B_NOISE", d.k_a);
  param("EKF2_ACC_NOISE", d.n_a);
  param("EKF2_GYR_B_NOISE", d.k_g);
  param("EKF2_GYR_NOISE", d.n_g);
  return c.text();
}

std::string robot_localization(const models::NoiseModel& model, const ExportRequest& request,
                               const FilterParameters& p, double rate) {
  Config c("#", model, request, rate);
  c.rules(p);
  const auto v = rw_only(p, c, request.format, request.parameters.conservative);
  c.line(
      "robot_localization has no IMU bias states: the IMU enters as measurements whose "
      "covariances the driver puts in each sensor_msgs/Imu message:");
  c.line("  angular_velocity_covariance diagonal = N_g^2*rate = " + real(v.n_g * v.n_g * rate) +
         " (rad/s)^2");
  c.line("  linear_acceleration_covariance diagonal = N_a^2*rate = " + real(v.n_a * v.n_a * rate) +
         " (m/s^2)^2");
  c.line(
      "process_noise_covariance is a density the filter multiplies by dt: the angular "
      "velocity states (vroll, vpitch, vyaw) get K_g^2 [rad^2/s^3] and the acceleration "
      "states (ax, ay, az) K_a^2 [m^2/s^5], so the filter lets its rate and acceleration "
      "estimates wander as fast as the sensor biases do");
  c.line(
      "the other 9 diagonal entries are 0 here: they describe your vehicle's motion, not the "
      "IMU — keep your own values for x, y, z, roll, pitch, yaw, vx, vy, vz");
  c.conversion("angular_velocity_covariance (diag)", "N_g^2*rate", v.n_g * v.n_g * rate,
               "(rad/s)^2");
  c.conversion("linear_acceleration_covariance (diag)", "N_a^2*rate", v.n_a * v.n_a * rate,
               "(m/s^2)^2");
  c.conversion("process_noise_covariance[vroll..vyaw]", "K_g^2", v.k_g * v.k_g, "rad^2/s^3");
  c.conversion("process_noise_covariance[ax..az]", "K_a^2", v.k_a * v.k_a, "m^2/s^5");
  auto& b = c.body();
  b << "\nekf_filter_node:\n  ros__parameters:\n";
  b << "    # state order: x, y, z, roll, pitch, yaw, vx, vy, vz, vroll, vpitch, vyaw, ax, ay, "
       "az\n";
  b << "    process_noise_covariance: [";
  for (int r = 0; r < 15; ++r) {
    b << (r ? ",\n                               " : "");
    for (int col = 0; col < 15; ++col) {
      double value = 0.0;
      if (r == col && r >= 9 && r < 12) value = v.k_g * v.k_g;
      if (r == col && r >= 12) value = v.k_a * v.k_a;
      b << (col ? ", " : "") << real(value);
    }
  }
  b << "]\n";
  return c.text();
}

}  // namespace

namespace detail {
std::string_view export_consumer_name(ExportFormat format) { return info(format).consumer; }
}  // namespace detail

const std::vector<ExportFormat>& all_export_formats() {
  static const std::vector<ExportFormat> formats = [] {
    std::vector<ExportFormat> out;
    for (const auto& f : kFormats) out.push_back(f.format);
    return out;
  }();
  return formats;
}

std::string_view export_format_name(ExportFormat format) { return info(format).name; }

std::string_view export_format_consumer(ExportFormat format) { return info(format).consumer; }

std::optional<ExportFormat> parse_export_format(std::string_view name) {
  for (const auto& f : kFormats)
    if (name == f.name) return f.format;
  if (name == "kf_gins") return ExportFormat::kf_gins;
  if (name == "gnss_ins_sim") return ExportFormat::gnss_ins_sim;
  if (name == "robot-localization") return ExportFormat::robot_localization;
  if (name == "lio_sam" || name == "liosam") return ExportFormat::lio_sam;
  if (name == "fast_lio" || name == "fast-lio2" || name == "fastlio") return ExportFormat::fast_lio;
  if (name == "ardupilot-ekf3" || name == "ekf3") return ExportFormat::ardupilot;
  if (name == "kimera-vio") return ExportFormat::kimera;
  if (name == "imu-utils") return ExportFormat::imu_utils;
  return std::nullopt;
}

std::string_view default_export_file_name(ExportFormat format) { return info(format).file_name; }

double default_export_rate_hz(ExportFormat format, const models::NoiseModel& model) {
  if (format == ExportFormat::px4) return 100.0;
  if (format == ExportFormat::ardupilot) return 1.0 / 0.012;  // EKF_TARGET_DT
  return model.sample_rate_hz;
}

ExportOutput export_file(const models::NoiseModel& model, const ExportRequest& request) {
  if (request.format == ExportFormat::native) {
    if (request.parameters.conservative)
      throw InputError("--conservative does not apply to --to native (a lossless copy)");
    return {format_model_yaml(model), {}};
  }
  if (request.rate_hz != 0.0 && !(request.rate_hz > 0.0 && std::isfinite(request.rate_hz)))
    throw InputError("the export rate must be > 0 Hz, got " +
                     shortest_number_text(request.rate_hz));
  const double rate =
      request.rate_hz > 0.0 ? request.rate_hz : default_export_rate_hz(request.format, model);
  if (!std::isfinite(rate) || !(rate > 0.0))
    throw InputError("the export rate must be > 0 Hz, got " + shortest_number_text(rate));
  auto options = request.parameters;
  options.filter_rate_hz = rate;
  options.upper_bound_when_not_identified = !request.strict;
  const auto params = models::select_filter_parameters(model, options);
  ExportOutput out;
  for (const auto& line : detail::unidentified_lines(params, request.format, request.strict))
    if (line.rfind("upper bound: ", 0) == 0 || line.rfind("not identified: ", 0) == 0)
      out.warnings.push_back(std::string(export_format_name(request.format)) + ": " + line);
  const detail::ExportContext x{model, request, params, rate, out.warnings};
  switch (request.format) {
    case ExportFormat::kalibr:
      out.text = kalibr_like(model, request, params, rate, false);
      break;
    case ExportFormat::openvins:
      out.text = kalibr_like(model, request, params, rate, true);
      break;
    case ExportFormat::vins:
      out.text = vins(model, request, params, rate);
      break;
    case ExportFormat::orbslam3:
      out.text = orbslam3(model, request, params, rate);
      break;
    case ExportFormat::okvis:
      out.text = okvis(model, request, params, rate);
      break;
    case ExportFormat::kf_gins:
      out.text = kf_gins(model, request, params, rate);
      break;
    case ExportFormat::gnss_ins_sim:
      out.text = gnss_ins_sim(model, request, params, rate);
      break;
    case ExportFormat::matlab:
      out.text = matlab(model, request, params, rate);
      break;
    case ExportFormat::px4:
      out.text = px4(model, request, params, rate);
      break;
    case ExportFormat::robot_localization:
      out.text = robot_localization(model, request, params, rate);
      break;
    case ExportFormat::lio_sam:
      out.text = detail::lio_sam(x);
      break;
    case ExportFormat::fast_lio:
      out.text = detail::fast_lio(x);
      break;
    case ExportFormat::basalt:
      out.text = detail::basalt(x);
      break;
    case ExportFormat::gtsam:
      out.text = detail::gtsam(x);
      break;
    case ExportFormat::ardupilot:
      out.text = detail::ardupilot(x);
      break;
    case ExportFormat::kimera:
      out.text = detail::kimera(x);
      break;
    case ExportFormat::imu_utils:
      out.text = detail::imu_utils(x);
      break;
    case ExportFormat::native:
      out.text = format_model_yaml(model);
      break;
  }
  return out;
}

std::string export_config(const models::NoiseModel& model, const ExportRequest& request) {
  return export_file(model, request).text;
}

}  // namespace imunoise::io
