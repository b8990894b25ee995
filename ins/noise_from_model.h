/// @file
/// @brief The IMU noise of a fitted models::NoiseModel as the per-axis InsSensorNoise of the
/// INS error-state model (theory.md §6.3): white noise N, bias random walk K and bias
/// instability B as one first-order Gauss–Markov term (theory.md §4.4) for each body axis.
#pragma once

#include <string>
#include <vector>

#include "ins/error_state_model.h"
#include "models/bias_instability_gm.h"
#include "models/filter_parameters.h"
#include "models/noise_model.h"

namespace imunoise::ins {

struct InsNoiseOptions {
  /// false: point estimates; true: the upper end of each coefficient's interval (a term not
  /// identified: its upper bound), as models::FilterParameterOptions::conservative. Nothing
  /// is folded: the error-state model carries N, K and the GM separately.
  bool conservative = false;
  /// Which single GM stands for B (theory.md §4.4 (a)–(c)).
  models::GmConvention gm_convention = models::GmConvention::peak_match;
  /// The names select_filter_parameters()'s messages give the settings (the CLI: its flags).
  models::FilterSettingNames setting_names;
  /// true: every stochastic term of the model as its own state (the drift prediction):
  /// B as the axis' multi_gm terms (AxisModel::multi_gm, theory.md §4.4 "preferred") in
  /// gm_terms, falling back to the single GM of gm_convention in bias_gm only for an axis
  /// with B but no multi_gm (single_gm_fallback_axes() names them); every fitted GM term in
  /// gm_terms; R in ramp. Point values (the conservative flag still applies to N and K; GM
  /// terms and R carry no interval to take the upper end of).
  bool model_terms_as_states = false;
};

/// Per body axis x, y, z of the gyro and the accelerometer: white_noise = N,
/// random_walk = K and bias_gm = B as one GM by options.gm_convention (without B, the
/// largest fitted GM term; σ = 0 when neither), all from
/// models::select_filter_parameters(MODEL, {axis = each, conservative, gm_convention,
/// filter_rate_hz = MODEL.sample_rate_hz}) — the rate only bounds a quantization fold that is
/// not used here. Axes are matched to x, y, z by their name suffix (_x, _y, _z), else in model
/// order. Quantization, ramp, sinusoids and further GM terms are not carried (callers that
/// need them note it), except with options.model_terms_as_states: then the ramp, the GM terms
/// and quantization (SensorAxisNoise::quantization, which gets no state) are. turn_on_bias_sigma
/// and scale_factor_sigma stay 0: a stationary noise fit cannot see constants (AVAR is blind to
/// them, theory.md §7.7), so they are the caller's.
/// @throws InputError unless MODEL has exactly three gyro and three accel axes ("... needs
///   three gyro and three accel axes; the model has G and A"), when its sample_rate_hz is
///   not > 0, or as select_filter_parameters() (e.g. B without τ of the ADEV minimum).
InsSensorNoise ins_sensor_noise(const models::NoiseModel& model, const InsNoiseOptions& options);

/// The axes of MODEL whose B is identified but that hold no multi_gm: with
/// InsNoiseOptions::model_terms_as_states they carry B as one GM (the fallback), in model order.
std::vector<std::string> single_gm_fallback_axes(const models::NoiseModel& model);

}  // namespace imunoise::ins
