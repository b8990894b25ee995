/// @file
/// @brief Conversions to and from imunoise's LCM messages (see lcm_messages.h).
#include "io/lcm_messages.h"

#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "common/errors.h"
#include "common/sensor_kind.h"

namespace imunoise::io {

namespace {

/// The four arrays of each IEEE-952 term in a noise_model_t, in NoiseTerm order (const or
/// not with the message), so writing and reading walk the same table.
template <typename Message>
auto term_arrays(Message& m) {
  struct Arrays {
    decltype(&m.quantization) value, ci_low, ci_high;
    decltype(&m.quantization_identified) identified;
  };
  return std::array<Arrays, 5>{{
      {&m.quantization, &m.quantization_ci_low, &m.quantization_ci_high,
       &m.quantization_identified},
      {&m.white_noise, &m.white_noise_ci_low, &m.white_noise_ci_high, &m.white_noise_identified},
      {&m.bias_instability, &m.bias_instability_ci_low, &m.bias_instability_ci_high,
       &m.bias_instability_identified},
      {&m.random_walk, &m.random_walk_ci_low, &m.random_walk_ci_high, &m.random_walk_identified},
      {&m.ramp, &m.ramp_ci_low, &m.ramp_ci_high, &m.ramp_identified},
  }};
}

}  // namespace

std::string first_non_finite_field(const imunoise::imu_sample_t& m, std::int64_t* count) {
  std::string first;
  const auto check = [&](const double* values, int n, const char* field) {
    for (int i = 0; i < n; ++i) {
      if (std::isfinite(values[i])) continue;
      ++*count;
      if (first.empty()) {
        // Built with append() only: GCC 12 raises a false -Wrestrict on `"[" + to_string(…)`.
        first.append(field);
        if (n > 1) first.append("[").append(std::to_string(i)).append("]");
        first.append(" (")
            .append(std::isnan(values[i]) ? "NaN" : (values[i] > 0 ? "+Inf" : "-Inf"))
            .append(")");
      }
    }
  };
  if (m.has_increments) {
    check(m.delta_angle_rad, 3, "delta_angle_rad");
    check(m.delta_velocity_m_per_s, 3, "delta_velocity_m_per_s");
  } else {
    check(m.angular_rate_rad_per_s, 3, "angular_rate_rad_per_s");
    check(m.specific_force_m_per_s2, 3, "specific_force_m_per_s2");
  }
  if (m.has_temperature) check(&m.temperature_degc, 1, "temperature_degc");
  return first;
}

void append_imu_sample(const imunoise::imu_sample_t& m, pipeline::ImuSampleColumns& samples) {
  const bool increments = m.has_increments != 0;
  if (samples.size() == 0) {
    samples.increments = increments;
    // Built with append() only: GCC 12 raises a false -Wrestrict on `"literal" + string`.
    const auto field = [](const char* name, std::size_t a) {
      return std::string(name).append("[").append(std::to_string(a)).append("]");
    };
    for (std::size_t a = 0; a < 3; ++a) {
      samples.source_fields[a] =
          field(increments ? "delta_angle_rad" : "angular_rate_rad_per_s", a);
      samples.source_units[a] = increments ? "rad" : "rad/s";
      samples.source_fields[3 + a] =
          field(increments ? "delta_velocity_m_per_s" : "specific_force_m_per_s2", a);
      samples.source_units[3 + a] = increments ? "m/s" : "m/s^2";
    }
    samples.temperature_field = "temperature_degc";
  }
  samples.utime_us.push_back(m.utime);
  const double* gyro = increments ? m.delta_angle_rad : m.angular_rate_rad_per_s;
  const double* accel = increments ? m.delta_velocity_m_per_s : m.specific_force_m_per_s2;
  for (std::size_t a = 0; a < 3; ++a) {
    samples.values[a].push_back(gyro[a]);
    samples.values[3 + a].push_back(accel[a]);
  }
  pipeline::append_sample_temperature(
      samples, m.has_temperature ? std::optional<double>(m.temperature_degc) : std::nullopt);
}

imunoise::noise_model_t noise_model_message(const models::NoiseModel& model,
                                            std::int64_t utime_us) {
  imunoise::noise_model_t msg{};
  msg.utime = utime_us;
  msg.sensor_name = model.sensor_name;
  msg.sample_rate_hz = model.sample_rate_hz;
  msg.confidence_level = model.confidence;
  msg.n_axes = static_cast<std::int32_t>(model.axes.size());
  const auto terms = term_arrays(msg);

  for (const models::AxisModel& axis : model.axes) {
    msg.axis_names.push_back(axis.name);
    msg.is_gyro.push_back(axis.kind == SensorKind::gyro ? 1 : 0);
    for (std::size_t t = 0; t < 5; ++t) {
      const models::Estimate& e = axis.terms[t];
      terms[t].value->push_back(e.value);
      terms[t].ci_low->push_back(e.ci_low);
      terms[t].ci_high->push_back(e.ci_high);
      terms[t].identified->push_back(e.identified ? 1 : 0);
    }
    // The message carries one GM per axis (the type's documented limit): the first fitted one.
    const bool has_gm = !axis.gauss_markov.empty();
    msg.gm_sigma.push_back(has_gm ? axis.gauss_markov.front().value.sigma : 0.0);
    msg.gm_tau_c_s.push_back(has_gm ? axis.gauss_markov.front().value.tau_c_s : 0.0);
  }
  return msg;
}

models::NoiseModel noise_model_from_message(const imunoise::noise_model_t& msg) {
  const auto n = static_cast<std::size_t>(msg.n_axes < 0 ? 0 : msg.n_axes);
  const auto check = [&](std::size_t size, const char* field) {
    if (size != n) {
      throw InputError(std::string("noise_model_t: ") + field + " has " + std::to_string(size) +
                       " entries, n_axes is " + std::to_string(msg.n_axes));
    }
  };
  check(msg.axis_names.size(), "axis_names");
  check(msg.is_gyro.size(), "is_gyro");
  const auto terms = term_arrays(msg);

  for (const auto& t : terms) {
    check(t.value->size(), "a coefficient array");
    check(t.ci_low->size(), "a ci_low array");
    check(t.ci_high->size(), "a ci_high array");
    check(t.identified->size(), "an identified array");
  }
  check(msg.gm_sigma.size(), "gm_sigma");
  check(msg.gm_tau_c_s.size(), "gm_tau_c_s");

  models::NoiseModel model;
  model.sensor_name = msg.sensor_name;
  model.sample_rate_hz = msg.sample_rate_hz;
  model.confidence = msg.confidence_level;
  for (std::size_t i = 0; i < n; ++i) {
    models::AxisModel axis;
    axis.name = msg.axis_names[i];
    axis.kind = msg.is_gyro[i] != 0 ? SensorKind::gyro : SensorKind::accel;
    for (std::size_t t = 0; t < 5; ++t) {
      models::Estimate& e = axis.terms[t];
      e.value = (*terms[t].value)[i];
      e.ci_low = (*terms[t].ci_low)[i];
      e.ci_high = (*terms[t].ci_high)[i];
      e.identified = (*terms[t].identified)[i] != 0;
    }
    if (msg.gm_sigma[i] > 0.0) {
      models::GaussMarkovEstimate gm;
      gm.value.sigma = msg.gm_sigma[i];
      gm.value.tau_c_s = msg.gm_tau_c_s[i];
      axis.gauss_markov.push_back(gm);
    }
    model.axes.push_back(std::move(axis));
  }
  return model;
}

imunoise::allan_curve_t allan_curve_message(const std::string& axis_name,
                                            const analysis::DeviationCurve& curve,
                                            std::int64_t utime_us) {
  imunoise::allan_curve_t msg{};
  msg.utime = utime_us;
  msg.axis_name = axis_name;
  msg.statistic = std::string(analysis::to_string(curve.type));
  msg.unit =
      std::string(si_rate_unit(sensor_kind_of_channel(axis_name).value_or(SensorKind::gyro)));
  msg.confidence_level = curve.confidence;
  msg.n = static_cast<std::int32_t>(curve.points.size());
  for (const analysis::DeviationPoint& p : curve.points) {
    msg.tau_s.push_back(p.tau_s);
    msg.deviation.push_back(p.value);
    msg.ci_low.push_back(p.ci_low);
    msg.ci_high.push_back(p.ci_high);
  }
  return msg;
}

imunoise::drift_prediction_t drift_prediction_message(const pipeline::DriftSeries& drift,
                                                      std::int64_t utime_us) {
  imunoise::drift_prediction_t msg{};
  msg.utime = utime_us;
  msg.height_hold = 1;
  const std::size_t n = drift.time_s.size();
  msg.n = static_cast<std::int32_t>(n);
  msg.time_s = drift.time_s;
  msg.horizontal_sigma_m = drift.predicted_drms_m;
  msg.vertical_sigma_m.assign(n, 0.0);
  msg.attitude_sigma_rad = drift.predicted_attitude_sigma_rad;
  msg.has_actual = drift.recorded_rms_m.size() == n && n > 0 ? 1 : 0;
  msg.actual_horizontal_m = msg.has_actual ? drift.recorded_rms_m : std::vector<double>(n, 0.0);
  // Arrays the caller left short would make encode() read past them: pad with zeros.
  msg.horizontal_sigma_m.resize(n, 0.0);
  msg.attitude_sigma_rad.resize(n, 0.0);
  return msg;
}

}  // namespace imunoise::io
