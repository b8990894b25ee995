/// @file
/// @brief NoiseModel → InsSensorNoise (see noise_from_model.h; theory.md §4.4, §6.3).
#include "ins/noise_from_model.h"

#include <cmath>
#include <string>

#include "common/errors.h"
#include "common/number_text.h"
#include "models/filter_parameters.h"

namespace imunoise::ins {
namespace {

SensorAxisNoise axis_noise(const models::SensorAxisParameters& p) {
  SensorAxisNoise n;
  n.white_noise = p.white_noise;
  n.random_walk = p.random_walk;
  n.bias_gm = p.bias_gm;
  return n;
}

}  // namespace

InsSensorNoise ins_sensor_noise(const models::NoiseModel& model, const InsNoiseOptions& options) {
  int gyro_axes = 0, accel_axes = 0;
  for (const auto& axis : model.axes) (axis.kind == SensorKind::gyro ? gyro_axes : accel_axes) += 1;
  IMUNOISE_CHECK(gyro_axes == 3 && accel_axes == 3, InputError,
                 "ins_sensor_noise: the INS error state needs three gyro and three accel axes; "
                 "the model has " +
                     std::to_string(gyro_axes) + " and " + std::to_string(accel_axes));
  IMUNOISE_CHECK(model.sample_rate_hz > 0.0 && std::isfinite(model.sample_rate_hz), InputError,
                 "ins_sensor_noise: the model's sample_rate_hz must be > 0 (got " +
                     shortest_number_text(model.sample_rate_hz) + ")");
  models::FilterParameterOptions select;
  select.axis = models::AxisChoice::each;
  select.conservative = options.conservative;
  select.gm_convention = options.gm_convention;
  select.filter_rate_hz = model.sample_rate_hz;
  select.setting_names = options.setting_names;
  const models::FilterParameters params = models::select_filter_parameters(model, select);
  InsSensorNoise noise;
  for (int i = 0; i < 3; ++i) {
    noise.gyro[i] = axis_noise(params.gyro->axes[i]);
    noise.accel[i] = axis_noise(params.accel->axes[i]);
  }
  return noise;
}

}  // namespace imunoise::ins
