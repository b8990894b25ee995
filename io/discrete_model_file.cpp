#include "io/discrete_model_file.h"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/yaml_scalar.h"

namespace imunoise::io {

namespace {

/// @name The keys of the schema, named once for the writers and the readers
/// @{
constexpr const char* kFormat = "imunoise-discrete-model";
constexpr int kFormatVersion = 1;
constexpr const char* kFormatKey = "format";
constexpr const char* kFormatVersionKey = "format_version";
constexpr const char* kSourceModelKey = "source_model";
constexpr const char* kDescriptionKey = "description";        // JSON only
constexpr const char* kDiscretizationKey = "discretization";  // JSON only
constexpr const char* kNotesKey = "notes";                    // JSON only
constexpr const char* kDtKey = "dt_s";
constexpr const char* kStatesKey = "states";
constexpr const char* kNoisesKey = "noises";
constexpr const char* kPhiKey = "phi";
constexpr const char* kQdKey = "qd";
constexpr const char* kInitialVarianceKey = "initial_variance";
constexpr const char* kContinuousKey = "continuous";
constexpr const char* kFKey = "F";
constexpr const char* kGKey = "G";
constexpr const char* kQcKey = "Qc";
constexpr const char* kWhiteNoiseKey = "white_noise";
constexpr const char* kAxisKey = "axis";
/// The unit-carrying keys of one white-noise input, gyro or accelerometer.
struct WhiteNoiseKeys {
  const char* density;
  const char* rate_sigma;
  const char* increment_sigma;
};
constexpr WhiteNoiseKeys kGyroWhiteKeys{"density_rad_per_sqrt_s", "rate_sigma_rad_per_s",
                                        "increment_sigma_rad"};
constexpr WhiteNoiseKeys kAccelWhiteKeys{"density_m_per_s_sqrt_s", "rate_sigma_m_per_s2",
                                         "increment_sigma_m_per_s"};
const WhiteNoiseKeys& white_keys(SensorKind kind) {
  return kind == SensorKind::gyro ? kGyroWhiteKeys : kAccelWhiteKeys;
}
/// @}

// ---------------------------------------------------------------------------------------
// Writing

nlohmann::json matrix_json(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

std::string matrix_yaml(const Eigen::MatrixXd& m, const std::string& indent) {
  if (m.rows() == 0) return " []\n";
  std::ostringstream out;
  out << "\n";
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    out << indent << "- [";
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      out << (c ? ", " : "") << shortest_number_text(m(r, c));
    out << "]\n";
  }
  return out.str();
}

std::string names_yaml(const std::vector<std::string>& names) {
  std::string s = "[";
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + "]";
}

// ---------------------------------------------------------------------------------------
// Reading: one reader of the schema over two kinds of node (YAML, JSON)

/// A YAML node at a key path; failures are InputErrors located at the node.
class YamlValue {
 public:
  YamlValue(YAML::Node node, std::string path, const std::string* source)
      : node_(std::move(node)), path_(std::move(path)), source_(source) {}

  bool is_null() const { return node_.IsNull(); }
  bool is_map() const { return node_.IsMap(); }
  bool is_list() const { return node_.IsSequence(); }
  std::size_t size() const { return node_.size(); }
  YamlValue item(std::size_t i) const {
    return {node_[i], path_ + "[" + std::to_string(i) + "]", source_};
  }
  std::optional<YamlValue> find(const char* key) const {
    const YAML::Node child = node_[key];
    if (!child) return std::nullopt;
    return YamlValue(child, path_.empty() ? key : path_ + "." + key, source_);
  }
  std::string text() const {
    if (!node_.IsScalar()) fail("expected a text");
    return node_.Scalar();
  }
  double number() const {
    if (!node_.IsScalar() || node_.Tag() == "!") fail("expected a finite number");
    const std::string& s = node_.Scalar();
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(value)) {
      fail("expected a finite number, got '" + s + "'");
    }
    return value;
  }
  std::int64_t integer() const {
    if (!node_.IsScalar() || node_.Tag() == "!") fail("expected an integer");
    const std::string& s = node_.Scalar();
    std::int64_t value = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || ptr != s.data() + s.size())
      fail("expected an integer, got '" + s + "'");
    return value;
  }
  [[noreturn]] void fail(const std::string& what) const {
    const YAML::Mark mark = node_.Mark();
    throw InputError(located_message(*source_, mark.line + 1, mark.column + 1,
                                     path_.empty() ? what : path_ + ": " + what));
  }

 private:
  YAML::Node node_;
  std::string path_;
  const std::string* source_;
};

/// A JSON value at a key path; failures are InputErrors naming the file and the path.
class JsonValue {
 public:
  JsonValue(const nlohmann::json* value, std::string path, const std::string* source)
      : value_(value), path_(std::move(path)), source_(source) {}

  bool is_null() const { return value_->is_null(); }
  bool is_map() const { return value_->is_object(); }
  bool is_list() const { return value_->is_array(); }
  std::size_t size() const { return value_->size(); }
  JsonValue item(std::size_t i) const {
    return {&(*value_)[i], path_ + "[" + std::to_string(i) + "]", source_};
  }
  std::optional<JsonValue> find(const char* key) const {
    const auto it = value_->find(key);
    if (it == value_->end()) return std::nullopt;
    return JsonValue(&*it, path_.empty() ? key : path_ + "." + key, source_);
  }
  std::string text() const {
    if (!value_->is_string()) fail("expected a text");
    return value_->get<std::string>();
  }
  double number() const {
    if (!value_->is_number()) fail("expected a finite number, got " + value_->dump());
    const double value = value_->get<double>();
    if (!std::isfinite(value)) fail("expected a finite number, got " + value_->dump());
    return value;
  }
  std::int64_t integer() const {
    if (!value_->is_number_integer()) fail("expected an integer, got " + value_->dump());
    return value_->get<std::int64_t>();
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(located_message(*source_, 0, 0, path_.empty() ? what : path_ + ": " + what));
  }

 private:
  const nlohmann::json* value_;
  std::string path_;
  const std::string* source_;
};

template <class Value>
Value require(const Value& map, const char* key) {
  if (!map.is_map()) map.fail("expected a mapping");
  std::optional<Value> child = map.find(key);
  if (!child) map.fail(std::string("missing required key '") + key + "'");
  return *child;
}

template <class Value>
std::vector<std::string> read_names(const Value& list) {
  if (!list.is_list()) list.fail("expected a list of names");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) names.push_back(list.item(i).text());
  return names;
}

template <class Value>
Eigen::VectorXd read_vector(const Value& list, std::size_t expected_size) {
  if (!list.is_list()) list.fail("expected a list of numbers");
  if (list.size() != expected_size) {
    list.fail(std::to_string(list.size()) + " values, expected " + std::to_string(expected_size));
  }
  Eigen::VectorXd v(static_cast<Eigen::Index>(list.size()));
  for (std::size_t i = 0; i < list.size(); ++i)
    v(static_cast<Eigen::Index>(i)) = list.item(i).number();
  return v;
}

/// A ROWS × COLS matrix written row by row. A matrix of 0 rows is written "[]" and carries no
/// column count: it reads as 0 × COLS.
template <class Value>
Eigen::MatrixXd read_matrix(const Value& list, std::size_t rows, std::size_t cols) {
  if (!list.is_list()) list.fail("expected a list of rows");
  if (list.size() != rows) {
    list.fail(std::to_string(list.size()) + " rows, expected " + std::to_string(rows));
  }
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  for (std::size_t r = 0; r < rows; ++r) {
    const Value row = list.item(r);
    if (!row.is_list()) row.fail("expected a row of numbers");
    if (row.size() != cols) {
      row.fail(std::to_string(row.size()) + " columns, expected " + std::to_string(cols));
    }
    for (std::size_t c = 0; c < cols; ++c) {
      m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = row.item(c).number();
    }
  }
  return m;
}

template <class Value>
pipeline::WhiteNoiseInput read_white_noise(const Value& entry) {
  pipeline::WhiteNoiseInput w;
  w.axis = require(entry, kAxisKey).text();
  // The kind is spelled by the unit of the density key.
  w.kind = entry.find(kGyroWhiteKeys.density) ? SensorKind::gyro : SensorKind::accel;
  if (w.kind == SensorKind::accel && !entry.find(kAccelWhiteKeys.density)) {
    entry.fail(std::string("missing required key '") + kGyroWhiteKeys.density + "' or '" +
               kAccelWhiteKeys.density + "'");
  }
  const WhiteNoiseKeys& keys = white_keys(w.kind);
  w.density = require(entry, keys.density).number();
  w.rate_sigma = require(entry, keys.rate_sigma).number();
  w.increment_sigma = require(entry, keys.increment_sigma).number();
  return w;
}

/// The keys both files carry.
template <class Value>
DiscreteModelFile read_content(const Value& root) {
  if (!root.is_map()) root.fail("expected a mapping (an imunoise discrete model)");
  const std::string format = require(root, kFormatKey).text();
  if (format != kFormat) {
    require(root, kFormatKey).fail("expected '" + std::string(kFormat) + "', got '" + format + "'");
  }
  const Value version = require(root, kFormatVersionKey);
  if (version.integer() != kFormatVersion) {
    version.fail("version " + std::to_string(version.integer()) + " is not supported (expected " +
                 std::to_string(kFormatVersion) + ")");
  }
  DiscreteModelFile file;
  file.source_model = require(root, kSourceModelKey).text();
  const Value dt = require(root, kDtKey);
  file.discrete.dt_s = dt.number();
  if (!(file.discrete.dt_s > 0.0)) dt.fail("must be > 0");
  file.discrete.state_names = read_names(require(root, kStatesKey));
  file.continuous.state_names = file.discrete.state_names;
  file.continuous.noise_names = read_names(require(root, kNoisesKey));
  const std::size_t n = file.discrete.state_names.size();
  const std::size_t p = file.continuous.noise_names.size();
  file.discrete.Phi = read_matrix(require(root, kPhiKey), n, n);
  file.discrete.Qd = read_matrix(require(root, kQdKey), n, n);
  file.continuous.initial_variance = read_vector(require(root, kInitialVarianceKey), n);
  const Value continuous = require(root, kContinuousKey);
  file.continuous.F = read_matrix(require(continuous, kFKey), n, n);
  file.continuous.G = read_matrix(require(continuous, kGKey), n, p);
  file.continuous.Qc = read_matrix(require(continuous, kQcKey), p, p);
  // An empty list is written as nothing after the key (YAML: null).
  const Value white = require(root, kWhiteNoiseKey);
  if (white.is_null()) return file;
  if (!white.is_list()) white.fail("expected a list");
  for (std::size_t i = 0; i < white.size(); ++i) {
    file.white_noise.push_back(read_white_noise(white.item(i)));
  }
  return file;
}

}  // namespace

std::string format_discrete_model_yaml(const DiscreteModelFile& file) {
  const models::ContinuousStateModel& continuous = file.continuous;
  const models::DiscreteStateModel& discrete = file.discrete;
  // The same content as the JSON, with a comment header for people.
  std::ostringstream y;
  // The path as given in the comment (people read it); on one line even when it holds a
  // control character. The key below holds it as a quoted scalar that reads back unchanged.
  y << "# imunoise discrete state model from "
    << (has_control_character(file.source_model) ? yaml_double_quoted(file.source_model)
                                                 : file.source_model)
    << "\n";
  y << "# " << file.description << "\n";
  y << "# x_{k+1} = phi x_k + w_k, cov(w_k) = qd; continuous xdot = F x + G w, E[w w'] = Qc "
       "delta\n";
  y << "# discretization: " << discrete.method << " (exact: Van Loan, theory.md §6.2)\n";
  y << "# values: " << (file.conservative ? "conservative (upper interval ends)" : "best estimates")
    << "; bias model: " << file.bias_model << "; B as GM by convention " << file.gm_convention
    << "\n";
  for (const auto& n : file.notes) y << "# note: " << n << "\n";
  y << "# " << discrete.state_names.size() << " states\n";
  y << kFormatKey << ": " << kFormat << "\n" << kFormatVersionKey << ": " << kFormatVersion << "\n";
  y << kSourceModelKey << ": " << yaml_double_quoted(file.source_model) << "\n";
  y << kDtKey << ": " << shortest_number_text(discrete.dt_s) << "\n";
  y << kStatesKey << ": " << names_yaml(discrete.state_names) << "\n";
  y << kNoisesKey << ": " << names_yaml(continuous.noise_names) << "\n";
  y << kPhiKey << ":" << matrix_yaml(discrete.Phi, "  ");
  y << kQdKey << ":" << matrix_yaml(discrete.Qd, "  ");
  y << kInitialVarianceKey << ": [";
  for (Eigen::Index i = 0; i < continuous.initial_variance.size(); ++i)
    y << (i ? ", " : "") << shortest_number_text(continuous.initial_variance(i));
  y << "]\n";
  y << kContinuousKey << ":\n  " << kFKey << ":" << matrix_yaml(continuous.F, "    ");
  y << "  " << kGKey << ":" << matrix_yaml(continuous.G, "    ");
  y << "  " << kQcKey << ":" << matrix_yaml(continuous.Qc, "    ");
  y << kWhiteNoiseKey << ":  # inputs, not states: per-sample sigma for rates and for increments\n";
  for (const auto& w : file.white_noise) {
    const WhiteNoiseKeys& keys = white_keys(w.kind);
    y << "  - {" << kAxisKey << ": " << w.axis << ", " << keys.density << ": "
      << shortest_number_text(w.density) << ", " << keys.rate_sigma << ": "
      << shortest_number_text(w.rate_sigma) << ", " << keys.increment_sigma << ": "
      << shortest_number_text(w.increment_sigma) << "}\n";
  }
  return y.str();
}

std::string format_discrete_model_json(const DiscreteModelFile& file) {
  const models::ContinuousStateModel& continuous = file.continuous;
  const models::DiscreteStateModel& discrete = file.discrete;
  nlohmann::json white_json = nlohmann::json::array();
  for (const auto& w : file.white_noise) {
    const WhiteNoiseKeys& keys = white_keys(w.kind);
    white_json.push_back({{kAxisKey, w.axis},
                          {keys.density, w.density},
                          {keys.rate_sigma, w.rate_sigma},
                          {keys.increment_sigma, w.increment_sigma}});
  }
  nlohmann::json j;
  j[kFormatKey] = kFormat;
  j[kFormatVersionKey] = kFormatVersion;
  j[kSourceModelKey] = file.source_model;
  j[kDescriptionKey] = file.description;
  j[kDiscretizationKey] = discrete.method;
  j[kNotesKey] = file.notes;
  j[kDtKey] = discrete.dt_s;
  j[kStatesKey] = discrete.state_names;
  j[kNoisesKey] = continuous.noise_names;
  j[kPhiKey] = matrix_json(discrete.Phi);
  j[kQdKey] = matrix_json(discrete.Qd);
  j[kInitialVarianceKey] =
      std::vector<double>(continuous.initial_variance.data(),
                          continuous.initial_variance.data() + continuous.initial_variance.size());
  j[kContinuousKey] = {{kFKey, matrix_json(continuous.F)},
                       {kGKey, matrix_json(continuous.G)},
                       {kQcKey, matrix_json(continuous.Qc)}};
  j[kWhiteNoiseKey] = white_json;
  return j.dump(2) + "\n";
}

std::string write_discrete_model(const DiscreteModelFile& file, const std::string& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw InputError(directory + ": cannot create the directory: " + ec.message());
  const std::string base = (std::filesystem::path(directory) / "discrete_model").string();
  write_file_atomically(base + ".yaml", format_discrete_model_yaml(file));
  write_file_atomically(base + ".json", format_discrete_model_json(file));
  return base;
}

DiscreteModelFile parse_discrete_model_yaml(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(
        located_message(source, e.mark.line + 1, e.mark.column + 1, "YAML syntax: " + e.msg));
  }
  try {
    return read_content(YamlValue(root, "", &source));
  } catch (const YAML::Exception& e) {  // not expected: every access above is checked
    throw InputError(located_message(source, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
}

DiscreteModelFile parse_discrete_model_json(const std::string& text, const std::string& source) {
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(located_message(source, 0, 0, std::string("JSON syntax: ") + e.what()));
  }
  const JsonValue value(&root, "", &source);
  DiscreteModelFile file = read_content(value);
  file.description = require(value, kDescriptionKey).text();
  file.discrete.method = require(value, kDiscretizationKey).text();
  file.notes = read_names(require(value, kNotesKey));
  return file;
}

DiscreteModelFile load_discrete_model(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(located_message(
        path, 0, 0, std::string("cannot open the discrete model (") + std::strerror(errno) + ")"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(located_message(path, 0, 0, "reading the discrete model failed"));
  return std::filesystem::path(path).extension() == ".json"
             ? parse_discrete_model_json(text.str(), path)
             : parse_discrete_model_yaml(text.str(), path);
}

}  // namespace imunoise::io
