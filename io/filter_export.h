/// @file
/// @brief Filter and simulator configs from a fitted model: the keys and units each consumer
/// reads (../shared/docs/filter-formats.md, docs/exports.md), every file opening with a
/// comment header that names the source model, the rules applied and each conversion with
/// its formula and value.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/filter_parameters.h"
#include "models/noise_model.h"

namespace imunoise::io {

enum class ExportFormat {
  native,              ///< model.yaml itself (lossless copy)
  kalibr,              ///< Kalibr imu.yaml
  openvins,            ///< OpenVINS kalibr_imu_chain.yaml
  vins,                ///< VINS-Mono / VINS-Fusion IMU keys (discrete sigmas)
  orbslam3,            ///< ORB-SLAM3 settings IMU keys
  okvis,               ///< OKVIS imu_parameters block
  kf_gins,             ///< KF-GINS imunoise block (GM biases)
  gnss_ins_sim,        ///< gnss-ins-sim imu_err dict (Python)
  matlab,              ///< MATLAB gyroparams / accelparams script
  px4,                 ///< PX4 EKF2 parameters (QGroundControl .params)
  robot_localization,  ///< robot_localization ekf.yaml + IMU message covariances
  lio_sam,             ///< LIO-SAM params.yaml IMU keys (densities, GTSAM preintegration)
  fast_lio,            ///< FAST-LIO / FAST-LIO2 mapping block (per-sample variances)
  basalt,              ///< Basalt calibration JSON IMU noise fields (value0)
  gtsam,               ///< GTSAM PreintegrationCombinedParams YAML + C++/Python snippets
  ardupilot,           ///< ArduPilot EKF3 .parm (EK3_*_P_NSE at the EKF rate)
  kimera,              ///< Kimera-VIO ImuParams.yaml (OpenCV %YAML:1.0)
  imu_utils,           ///< imu_utils' <name>_imu_param.yaml (its own key meanings)
};

/// Every format, in the order above.
const std::vector<ExportFormat>& all_export_formats();
/// The name used on the command line ("kalibr", "kf-gins", "robot_localization", …).
std::string_view export_format_name(ExportFormat format);
/// The program that reads the format and its file ("Kalibr (imu.yaml)", "PX4 EKF2 (…)", …).
std::string_view export_format_consumer(ExportFormat format);
/// Parses a command-line name; nullopt if unknown.
std::optional<ExportFormat> parse_export_format(std::string_view name);
/// A file name that suits the format ("kalibr_imu.yaml", "imu_params.m", …).
std::string_view default_export_file_name(ExportFormat format);
/// The rate a format's discrete values refer to when the user gives none: the model's
/// sample rate, except PX4 (EKF2 runs at a fixed 100 Hz filter update, FILTER_UPDATE_PERIOD)
/// and ArduPilot (EKF3's target step EKF_TARGET_DT = 12 ms: 83.33 Hz).
double default_export_rate_hz(ExportFormat format, const models::NoiseModel& model);

struct ExportRequest {
  ExportFormat format = ExportFormat::kalibr;
  double rate_hz = 0.0;                       ///< 0 = default_export_rate_hz()
  models::FilterParameterOptions parameters;  ///< axis rule, conservative, GM convention
  std::string model_path;                     ///< named in the header
  std::string command;                        ///< the command line, named in the header
  /// false (default): a term a format carries that is not identified takes its upper bound,
  /// with a header line and a warning. true: such a term is refused (InputError naming it).
  bool strict = false;
};

/// A config and the warnings its caller shows the user (one per upper bound used in place of
/// a term not identified); the same lines are in the file's header.
struct ExportOutput {
  std::string text;
  std::vector<std::string> warnings;
};

/// The text of the config. For `native` it is format_model_yaml(MODEL) (lossless; the axis
/// and conservative options are refused there, since they would change the model).
/// @throws InputError when the model lacks what the format needs (e.g. no accel axes for
///   Kalibr), an option does not apply to the format, or a term the format carries is not
///   identified and REQUEST.strict (or the model has no upper bound and the consumer needs > 0).
ExportOutput export_file(const models::NoiseModel& model, const ExportRequest& request);
/// export_file(MODEL, REQUEST).text.
std::string export_config(const models::NoiseModel& model, const ExportRequest& request);

}  // namespace imunoise::io
