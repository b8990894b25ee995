// The robotics family of io/filter_export: LIO-SAM, FAST-LIO, Basalt, GTSAM, ArduPilot EKF3,
// Kimera-VIO and imu_utils. Keys, units and how each consumer uses them were read from the
// consumers' sources; docs/exports.md cites repository, file and key for each.
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "common/units.h"
#include "io/filter_export_internal.h"

namespace imunoise::io::detail {
namespace {

using models::SensorAxisParameters;
using models::SensorParameters;

/// sqrt(2 ln2 / π): the ADEV floor of bias instability B (theory.md §4.1).
const double kFlickerAdevFactor = std::sqrt(2.0 * std::numbers::ln2 / std::numbers::pi);

/// The white + RW pair of slot I of S (the per-axis formats: Basalt, GTSAM).
double white(const SensorParameters& s, int i) { return s.axes[i].rw_only_white_noise; }
double walk(const SensorParameters& s, int i) { return s.axes[i].rw_only_random_walk; }

/// "[f(0), f(1), f(2)]" with the values as real().
template <class F>
std::string list3(F f) {
  return "[" + real(f(0)) + ", " + real(f(1)) + ", " + real(f(2)) + "]";
}

/// The rows of diag(f(0), f(1), f(2)) as a YAML flow sequence of rows.
template <class F>
std::string diagonal_rows(F f) {
  std::string out = "[";
  for (int r = 0; r < 3; ++r) {
    out += r ? ", [" : "[";
    for (int c = 0; c < 3; ++c) out += (c ? ", " : "") + real(r == c ? f(r) : 0.0);
    out += "]";
  }
  return out + "]";
}

/// A JSON string literal of TEXT (quotes, backslashes and control characters escaped).
std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (u < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", u);
      out += buffer;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

}  // namespace

std::string lio_sam(const ExportContext& x) {
  Config c("#", x.model, x.request, x.rate);
  c.rules(x.p);
  const auto v = rw_only(x.p, c, x.request.format, x.request.parameters.conservative);
  c.line(
      "LIO-SAM (src/imuPreintegration.cpp) puts pow(imuAccNoise, 2) and pow(imuGyrNoise, 2) into "
      "GTSAM's continuous-time accelerometerCovariance / gyroscopeCovariance, and "
      "sqrt(deltaTij) * imuAccBiasN / imuGyrBiasN as the sigmas of the bias BetweenFactor: all "
      "four are continuous densities (N, K), independent of the IMU rate");
  c.line(
      "merge these keys into your config/params.yaml; the ROS 2 branch keeps them under "
      "'/**: ros__parameters:' instead of 'lio_sam:'. imuGravity is standard gravity (put your "
      "local value); imuRPYWeight is not a noise-model value and keeps LIO-SAM's default 0.01");
  c.conversion("imuAccNoise", "N_a", v.n_a, "m/s^2/sqrt(Hz)");
  c.conversion("imuGyrNoise", "N_g", v.n_g, "rad/s/sqrt(Hz)");
  c.conversion("imuAccBiasN", "K_a", v.k_a, "m/s^3/sqrt(Hz)");
  c.conversion("imuGyrBiasN", "K_g", v.k_g, "rad/s^2/sqrt(Hz)");
  auto& b = c.body();
  b << "\nlio_sam:\n";
  b << "  imuAccNoise: " << real(v.n_a)
    << "  # accelerometer white noise density [m/s^2/sqrt(Hz)]\n";
  b << "  imuGyrNoise: " << real(v.n_g) << "  # gyroscope white noise density [rad/s/sqrt(Hz)]\n";
  b << "  imuAccBiasN: " << real(v.k_a) << "  # accelerometer bias random walk [m/s^3/sqrt(Hz)]\n";
  b << "  imuGyrBiasN: " << real(v.k_g) << "  # gyroscope bias random walk [rad/s^2/sqrt(Hz)]\n";
  b << "  imuGravity: " << real(units::kStandardGravity) << "  # [m/s^2]\n";
  b << "  imuRPYWeight: 0.01  # LIO-SAM's default (not from the noise model)\n";
  return c.text();
}

std::string fast_lio(const ExportContext& x) {
  Config c("#", x.model, x.request, x.rate);
  c.rules(x.p);
  const auto v = rw_only(x.p, c, x.request.format, x.request.parameters.conservative);
  c.line(
      "FAST-LIO (src/IMU_Processing.hpp) puts gyr_cov, acc_cov, b_gyr_cov, b_acc_cov on the "
      "diagonal of Q, and its ESKF (IKFoM esekfom.hpp predict) adds (dt*F_w) Q (dt*F_w)^T at "
      "every IMU sample: per-sample variances, so the attitude variance grows by "
      "dt^2*gyr_cov = N_g^2*dt per step when gyr_cov = N_g^2*rate, and the bias variance by "
      "dt^2*b_gyr_cov = K_g^2*dt when b_gyr_cov = K_g^2*rate");
  c.line(
      "rate = the IMU sample rate (dt is the interval between IMU messages): re-export with "
      "--rate if your driver publishes at another rate than the recording");
  c.line(
      "merge into the mapping: block of your config/*.yaml (ROS 2: under '/**: "
      "ros__parameters:'); FAST-LIO's defaults are acc_cov 0.1, gyr_cov 0.1, b_*_cov 0.0001");
  const double r = x.rate;
  c.conversion("acc_cov", "N_a^2*rate", v.n_a * v.n_a * r, "(m/s^2)^2");
  c.conversion("gyr_cov", "N_g^2*rate", v.n_g * v.n_g * r, "(rad/s)^2");
  c.conversion("b_acc_cov", "K_a^2*rate", v.k_a * v.k_a * r, "(m/s^3)^2");
  c.conversion("b_gyr_cov", "K_g^2*rate", v.k_g * v.k_g * r, "(rad/s^2)^2");
  auto& b = c.body();
  b << "\nmapping:\n";
  b << "  acc_cov: " << real(v.n_a * v.n_a * r) << "  # per-sample variance [(m/s^2)^2]\n";
  b << "  gyr_cov: " << real(v.n_g * v.n_g * r) << "  # per-sample variance [(rad/s)^2]\n";
  b << "  b_acc_cov: " << real(v.k_a * v.k_a * r)
    << "  # per-sample bias variance rate [(m/s^3)^2]\n";
  b << "  b_gyr_cov: " << real(v.k_g * v.k_g * r)
    << "  # per-sample bias variance rate [(rad/s^2)^2]\n";
  return c.text();
}

std::string basalt(const ExportContext& x) {
  const auto& g = need(x.p.gyro, SensorKind::gyro, x.request.format);
  const auto& a = need(x.p.accel, SensorKind::accel, x.request.format);
  Config c("#", x.model, x.request, x.rate);
  c.rules(x.p);
  rw_only(x.p, c, x.request.format, x.request.parameters.conservative);
  c.line(
      "Basalt (basalt-headers calibration.hpp) reads accel_noise_std / gyro_noise_std as "
      "continuous-time noise densities (its dicrete_time_*_noise_std() multiplies them by "
      "sqrt(imu_update_rate)) and accel_bias_std / gyro_bias_std as continuous-time bias "
      "random walks: N and K per axis");
  c.line(
      "merge the five keys into the value0 object of your calibration JSON (Basalt's loader "
      "needs the camera keys too); JSON has no comments, so this header is the imunoise_header "
      "array, which Basalt's cereal loader does not read");
  for (int i = 0; i < 3; ++i) {
    const std::string s = bracketed(i, '[', ']');
    c.conversion("accel_noise_std" + s, "N_a", white(a, i), "m/s^2/sqrt(Hz)");
    c.conversion("gyro_noise_std" + s, "N_g", white(g, i), "rad/s/sqrt(Hz)");
    c.conversion("accel_bias_std" + s, "K_a", walk(a, i), "m/s^3/sqrt(Hz)");
    c.conversion("gyro_bias_std" + s, "K_g", walk(g, i), "rad/s^2/sqrt(Hz)");
  }
  std::string out = "{\n    \"value0\": {\n";
  out += "        \"imu_update_rate\": " + real(x.rate) + ",\n";
  out += "        \"accel_noise_std\": " + list3([&](int i) { return white(a, i); }) + ",\n";
  out += "        \"gyro_noise_std\": " + list3([&](int i) { return white(g, i); }) + ",\n";
  out += "        \"accel_bias_std\": " + list3([&](int i) { return walk(a, i); }) + ",\n";
  out += "        \"gyro_bias_std\": " + list3([&](int i) { return walk(g, i); }) + "\n";
  out += "    },\n    \"imunoise_header\": [\n";
  const auto lines = c.header_lines();
  for (std::size_t i = 0; i < lines.size(); ++i)
    out += "        " + json_string(lines[i]) + (i + 1 < lines.size() ? ",\n" : "\n");
  out += "    ]\n}\n";
  return out;
}

std::string gtsam(const ExportContext& x) {
  const auto& g = need(x.p.gyro, SensorKind::gyro, x.request.format);
  const auto& a = need(x.p.accel, SensorKind::accel, x.request.format);
  Config c("#", x.model, x.request, x.rate);
  c.rules(x.p);
  rw_only(x.p, c, x.request.format, x.request.parameters.conservative);
  c.line(
      "GTSAM (gtsam/navigation/PreintegrationParams.h, PreintegrationCombinedParams.h) takes "
      "continuous-time \"covariances\", i.e. squared densities: accelerometerCovariance = "
      "N_a^2, gyroscopeCovariance = N_g^2, biasAccCovariance = K_a^2, biasOmegaCovariance = "
      "K_g^2 (3x3, per axis on the diagonal); it discretizes with the dt of each measurement");
  c.line(
      "integrationCovariance (1e-8 I, m^2/s) and biasAccOmegaInt (the initial bias "
      "covariance, left to GTSAM's default) are not noise-model values; gravity_m_per_s2 is "
      "standard gravity (MakeSharedU: z up; MakeSharedD for NED); put your local value");
  const auto sq = [](double v) { return v * v; };
  const auto acc = [&](int i) { return sq(white(a, i)); };
  const auto gyr = [&](int i) { return sq(white(g, i)); };
  const auto bacc = [&](int i) { return sq(walk(a, i)); };
  const auto bgyr = [&](int i) { return sq(walk(g, i)); };
  for (int i = 0; i < 3; ++i) {
    const std::string s = bracketed(i, '(', ')');
    c.conversion("accelerometerCovariance" + s, "N_a^2", acc(i), "(m/s^2)^2/Hz");
    c.conversion("gyroscopeCovariance" + s, "N_g^2", gyr(i), "(rad/s)^2/Hz");
    c.conversion("biasAccCovariance" + s, "K_a^2", bacc(i), "(m/s^3)^2/Hz");
    c.conversion("biasOmegaCovariance" + s, "K_g^2", bgyr(i), "(rad/s^2)^2/Hz");
  }
  const std::string gravity = real(units::kStandardGravity);
  auto& b = c.body();
  b << "\naccelerometerCovariance: " << diagonal_rows(acc) << "  # [(m/s^2)^2/Hz]\n";
  b << "gyroscopeCovariance: " << diagonal_rows(gyr) << "  # [(rad/s)^2/Hz]\n";
  b << "integrationCovariance: " << diagonal_rows([](int) { return 1e-8; })
    << "  # [m^2/s] not from the noise model\n";
  b << "biasAccCovariance: " << diagonal_rows(bacc) << "  # [(m/s^3)^2/Hz]\n";
  b << "biasOmegaCovariance: " << diagonal_rows(bgyr) << "  # [(rad/s^2)^2/Hz]\n";
  b << "gravity_m_per_s2: " << gravity << "\n";
  const auto vec = [](auto f) {
    return "gtsam::Vector3(" + real(f(0)) + ", " + real(f(1)) + ", " + real(f(2)) + ")";
  };
  const auto npdiag = [](auto f) {
    return "np.diag([" + real(f(0)) + ", " + real(f(1)) + ", " + real(f(2)) + "])";
  };
  b << "\n# C++ (GTSAM 4.x): the same numbers\n";
  b << "# #include <gtsam/navigation/CombinedImuFactor.h>\n";
  b << "# auto p = gtsam::PreintegrationCombinedParams::MakeSharedU(" << gravity << ");\n";
  b << "# p->accelerometerCovariance = " << vec(acc) << ".asDiagonal();\n";
  b << "# p->gyroscopeCovariance = " << vec(gyr) << ".asDiagonal();\n";
  b << "# p->integrationCovariance = gtsam::I_3x3 * 1.0e-08;\n";
  b << "# p->biasAccCovariance = " << vec(bacc) << ".asDiagonal();\n";
  b << "# p->biasOmegaCovariance = " << vec(bgyr) << ".asDiagonal();\n";
  b << "# // ImuFactor only: gtsam::PreintegrationParams::MakeSharedU with the first three\n";
  b << "\n# Python (gtsam): the same numbers\n";
  b << "# import gtsam\n# import numpy as np\n";
  b << "# p = gtsam.PreintegrationCombinedParams.MakeSharedU(" << gravity << ")\n";
  b << "# p.setAccelerometerCovariance(" << npdiag(acc) << ")\n";
  b << "# p.setGyroscopeCovariance(" << npdiag(gyr) << ")\n";
  b << "# p.setIntegrationCovariance(np.eye(3) * 1.0e-08)\n";
  b << "# p.setBiasAccCovariance(" << npdiag(bacc) << ")\n";
  b << "# p.setBiasOmegaCovariance(" << npdiag(bgyr) << ")\n";
  return c.text();
}

std::string ardupilot(const ExportContext& x) {
  Config c("#", x.model, x.request, x.rate);
  c.rules(x.p);
  const auto v = rw_only(x.p, c, x.request.format, x.request.parameters.conservative);
  c.line(
      "EKF3 (libraries/AP_NavEKF3/AP_NavEKF3_core.cpp CovariancePrediction) adds "
      "(dt*EK3_GYRO_P_NSE)^2 to each delta-angle variance and (dt^2*EK3_GBIAS_P_NSE)^2 to each "
      "delta-angle-bias variance per filter step dt (accel likewise): noise = N*sqrt(rate), "
      "bias noise = K*sqrt(rate), rate = the EKF step rate (EKF_TARGET_DT = 12 ms: 83.33 Hz; "
      "--rate for yours)");
  const auto d = per_sample(c, v, x.rate,
                            {{"EK3_GYRO_P_NSE", Slot::n_g},
                             {"EK3_ACC_P_NSE", Slot::n_a},
                             {"EK3_GBIAS_P_NSE", Slot::k_g},
                             {"EK3_ABIAS_P_NSE", Slot::k_a}});
  struct Param {
    const char* name;
    double value, min, max;
    const char* unit;
  };
  // @Range of each parameter in libraries/AP_NavEKF3/AP_NavEKF3.cpp.
  std::array<Param, 4> params{{{"EK3_ABIAS_P_NSE", d.k_a, 1e-5, 0.02, "m/s/s/s"},
                               {"EK3_ACC_P_NSE", d.n_a, 0.01, 1.0, "m/s/s"},
                               {"EK3_GBIAS_P_NSE", d.k_g, 1e-5, 1e-3, "rad/s/s"},
                               {"EK3_GYRO_P_NSE", d.n_g, 1e-4, 0.1, "rad/s"}}};
  for (auto& q : params) {
    if (q.value >= q.min && q.value <= q.max) continue;
    const double clamped = q.value < q.min ? q.min : q.max;
    const std::string text = std::string("WARNING: ") + q.name + " = " + real(q.value) + " " +
                             q.unit + " is outside EKF3's documented range [" + real(q.min) + ", " +
                             real(q.max) + "]: " + real(clamped) + " is written";
    c.line(text);
    x.warnings.push_back("ardupilot: " + text.substr(9));
    q.value = clamped;
  }
  c.line(
      "load with Mission Planner (Config > Full Parameter List > Load from file) or MAVProxy "
      "'param load'; lines are NAME VALUE");
  auto& b = c.body();
  b << "\n";
  for (const auto& q : params) b << q.name << ' ' << real(q.value) << '\n';
  return c.text();
}

std::string kimera(const ExportContext& x) {
  Config c("#", x.model, x.request, x.rate);
  c.rules(x.p);
  const auto v = rw_only(x.p, c, x.request.format, x.request.parameters.conservative);
  c.line(
      "Kimera-VIO (src/imu-frontend/ImuFrontend.cpp) squares the densities into GTSAM's "
      "continuous-time covariances and CHECKs each is > 0; ImuFrontendParams.cpp reads every "
      "key below (a missing one is fatal)");
  c.line(
      "imu_preintegration_type 1 (ImuFactor, Kimera's EuRoC default; 0 = CombinedImuFactor), "
      "T_BS identity, imu_integration_sigma, imu_time_shift, do_initial_time_alignment and "
      "n_gravity (standard gravity, z up) are not noise-model values");
  c.conversion("gyroscope_noise_density", "N_g", v.n_g, "rad/s/sqrt(Hz)");
  c.conversion("gyroscope_random_walk", "K_g", v.k_g, "rad/s^2/sqrt(Hz)");
  c.conversion("accelerometer_noise_density", "N_a", v.n_a, "m/s^2/sqrt(Hz)");
  c.conversion("accelerometer_random_walk", "K_a", v.k_a, "m/s^3/sqrt(Hz)");
  auto& b = c.body();
  b << "\nimu_preintegration_type: 1\n";
  b << "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  for (int i = 0; i < 16; ++i) b << (i ? ", " : "") << (i % 5 == 0 ? "1.0" : "0.0");
  b << "]\n";
  b << "rate_hz: " << real(x.rate) << "  # [Hz]\n";
  b << "gyroscope_noise_density: " << real(v.n_g) << "  # [rad/s/sqrt(Hz)]\n";
  b << "gyroscope_random_walk: " << real(v.k_g) << "  # [rad/s^2/sqrt(Hz)]\n";
  b << "accelerometer_noise_density: " << real(v.n_a) << "  # [m/s^2/sqrt(Hz)]\n";
  b << "accelerometer_random_walk: " << real(v.k_a) << "  # [m/s^3/sqrt(Hz)]\n";
  b << "imu_integration_sigma: 1.0e-08\n";
  b << "imu_time_shift: 0.0  # [s]\n";
  b << "do_initial_time_alignment: 0\n";
  b << "n_gravity: [0.0, 0.0, " << real(-units::kStandardGravity) << "]  # [m/s^2]\n";
  return c.text("%YAML:1.0");
}

std::string imu_utils(const ExportContext& x) {
  const auto& g = need(x.p.gyro, SensorKind::gyro, x.request.format);
  const auto& a = need(x.p.accel, SensorKind::accel, x.request.format);
  Config c("#", x.model, x.request, x.rate);
  c.rules(x.p);
  c.line(
      "imu_utils' keys keep imu_utils' meanings (gaowenliang/imu_utils src/imu_an.cpp "
      "writeYAML, src/gyr_lib/fitallan_gyr.cpp, src/acc_lib/fitallan_acc.h), which are not "
      "the names' usual ones:");
  c.line(
      "  gyr_n = sqrt(rate) * ADEV(1 s): a per-sample sigma [rad/s] (N_g*sqrt(rate) here); "
      "acc_n = ADEV(1 s) without sqrt(rate): a density [m/s^2/sqrt(Hz)] under the unit "
      "\" m/s^2\" (N_a here)");
  c.line(
      "  gyr_w / acc_w = the minimum of the fitted ADEV curve, a bias-instability floor, not a "
      "random walk: sqrt(2 ln2/pi)*B here (the floor B alone gives); the model's K is not in "
      "this format (use --to kalibr for N and K)");
  c.line(
      "  avg-axis = the arithmetic mean of the three axes, as imu_utils; its 57.3 deg/rad is "
      "not reproduced (SI throughout)");
  const double sr = std::sqrt(x.rate);
  const auto gyr_n = [&](int i) { return g.axes[i].white_noise * sr; };
  const auto gyr_w = [&](int i) { return g.axes[i].bias_instability * kFlickerAdevFactor; };
  const auto acc_n = [&](int i) { return a.axes[i].white_noise; };
  const auto acc_w = [&](int i) { return a.axes[i].bias_instability * kFlickerAdevFactor; };
  const char* names[3] = {"x-axis", "y-axis", "z-axis"};
  for (int i = 0; i < 3; ++i) {
    c.conversion(std::string("Gyr.") + names[i] + ".gyr_n", "N_g*sqrt(rate)", gyr_n(i), "rad/s");
    c.conversion(std::string("Gyr.") + names[i] + ".gyr_w", "0.664*B_g", gyr_w(i), "rad/s");
    c.conversion(std::string("Acc.") + names[i] + ".acc_n", "N_a", acc_n(i), "m/s^2/sqrt(Hz)");
    c.conversion(std::string("Acc.") + names[i] + ".acc_w", "0.664*B_a", acc_w(i), "m/s^2");
  }
  auto& b = c.body();
  const auto block = [&](const char* sensor, const char* unit, const char* n_key, const char* w_key,
                         auto n, auto w) {
    b << sensor << ":\n   unit: \"" << unit << "\"\n";
    b << "   avg-axis:\n      " << n_key << ": " << real((n(0) + n(1) + n(2)) / 3.0) << "\n      "
      << w_key << ": " << real((w(0) + w(1) + w(2)) / 3.0) << "\n";
    for (int i = 0; i < 3; ++i)
      b << "   " << names[i] << ":\n      " << n_key << ": " << real(n(i)) << "\n      " << w_key
        << ": " << real(w(i)) << "\n";
  };
  b << "type: IMU\n";
  b << "name: " << json_string(x.model.sensor_name.empty() ? "imu" : x.model.sensor_name) << "\n";
  block("Gyr", " rad/s", "gyr_n", "gyr_w", gyr_n, gyr_w);
  block("Acc", " m/s^2", "acc_n", "acc_w", acc_n, acc_w);
  return c.text("%YAML:1.0\n---");
}

}  // namespace imunoise::io::detail
