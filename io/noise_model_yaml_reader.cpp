/// @file
/// @brief The strict loader of the native model.yaml (see noise_model_yaml.h): every key
/// checked against the schema, every failure an InputError located at the offending node.
#include <yaml-cpp/yaml.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/noise_model_yaml.h"
#include "io/noise_model_yaml_internal.h"

namespace imunoise::io {
namespace {

using models::AxisModel;
using models::BiasInstabilityGm;
using models::Estimate;
using models::GaussMarkovEstimate;
using models::NoiseModel;
using models::SinusoidEstimate;
using namespace detail;  // the schema's key names (noise_model_yaml_internal.h)

/// A scalar's text for a message: on one line, at most about 60 bytes.
std::string shown(std::string_view text) {
  constexpr std::size_t kMax = 60;
  std::string out;
  for (const char c : text) {
    if (out.size() >= kMax && (static_cast<unsigned char>(c) & 0xC0) != 0x80) {
      out += "...";
      break;
    }
    out += (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
  }
  return out;
}

/// What a node is, for "expected …, got …".
std::string got(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return "nothing";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Scalar:
      // yaml-cpp tags quoted scalars "!" and plain ones "?".
      return node.Tag() == "!" ? "the quoted string \"" + shown(node.Scalar()) + "\""
                               : "'" + shown(node.Scalar()) + "'";
    case YAML::NodeType::Undefined:
      break;
  }
  return "an undefined node";
}

std::string joined(const std::vector<std::string_view>& names) {
  std::string out;
  for (const std::string_view name : names) out.append(out.empty() ? "" : ", ").append(name);
  return out;
}

/// Allowed range of a number.
enum class Range {
  kAny,          ///< finite
  kNonNegative,  ///< finite, ≥ 0
  kPositive,     ///< finite, > 0
  kFraction,     ///< finite, in [0, 1]
  kOpenFraction  ///< finite, in (0, 1)
};

class Reader;

/// One YAML mapping at a key path: its entries in file order, keys unique plain scalars.
class Map {
 public:
  struct Entry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
  };

  Map(const Reader& reader, const YAML::Node& node, std::string path);

  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  const std::vector<Entry>& entries() const { return entries_; }
  std::string child(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }

  /// The value of KEY, or nullptr when absent.
  const YAML::Node* find(std::string_view key) const;
  /// The value of KEY; fails "PATH: missing required key 'KEY'" when absent.
  const YAML::Node& require(std::string_view key) const;
  /// Fails on the first key not in ACCEPTED, listing them; OWNER (e.g. "an accel axis")
  /// qualifies the message when not empty.
  void accept_only(const std::vector<std::string_view>& accepted,
                   const std::string& owner = "") const;

  /// @name Typed values of optional keys (DEFAULT when absent)
  /// @{
  double number_or(std::string_view key, double fallback, Range range) const;
  std::string text_or(std::string_view key, const std::string& fallback) const;
  /// @}

 private:
  const Reader& reader_;
  YAML::Node node_;
  std::string path_;
  std::vector<Entry> entries_;
};

/// Converts a YAML document into a NoiseModel; every failure is an InputError located at the
/// offending node and naming its key path.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  NoiseModel read(const std::string& text) const {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw InputError(
          located_message(source_, e.mark.line + 1, e.mark.column + 1, "YAML syntax: " + e.msg));
    }
    try {
      return read_root(root);
    } catch (const YAML::Exception& e) {  // not expected: every access above is checked
      throw InputError(located_message(source_, e.mark.line + 1, e.mark.column + 1, e.msg));
    }
  }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& path,
                         const std::string& what) const {
    const YAML::Mark mark = node.Mark();
    throw InputError(located_message(source_, mark.line + 1, mark.column + 1,
                                     path.empty() ? what : path + ": " + what));
  }

  double number(const YAML::Node& node, const std::string& path, Range range) const {
    if (!node.IsScalar() || node.Tag() == "!") {
      fail(node, path, "expected a finite number, got " + got(node));
    }
    std::string_view text = node.Scalar();
    if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') {
      text.remove_prefix(1);  // YAML allows "+1.5"; std::from_chars does not
    }
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
      fail(node, path, "expected a finite number, got " + got(node));
    }
    switch (range) {
      case Range::kAny:
        break;
      case Range::kNonNegative:
        if (value < 0.0) fail(node, path, "must be >= 0, got " + node.Scalar());
        break;
      case Range::kPositive:
        if (!(value > 0.0)) fail(node, path, "must be > 0, got " + node.Scalar());
        break;
      case Range::kFraction:
        if (value < 0.0 || value > 1.0) {
          fail(node, path, "must be in [0, 1], got " + node.Scalar());
        }
        break;
      case Range::kOpenFraction:
        if (!(value > 0.0 && value < 1.0)) {
          fail(node, path, "must be in (0, 1), got " + node.Scalar());
        }
        break;
    }
    return value;
  }

  std::int64_t integer(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar() || node.Tag() == "!") {
      fail(node, path, "expected an integer, got " + got(node));
    }
    const std::string& text = node.Scalar();
    std::int64_t value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end) fail(node, path, "expected an integer, got " + got(node));
    return value;
  }

  bool boolean(const YAML::Node& node, const std::string& path) const {
    if (node.IsScalar() && node.Tag() != "!") {
      const std::string& text = node.Scalar();
      if (text == "true" || text == "True" || text == "TRUE") return true;
      if (text == "false" || text == "False" || text == "FALSE") return false;
    }
    fail(node, path, "expected true or false, got " + got(node));
  }

  std::string text(const YAML::Node& node, const std::string& path) const {
    if (node.IsScalar()) return node.Scalar();
    std::string what = "expected a string, got " + got(node);
    if (node.IsNull()) what += " (write \"\" for an empty string)";
    fail(node, path, what);
  }

 private:
  NoiseModel read_root(const YAML::Node& root) const {
    if (!root.IsMap()) {
      fail(root, "",
           "expected a mapping of keys (format: imunoise-noise-model, format_version, …), got " +
               got(root));
    }
    const Map map(*this, root, "");
    // Format first: a file of another kind gets one clear message, not an unknown-key error.
    const YAML::Node& format = map.require(kFormatKey);
    if (text(format, map.child(kFormatKey)) != kModelYamlFormat) {
      fail(format, map.child(kFormatKey),
           std::string("expected '") + kModelYamlFormat + "', got " + got(format) +
               " (not an imunoise noise model)");
    }
    const YAML::Node& version = map.require(kVersionKey);
    const std::int64_t version_number = integer(version, map.child(kVersionKey));
    if (version_number != kModelYamlVersion) {
      fail(version, map.child(kVersionKey),
           "unsupported version " + std::to_string(version_number) + " (this build reads " +
               std::to_string(kModelYamlVersion) + ")");
    }
    map.accept_only({kRootKeys.begin(), kRootKeys.end()});

    NoiseModel model;
    model.software = map.text_or(kSoftware, model.software);
    model.sensor_name = map.text_or(kSensorName, "");
    model.source = map.text_or(kSource, "");
    model.sample_rate_hz =
        number(map.require(kSampleRate), map.child(kSampleRate), Range::kPositive);
    model.duration_s = map.number_or(kDuration, 0.0, Range::kNonNegative);
    if (const YAML::Node* samples = map.find(kSamples)) {
      model.samples = integer(*samples, map.child(kSamples));
      if (model.samples < 0) fail(*samples, map.child(kSamples), "must be >= 0");
    }
    model.confidence = map.number_or(kConfidence, model.confidence, Range::kOpenFraction);
    if (const YAML::Node* findings = map.find(kDataQuality)) {
      read_list(*findings, map.child(kDataQuality), [&](const YAML::Node& item, const auto& at) {
        model.data_quality.push_back(text(item, at));
      });
    }

    const Map axes(*this, map.require(kAxes), map.child(kAxes));
    if (axes.entries().empty()) fail(axes.node(), axes.path(), "expected at least one axis");
    for (const Map::Entry& entry : axes.entries()) {
      model.axes.push_back(read_axis(entry.key, entry.value, axes.child(entry.key)));
    }
    return model;
  }

  AxisModel read_axis(const std::string& name, const YAML::Node& node,
                      const std::string& path) const {
    const Map map(*this, node, path);
    const YAML::Node& sensor = map.require(kSensor);
    const std::string sensor_text = text(sensor, map.child(kSensor));
    const std::optional<SensorKind> kind = parse_sensor_name(sensor_text);
    if (!kind) {
      fail(sensor, map.child(kSensor),
           "unknown sensor " + got(sensor) + " (expected gyro or accel)");
    }
    AxisModel axis;
    axis.name = name;
    axis.kind = *kind;
    const SensorKeys& keys = keys_for(axis.kind);

    std::vector<std::string_view> accepted{kSensor};
    accepted.insert(accepted.end(), keys.terms.begin(), keys.terms.end());
    accepted.insert(accepted.end(), {kGaussMarkov, kGaussMarkovBound, kSinusoids, kBiasGm, kMultiGm,
                                     kFit, kReadoff, kPsdCheck});
    map.accept_only(accepted,
                    (axis.kind == SensorKind::gyro ? "a " : "an ") + sensor_text + " axis");

    for (std::size_t t = 0; t < kTermCount; ++t) {
      axis.terms[t] = read_estimate(map.require(keys.terms[t]), map.child(keys.terms[t]));
    }
    if (const YAML::Node* list = map.find(kGaussMarkov)) {
      read_list(*list, map.child(kGaussMarkov), [&](const YAML::Node& item, const auto& at) {
        axis.gauss_markov.push_back(read_gauss_markov(item, at, keys));
      });
    }
    if (const YAML::Node* list = map.find(kGaussMarkovBound)) {
      read_list(*list, map.child(kGaussMarkovBound), [&](const YAML::Node& item, const auto& at) {
        const Map entry(*this, item, at);
        entry.accept_only({kTauC, keys.sigma_max});
        GaussMarkovBound b;
        b.tau_c_s = number(entry.require(kTauC), entry.child(kTauC), Range::kPositive);
        b.sigma_max =
            number(entry.require(keys.sigma_max), entry.child(keys.sigma_max), Range::kNonNegative);
        axis.gauss_markov_bounds.push_back(b);
      });
    }
    if (const YAML::Node* list = map.find(kSinusoids)) {
      read_list(*list, map.child(kSinusoids), [&](const YAML::Node& item, const auto& at) {
        const Map sine(*this, item, at);
        sine.accept_only(
            {keys.amplitude, kFrequency, kPhase, keys.amplitude_ci_low, keys.amplitude_ci_high});
        SinusoidEstimate s;
        s.value.amplitude =
            number(sine.require(keys.amplitude), sine.child(keys.amplitude), Range::kAny);
        s.value.frequency_hz =
            number(sine.require(kFrequency), sine.child(kFrequency), Range::kNonNegative);
        s.value.phase_rad = sine.number_or(kPhase, 0.0, Range::kAny);
        // The interval keys came with automatic line detection; a model without them has an
        // empty interval at the amplitude (as a Gauss-Markov term without the bootstrap).
        s.amplitude_ci_low = sine.number_or(keys.amplitude_ci_low, s.value.amplitude, Range::kAny);
        s.amplitude_ci_high =
            sine.number_or(keys.amplitude_ci_high, s.value.amplitude, Range::kAny);
        axis.sinusoids.push_back(s);
      });
    }
    if (const YAML::Node* list = map.find(kBiasGm)) {
      read_list(*list, map.child(kBiasGm), [&](const YAML::Node& item, const auto& at) {
        const Map entry(*this, item, at);
        entry.accept_only({kConvention, keys.sigma, kTauC});
        BiasInstabilityGm b;
        b.convention = text(entry.require(kConvention), entry.child(kConvention));
        b.value = read_gm_value(entry, keys);
        axis.bias_instability_gm.push_back(b);
      });
    }
    if (const YAML::Node* multi = map.find(kMultiGm)) {
      const Map block(*this, *multi, map.child(kMultiGm));
      block.accept_only({kMultiGmTerms, kMultiGmFraction});
      if (const YAML::Node* list = block.find(kMultiGmTerms)) {
        read_list(*list, block.child(kMultiGmTerms), [&](const YAML::Node& item, const auto& at) {
          const Map entry(*this, item, at);
          entry.accept_only({keys.sigma, kTauC});
          axis.multi_gm.push_back(read_gm_value(entry, keys));
        });
      }
      axis.multi_gm_fraction_inside_ci = block.number_or(kMultiGmFraction, 0.0, Range::kFraction);
    }
    if (const YAML::Node* fit = map.find(kFit)) {
      const Map block(*this, *fit, map.child(kFit));
      block.accept_only({kFitKeys.begin(), kFitKeys.end()});
      axis.fit_tau_min_s = block.number_or(kFitKeys[0], 0.0, Range::kNonNegative);
      axis.fit_tau_max_s = block.number_or(kFitKeys[1], 0.0, Range::kNonNegative);
      axis.tau_min_adev_s = block.number_or(kFitKeys[2], 0.0, Range::kNonNegative);
      axis.fit_note = block.text_or(kFitKeys[3], "");
      if (axis.fit_tau_max_s > 0.0 && axis.fit_tau_min_s > axis.fit_tau_max_s) {
        check_order(block, kFitKeys[0], kFitKeys[1], axis.fit_tau_min_s, axis.fit_tau_max_s);
      }
    }
    if (const YAML::Node* readoff = map.find(kReadoff)) {
      const Map block(*this, *readoff, map.child(kReadoff));
      block.accept_only({kReadoffKeys.begin(), kReadoffKeys.end()});
      const std::array<std::array<double, kTermCount>*, 2> targets{&axis.readoff.slope,
                                                                   &axis.readoff.psd};
      for (std::size_t r = 0; r < targets.size(); ++r) {
        const YAML::Node* values = block.find(kReadoffKeys[r]);
        if (values == nullptr) continue;
        const Map terms(*this, *values, block.child(kReadoffKeys[r]));
        terms.accept_only({keys.terms.begin(), keys.terms.end()});
        for (std::size_t t = 0; t < kTermCount; ++t) {
          (*targets[r])[t] = terms.number_or(keys.terms[t], 0.0, Range::kNonNegative);
        }
      }
    }
    if (const YAML::Node* check = map.find(kPsdCheck)) {
      const Map block(*this, *check, map.child(kPsdCheck));
      block.accept_only({kPsdCheckKeys.begin(), kPsdCheckKeys.end()});
      if (const YAML::Node* pass = block.find(kPsdCheckKeys[0])) {
        axis.psd_check_pass = boolean(*pass, block.child(kPsdCheckKeys[0]));
      }
      axis.psd_check_note = block.text_or(kPsdCheckKeys[1], "");
    }
    return axis;
  }

  /// {value, ci_low, ci_high, identified, method, interval_method}; only value is required.
  Estimate read_estimate(const YAML::Node& node, const std::string& path) const {
    const Map map(*this, node, path);
    map.accept_only({kEstimateKeys.begin(), kEstimateKeys.end()});
    Estimate e;
    e.value = number(map.require(kValue), map.child(kValue), Range::kNonNegative);
    e.ci_low = map.number_or(kCiLow, e.value, Range::kNonNegative);
    e.ci_high = map.number_or(kCiHigh, e.value, Range::kNonNegative);
    check_order(map, kCiLow, kCiHigh, e.ci_low, e.ci_high);
    if (const YAML::Node* identified = map.find(kIdentified)) {
      e.identified = boolean(*identified, map.child(kIdentified));
    } else {
      e.identified = e.value > 0.0;
    }
    e.method = map.text_or(kMethod, "");
    e.interval_method = map.text_or(kIntervalMethod, "");
    return e;
  }

  /// σ (≥ 0) and T_c (> 0) of one Gauss–Markov term, both required.
  GaussMarkov read_gm_value(const Map& map, const SensorKeys& keys) const {
    GaussMarkov gm;
    gm.sigma = number(map.require(keys.sigma), map.child(keys.sigma), Range::kNonNegative);
    gm.tau_c_s = number(map.require(kTauC), map.child(kTauC), Range::kPositive);
    return gm;
  }

  GaussMarkovEstimate read_gauss_markov(const YAML::Node& node, const std::string& path,
                                        const SensorKeys& keys) const {
    const Map map(*this, node, path);
    map.accept_only(
        {keys.sigma, kTauC, keys.sigma_ci_low, keys.sigma_ci_high, kTauCLow, kTauCHigh});
    GaussMarkovEstimate gm;
    gm.value = read_gm_value(map, keys);
    gm.sigma_ci_low = map.number_or(keys.sigma_ci_low, gm.value.sigma, Range::kNonNegative);
    gm.sigma_ci_high = map.number_or(keys.sigma_ci_high, gm.value.sigma, Range::kNonNegative);
    check_order(map, keys.sigma_ci_low, keys.sigma_ci_high, gm.sigma_ci_low, gm.sigma_ci_high);
    gm.tau_c_ci_low_s = map.number_or(kTauCLow, gm.value.tau_c_s, Range::kNonNegative);
    gm.tau_c_ci_high_s = map.number_or(kTauCHigh, gm.value.tau_c_s, Range::kNonNegative);
    check_order(map, kTauCLow, kTauCHigh, gm.tau_c_ci_low_s, gm.tau_c_ci_high_s);
    return gm;
  }

  /// Fails unless LOW ≤ HIGH, at the HIGH key if written, else at LOW, else at the mapping.
  void check_order(const Map& map, std::string_view low_key, std::string_view high_key, double low,
                   double high) const {
    if (low <= high) return;
    const YAML::Node* at = map.find(high_key);
    if (at == nullptr) at = map.find(low_key);
    fail(at != nullptr ? *at : map.node(), map.path(),
         std::string(low_key) + " (" + shortest_number_text(low) + ") is greater than " +
             std::string(high_key) + " (" + shortest_number_text(high) + ")");
  }

  /// Calls READ_ITEM(item, "PATH[i]") for each item of the list NODE.
  template <class ReadItem>
  void read_list(const YAML::Node& node, const std::string& path, ReadItem read_item) const {
    if (!node.IsSequence()) fail(node, path, "expected a list ([] for none), got " + got(node));
    std::size_t index = 0;
    for (const YAML::Node& item : node) {
      read_item(item, path + "[" + std::to_string(index++) + "]");
    }
  }

  std::string source_;
};

Map::Map(const Reader& reader, const YAML::Node& node, std::string path)
    : reader_(reader), node_(node), path_(std::move(path)) {
  if (!node.IsMap()) reader_.fail(node, path_, "expected a mapping, got " + got(node));
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key = it->first;  // a copy: it-> yields a temporary pair
    if (!key.IsScalar()) reader_.fail(key, path_, "expected a plain key name, got " + got(key));
    for (const Entry& seen : entries_) {
      if (seen.key == key.Scalar()) {
        reader_.fail(
            key, child(key.Scalar()),
            "duplicate key (first at line " + std::to_string(seen.key_node.Mark().line + 1) + ")");
      }
    }
    entries_.push_back({key.Scalar(), key, it->second});
  }
}

const YAML::Node* Map::find(std::string_view key) const {
  for (const Entry& entry : entries_) {
    if (entry.key == key) return &entry.value;
  }
  return nullptr;
}

const YAML::Node& Map::require(std::string_view key) const {
  const YAML::Node* value = find(key);
  if (value == nullptr) {
    reader_.fail(node_, path_, "missing required key '" + std::string(key) + "'");
  }
  return *value;
}

void Map::accept_only(const std::vector<std::string_view>& accepted,
                      const std::string& owner) const {
  for (const Entry& entry : entries_) {
    bool known = false;
    for (const std::string_view name : accepted) known = known || entry.key == name;
    if (!known) {
      reader_.fail(entry.key_node, child(entry.key),
                   "unknown key" + (owner.empty() ? "" : " for " + owner) +
                       " (accepted: " + joined(accepted) + ")");
    }
  }
}

double Map::number_or(std::string_view key, double fallback, Range range) const {
  const YAML::Node* value = find(key);
  return value == nullptr ? fallback : reader_.number(*value, child(key), range);
}

std::string Map::text_or(std::string_view key, const std::string& fallback) const {
  const YAML::Node* value = find(key);
  return value == nullptr ? fallback : reader_.text(*value, child(key));
}

}  // namespace

NoiseModel load_model_yaml(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(located_message(path, 0, 0, "cannot read the model file (a directory)"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(located_message(
        path, 0, 0, std::string("cannot open the model file (") + std::strerror(errno) + ")"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(located_message(path, 0, 0, "reading the model file failed"));
  return parse_model_yaml(text.str(), path);
}

NoiseModel parse_model_yaml(const std::string& text, const std::string& source_name) {
  return Reader(source_name).read(text);
}

}  // namespace imunoise::io
