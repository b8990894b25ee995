/// @file
/// @brief Reader of the simulator's YAML model file (io/simulation_model.h): key tables with
/// their unit factors, located errors, per-axis overrides.
#include "io/simulation_model.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <span>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/units.h"

namespace imunoise::io {

namespace {

/// A key naming a quantity in one unit: value × factor = SI.
struct UnitKey {
  std::string_view key;
  double factor = 1.0;
};

/// One quantity and the keys that may give it, the SI key first (unused slots empty).
struct Quantity {
  std::string_view what;  ///< for messages
  std::array<UnitKey, 3> keys;
  bool may_be_negative = false;
};

/// The scalar fields of a SimulationAxis.
enum class Field {
  kQuantization,
  kWhiteNoise,
  kBiasInstability,
  kRandomWalk,
  kRamp,
  kBias,
  kSignal,
  kOutputLsb
};

/// The field of AXIS (a SimulationAxis, const or not).
template <typename Axis>
auto& field_of(Axis& axis, Field field) {
  switch (field) {
    case Field::kQuantization:
      return axis.coefficients.quantization;
    case Field::kWhiteNoise:
      return axis.coefficients.white_noise;
    case Field::kBiasInstability:
      return axis.coefficients.bias_instability;
    case Field::kRandomWalk:
      return axis.coefficients.random_walk;
    case Field::kRamp:
      return axis.coefficients.ramp;
    case Field::kBias:
      return axis.bias;
    case Field::kSignal:
      return axis.signal;
    case Field::kOutputLsb:
      return axis.output_lsb;
  }
  return axis.bias;  // unreachable
}

struct ScalarTerm {
  Field field;
  Quantity quantity;
};

/// The keys of one sensor. Factors: common/units.h, derived from theory.md §1.3.
struct SensorSchema {
  std::string_view sensor;  ///< "gyro" or "accel"
  std::array<ScalarTerm, 8> scalars;
  Quantity gm_sigma;        ///< σ inside a gauss_markov item
  Quantity sine_amplitude;  ///< amplitude inside a sinusoids item
};

using namespace units;

const SensorSchema kGyro{
    "gyro",
    {{{Field::kQuantization,
       {"quantization Q",
        {{{"quantization_rad", 1.0},
          {"quantization_deg", kDeg},
          {"quantization_urad", kMicroradian}}}}},
      {Field::kWhiteNoise,
       {"ARW N",
        {{{"arw_rad_per_sqrt_s", 1.0},
          {"arw_deg_per_sqrt_h", kDegPerSqrtHour},
          {"arw_deg_per_s_per_sqrt_hz", kDegPerSPerSqrtHz}}}}},
      {Field::kBiasInstability,
       {"bias instability B",
        {{{"bias_instability_rad_per_s", 1.0},
          {"bias_instability_deg_per_h", kDegPerHour},
          {"bias_instability_deg_per_s", kDegPerS}}}}},
      {Field::kRandomWalk,
       {"rate random walk K",
        {{{"rrw_rad_per_s_sqrt_s", 1.0},
          {"rrw_deg_per_h_per_sqrt_h", kDegPerHourPerSqrtHour},
          {"rrw_deg_per_s_per_sqrt_s", kDegPerSPerSqrtS}}}}},
      {Field::kRamp,
       {"rate ramp R",
        {{{"ramp_rad_per_s2", 1.0},
          {"ramp_deg_per_h2", kDegPerHourSquared},
          {"ramp_deg_per_s_per_h", kDegPerSPerHour}}},
        true}},
      {Field::kBias,
       {"constant bias",
        {{{"bias_rad_per_s", 1.0}, {"bias_deg_per_h", kDegPerHour}, {"bias_deg_per_s", kDegPerS}}},
        true}},
      {Field::kSignal,
       {"true angular rate",
        {{{"angular_rate_rad_per_s", 1.0}, {"angular_rate_deg_per_s", kDegPerS}}},
        true}},
      {Field::kOutputLsb,
       {"output LSB", {{{"output_lsb_rad_per_s", 1.0}, {"output_lsb_deg_per_s", kDegPerS}}}}}}},
    {"Gauss-Markov sigma",
     {{{"sigma_rad_per_s", 1.0}, {"sigma_deg_per_h", kDegPerHour}, {"sigma_deg_per_s", kDegPerS}}}},
    {"sinusoid amplitude",
     {{{"amplitude_rad_per_s", 1.0},
       {"amplitude_deg_per_h", kDegPerHour},
       {"amplitude_deg_per_s", kDegPerS}}},
     true}};

const SensorSchema kAccel{
    "accel",
    {{{Field::kQuantization, {"quantization Q", {{{"quantization_m_per_s", 1.0}}}}},
      {Field::kWhiteNoise,
       {"VRW N",
        {{{"vrw_m_per_s_sqrt_s", 1.0},
          {"vrw_m_per_s_per_sqrt_h", kMPerSPerSqrtHour},
          {"vrw_ug_per_sqrt_hz", kMicroGPerSqrtHz}}}}},
      {Field::kBiasInstability,
       {"bias instability B",
        {{{"bias_instability_m_per_s2", 1.0},
          {"bias_instability_ug", kMicroG},
          {"bias_instability_mg", kMilliG}}}}},
      {Field::kRandomWalk,
       {"acceleration random walk K",
        {{{"rw_m_per_s2_sqrt_s", 1.0},
          {"rw_m_per_s_per_h_per_sqrt_h", kMPerSPerHourPerSqrtHour},
          {"rw_ug_per_sqrt_s", kMicroGPerSqrtS}}}}},
      {Field::kRamp,
       {"acceleration ramp R",
        {{{"ramp_m_per_s3", 1.0}, {"ramp_m_per_s2_per_h", kMPerS2PerHour}}},
        true}},
      {Field::kBias,
       {"constant bias",
        {{{"bias_m_per_s2", 1.0}, {"bias_mg", kMilliG}, {"bias_ug", kMicroG}}},
        true}},
      {Field::kSignal,
       {"true specific force",
        {{{"specific_force_m_per_s2", 1.0}, {"specific_force_g", kG}}},
        true}},
      {Field::kOutputLsb,
       {"output LSB", {{{"output_lsb_m_per_s2", 1.0}, {"output_lsb_mg", kMilliG}}}}}}},
    {"Gauss-Markov sigma",
     {{{"sigma_m_per_s2", 1.0}, {"sigma_ug", kMicroG}, {"sigma_mg", kMilliG}}}},
    {"sinusoid amplitude",
     {{{"amplitude_m_per_s2", 1.0}, {"amplitude_ug", kMicroG}, {"amplitude_mg", kMilliG}}},
     true}};

const Quantity kCorrelationTime{"correlation time", {{{"tau_c_s", 1.0}, {"tau_c_h", kHour}}}};
const Quantity kFrequency{"frequency", {{{"frequency_hz", 1.0}}}};
const Quantity kPhase{"phase", {{{"phase_rad", 1.0}, {"phase_deg", kDeg}}}, true};

constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

const SensorSchema& schema_of(SensorKind kind) { return kind == SensorKind::gyro ? kGyro : kAccel; }

/// "a|b|c": the keys of Q.
std::string alternatives(const Quantity& q) {
  std::string text;
  for (const UnitKey& k : q.keys) {
    if (k.key.empty()) continue;
    if (!text.empty()) text += "|";
    text += k.key;
  }
  return text;
}

/// The factor of KEY if it names Q.
std::optional<double> factor_of(const Quantity& q, std::string_view key) {
  for (const UnitKey& k : q.keys) {
    if (!k.key.empty() && k.key == key) return k.factor;
  }
  return std::nullopt;
}

/// Which of QUANTITIES a mapping has set, and by which key (for the duplicate message).
class SeenTerms {
 public:
  explicit SeenTerms(std::size_t count) : keys_(count), lines_(count, 0) {}
  /// The key that already set quantity I, or "" if none; records KEY at LINE otherwise.
  std::pair<std::string, int> claim(std::size_t i, const std::string& key, int line) {
    if (!keys_[i].empty()) return {keys_[i], lines_[i]};
    keys_[i] = key;
    lines_[i] = line;
    return {"", 0};
  }

 private:
  std::vector<std::string> keys_;
  std::vector<int> lines_;
};

/// Reads one YAML document with file:line:col and the key path in every error.
class ModelParser {
 public:
  explicit ModelParser(std::string source) : source_(std::move(source)) {}

  SimulationModelFile parse(const YAML::Node& root) const {
    SimulationModelFile model;
    model.source = source_;
    if (!root.IsMap()) fail(root, "model", "expected a mapping of keys (name, gyro, accel, …)");
    constexpr std::array<std::string_view, 5> kRootKeys{"name", "sample_rate_hz", "flicker_band_s",
                                                        "gyro", "accel"};
    SeenTerms seen(kRootKeys.size());
    for (const auto& entry : root) {
      const std::string key = key_text(entry.first, "model");
      const YAML::Node& value = entry.second;
      const auto known = std::find(kRootKeys.begin(), kRootKeys.end(), key);
      if (known == kRootKeys.end()) {
        fail(entry.first, key,
             "unknown key (expected name, sample_rate_hz, flicker_band_s, gyro, accel)");
      }
      claim_once(seen, static_cast<std::size_t>(known - kRootKeys.begin()), entry.first, key, key);
      if (key == "name") {
        if (!value.IsScalar()) fail(value, key, "expected a string");
        model.name = value.Scalar();
        std::replace(model.name.begin(), model.name.end(), '\n', ' ');  // one header line
      } else if (key == "sample_rate_hz") {
        model.sample_rate_hz = positive(value, key);
      } else if (key == "flicker_band_s") {
        if (!value.IsSequence() || value.size() != 2) {
          fail(value, key, "expected [tau_min_s, tau_max_s]");
        }
        const double low = positive(value[0], key + "[0]");
        const double high = positive(value[1], key + "[1]");
        if (!(high > low)) fail(value, key, "expected tau_min_s < tau_max_s");
        model.flicker_band = models::FlickerBand{low, high};
      } else if (key == "gyro") {
        read_sensor(value, kGyro, model.gyro);
      } else {
        read_sensor(value, kAccel, model.accel);
      }
    }
    return model;
  }

 private:
  [[noreturn]] void fail(const YAML::Node& node, const std::string& path,
                         const std::string& what) const {
    const YAML::Mark mark = node.Mark();
    const std::string message = path + ": " + what;
    if (mark.is_null()) throw InputError(located_message(source_, 0, 0, message));
    throw InputError(located_message(source_, mark.line + 1, mark.column + 1, message));
  }

  /// The text of a mapping key, which must be a plain scalar.
  std::string key_text(const YAML::Node& key, const std::string& where) const {
    if (!key.IsScalar()) fail(key, where, "keys must be plain names");
    return key.Scalar();
  }

  /// Marks slot I of a mapping as set by KEY_NODE; a second setter is an error naming both
  /// keys. WHAT names the term in that message ("" for plain keys).
  void claim_once(SeenTerms& seen, std::size_t i, const YAML::Node& key_node,
                  const std::string& key, const std::string& path,
                  std::string_view what = {}) const {
    const int line = key_node.Mark().is_null() ? 0 : key_node.Mark().line + 1;
    const auto [previous, previous_line] = seen.claim(i, key, line);
    if (previous.empty()) return;
    std::string where;
    if (previous_line > 0) {
      where.append(" (line ").append(std::to_string(previous_line)).append(")");
    }
    if (previous == key) fail(key_node, path, "given twice in one mapping" + where);
    std::string message = "sets the same term";
    if (!what.empty()) message.append(" (").append(what).append(")");
    message.append(" as '").append(previous).append("'").append(where);
    message.append("; give each term once, in one unit: ").append(key).append(" or ");
    fail(key_node, path, message.append(previous));
  }

  double number(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar()) fail(node, path, "expected a number");
    const std::string& text = node.Scalar();
    double value = 0.0;
    const char* begin = text.data();
    const char* end = text.data() + text.size();
    if (begin != end && *begin == '+') ++begin;  // YAML allows "+1.5"
    const auto [ptr, ec] = std::from_chars(begin, end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
      fail(node, path, "expected a finite number, got '" + text + "'");
    }
    return value;
  }

  double positive(const YAML::Node& node, const std::string& path) const {
    const double value = number(node, path);
    if (!(value > 0.0)) fail(node, path, "must be > 0, got " + node.Scalar());
    return value;
  }

  /// The value of Q given under a key with FACTOR, in SI, range-checked in the unit given.
  double quantity_value(const YAML::Node& node, const std::string& path, const Quantity& q,
                        double factor, bool strictly_positive = false) const {
    const double value = strictly_positive ? positive(node, path) : number(node, path);
    if (!q.may_be_negative && value < 0.0) fail(node, path, "must be >= 0, got " + node.Scalar());
    const double si = value * factor;
    if (!std::isfinite(si)) fail(node, path, "out of range in SI units");
    return si;
  }

  void read_sensor(const YAML::Node& node, const SensorSchema& schema,
                   std::array<SimulationAxis, 3>& axes) const {
    const std::string where(schema.sensor);
    if (!node.IsMap()) fail(node, where, "expected a mapping of term keys");
    SimulationAxis shared;
    read_terms(node, schema, where, shared, true);
    for (std::size_t a = 0; a < 3; ++a) {
      axes[a] = shared;
      const YAML::Node axis = node[std::string(kAxes[a])];
      if (!axis) continue;
      const std::string axis_where = where + "." + std::string(kAxes[a]);
      if (!axis.IsMap()) fail(axis, axis_where, "expected a mapping of term keys");
      read_terms(axis, schema, axis_where, axes[a], false);
    }
  }

  /// Sets the terms present in NODE on AXIS (per-axis values replace the shared ones).
  void read_terms(const YAML::Node& node, const SensorSchema& schema, const std::string& where,
                  SimulationAxis& axis, bool allow_axes) const {
    // Slots: the scalar terms, then gauss_markov, sinusoids, x, y, z.
    const std::size_t kGaussMarkovSlot = schema.scalars.size();
    SeenTerms seen(schema.scalars.size() + 5);
    for (const auto& entry : node) {
      const std::string key = key_text(entry.first, where);
      const std::string path = where + "." + key;
      const YAML::Node& value = entry.second;
      if (allow_axes) {
        const auto axis_it = std::find(kAxes.begin(), kAxes.end(), key);
        if (axis_it != kAxes.end()) {
          claim_once(seen, kGaussMarkovSlot + 2 + static_cast<std::size_t>(axis_it - kAxes.begin()),
                     entry.first, key, path);
          continue;  // read by read_sensor()
        }
      }
      bool found = false;
      for (std::size_t i = 0; i < schema.scalars.size() && !found; ++i) {
        const ScalarTerm& term = schema.scalars[i];
        const std::optional<double> factor = factor_of(term.quantity, key);
        if (!factor) continue;
        claim_once(seen, i, entry.first, key, path, term.quantity.what);
        field_of(axis, term.field) = quantity_value(value, path, term.quantity, *factor);
        found = true;
      }
      if (found) continue;
      if (key == "gauss_markov") {
        claim_once(seen, kGaussMarkovSlot, entry.first, key, path);
        axis.coefficients.gauss_markov = read_gauss_markov(value, path, schema);
      } else if (key == "sinusoids") {
        claim_once(seen, kGaussMarkovSlot + 1, entry.first, key, path);
        axis.coefficients.sinusoids = read_sinusoids(value, path, schema);
      } else {
        std::string expected;
        for (const ScalarTerm& term : schema.scalars) {
          expected += alternatives(term.quantity) + ", ";
        }
        expected += "gauss_markov, sinusoids";
        if (allow_axes) expected += ", x, y, z";
        fail(entry.first, path, "unknown key (expected one of: " + expected + ")");
      }
    }
  }

  /// Values of the FIELDS of each mapping in the list NODE (nullopt where absent).
  template <std::size_t N>
  std::vector<std::array<std::optional<double>, N>> read_items(
      const YAML::Node& node, const std::string& path, const std::array<const Quantity*, N>& fields,
      const std::array<bool, N>& required, const std::array<bool, N>& strictly_positive) const {
    if (!node.IsSequence()) fail(node, path, "expected a list of mappings");
    std::vector<std::array<std::optional<double>, N>> items;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node item = node[i];
      const std::string item_path = path + "[" + std::to_string(i) + "]";
      if (!item.IsMap()) fail(item, item_path, "expected a mapping");
      std::array<std::optional<double>, N> values;
      SeenTerms seen(N);
      for (const auto& entry : item) {
        const std::string key = key_text(entry.first, item_path);
        const std::string key_path = item_path + "." + key;
        bool found = false;
        for (std::size_t f = 0; f < N && !found; ++f) {
          const std::optional<double> factor = factor_of(*fields[f], key);
          if (!factor) continue;
          claim_once(seen, f, entry.first, key, key_path, fields[f]->what);
          values[f] =
              quantity_value(entry.second, key_path, *fields[f], *factor, strictly_positive[f]);
          found = true;
        }
        if (!found) {
          std::string list;
          for (const Quantity* q : fields) list += (list.empty() ? "" : ", ") + alternatives(*q);
          fail(entry.first, key_path, "unknown key (expected " + list + ")");
        }
      }
      for (std::size_t f = 0; f < N; ++f) {
        if (required[f] && !values[f]) {
          fail(item, item_path, "missing key " + alternatives(*fields[f]));
        }
      }
      items.push_back(values);
    }
    return items;
  }

  std::vector<GaussMarkov> read_gauss_markov(const YAML::Node& node, const std::string& path,
                                             const SensorSchema& schema) const {
    std::vector<GaussMarkov> terms;
    for (const auto& v : read_items<2>(node, path, {&schema.gm_sigma, &kCorrelationTime},
                                       {true, true}, {false, true})) {
      terms.push_back(GaussMarkov{*v[0], *v[1]});
    }
    return terms;
  }

  std::vector<Sinusoid> read_sinusoids(const YAML::Node& node, const std::string& path,
                                       const SensorSchema& schema) const {
    std::vector<Sinusoid> terms;
    for (const auto& v : read_items<3>(node, path, {&schema.sine_amplitude, &kFrequency, &kPhase},
                                       {true, true, false}, {false, false, false})) {
      terms.push_back(Sinusoid{*v[0], *v[1], v[2].value_or(0.0)});
    }
    return terms;
  }

  std::string source_;
};

SimulationModelFile parse_root(const std::string& source, const YAML::Node& root) {
  try {
    return ModelParser(source).parse(root);
  } catch (const YAML::Exception& e) {  // e.g. a conversion we did not anticipate
    throw InputError(located_message(source, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
}

}  // namespace

SimulationModelFile load_simulation_model(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(located_message(path, 0, 0, "cannot open the model file"));
  } catch (const YAML::Exception& e) {
    throw InputError(
        located_message(path, e.mark.line + 1, e.mark.column + 1, "YAML syntax: " + e.msg));
  }
  return parse_root(path, root);
}

SimulationModelFile parse_simulation_model(const std::string& yaml_text,
                                           const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw InputError(
        located_message(source_name, e.mark.line + 1, e.mark.column + 1, "YAML syntax: " + e.msg));
  }
  return parse_root(source_name, root);
}

models::ChannelNoiseModel channel_model(const SimulationAxis& axis) {
  models::ChannelNoiseModel model = models::channel_model_from(axis.coefficients);
  model.constant = axis.bias + axis.signal;
  model.output_lsb = axis.output_lsb;
  return model;
}

std::string si_terms_text(const SimulationAxis& axis, SensorKind kind) {
  // Built with append() only: GCC 12 raises a false -Wrestrict on `" " + std::string(…)`.
  const SensorSchema& schema = schema_of(kind);
  std::string text;
  const auto add = [&text](std::string_view key, double value) {
    text.append(key).append("=").append(shortest_number_text(value));
  };
  for (const ScalarTerm& term : schema.scalars) {
    const double value = field_of(axis, term.field);
    if (value == 0.0) continue;
    text.append(" ");
    add(term.quantity.keys[0].key, value);
  }
  for (const GaussMarkov& gm : axis.coefficients.gauss_markov) {
    text.append(" gauss_markov{");
    add(schema.gm_sigma.keys[0].key, gm.sigma);
    text.append(" ");
    add("tau_c_s", gm.tau_c_s);
    text.append("}");
  }
  for (const Sinusoid& s : axis.coefficients.sinusoids) {
    text.append(" sinusoid{");
    add(schema.sine_amplitude.keys[0].key, s.amplitude);
    text.append(" ");
    add("frequency_hz", s.frequency_hz);
    text.append(" ");
    add("phase_rad", s.phase_rad);
    text.append("}");
  }
  return text.empty() ? " (no terms)" : text;
}

}  // namespace imunoise::io
