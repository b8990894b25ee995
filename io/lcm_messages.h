/// @file
/// @brief Conversions between imunoise's values and its LCM messages (lcmtypes/): IMU samples
/// in, noise model / deviation curves / drift prediction out. Pure conversions; publishing and
/// subscribing live in tools/ (they need the LCM runtime).
#pragma once

#include <cstdint>
#include <imunoise/allan_curve_t.hpp>
#include <imunoise/drift_prediction_t.hpp>
#include <imunoise/imu_sample_t.hpp>
#include <imunoise/noise_model_t.hpp>
#include <string>
#include <vector>

#include "analysis/deviation.h"
#include "pipeline/imu_samples.h"
#include "models/noise_model.h"
#include "pipeline/drift_series.h"

namespace imunoise::io {

/// The first non-finite value among the fields of `m` that a reader uses (rates or increments,
/// temperature when present), as "field[i] (NaN)", or empty. Adds the number of non-finite
/// used values to *count.
std::string first_non_finite_field(const imunoise::imu_sample_t& m, std::int64_t* count);

/// Appends `m` to `samples`: rates, or increments when has_increments (the first sample of an
/// empty `samples` sets `increments` and the source field names; the caller checks that later
/// samples agree). Temperature is kept while every sample has one.
void append_imu_sample(const imunoise::imu_sample_t& m, pipeline::ImuSampleColumns& samples);

/// The noise_model_t of `model` (axes in model order; one GM per axis: the first fitted GM
/// term, else none). `utime_us` is the publication time.
imunoise::noise_model_t noise_model_message(const models::NoiseModel& model, std::int64_t utime_us);

/// The NoiseModel a noise_model_t describes: sensor name, rate, confidence, per axis the five
/// terms (value, interval, identified) and the GM term (no methods, notes or read-offs — the
/// message does not carry them). Throws InputError when the array lengths disagree with
/// n_axes (a message from a broken publisher).
models::NoiseModel noise_model_from_message(const imunoise::noise_model_t& message);

/// The deviation CURVE of axis AXIS_NAME (gyro_… in rad/s, accel_… in m/s^2) as an
/// allan_curve_t: statistic, unit, confidence and per point τ, deviation and interval.
imunoise::allan_curve_t allan_curve_message(const std::string& axis_name,
                                            const analysis::DeviationCurve& curve,
                                            std::int64_t utime_us);

/// Predicted drift (and the recorded one, if any) as a drift_prediction_t: time_s,
/// horizontal_sigma_m = predicted_drms_m, attitude_sigma_rad = predicted_attitude_sigma_rad,
/// actual_horizontal_m = recorded_rms_m (has_actual = false when that is empty), height hold
/// with vertical_sigma_m 0 (the drift analysis holds the vertical channel, theory.md §7.2).
/// Vectors shorter than time_s are padded with zeros.
imunoise::drift_prediction_t drift_prediction_message(const pipeline::DriftSeries& drift,
                                                      std::int64_t utime_us);

}  // namespace imunoise::io
