/// @file
/// @brief The datasheet spec of `imunoise fleet` (see fleet_spec.h).
#include "io/fleet_spec.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/yaml_scalar.h"
#include "models/datasheet_units.h"

namespace imunoise::io {

namespace {

[[noreturn]] void fail(const std::string& source, const YAML::Mark& mark, const std::string& what) {
  throw InputError(located_message(source, mark.line + 1, mark.column + 1, what));
}

/// The SI value of one datasheet-unit maximum: value / (SI → datasheet factor).
double si_of(double datasheet_value, SensorKind sensor, NoiseTerm term) {
  return datasheet_value / models::datasheet_unit(term, sensor).factor;
}

}  // namespace

std::string_view fleet_spec_key(SensorKind sensor, NoiseTerm term) {
  // The units of models::datasheet_unit, term by term (Q, N, B, K, R).
  static constexpr std::string_view kGyro[] = {"quantization_urad", "arw_deg_per_sqrt_h",
                                               "bias_instability_deg_per_h",
                                               "rrw_deg_per_h_per_sqrt_h", "ramp_deg_per_h2"};
  static constexpr std::string_view kAccel[] = {"quantization_mm_per_s", "vrw_ug_per_sqrt_hz",
                                                "bias_instability_ug",
                                                "rw_m_per_s_per_h_per_sqrt_h", "ramp_ug_per_h"};
  const auto t = static_cast<std::size_t>(term);
  return sensor == SensorKind::gyro ? kGyro[t] : kAccel[t];
}

pipeline::FleetSpec parse_fleet_spec(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    fail(source, e.mark, "YAML syntax: " + e.msg);
  }
  if (!root.IsMap()) fail(source, root.Mark(), "a fleet spec is a mapping (name, gyro, accel)");
  pipeline::FleetSpec spec;
  std::set<std::string> seen;
  for (const auto& item : root) {
    const std::string key = item.first.Scalar();
    if (!seen.insert(key).second) fail(source, item.first.Mark(), "'" + key + "' given twice");
    if (key == "name") {
      if (!item.second.IsScalar()) fail(source, item.second.Mark(), "name: expected text");
      spec.name = item.second.Scalar();
      continue;
    }
    std::optional<SensorKind> sensor;
    for (const SensorKind k : kSensorKinds)
      if (key == sensor_name(k)) sensor = k;
    if (!sensor) fail(source, item.first.Mark(), "unknown key '" + key + "' (name, gyro, accel)");
    if (!item.second.IsMap())
      fail(source, item.second.Mark(), key + ": expected a mapping of term maxima");
    std::set<std::string> terms_seen;
    for (const auto& term_item : item.second) {
      const std::string term_key = term_item.first.Scalar();
      if (!terms_seen.insert(term_key).second)
        fail(source, term_item.first.Mark(), key + "." + term_key + " given twice");
      std::optional<NoiseTerm> term;
      std::string known;
      for (NoiseTerm t : kNoiseTerms) {
        known.append(known.empty() ? "" : ", ").append(fleet_spec_key(*sensor, t));
        if (term_key == fleet_spec_key(*sensor, t)) term = t;
      }
      if (!term)
        fail(source, term_item.first.Mark(),
             key + ": unknown key '" + term_key + "' (one of " + known + ")");
      double value = 0.0;
      try {
        value = term_item.second.as<double>();
      } catch (const YAML::Exception&) {
        fail(source, term_item.second.Mark(), key + "." + term_key + ": expected a number");
      }
      if (!std::isfinite(value) || !(value > 0.0))
        fail(source, term_item.second.Mark(),
             key + "." + term_key + ": the maximum must be finite and > 0 (got " +
                 significant_number_text(value) + ")");
      spec.limits.push_back({*sensor, *term, si_of(value, *sensor, *term)});
    }
  }
  if (spec.limits.empty())
    fail(source, root.Mark(), "the spec gives no maximum (gyro: or accel: with term keys)");
  return spec;
}

pipeline::FleetSpec read_fleet_spec(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(located_message(path, 0, 0, "cannot open the spec file"));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_fleet_spec(text.str(), path);
}

std::string fleet_spec_text(const pipeline::FleetSpec& spec) {
  std::ostringstream out;
  out << "# imunoise fleet spec: per sensor and term a maximum in datasheet units\n";
  out << "name: " << yaml_double_quoted(spec.name) << "\n";
  for (const SensorKind sensor : kSensorKinds) {
    bool any = false;
    for (const pipeline::SpecLimit& l : spec.limits) {
      if (l.sensor != sensor) continue;
      if (!any) out << sensor_name(sensor) << ":\n";
      any = true;
      out << "  " << fleet_spec_key(sensor, l.term) << ": "
          << shortest_number_text(l.max_si * models::datasheet_unit(l.term, sensor).factor) << "\n";
    }
  }
  return out.str();
}

}  // namespace imunoise::io
