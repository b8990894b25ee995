/// @file
/// @brief The continuous state model of a fitted NoiseModel that `imunoise discretize`
/// discretizes: per-axis sensor error states (theory.md §6.1) or the 15/21/27-state INS error
/// state at a stationary nominal (theory.md §6.3, §7.4), every state labelled with its unit;
/// the white-noise inputs beside it (white noise is an input, not a state) and the fitted
/// terms the chosen bias model leaves out. Pure computation composing models/ and ins/.
#pragma once

#include <string>
#include <vector>

#include "ins/error_state_model.h"
#include "models/filter_parameters.h"
#include "models/noise_model.h"
#include "models/state_space.h"

namespace imunoise::pipeline {

/// One white-noise input of one axis, with its per-sample σ at the model's step Δt.
struct WhiteNoiseInput {
  std::string axis;                    ///< gyro_x … accel_z
  SensorKind kind = SensorKind::gyro;  ///< gyro (rad…) or accelerometer (m/s…)
  double density = 0.0;                ///< N [rad/√s | m/s/√s]
  double rate_sigma = 0.0;             ///< σ of a rate sample, N/√Δt [rad/s | m/s²]
  double increment_sigma = 0.0;        ///< σ of an increment over Δt, N·√Δt [rad | m/s]
};

/// A fitted term of one axis that the chosen bias model cannot carry: it is absent from the
/// states (the caller says so).
struct DroppedTerm {
  enum class Kind {
    random_walk,   ///< K, dropped by the Gauss–Markov bias model
    gauss_markov,  ///< B and the fitted GM terms, dropped by the random-walk bias model
  };
  std::string axis;  ///< gyro_x … accel_z
  Kind kind = Kind::random_walk;
};

/// A continuous state model with what it leaves beside it.
struct SensorStates {
  models::ContinuousStateModel continuous;   ///< states named NAME_UNIT
  std::vector<WhiteNoiseInput> white_noise;  ///< one per axis, in the model's axis order
  std::vector<DroppedTerm> dropped;          ///< in axis order
  std::string description;                   ///< one line saying what the states are
};

/// Per-axis sensor error states of every axis of MODEL (theory.md §6.1), block-diagonal in
/// axis order: an RW bias (BIAS random_walk or both, K > 0), GM biases (BIAS gauss_markov or
/// both: each fitted GM term — its σ the upper interval end when options.conservative — and B
/// as one GM by options.gm_convention), the ramp as [bias, slope] (R > 0). The terms of
/// models::axis_filter_parameters(axis, OPTIONS) with options.axis = each; DT_S (> 0) is the
/// step of the white-noise σ.
/// @throws InputError as models::axis_filter_parameters().
SensorStates sensor_states(const models::NoiseModel& model, ins::BiasModel bias,
                           const models::FilterParameterOptions& options, double dt_s);

/// The INS error-state model of ins_states().
struct InsStateOptions {
  ins::ErrorStateOptions error_state;  ///< bias model, scale factors, height hold
  /// The stationary nominal as the user gives it: latitude [deg], height [m], heading [deg]
  /// (converted once with units::kDeg; the description quotes these values).
  double latitude_deg = 45.0, height_m = 0.0, heading_deg = 0.0;
  /// Scale-factor σ of every gyro and accel axis [1] (not observable from a stationary record).
  double gyro_scale_factor_sigma = 0.0, accel_scale_factor_sigma = 0.0;
  double dt_s = 0.0;  ///< step of the white-noise σ [s], > 0
};

/// The terms of one INS axis that BIAS cannot carry (ins_error_state_model drops them): the
/// GM with the random-walk model, K with the Gauss–Markov model.
std::vector<DroppedTerm> dropped_terms(const ins::SensorAxisNoise& noise, ins::BiasModel bias,
                                       const std::string& axis);

/// The INS error state (theory.md §6.3, §7.4) at stationary_nominal(OPTIONS) of NOISE (from
/// ins::ins_sensor_noise) with OPTIONS' scale-factor σ: white noise gyro x y z then accel x y
/// z, dropped terms per axis gyro then accel.
/// @throws InputError as ins::stationary_nominal() and ins::ins_error_state_model().
SensorStates ins_states(ins::InsSensorNoise noise, const InsStateOptions& options);

}  // namespace imunoise::pipeline
