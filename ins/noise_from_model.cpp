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

bool has_single_gm_fallback(const models::AxisModel& axis) {
  return axis.terms[NoiseTerm::bias_instability].value > 0.0 && axis.multi_gm.empty();
}

SensorAxisNoise axis_noise(const models::SensorAxisParameters& p, const models::NoiseModel& model,
                           bool model_terms) {
  SensorAxisNoise n;
  n.white_noise = p.white_noise;
  n.random_walk = p.random_walk;
  n.bias_gm = p.bias_gm;
  if (!model_terms) return n;
  const models::AxisModel* axis = model.find_axis(p.from);
  if (axis == nullptr) return n;
  // B as its multi-GM terms (or, without them, the single GM select_filter_parameters chose
  // for B); every fitted GM term as its own state beside them (theory.md §4.4, §6.3).
  if (!has_single_gm_fallback(*axis)) n.bias_gm = {};
  n.gm_terms = axis->multi_gm;
  n.bias_instability_terms = axis->multi_gm.size();
  for (const models::GaussMarkovEstimate& gm : axis->gauss_markov) n.gm_terms.push_back(gm.value);
  n.ramp = axis->terms[NoiseTerm::ramp].value;
  n.quantization = axis->terms[NoiseTerm::quantization].value;
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
    noise.gyro[i] = axis_noise(params.gyro->axes[i], model, options.model_terms_as_states);
    noise.accel[i] = axis_noise(params.accel->axes[i], model, options.model_terms_as_states);
  }
  return noise;
}

std::vector<std::string> single_gm_fallback_axes(const models::NoiseModel& model) {
  std::vector<std::string> out;
  for (const models::AxisModel& axis : model.axes)
    if (has_single_gm_fallback(axis)) out.push_back(axis.name);
  return out;
}

}  // namespace imunoise::ins
