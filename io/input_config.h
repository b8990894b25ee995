/// @file
/// @brief How to read a recording: delimiter, time column or fixed rate, which columns hold
/// the gyro and accelerometer axes and in which units. Filled from flags and/or a YAML file
/// (schema: configs/example_input.yaml); every field left unset means "automatic/default".
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::io {

/// Field separator of a text table.
enum class Delimiter {
  kAuto,       ///< detect from the first lines
  kComma,      ///< ','
  kTab,        ///< '\t' (one tab = one separator)
  kSemicolon,  ///< ';'
  kWhitespace  ///< runs of spaces and/or tabs
};

/// Unit of a time-stamp column.
enum class TimeUnit { kSecond, kMillisecond, kMicrosecond, kNanosecond };

/// Unit of a gyro column: a rate, or an angle increment per sample.
enum class GyroUnit { kRadPerS, kDegPerS, kDegPerHour, kRadIncrement, kDegIncrement };

/// Unit of an accelerometer column: specific force, or a velocity increment per sample.
enum class AccelUnit { kMPerS2, kG, kMilliG, kMPerSIncrement };

/// @name Unit names (as written in configs and flags) and their SI factors
/// @{
std::optional<Delimiter> parse_delimiter(
    std::string_view text);                                      ///< auto|comma|tab|semicolon|space
std::optional<TimeUnit> parse_time_unit(std::string_view text);  ///< s|ms|us|ns
std::optional<GyroUnit> parse_gyro_unit(std::string_view text);  ///< rad/s|deg/s|deg/h|rad|deg
std::optional<AccelUnit> parse_accel_unit(std::string_view text);  ///< m/s^2|g|mg|m/s
std::string_view to_string(Delimiter d);
std::string_view to_string(TimeUnit u);
std::string_view to_string(GyroUnit u);
std::string_view to_string(AccelUnit u);
double si_factor(TimeUnit u);   ///< value × factor = seconds
double si_factor(GyroUnit u);   ///< value × factor = rad/s, or rad for increments
double si_factor(AccelUnit u);  ///< value × factor = m/s², or m/s for increments
bool is_increment(GyroUnit u);
bool is_increment(AccelUnit u);
/// @}

/// A column read as-is into a channel of its own (temperature, counters, …).
struct ExtraColumn {
  std::string name;    ///< channel name in the pipeline::Recording
  std::string column;  ///< header name or 1-based index
};

/// Column mapping and units. Columns are header names or 1-based indices ("3").
/// Unset fields: delimiter auto-detected; time from a `time_s|ms|us|ns` column; gyro/accel from
/// the columns `imunoise simulate` writes (`gyro_x_rad_per_s` … `accel_z_m_per_s2`).
struct InputConfig {
  std::optional<Delimiter> delimiter;
  std::string time_column;                 ///< time-stamp column; empty = automatic
  std::optional<TimeUnit> time_unit;       ///< unit of time_column (default s)
  std::optional<double> rate_hz;           ///< fixed sample rate [Hz], instead of a time column
  std::vector<std::string> gyro_columns;   ///< 1–3 columns (x, y, z order); empty = automatic
  std::optional<GyroUnit> gyro_unit;       ///< default rad/s
  std::vector<std::string> accel_columns;  ///< 1–3 columns; empty = automatic
  std::optional<AccelUnit> accel_unit;     ///< default m/s²
  std::optional<bool> drop_non_finite;     ///< drop rows holding NaN/Inf instead of failing
  /// |rate| at or beyond this counts as saturated [rad/s] (config key in deg/s)
  std::optional<double> gyro_full_scale_rad_per_s;
  /// |specific force| at or beyond this counts as saturated [m/s²] (config key in g)
  std::optional<double> accel_full_scale_m_per_s2;
  std::vector<ExtraColumn> extra_columns;
};

/// Reads a YAML input config (schema: configs/example_input.yaml). Throws InputError
/// "FILE:LINE:COL: …" naming the key on a syntax error, unknown key, wrong type or unknown unit.
InputConfig load_input_config(const std::string& yaml_path);

/// As load_input_config, from YAML text; `source_name` is used in error messages.
InputConfig parse_input_config(const std::string& yaml_text, const std::string& source_name);

/// Field-wise merge: every field set in `overrides` replaces the one in `base`. Setting either
/// a time column or a rate in `overrides` replaces both (they exclude each other).
InputConfig merge_input_configs(const InputConfig& base, const InputConfig& overrides);

}  // namespace imunoise::io
