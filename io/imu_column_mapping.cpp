/// @file
/// @brief The entry points over TableReader (see csv_reader.h): read_series (one column, and
/// optionally the time column, for `imunoise allan`) and read_recording (time column or rate,
/// gyro and accel columns mapped by flag, config or the project's column names, converted to
/// SI channels, with the sampling report).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/sensor_kind.h"
#include "io/csv_reader.h"
#include "io/imu_header_mapping.h"
#include "pipeline/sampling_checks.h"

namespace imunoise::io {

Series read_series(const std::string& path, const SeriesReadOptions& options) {
  TableReader reader(path, options.delimiter);
  const TableLayout& layout = reader.layout();
  std::size_t column = 0;
  if (!options.column.empty()) {
    column = reader.resolve_column(options.column);
  } else if (layout.column_count != 1) {
    throw InputError(located_message(
        path, layout.header_line, 0,
        "the file has " + std::to_string(layout.column_count) +
            " columns; choose one by name or 1-based index (--column); available columns: " +
            layout.describe_columns()));
  }
  // The time column, when asked for and the header names one in a known unit.
  std::optional<std::size_t> time_column;
  double time_factor = 1.0;
  std::string time_name;
  if (options.read_time && layout.has_header()) {
    for (const auto& [name, unit] :
         {std::pair{"time_s", TimeUnit::kSecond}, std::pair{"time_ms", TimeUnit::kMillisecond},
          std::pair{"time_us", TimeUnit::kMicrosecond},
          std::pair{"time_ns", TimeUnit::kNanosecond}}) {
      const auto found = reader.find_column(name);
      if (found && *found != column) {
        time_column = found;
        time_factor = si_factor(unit);
        time_name = name;
        break;
      }
    }
  }
  std::vector<ColumnRequest> requests{{column, false}};
  // Stamps relative to the first keep their digits (e.g. ns since the epoch beyond 2^53).
  if (time_column) requests.push_back({*time_column, true});
  TableData data = reader.read(requests, options.drop_non_finite, {},
                               ReadParallelism{.threads = options.threads});
  Series series;
  if (time_column) {
    series.time_column = time_name;
    series.time_s = std::move(data.columns[1]);
    for (double& t : series.time_s) t *= time_factor;
  }
  series.source_path = path;
  series.column_name = layout.has_header() && !layout.column_names[column].empty()
                           ? layout.column_names[column]
                           : "column " + std::to_string(column + 1);
  series.values = std::move(data.columns[0]);
  series.non_finite_dropped = data.non_finite_dropped;
  series.first_data_line = data.first_data_line;
  return series;
}

// ---------------------------------------------------------------------------------------------

namespace {

constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

/// Stamps of UNIT per second, exactly (1 / si_factor is not exact for ns).
double ticks_per_second(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kSecond:
      return 1.0;
    case TimeUnit::kMillisecond:
      return 1e3;
    case TimeUnit::kMicrosecond:
      return 1e6;
    case TimeUnit::kNanosecond:
      return 1e9;
  }
  return 1.0;
}

/// A sensor group as mapped: column indices (x, y, z order), their axes and the unit.
template <typename Unit>
struct GroupMapping {
  std::vector<std::size_t> columns;
  std::vector<std::size_t> axes;  ///< 0 = x, 1 = y, 2 = z
  Unit unit{};
};

[[noreturn]] void fail_at(const TableLayout& layout, std::int64_t line, const std::string& what) {
  throw InputError(located_message(layout.path, line, 0, what));
}

/// The gyro or accel columns: the flags' (1 to 3, x, y, z in order; unit default DEFAULT_UNIT),
/// else the header's (csv_detail::map_imu_header). A named group whose unit neither the header
/// nor the flag gives is an error asking for the flag, unless REQUIRED is false (the flags map
/// other columns: then it is left out, as before names were recognised).
template <typename Unit>
std::optional<GroupMapping<Unit>> map_group(
    const TableReader& reader, std::string_view group, const std::vector<std::string>& selectors,
    const std::optional<Unit>& unit, Unit default_unit,
    const std::optional<csv_detail::HeaderGroup<Unit>>& named, const std::string& problem,
    bool required, std::string_view units) {
  const TableLayout& layout = reader.layout();
  if (!selectors.empty()) {
    if (selectors.size() > 3) {
      fail_at(layout, 0,
              std::string(group) + " columns: give 1 to 3 (x, y, z), got " +
                  std::to_string(selectors.size()));
    }
    GroupMapping<Unit> mapping{{}, {}, unit.value_or(default_unit)};
    for (const std::string& s : selectors) {
      mapping.axes.push_back(mapping.columns.size());
      mapping.columns.push_back(reader.resolve_column(s));
    }
    return mapping;
  }
  if (!problem.empty()) {
    if (!required) return std::nullopt;
    throw InputError(problem);
  }
  if (!named) return std::nullopt;
  if (named->unit && unit && *unit != *named->unit) {
    fail_at(layout, layout.header_line,
            "column '" + layout.column_names[named->columns[0]] + "' is in " +
                std::string(to_string(*named->unit)) + " but " + std::string(group) + " unit " +
                std::string(to_string(*unit)) + " was given; map the columns explicitly");
  }
  if (!named->unit && !unit) {
    if (!required) return std::nullopt;
    fail_at(layout, layout.header_line,
            layout.column_label(named->columns[0]) + (group == "accel" ? " is an " : " is a ") +
                std::string(group) + " axis but the header states no unit: give --" +
                std::string(group) + "-unit " + std::string(units) + " (or " + std::string(group) +
                ".unit in the config)");
  }
  return GroupMapping<Unit>{named->columns, named->axes, named->unit ? *named->unit : *unit};
}

}  // namespace

pipeline::Recording read_recording(const std::string& path, const InputConfig& config,
                                   const ProgressCallback& progress, unsigned threads) {
  TableReader reader(path, config.delimiter.value_or(Delimiter::kAuto));
  const TableLayout& layout = reader.layout();

  if (config.rate_hz && !config.time_column.empty()) {
    throw InputError(located_message(path, 0, 0, "give either a time column or a rate, not both"));
  }
  if (config.rate_hz && !(std::isfinite(*config.rate_hz) && *config.rate_hz > 0.0)) {
    throw InputError(
        located_message(path, 0, 0, "the sample rate must be a positive number of Hz"));
  }

  const csv_detail::HeaderMapping named = csv_detail::map_imu_header(layout);

  // Time: a fixed rate, an explicit column, or the header's (one column or a sec + ns pair).
  std::optional<std::size_t> time_column;
  std::optional<std::size_t> nanoseconds_column;
  TimeUnit time_unit = config.time_unit.value_or(TimeUnit::kSecond);
  if (!config.rate_hz) {
    if (!config.time_column.empty()) {
      time_column = reader.resolve_column(config.time_column);
      // The header's unit for that column, when the flag gives none (time_ns, "#timestamp [ns]").
      if (!config.time_unit && named.time && named.time->column == *time_column &&
          !named.time->nanoseconds_column && named.time->unit) {
        time_unit = *named.time->unit;
      }
    } else if (named.time) {
      time_column = named.time->column;
      nanoseconds_column = named.time->nanoseconds_column;
      if (nanoseconds_column) {
        time_unit = TimeUnit::kNanosecond;  // seconds × 1e9 + nanoseconds
      } else if (!config.time_unit) {
        if (!named.time->unit) {
          fail_at(layout, layout.header_line,
                  layout.column_label(*time_column) +
                      " is the time stamp but the header states no unit: give --time-unit "
                      "s|ms|us|ns (or time.unit in the config)");
        }
        time_unit = *named.time->unit;
      }
    } else if (!named.time_problem.empty()) {
      throw InputError(named.time_problem);
    }
    if (!time_column) {
      throw InputError(located_message(
          path, layout.header_line, 0,
          "no time column: give --time-col COL [--time-unit s|ms|us|ns] or --rate HZ (or "
          "time.column / rate_hz in the config); available columns: " +
              layout.describe_columns()));
    }
  }

  // Named groups without a unit are an error only when nothing else is mapped by the flags.
  const bool flags_map = !config.gyro_columns.empty() || !config.accel_columns.empty();
  const auto gyro =
      map_group<GyroUnit>(reader, "gyro", config.gyro_columns, config.gyro_unit, GyroUnit::kRadPerS,
                          named.gyro, named.gyro_problem, !flags_map, "rad/s|deg/s|deg/h|rad|deg");
  const auto accel = map_group<AccelUnit>(reader, "accel", config.accel_columns, config.accel_unit,
                                          AccelUnit::kMPerS2, named.accel, named.accel_problem,
                                          !flags_map, "m/s^2|g|mg|m/s");
  std::vector<std::size_t> extra;
  for (const ExtraColumn& e : config.extra_columns)
    extra.push_back(reader.resolve_column(e.column));
  if (!gyro && !accel && extra.empty()) {
    throw InputError(located_message(
        path, layout.header_line, 0,
        "no gyro or accel columns: map them with --gyro-cols / --accel-cols (or gyro.columns / "
        "accel.columns in the config), or name them gyro_x_rad_per_s ... accel_z_m_per_s2 "
        "(docs/csv-dialects.md lists the names recognised); available columns: " +
            layout.describe_columns()));
  }

  // One request per column; the time column first, relative so ns stamps stay exact.
  std::vector<ColumnRequest> requests;
  if (time_column) requests.push_back({*time_column, true});
  if (nanoseconds_column) requests.push_back({*nanoseconds_column, true});
  const std::size_t first_channel_request = requests.size();
  if (gyro) {
    for (std::size_t c : gyro->columns) requests.push_back({c, false});
  }
  if (accel) {
    for (std::size_t c : accel->columns) requests.push_back({c, false});
  }
  for (std::size_t c : extra) requests.push_back({c, false});
  for (std::size_t r = first_channel_request; time_column && r < requests.size(); ++r) {
    for (std::size_t t = 0; t < first_channel_request; ++t) {
      if (requests[r].index == requests[t].index) {
        throw InputError(
            located_message(path, layout.header_line, 0,
                            layout.column_label(requests[t].index) +
                                " is mapped both as the time column and as a channel"));
      }
    }
  }

  TableData data = reader.read(requests, config.drop_non_finite.value_or(false), progress,
                               ReadParallelism{.threads = threads});
  const std::size_t n = data.columns.front().size();

  pipeline::Recording rec;
  rec.source_path = path;
  pipeline::SamplingOptions options;
  options.line_of_sample = [&data](std::size_t i) { return data.lines.line_of(i); };
  pipeline::TimingReport timing;
  if (time_column) {
    pipeline::require_min_samples(path, n, 2, "a sample rate from time stamps");
    const double factor = si_factor(time_unit);
    rec.time_s = std::move(data.columns[0]);
    rec.start_time_s = data.first_values[0] * factor;
    if (nanoseconds_column) {
      // Seconds and nanoseconds, each relative to the first row: exact integers up to 2^53 ns.
      const std::vector<double>& ns = data.columns[1];
      for (std::size_t i = 0; i < n; ++i) rec.time_s[i] = rec.time_s[i] * 1e9 + ns[i];
      rec.start_time_s = data.first_values[0] + data.first_values[1] * 1e-9;
    }
    // Integer ns (µs, ms, s) stamps: the median interval exactly, from the integers.
    const auto exact = pipeline::exact_tick_median(rec.time_s, ticks_per_second(time_unit));
    for (double& t : rec.time_s) t *= factor;
    timing = pipeline::analyze_timing(rec.time_s, options, exact);
    if (!(timing.median_interval_s > 0.0)) {
      throw InputError(located_message(path, data.first_data_line, 0,
                                       "cannot estimate the sample rate: the time stamps never "
                                       "increase"));
    }
    rec.sample_period_s = timing.sample_period_s;
  } else {
    rec.sample_period_s = 1.0 / *config.rate_hz;
    timing = pipeline::fixed_rate_timing(*config.rate_hz, static_cast<std::int64_t>(n));
  }

  std::size_t next = first_channel_request;
  const auto add_channel = [&](std::string name, std::optional<SensorKind> kind,
                               std::string source_unit, double factor, bool increments) {
    const std::size_t column = requests[next].index;
    pipeline::Channel ch;
    ch.name = std::move(name);
    ch.kind = kind;
    ch.source_unit = std::move(source_unit);
    ch.source_column = layout.has_header() && !layout.column_names[column].empty()
                           ? layout.column_names[column]
                           : "column " + std::to_string(column + 1);
    ch.from_increments = increments;
    ch.values = std::move(data.columns[next]);
    if (factor != 1.0) {
      for (double& v : ch.values) v *= factor;
    }
    rec.channels.push_back(std::move(ch));
    ++next;
  };
  if (gyro) {
    const bool inc = is_increment(gyro->unit);
    const double factor = si_factor(gyro->unit) / (inc ? rec.sample_period_s : 1.0);
    for (std::size_t a = 0; a < gyro->columns.size(); ++a) {
      add_channel("gyro_" + std::string(kAxes[gyro->axes[a]]), SensorKind::gyro,
                  std::string(to_string(gyro->unit)), factor, inc);
    }
  }
  if (accel) {
    const bool inc = is_increment(accel->unit);
    const double factor = si_factor(accel->unit) / (inc ? rec.sample_period_s : 1.0);
    for (std::size_t a = 0; a < accel->columns.size(); ++a) {
      add_channel("accel_" + std::string(kAxes[accel->axes[a]]), SensorKind::accel,
                  std::string(to_string(accel->unit)), factor, inc);
    }
  }
  for (const ExtraColumn& e : config.extra_columns)
    add_channel(e.name, std::nullopt, "", 1.0, false);

  rec.report.samples = static_cast<std::int64_t>(n);
  rec.report.timing = timing;
  rec.report.non_finite_dropped = data.non_finite_dropped;
  rec.report.rows_dropped = data.rows_dropped;
  rec.report.channels = pipeline::check_channels(rec.channels, config.gyro_full_scale_rad_per_s,
                                                 config.accel_full_scale_m_per_s2, options);
  return rec;
}

}  // namespace imunoise::io
