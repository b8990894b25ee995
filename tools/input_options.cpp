#include "tools/input_options.h"

#include <CLI/CLI.hpp>
#include <string_view>
#include <vector>

#include "common/units.h"

namespace imunoise::tools {

namespace {

/// "gx, gy,gz" → {"gx", "gy", "gz"} (blanks around names are not part of them).
std::vector<std::string> split_columns(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto first = item.find_first_not_of(" \t");
    const auto last = item.find_last_not_of(" \t");
    out.push_back(first == std::string::npos ? std::string()
                                             : item.substr(first, last - first + 1));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

std::string check_columns(const std::string& text) {
  const std::vector<std::string> columns = split_columns(text);
  if (columns.size() > 3)
    return "give 1 to 3 columns (x,y,z), got " + std::to_string(columns.size());
  for (const std::string& c : columns) {
    if (c.empty()) return "empty column in '" + text + "' (use names or 1-based indices: 2,3,4)";
  }
  return {};
}

/// A CLI11 check from one of the io::parse_* functions, naming the accepted spellings.
template <typename Parse>
auto spelled(Parse parse, std::string expected) {
  return [parse, expected](const std::string& text) {
    return parse(text) ? std::string() : "unknown value '" + text + "' (expected " + expected + ")";
  };
}

}  // namespace

void add_input_options(CLI::App& cmd, io::InputConfig& config, std::string& config_path) {
  const std::string group = "Input (flags override --config)";
  cmd.add_option("--config", config_path,
                 "YAML input config (column mapping and units; see configs/example_input.yaml)")
      ->check(CLI::ExistingFile)
      ->group(group);
  auto* time_col = cmd.add_option_function<std::string>(
                          "--time-col", [&config](const std::string& v) { config.time_column = v; },
                          "time-stamp column: header name or 1-based index (default: a column "
                          "named time_s, time_ms, time_us or time_ns)")
                       ->type_name("COL")
                       ->group(group);
  cmd.add_option_function<std::string>(
         "--time-unit",
         [&config](const std::string& v) { config.time_unit = io::parse_time_unit(v); },
         "unit of the time column: s, ms, us, ns (default s)")
      ->check(spelled(io::parse_time_unit, "s, ms, us, ns"))
      ->type_name("UNIT")
      ->group(group);
  auto* rate = cmd.add_option_function<double>(
                      "--rate", [&config](const double& v) { config.rate_hz = v; },
                      "fixed sample rate [Hz], instead of a time column")
                   ->check(CLI::PositiveNumber)
                   ->type_name("HZ")
                   ->group(group);
  rate->excludes(time_col);
  cmd.add_option_function<std::string>(
         "--gyro-cols", [&config](const std::string& v) { config.gyro_columns = split_columns(v); },
         "gyro x,y,z columns: names or 1-based indices (default: gyro_x_rad_per_s, ...)")
      ->check(check_columns)
      ->type_name("A,B,C")
      ->group(group);
  cmd.add_option_function<std::string>(
         "--gyro-unit",
         [&config](const std::string& v) { config.gyro_unit = io::parse_gyro_unit(v); },
         "rad/s, deg/s, deg/h, or rad / deg for angle increments per sample (default rad/s)")
      ->check(spelled(io::parse_gyro_unit, "rad/s, deg/s, deg/h, rad, deg"))
      ->type_name("UNIT")
      ->group(group);
  cmd.add_option_function<std::string>(
         "--accel-cols",
         [&config](const std::string& v) { config.accel_columns = split_columns(v); },
         "accel x,y,z columns: names or 1-based indices (default: accel_x_m_per_s2, ...)")
      ->check(check_columns)
      ->type_name("A,B,C")
      ->group(group);
  cmd.add_option_function<std::string>(
         "--accel-unit",
         [&config](const std::string& v) { config.accel_unit = io::parse_accel_unit(v); },
         "m/s^2, g, mg, or m/s for velocity increments per sample (default m/s^2)")
      ->check(spelled(io::parse_accel_unit, "m/s^2, g, mg, m/s"))
      ->type_name("UNIT")
      ->group(group);
  cmd.add_option_function<std::string>(
         "--delimiter",
         [&config](const std::string& v) { config.delimiter = io::parse_delimiter(v); },
         "field separator: auto, comma, tab, semicolon, space (default auto)")
      ->check(spelled(io::parse_delimiter, "auto, comma, tab, semicolon, space"))
      ->type_name("SEP")
      ->group(group);
  cmd.add_flag_callback(
         "--drop-non-finite", [&config] { config.drop_non_finite = true; },
         "drop rows holding NaN/Inf (counted in the report) instead of failing")
      ->group(group);
  cmd.add_option_function<double>(
         "--full-scale-gyro",
         [&config](const double& v) { config.gyro_full_scale_rad_per_s = v * units::kDegPerS; },
         "gyro full-scale range [deg/s]: |rate| at or beyond counts as saturated")
      ->check(CLI::PositiveNumber)
      ->type_name("DEG_PER_S")
      ->group(group);
  cmd.add_option_function<double>(
         "--full-scale-accel",
         [&config](const double& v) { config.accel_full_scale_m_per_s2 = v * units::kG; },
         "accel full-scale range [g]: |specific force| at or beyond counts as saturated")
      ->check(CLI::PositiveNumber)
      ->type_name("G")
      ->group(group);
}

io::InputConfig resolve_input_config(const io::InputConfig& flags, const std::string& config_path) {
  const io::InputConfig file =
      config_path.empty() ? io::InputConfig{} : io::load_input_config(config_path);
  return io::merge_input_configs(file, flags);
}

}  // namespace imunoise::tools
