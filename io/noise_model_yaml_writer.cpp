/// @file
/// @brief The writer of the native model.yaml (see noise_model_yaml.h): a deterministic text,
/// checked by parsing it back with the loader before it is returned or written.
#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/noise_model_yaml.h"
#include "io/noise_model_yaml_internal.h"
#include "io/yaml_scalar.h"

namespace imunoise::io {
namespace {

using models::AxisModel;
using models::BiasInstabilityGm;
using models::Estimate;
using models::GaussMarkovEstimate;
using models::NoiseModel;
using models::SinusoidEstimate;
using namespace detail;  // the schema's key names (noise_model_yaml_internal.h)

std::string integer_text(std::int64_t value) {
  std::array<char, 24> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

/// An axis name as a mapping key: plain when it is a simple name (gyro_x), quoted otherwise.
std::string key_text(std::string_view name) {
  const auto simple = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  };
  bool plain = !name.empty() && !(name[0] >= '0' && name[0] <= '9');
  for (const char c : name) plain = plain && simple(c);
  plain = plain && name != "null" && name != "Null" && name != "NULL";  // YAML's null spellings
  return plain ? std::string(name) : yaml_double_quoted(name);
}

/// A one-line flow mapping "{key: value, …}" built in key order.
class FlowMap {
 public:
  FlowMap& raw(std::string_view key, const std::string& value_text) {
    text_.append(text_.size() == 1 ? "" : ", ").append(key).append(": ").append(value_text);
    return *this;
  }
  FlowMap& number(std::string_view key, double value) {
    return raw(key, shortest_number_text(value));
  }
  FlowMap& boolean(std::string_view key, bool value) { return raw(key, value ? "true" : "false"); }
  FlowMap& string(std::string_view key, std::string_view value) {
    return raw(key, yaml_double_quoted(value));
  }
  std::string text() const { return text_ + "}"; }

 private:
  std::string text_ = "{";
};

/// Builds the document line by line.
class Writer {
 public:
  std::string write(const NoiseModel& model) {
    line(0, "# imunoise noise model (native schema v1). SI units, named in every key.");
    line(0,
         "# Coefficients per theory.md §1.3: AVAR = 3Q²/τ² + N²/τ + (2 ln2/π)B² + K²τ/3 + "
         "R²τ²/2.");
    line(0,
         "# identified: false means the data did not show the term; value is then 0 and "
         "ci_high an upper bound.");
    entry(0, kFormatKey, kModelYamlFormat);
    entry(0, kVersionKey, std::to_string(kModelYamlVersion));
    entry(0, kSoftware, yaml_double_quoted(model.software));
    entry(0, kSensorName, yaml_double_quoted(model.sensor_name));
    entry(0, kSource, yaml_double_quoted(model.source));
    entry(0, kSampleRate, shortest_number_text(model.sample_rate_hz));
    entry(0, kDuration, shortest_number_text(model.duration_s));
    entry(0, kSamples, integer_text(model.samples));
    entry(0, kConfidence,
          shortest_number_text(model.confidence) + "  # level of every [ci_low, ci_high]");
    std::vector<std::string> findings;
    for (const std::string& finding : model.data_quality)
      findings.push_back(yaml_double_quoted(finding));
    list(0, kDataQuality, findings, "");
    line(0, std::string(kAxes) + ":");
    for (const AxisModel& axis : model.axes) write_axis(axis);
    return std::move(out_);
  }

 private:
  void line(int indent, const std::string& text) {
    out_.append(static_cast<std::size_t>(indent), ' ').append(text).append("\n");
  }

  /// "key: value".
  void entry(int indent, std::string_view key, const std::string& value_text) {
    line(indent, std::string(key) + ": " + value_text);
  }

  /// "key: []  # comment", or "key:  # comment" followed by one "- item" line per item.
  void list(int indent, std::string_view key, const std::vector<std::string>& items,
            std::string_view comment) {
    const std::string tail = comment.empty() ? "" : "  # " + std::string(comment);
    if (items.empty()) {
      line(indent, std::string(key) + ": []" + tail);
      return;
    }
    line(indent, std::string(key) + ":" + tail);
    for (const std::string& item : items) line(indent + 2, "- " + item);
  }

  void write_axis(const AxisModel& axis) {
    const SensorKeys& keys = keys_for(axis.kind);
    line(2, key_text(axis.name) + ":");
    entry(4, kSensor, std::string(keys.sensor) + "  # gyro | accel: decides the unit suffixes");
    for (std::size_t t = 0; t < kTermCount; ++t) {
      const Estimate& e = axis.terms[t];
      const std::string flow = FlowMap()
                                   .number(kValue, e.value)
                                   .number(kCiLow, e.ci_low)
                                   .number(kCiHigh, e.ci_high)
                                   .boolean(kIdentified, e.identified)
                                   .string(kMethod, e.method)
                                   .string(kIntervalMethod, e.interval_method)
                                   .text();
      entry(4, keys.terms[t], flow + "  # " + std::string(keys.symbols[t]));
    }

    std::vector<std::string> items;
    for (const GaussMarkovEstimate& gm : axis.gauss_markov) {
      items.push_back(FlowMap()
                          .number(keys.sigma, gm.value.sigma)
                          .number(kTauC, gm.value.tau_c_s)
                          .number(keys.sigma_ci_low, gm.sigma_ci_low)
                          .number(keys.sigma_ci_high, gm.sigma_ci_high)
                          .number(kTauCLow, gm.tau_c_ci_low_s)
                          .number(kTauCHigh, gm.tau_c_ci_high_s)
                          .text());
    }
    list(4, kGaussMarkov, items, "first-order Gauss-Markov terms: sigma, correlation time");

    // The bound curve only when computed (analyze): a model from a datasheet or an older file
    // is written as before.
    if (!axis.gauss_markov_bounds.empty()) {
      items.clear();
      for (const GaussMarkovBound& b : axis.gauss_markov_bounds) {
        items.push_back(
            FlowMap().number(kTauC, b.tau_c_s).number(keys.sigma_max, b.sigma_max).text());
      }
      list(4, kGaussMarkovBound, items,
           "one more GM term of this T_c with a larger sigma is excluded (profile bound)");
    }

    items.clear();
    for (const SinusoidEstimate& s : axis.sinusoids) {
      items.push_back(FlowMap()
                          .number(keys.amplitude, s.value.amplitude)
                          .number(kFrequency, s.value.frequency_hz)
                          .number(kPhase, s.value.phase_rad)
                          .number(keys.amplitude_ci_low, s.amplitude_ci_low)
                          .number(keys.amplitude_ci_high, s.amplitude_ci_high)
                          .text());
    }
    list(4, kSinusoids, items, "A sin(2 pi f t + phase)");

    items.clear();
    for (const BiasInstabilityGm& b : axis.bias_instability_gm) {
      items.push_back(FlowMap()
                          .string(kConvention, b.convention)
                          .number(keys.sigma, b.value.sigma)
                          .number(kTauC, b.value.tau_c_s)
                          .text());
    }
    list(4, kBiasGm, items, "B as one Gauss-Markov term, theory.md §4.4 conventions");

    line(4, std::string(kMultiGm) + ":  # B as a sum of Gauss-Markov terms (theory.md §4.4)");
    items.clear();
    for (const GaussMarkov& gm : axis.multi_gm) {
      items.push_back(FlowMap().number(keys.sigma, gm.sigma).number(kTauC, gm.tau_c_s).text());
    }
    list(6, kMultiGmTerms, items, "");
    entry(6, kMultiGmFraction, shortest_number_text(axis.multi_gm_fraction_inside_ci));

    entry(4, kFit,
          FlowMap()
              .number(kFitKeys[0], axis.fit_tau_min_s)
              .number(kFitKeys[1], axis.fit_tau_max_s)
              .number(kFitKeys[2], axis.tau_min_adev_s)
              .string(kFitKeys[3], axis.fit_note)
              .text());

    line(4,
         std::string(kReadoff) + ":  # graphical read-offs, for traceability only; 0 = not found");
    const std::array<const std::array<double, kTermCount>*, 2> readoffs{&axis.readoff.slope,
                                                                        &axis.readoff.psd};
    for (std::size_t r = 0; r < readoffs.size(); ++r) {
      FlowMap flow;
      for (std::size_t t = 0; t < kTermCount; ++t) flow.number(keys.terms[t], (*readoffs[r])[t]);
      entry(6, kReadoffKeys[r], flow.text());
    }

    if (axis.psd_check_pass || !axis.psd_check_note.empty()) {
      FlowMap flow;
      if (axis.psd_check_pass) flow.boolean(kPsdCheckKeys[0], *axis.psd_check_pass);
      flow.string(kPsdCheckKeys[1], axis.psd_check_note);
      entry(4, kPsdCheck, flow.text() + "  # model PSD vs measured PSD");
    }
  }

  std::string out_;
};

}  // namespace

std::string format_model_yaml(const NoiseModel& model) {
  std::string text = Writer().write(model);
  // The loader is the one statement of the rules: a model it would reject is not written.
  try {
    parse_model_yaml(text, "model being written");
  } catch (const InputError& e) {
    throw ContractViolation(std::string("format_model_yaml: the model breaks a model.yaml "
                                        "rule (docs/model-yaml.md): ") +
                            e.what());
  }
  return text;
}

void write_model_yaml(const NoiseModel& model, const std::string& path) {
  write_file_atomically(path, format_model_yaml(model));
}

}  // namespace imunoise::io
