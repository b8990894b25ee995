#include "io/input_config.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "common/errors.h"
#include "common/units.h"

namespace imunoise::io {

std::optional<Delimiter> parse_delimiter(std::string_view text) {
  if (text == "auto") return Delimiter::kAuto;
  if (text == "comma" || text == ",") return Delimiter::kComma;
  if (text == "tab" || text == "\t" || text == "\\t") return Delimiter::kTab;
  if (text == "semicolon" || text == ";") return Delimiter::kSemicolon;
  if (text == "space" || text == "whitespace" || text == " ") return Delimiter::kWhitespace;
  return std::nullopt;
}

std::optional<TimeUnit> parse_time_unit(std::string_view text) {
  if (text == "s") return TimeUnit::kSecond;
  if (text == "ms") return TimeUnit::kMillisecond;
  if (text == "us") return TimeUnit::kMicrosecond;
  if (text == "ns") return TimeUnit::kNanosecond;
  return std::nullopt;
}

std::optional<GyroUnit> parse_gyro_unit(std::string_view text) {
  if (text == "rad/s") return GyroUnit::kRadPerS;
  if (text == "deg/s") return GyroUnit::kDegPerS;
  if (text == "deg/h") return GyroUnit::kDegPerHour;
  if (text == "rad") return GyroUnit::kRadIncrement;
  if (text == "deg") return GyroUnit::kDegIncrement;
  return std::nullopt;
}

std::optional<AccelUnit> parse_accel_unit(std::string_view text) {
  if (text == "m/s^2" || text == "m/s2") return AccelUnit::kMPerS2;
  if (text == "g") return AccelUnit::kG;
  if (text == "mg") return AccelUnit::kMilliG;
  if (text == "m/s") return AccelUnit::kMPerSIncrement;
  return std::nullopt;
}

std::string_view to_string(Delimiter d) {
  switch (d) {
    case Delimiter::kAuto:
      return "auto";
    case Delimiter::kComma:
      return "comma";
    case Delimiter::kTab:
      return "tab";
    case Delimiter::kSemicolon:
      return "semicolon";
    case Delimiter::kWhitespace:
      return "space";
  }
  return "?";
}

std::string_view to_string(TimeUnit u) {
  switch (u) {
    case TimeUnit::kSecond:
      return "s";
    case TimeUnit::kMillisecond:
      return "ms";
    case TimeUnit::kMicrosecond:
      return "us";
    case TimeUnit::kNanosecond:
      return "ns";
  }
  return "?";
}

std::string_view to_string(GyroUnit u) {
  switch (u) {
    case GyroUnit::kRadPerS:
      return "rad/s";
    case GyroUnit::kDegPerS:
      return "deg/s";
    case GyroUnit::kDegPerHour:
      return "deg/h";
    case GyroUnit::kRadIncrement:
      return "rad";
    case GyroUnit::kDegIncrement:
      return "deg";
  }
  return "?";
}

std::string_view to_string(AccelUnit u) {
  switch (u) {
    case AccelUnit::kMPerS2:
      return "m/s^2";
    case AccelUnit::kG:
      return "g";
    case AccelUnit::kMilliG:
      return "mg";
    case AccelUnit::kMPerSIncrement:
      return "m/s";
  }
  return "?";
}

double si_factor(TimeUnit u) {
  switch (u) {
    case TimeUnit::kSecond:
      return 1.0;
    case TimeUnit::kMillisecond:
      return units::kMillisecond;
    case TimeUnit::kMicrosecond:
      return units::kMicrosecond;
    case TimeUnit::kNanosecond:
      return units::kNanosecond;
  }
  return 1.0;
}

double si_factor(GyroUnit u) {
  switch (u) {
    case GyroUnit::kRadPerS:
      return 1.0;
    case GyroUnit::kDegPerS:
      return units::kDegPerS;
    case GyroUnit::kDegPerHour:
      return units::kDegPerHour;
    case GyroUnit::kRadIncrement:
      return 1.0;
    case GyroUnit::kDegIncrement:
      return units::kDeg;
  }
  return 1.0;
}

double si_factor(AccelUnit u) {
  switch (u) {
    case AccelUnit::kMPerS2:
      return 1.0;
    case AccelUnit::kG:
      return units::kG;
    case AccelUnit::kMilliG:
      return units::kMilliG;
    case AccelUnit::kMPerSIncrement:
      return 1.0;
  }
  return 1.0;
}

bool is_increment(GyroUnit u) {
  return u == GyroUnit::kRadIncrement || u == GyroUnit::kDegIncrement;
}

bool is_increment(AccelUnit u) { return u == AccelUnit::kMPerSIncrement; }

namespace {

/// Reads one YAML document with file/line/column in every error.
class ConfigParser {
 public:
  explicit ConfigParser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    const YAML::Mark mark = node.Mark();
    if (mark.is_null()) throw InputError(located_message(source_, 0, 0, message));
    throw InputError(located_message(source_, mark.line + 1, mark.column + 1, message));
  }

  /// Rejects keys outside `known` (typos must not be silently ignored).
  void check_keys(const YAML::Node& map, const std::string& prefix,
                  std::initializer_list<std::string_view> known) const {
    if (!map.IsMap()) fail(map, "'" + prefix + "' must be a mapping of keys to values");
    for (const auto& kv : map) {
      const std::string key = kv.first.Scalar();
      bool ok = false;
      std::string list;
      for (std::string_view k : known) {
        ok = ok || key == k;
        if (!list.empty()) list += ", ";
        list += k;
      }
      if (!ok) {
        fail(kv.first, "unknown key '" + prefix + (prefix.empty() ? "" : ".") + key +
                           "' (known keys: " + list + ")");
      }
    }
  }

  std::string scalar(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, "'" + key + "' must be a single value");
    return node.Scalar();
  }

  double number(const YAML::Node& node, const std::string& key, bool positive) const {
    const std::string text = scalar(node, key);
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(node, "'" + key + "' must be a number, got '" + text + "'");
    }
    if (!std::isfinite(value) || (positive && !(value > 0.0))) {
      fail(node, "'" + key + "' must be a positive finite number, got '" + text + "'");
    }
    return value;
  }

  bool boolean(const YAML::Node& node, const std::string& key) const {
    const std::string text = scalar(node, key);
    try {
      return node.as<bool>();
    } catch (const YAML::Exception&) {
      fail(node, "'" + key + "' must be true or false, got '" + text + "'");
    }
  }

  /// A column is a header name or a 1-based index; both are YAML scalars.
  std::string column(const YAML::Node& node, const std::string& key) const {
    std::string text = scalar(node, key);
    if (text.empty()) fail(node, "'" + key + "' must name a column (header name or 1-based index)");
    return text;
  }

  std::vector<std::string> columns(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence()) {
      fail(node, "'" + key + "' must be a list of 1 to 3 columns, e.g. [gx, gy, gz] or [2, 3, 4]");
    }
    if (node.size() < 1 || node.size() > 3) {
      fail(node,
           "'" + key + "' must list 1 to 3 columns (x, y, z), got " + std::to_string(node.size()));
    }
    std::vector<std::string> out;
    for (const auto& item : node) out.push_back(column(item, key));
    return out;
  }

  template <typename Unit>
  Unit unit(const YAML::Node& node, const std::string& key,
            std::optional<Unit> (*parse)(std::string_view), const char* expected) const {
    const std::string text = scalar(node, key);
    const std::optional<Unit> u = parse(text);
    if (!u) fail(node, "unknown unit '" + text + "' for '" + key + "' (expected " + expected + ")");
    return *u;
  }

  InputConfig parse(const YAML::Node& root) const {
    InputConfig config;
    if (!root || root.IsNull()) return config;  // an empty file means "all defaults"
    check_keys(
        root, "",
        {"delimiter", "time", "rate_hz", "gyro", "accel", "drop_non_finite", "extra_columns"});
    if (const auto n = root["delimiter"]) {
      const std::string text = scalar(n, "delimiter");
      config.delimiter = parse_delimiter(text);
      if (!config.delimiter) {
        fail(n, "unknown delimiter '" + text + "' (expected auto, comma, tab, semicolon, space)");
      }
    }
    if (const auto time = root["time"]) {
      check_keys(time, "time", {"column", "unit"});
      if (const auto n = time["column"]) config.time_column = column(n, "time.column");
      if (const auto n = time["unit"]) {
        config.time_unit = unit<TimeUnit>(n, "time.unit", parse_time_unit, "s, ms, us, ns");
      }
    }
    if (const auto n = root["rate_hz"]) {
      config.rate_hz = number(n, "rate_hz", true);
      if (!config.time_column.empty()) {
        fail(n, "give either 'time.column' or 'rate_hz', not both");
      }
    }
    if (const auto gyro = root["gyro"]) {
      check_keys(gyro, "gyro", {"columns", "unit", "full_scale_deg_per_s"});
      if (const auto n = gyro["columns"]) config.gyro_columns = columns(n, "gyro.columns");
      if (const auto n = gyro["unit"]) {
        config.gyro_unit =
            unit<GyroUnit>(n, "gyro.unit", parse_gyro_unit,
                           "rad/s, deg/s, deg/h, or rad / deg for angle increments per sample");
      }
      if (const auto n = gyro["full_scale_deg_per_s"]) {
        config.gyro_full_scale_rad_per_s =
            number(n, "gyro.full_scale_deg_per_s", true) * units::kDegPerS;
      }
    }
    if (const auto accel = root["accel"]) {
      check_keys(accel, "accel", {"columns", "unit", "full_scale_g"});
      if (const auto n = accel["columns"]) config.accel_columns = columns(n, "accel.columns");
      if (const auto n = accel["unit"]) {
        config.accel_unit =
            unit<AccelUnit>(n, "accel.unit", parse_accel_unit,
                            "m/s^2, g, mg, or m/s for velocity increments per sample");
      }
      if (const auto n = accel["full_scale_g"]) {
        config.accel_full_scale_m_per_s2 = number(n, "accel.full_scale_g", true) * units::kG;
      }
    }
    if (const auto n = root["drop_non_finite"]) {
      config.drop_non_finite = boolean(n, "drop_non_finite");
    }
    if (const auto extra = root["extra_columns"]) {
      if (!extra.IsMap()) {
        fail(extra, "'extra_columns' must map channel names to columns, e.g. {temperature: 8}");
      }
      for (const auto& kv : extra) {
        const std::string name = kv.first.Scalar();
        if (name.empty()) fail(kv.first, "empty channel name in 'extra_columns'");
        config.extra_columns.push_back({name, column(kv.second, "extra_columns." + name)});
      }
    }
    return config;
  }

 private:
  std::string source_;
};

}  // namespace

InputConfig parse_input_config(const std::string& yaml_text, const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    const bool has_mark = !e.mark.is_null();
    throw InputError(located_message(source_name, has_mark ? e.mark.line + 1 : 0,
                                     has_mark ? e.mark.column + 1 : 0, "invalid YAML: " + e.msg));
  }
  try {
    return ConfigParser(source_name).parse(root);
  } catch (const YAML::Exception& e) {  // defensive: any conversion we did not anticipate
    throw InputError(located_message(source_name, 0, 0, "invalid config: " + e.msg));
  }
}

InputConfig load_input_config(const std::string& yaml_path) {
  std::ifstream in(yaml_path, std::ios::binary);
  if (!in) throw InputError(located_message(yaml_path, 0, 0, "cannot open config file"));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(located_message(yaml_path, 0, 0, "cannot read config file"));
  return parse_input_config(text.str(), yaml_path);
}

InputConfig merge_input_configs(const InputConfig& base, const InputConfig& overrides) {
  InputConfig out = base;
  if (overrides.delimiter) out.delimiter = overrides.delimiter;
  if (!overrides.time_column.empty() || overrides.rate_hz) {
    out.time_column = overrides.time_column;
    out.rate_hz = overrides.rate_hz;
  }
  if (overrides.time_unit) out.time_unit = overrides.time_unit;
  if (!overrides.gyro_columns.empty()) out.gyro_columns = overrides.gyro_columns;
  if (overrides.gyro_unit) out.gyro_unit = overrides.gyro_unit;
  if (!overrides.accel_columns.empty()) out.accel_columns = overrides.accel_columns;
  if (overrides.accel_unit) out.accel_unit = overrides.accel_unit;
  if (overrides.drop_non_finite) out.drop_non_finite = overrides.drop_non_finite;
  if (overrides.gyro_full_scale_rad_per_s) {
    out.gyro_full_scale_rad_per_s = overrides.gyro_full_scale_rad_per_s;
  }
  if (overrides.accel_full_scale_m_per_s2) {
    out.accel_full_scale_m_per_s2 = overrides.accel_full_scale_m_per_s2;
  }
  if (!overrides.extra_columns.empty()) out.extra_columns = overrides.extra_columns;
  return out;
}

}  // namespace imunoise::io
