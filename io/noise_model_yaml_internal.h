/// @file
/// @brief Internal to io/noise_model_yaml_writer.cpp and io/noise_model_yaml_reader.cpp: every
/// key name of the model.yaml schema v1 (docs/model-yaml.md), written once, so the writer and
/// the strict loader cannot drift apart. Not part of the public API (io/noise_model_yaml.h).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "models/noise_model.h"

namespace imunoise::io::detail {

inline constexpr std::size_t kTermCount = kNoiseTerms.size();
static_assert(static_cast<std::size_t>(NoiseTerm::quantization) == 0 &&
                  static_cast<std::size_t>(NoiseTerm::ramp) == kTermCount - 1,
              "the key tables below are indexed by NoiseTerm");

/// The keys whose unit suffix depends on the sensor (units of theory.md §1.3).
struct SensorKeys {
  std::string_view sensor;                           ///< value of `sensor:`
  std::array<std::string_view, kTermCount> terms;    ///< per NoiseTerm
  std::array<std::string_view, kTermCount> symbols;  ///< comment written after each term key
  std::string_view sigma;                            ///< Gauss–Markov σ [rad/s | m/s²]
  std::string_view sigma_ci_low;
  std::string_view sigma_ci_high;
  std::string_view sigma_max;         ///< σ of the Gauss–Markov upper-bound curve
  std::string_view amplitude;         ///< sinusoid amplitude [rad/s | m/s²]
  std::string_view amplitude_ci_low;  ///< its interval (optional in files before it)
  std::string_view amplitude_ci_high;
};

inline constexpr SensorKeys kGyroKeys{
    sensor_name(SensorKind::gyro),
    {"quantization_rad", "white_noise_rad_per_sqrt_s", "bias_instability_rad_per_s",
     "random_walk_rad_per_s_sqrt_s", "ramp_rad_per_s2"},
    {"Q (angle quantization)", "N (ARW)", "B (bias instability)", "K (RRW)", "R (rate ramp)"},
    "sigma_rad_per_s",
    "sigma_ci_low_rad_per_s",
    "sigma_ci_high_rad_per_s",
    "sigma_max_rad_per_s",
    "amplitude_rad_per_s",
    "amplitude_ci_low_rad_per_s",
    "amplitude_ci_high_rad_per_s"};

inline constexpr SensorKeys kAccelKeys{
    sensor_name(SensorKind::accel),
    {"quantization_m_per_s", "white_noise_m_per_s_sqrt_s", "bias_instability_m_per_s2",
     "random_walk_m_per_s2_sqrt_s", "ramp_m_per_s3"},
    {"Q (velocity quantization)", "N (VRW)", "B (bias instability)", "K (accel random walk)",
     "R (accel ramp)"},
    "sigma_m_per_s2",
    "sigma_ci_low_m_per_s2",
    "sigma_ci_high_m_per_s2",
    "sigma_max_m_per_s2",
    "amplitude_m_per_s2",
    "amplitude_ci_low_m_per_s2",
    "amplitude_ci_high_m_per_s2"};

/// The keys of KIND's axes.
inline const SensorKeys& keys_for(SensorKind kind) {
  return kind == SensorKind::gyro ? kGyroKeys : kAccelKeys;
}

/// @name Root keys, in the order they are written
/// @{
inline constexpr std::string_view kFormatKey = "format";
inline constexpr std::string_view kVersionKey = "format_version";
inline constexpr std::string_view kSoftware = "software";
inline constexpr std::string_view kSensorName = "sensor_name";
inline constexpr std::string_view kSource = "source";
inline constexpr std::string_view kSampleRate = "sample_rate_hz";
inline constexpr std::string_view kDuration = "duration_s";
inline constexpr std::string_view kSamples = "samples";
inline constexpr std::string_view kConfidence = "confidence";
inline constexpr std::string_view kDataQuality = "data_quality";
inline constexpr std::string_view kAxes = "axes";
inline constexpr std::array<std::string_view, 11> kRootKeys{
    kFormatKey, kVersionKey, kSoftware,   kSensorName,  kSource, kSampleRate,
    kDuration,  kSamples,    kConfidence, kDataQuality, kAxes};
/// @}

/// @name Keys of one axis
/// @{
inline constexpr std::string_view kSensor = "sensor";
/// One noise term (the keys of SensorKeys::terms): an Estimate.
inline constexpr std::string_view kValue = "value";
inline constexpr std::string_view kCiLow = "ci_low";
inline constexpr std::string_view kCiHigh = "ci_high";
inline constexpr std::string_view kIdentified = "identified";
inline constexpr std::string_view kMethod = "method";
inline constexpr std::string_view kIntervalMethod = "interval_method";
inline constexpr std::array<std::string_view, 6> kEstimateKeys{
    kValue, kCiLow, kCiHigh, kIdentified, kMethod, kIntervalMethod};
/// Gauss–Markov terms (σ keys in SensorKeys), sinusoids, B as Gauss–Markov.
inline constexpr std::string_view kTauC = "tau_c_s";
inline constexpr std::string_view kTauCLow = "tau_c_ci_low_s";
inline constexpr std::string_view kTauCHigh = "tau_c_ci_high_s";
inline constexpr std::string_view kFrequency = "frequency_hz";
inline constexpr std::string_view kPhase = "phase_rad";
inline constexpr std::string_view kConvention = "convention";
inline constexpr std::string_view kGaussMarkov = "gauss_markov";
inline constexpr std::string_view kGaussMarkovBound = "gauss_markov_upper_bound";
inline constexpr std::string_view kSinusoids = "sinusoids";
inline constexpr std::string_view kBiasGm = "bias_instability_as_gauss_markov";
inline constexpr std::string_view kMultiGm = "bias_instability_multi_gm";
inline constexpr std::string_view kMultiGmTerms = "terms";
inline constexpr std::string_view kMultiGmFraction = "fraction_inside_ci";
/// The fit block: kFitKeys[0…3] = τ min, τ max, τ of the minimum ADEV, note.
inline constexpr std::string_view kFit = "fit";
inline constexpr std::array<std::string_view, 4> kFitKeys{"tau_min_s", "tau_max_s",
                                                          "tau_of_min_adev_s", "note"};
/// The read-off block: kReadoffKeys[0…1] = IEEE 952 slope read-offs, PSD read-offs.
inline constexpr std::string_view kReadoff = "readoff";
inline constexpr std::array<std::string_view, 2> kReadoffKeys{"ieee952_slope", "psd"};
/// The PSD check block: kPsdCheckKeys[0…1] = pass, note.
inline constexpr std::string_view kPsdCheck = "psd_check";
inline constexpr std::array<std::string_view, 2> kPsdCheckKeys{"pass", "note"};
/// @}

}  // namespace imunoise::io::detail
