#include "pipeline/sensor_states.h"

#include <algorithm>
#include <utility>

#include "common/number_text.h"
#include "common/units.h"
#include "pipeline/recording.h"

namespace imunoise::pipeline {

namespace {

/// Renames the states of BLOCK: NAME → NAME_UNIT (state_space labels carry no unit).
models::ContinuousStateModel with_units(models::ContinuousStateModel block,
                                        const std::vector<std::string>& units) {
  for (std::size_t i = 0; i < block.state_names.size() && i < units.size(); ++i)
    block.state_names[i] += "_" + units[i];
  return block;
}

/// Fills the per-sample σ of every white-noise input at DT_S (after the states are built, so
/// a bad coefficient fails there first, as the state constructors word it).
void set_white_noise_sigmas(std::vector<WhiteNoiseInput>& inputs, double dt_s) {
  for (WhiteNoiseInput& w : inputs) {
    w.rate_sigma = models::white_noise_rate_sigma(w.density, dt_s);
    w.increment_sigma = models::white_noise_increment_sigma(w.density, dt_s);
  }
}

}  // namespace

SensorStates sensor_states(const models::NoiseModel& model, ins::BiasModel bias,
                           const models::FilterParameterOptions& options, double dt_s) {
  SensorStates out;
  out.description = "per-axis sensor error states (theory.md §6.1); white noise is an input";
  std::vector<models::ContinuousStateModel> blocks;
  const bool rw = bias != ins::BiasModel::gauss_markov, gm = bias != ins::BiasModel::random_walk;
  for (const auto& axis : model.axes) {
    const auto p = models::axis_filter_parameters(axis, options);
    const std::string rate_unit(rate_unit_suffix(axis.kind));
    const std::string ramp_unit = axis.kind == SensorKind::gyro ? "rad_per_s2" : "m_per_s3";
    out.white_noise.push_back({axis.name, axis.kind, p.white_noise});
    if (rw && p.random_walk > 0.0)
      blocks.push_back(with_units(models::random_walk_state(p.random_walk, axis.name + "_bias_rw"),
                                  {rate_unit}));
    if (!rw && p.random_walk > 0.0)
      out.dropped.push_back({axis.name, DroppedTerm::Kind::random_walk});
    if (gm) {
      for (std::size_t j = 0; j < axis.gauss_markov.size(); ++j) {
        const auto& g = axis.gauss_markov[j].value;
        const double sigma =
            options.conservative ? std::max(g.sigma, axis.gauss_markov[j].sigma_ci_high) : g.sigma;
        blocks.push_back(
            with_units(models::gauss_markov_state(sigma, g.tau_c_s,
                                                  axis.name + "_bias_gm" + std::to_string(j + 1)),
                       {rate_unit}));
      }
      if (p.bias_instability > 0.0)
        blocks.push_back(with_units(models::gauss_markov_state(p.bias_gm.sigma, p.bias_gm.tau_c_s,
                                                               axis.name + "_bias_instability_gm"),
                                    {rate_unit}));
    } else if (p.bias_instability > 0.0 || !axis.gauss_markov.empty()) {
      out.dropped.push_back({axis.name, DroppedTerm::Kind::gauss_markov});
    }
    if (p.ramp > 0.0)
      blocks.push_back(
          with_units(models::ramp_state(p.ramp, axis.name + "_ramp"), {rate_unit, ramp_unit}));
  }
  out.continuous = models::block_diagonal(blocks);
  set_white_noise_sigmas(out.white_noise, dt_s);
  return out;
}

std::vector<DroppedTerm> dropped_terms(const ins::SensorAxisNoise& noise, ins::BiasModel bias,
                                       const std::string& axis) {
  std::vector<DroppedTerm> dropped;
  if (bias == ins::BiasModel::random_walk && noise.bias_gm.sigma > 0.0)
    dropped.push_back({axis, DroppedTerm::Kind::gauss_markov});
  if (bias == ins::BiasModel::gauss_markov && noise.random_walk > 0.0)
    dropped.push_back({axis, DroppedTerm::Kind::random_walk});
  return dropped;
}

SensorStates ins_states(ins::InsSensorNoise noise, const InsStateOptions& options) {
  SensorStates out;
  const ins::BiasModel bias = options.error_state.bias;
  const auto add_dropped = [&](const ins::SensorAxisNoise& n, const char* axis) {
    for (DroppedTerm& d : dropped_terms(n, bias, axis)) out.dropped.push_back(std::move(d));
  };
  for (std::size_t i = 0; i < 3; ++i) {
    noise.gyro[i].scale_factor_sigma = options.gyro_scale_factor_sigma;
    noise.accel[i].scale_factor_sigma = options.accel_scale_factor_sigma;
    add_dropped(noise.gyro[i], kImuChannelNames[i]);
    add_dropped(noise.accel[i], kImuChannelNames[3 + i]);
  }
  for (std::size_t i = 0; i < 3; ++i)
    out.white_noise.push_back({kImuChannelNames[i], SensorKind::gyro, noise.gyro[i].white_noise});
  for (std::size_t i = 0; i < 3; ++i)
    out.white_noise.push_back(
        {kImuChannelNames[3 + i], SensorKind::accel, noise.accel[i].white_noise});
  const auto nominal = ins::stationary_nominal(options.latitude_deg * units::kDeg, options.height_m,
                                               options.heading_deg * units::kDeg);
  out.continuous = ins::ins_error_state_model(nominal, noise, options.error_state);
  out.description = "INS error state (theory.md §6.3, §7.4), stationary at latitude " +
                    shortest_number_text(options.latitude_deg) + " deg, height " +
                    shortest_number_text(options.height_m) + " m, heading " +
                    shortest_number_text(options.heading_deg) + " deg" +
                    (options.error_state.height_hold ? ", vertical channel held" : "");
  set_white_noise_sigmas(out.white_noise, options.dt_s);
  return out;
}

}  // namespace imunoise::pipeline
