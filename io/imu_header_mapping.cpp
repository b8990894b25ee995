/// @file
/// @brief Column names to time, gyro and accel columns and units (see imu_header_mapping.h).
#include "io/imu_header_mapping.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>
#include <utility>

#include "common/errors.h"

namespace imunoise::io::csv_detail {

namespace {

enum class Sensor { kGyro, kAccel };

/// One column name taken apart: "#timestamp [ns]" → tokens {timestamp}, unit "ns".
struct Name {
  std::vector<std::string> tokens;  ///< lower-case runs of letters and digits
  std::string unit;                 ///< the bracketed or parenthesised unit, blanks removed
  bool percent = false;             ///< started with '%' (rostopic's %time)
  bool underscores = false;         ///< started with "__" (PlotJuggler's __time)
};

Name parse_name(std::string_view raw) {
  Name n;
  while (!raw.empty() && (raw.front() == ' ' || raw.front() == '#' || raw.front() == '%')) {
    n.percent = n.percent || raw.front() == '%';
    raw.remove_prefix(1);
  }
  n.underscores = raw.substr(0, 2) == "__";
  while (!raw.empty() && raw.back() == ' ') raw.remove_suffix(1);
  // A trailing "[unit]" or "(unit)"; "[0]" is an array index, not a unit.
  for (const auto& [open, close] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    if (raw.empty() || raw.back() != close) continue;
    const auto at = raw.rfind(open);
    if (at == std::string_view::npos) continue;
    const std::string_view inside = raw.substr(at + 1, raw.size() - at - 2);
    if (std::all_of(inside.begin(), inside.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      continue;
    }
    for (char c : inside) {
      if (c != ' ') n.unit += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    raw = raw.substr(0, at);
    break;
  }
  std::string token;
  for (char c : raw) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0) {
      token += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!token.empty()) {
      n.tokens.push_back(std::move(token));
      token.clear();
    }
  }
  if (!token.empty()) n.tokens.push_back(std::move(token));
  return n;
}

std::string joined(const std::vector<std::string>& tokens, std::size_t from, std::size_t to) {
  std::string out;
  for (std::size_t i = from; i < to; ++i) out += (i > from ? "_" : "") + tokens[i];
  return out;
}

// --- units ------------------------------------------------------------------------------------

std::optional<GyroUnit> gyro_unit_of(const std::string& text) {
  for (const auto& [spelled, unit] : std::initializer_list<std::pair<std::string_view, GyroUnit>>{
           {"rad/s", GyroUnit::kRadPerS},         {"rads^-1", GyroUnit::kRadPerS},
           {"rad*s^-1", GyroUnit::kRadPerS},      {"rad.s^-1", GyroUnit::kRadPerS},
           {"rad/sec", GyroUnit::kRadPerS},       {"rad_per_s", GyroUnit::kRadPerS},
           {"deg/s", GyroUnit::kDegPerS},         {"degs^-1", GyroUnit::kDegPerS},
           {"deg*s^-1", GyroUnit::kDegPerS},      {"deg/sec", GyroUnit::kDegPerS},
           {"\xC2\xB0/s", GyroUnit::kDegPerS},    {"dps", GyroUnit::kDegPerS},
           {"deg_per_s", GyroUnit::kDegPerS},     {"deg/h", GyroUnit::kDegPerHour},
           {"deg/hr", GyroUnit::kDegPerHour},     {"degh^-1", GyroUnit::kDegPerHour},
           {"\xC2\xB0/h", GyroUnit::kDegPerHour}, {"deg_per_h", GyroUnit::kDegPerHour},
           {"rad", GyroUnit::kRadIncrement},      {"deg", GyroUnit::kDegIncrement}}) {
    if (text == spelled) return unit;
  }
  return std::nullopt;
}

std::optional<AccelUnit> accel_unit_of(const std::string& text) {
  for (const auto& [spelled, unit] : std::initializer_list<std::pair<std::string_view, AccelUnit>>{
           {"m/s^2", AccelUnit::kMPerS2},
           {"m/s2", AccelUnit::kMPerS2},
           {"ms^-2", AccelUnit::kMPerS2},
           {"m*s^-2", AccelUnit::kMPerS2},
           {"m.s^-2", AccelUnit::kMPerS2},
           {"m/s/s", AccelUnit::kMPerS2},
           {"m/s\xC2\xB2", AccelUnit::kMPerS2},
           {"m/sec^2", AccelUnit::kMPerS2},
           {"m_per_s2", AccelUnit::kMPerS2},
           {"g", AccelUnit::kG},
           {"mg", AccelUnit::kMilliG},
           {"m/s", AccelUnit::kMPerSIncrement},
           {"m_per_s", AccelUnit::kMPerSIncrement}}) {
    if (text == spelled) return unit;
  }
  return std::nullopt;
}

std::optional<TimeUnit> time_unit_of(const std::string& text) {
  for (const auto& [spelled, unit] : std::initializer_list<std::pair<std::string_view, TimeUnit>>{
           {"s", TimeUnit::kSecond},
           {"sec", TimeUnit::kSecond},
           {"secs", TimeUnit::kSecond},
           {"ms", TimeUnit::kMillisecond},
           {"msec", TimeUnit::kMillisecond},
           {"us", TimeUnit::kMicrosecond},
           {"usec", TimeUnit::kMicrosecond},
           {"\xC2\xB5s", TimeUnit::kMicrosecond},
           {"\xCE\xBCs", TimeUnit::kMicrosecond},
           {"ns", TimeUnit::kNanosecond},
           {"nsec", TimeUnit::kNanosecond},
           {"nsecs", TimeUnit::kNanosecond}}) {
    if (text == spelled) return unit;
  }
  return std::nullopt;
}

// --- axes -------------------------------------------------------------------------------------

/// A column naming one axis of a sensor.
struct AxisName {
  Sensor sensor = Sensor::kGyro;
  std::size_t axis = 0;
  std::string source;      ///< the other name parts ("imu0", "rs_s"): which IMU it is
  std::string unit_text;   ///< as stated (bracketed or suffix); empty: none
  bool ros_field = false;  ///< angular_velocity / linear_acceleration: rad/s, m/s² by definition
  bool kalibr = false;     ///< omega / alpha
};

std::optional<std::size_t> axis_of(std::string_view token) {
  if (token == "x") return 0;
  if (token == "y") return 1;
  if (token == "z") return 2;
  return std::nullopt;
}

bool is_one_of(const std::string& token, std::initializer_list<std::string_view> words) {
  return std::find(words.begin(), words.end(), token) != words.end();
}

/// Gyro and accel words; "w" and "a" only first (EuRoC's w_RS_S_x, a_RS_S_x).
std::optional<Sensor> sensor_word(const std::string& token, bool first) {
  if (is_one_of(token, {"gyro", "gyr", "gyros", "gyroscope", "omega"}) || (first && token == "w")) {
    return Sensor::kGyro;
  }
  if (is_one_of(token, {"acc", "accel", "accelerometer", "acceleration", "alpha"}) ||
      (first && token == "a")) {
    return Sensor::kAccel;
  }
  return std::nullopt;
}

/// The axis a name points to, if any: the last x/y/z token (or "gyrox", "accz", "gx", "az"), a
/// sensor word before it, and after it nothing or a unit suffix (gyro_x_rad_per_s).
std::optional<AxisName> axis_name(const Name& n) {
  const std::vector<std::string>& t = n.tokens;
  for (std::size_t p = t.size(); p-- > 0;) {
    std::optional<std::size_t> axis = axis_of(t[p]);
    std::optional<Sensor> fused;  // "gyrox", "accz", "gx", "ax", "wz"
    if (!axis && t[p].size() >= 2) {
      const std::string word = t[p].substr(0, t[p].size() - 1);
      axis = axis_of(t[p].substr(t[p].size() - 1));
      fused = word == "g" ? std::optional<Sensor>(Sensor::kGyro) : sensor_word(word, true);
      if (!fused) axis.reset();
    }
    if (!axis) continue;
    AxisName a;
    a.axis = *axis;
    std::optional<Sensor> sensor = fused;
    bool excluded = false;
    std::vector<std::string> source;
    for (std::size_t i = 0; i < p; ++i) {
      const std::string& w = t[i];
      if (is_one_of(w, {"orientation", "covariance", "mag", "magnetometer", "magnetic", "euler",
                        "quaternion", "quat", "bias", "gravity", "position", "velocity"}) &&
          !(w == "velocity" && i > 0 && t[i - 1] == "angular")) {
        excluded = true;
      }
      if (w == "angular" && i + 1 < p && t[i + 1] == "velocity") {
        sensor = sensor ? sensor : Sensor::kGyro;
        a.ros_field = true;
        ++i;
        continue;
      }
      if (w == "linear" && i + 1 < p && t[i + 1] == "acceleration") {
        sensor = sensor ? sensor : Sensor::kAccel;
        a.ros_field = true;
        ++i;
        continue;
      }
      if (w == "angular") excluded = true;  // angular acceleration, rate, …: not a gyro or accel
      const std::optional<Sensor> s = sensor_word(w, i == 0);
      if (s && sensor && *s != *sensor) excluded = true;
      if (s) {
        sensor = s;
        a.kalibr = w == "omega" || w == "alpha";
        continue;
      }
      if (w != "field") source.push_back(w);
    }
    if (!sensor || excluded) return std::nullopt;
    a.sensor = *sensor;
    a.source = joined(source, 0, source.size());
    if (!n.unit.empty() && p + 1 == t.size()) {
      a.unit_text = n.unit;
    } else if (p + 1 < t.size()) {
      a.unit_text = joined(t, p + 1, t.size());  // suffix form, as imunoise writes it
      const bool known = a.sensor == Sensor::kGyro ? gyro_unit_of(a.unit_text).has_value()
                                                   : accel_unit_of(a.unit_text).has_value();
      if (!known) return std::nullopt;  // gyro_x_raw, accel_x_filtered: not ours to guess
    }
    return a;
  }
  return std::nullopt;
}

// --- time -------------------------------------------------------------------------------------

/// How likely a column is the time stamp: the message's own stamp, a plain time column, or a
/// log / receive time.
enum class TimeRank { kStamp = 0, kPlain = 1, kLog = 2 };

struct TimeName {
  TimeRank rank = TimeRank::kPlain;
  enum class Part { kWhole, kSeconds, kNanoseconds } part = Part::kWhole;
  std::string prefix;  ///< pairs seconds with nanoseconds
  std::optional<TimeUnit> unit;
  std::string unit_text;  ///< as stated, when not a known time unit (an error)
  std::string dialect;
};

std::optional<TimeName> time_name(const Name& n) {
  const std::vector<std::string>& t = n.tokens;
  if (t.empty()) return std::nullopt;
  TimeName tn;
  // ROS stamps: [field.]header.stamp[.sec|.secs|.nanosec|.nsecs]
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    if (t[i] != "header" || t[i + 1] != "stamp") continue;
    tn.rank = TimeRank::kStamp;
    tn.prefix = joined(t, 0, i);
    const std::size_t rest = t.size() - (i + 2);
    if (rest == 0) {
      tn.unit = t[0] == "field" ? std::optional<TimeUnit>(TimeUnit::kNanosecond) : std::nullopt;
      tn.dialect = t[0] == "field" ? "rostopic echo -p" : "";
    } else if (rest == 1 && is_one_of(t.back(), {"sec", "secs"})) {
      tn.part = TimeName::Part::kSeconds;
      tn.dialect = "ROS 2 stamp";
    } else if (rest == 1 && is_one_of(t.back(), {"nanosec", "nsec", "nsecs", "nanosecs"})) {
      tn.part = TimeName::Part::kNanoseconds;
      tn.dialect = "ROS 2 stamp";
    } else {
      return std::nullopt;
    }
    if (!n.unit.empty()) tn.unit = time_unit_of(n.unit);
    return tn;
  }
  if (n.percent && t.size() == 1 && t[0] == "time") {  // rostopic's receive time
    tn.rank = TimeRank::kLog;
    tn.unit = TimeUnit::kNanosecond;
    tn.dialect = "rostopic echo -p";
    return tn;
  }
  // [bag_|log_|receive_…]time|timestamp|t|stamp|utime[_unit] [unit]
  std::size_t i = 0;
  if (is_one_of(t[0], {"bag", "log", "receive", "recv", "rosbag", "publish", "sensor", "imu"})) {
    tn.rank = t[0] == "sensor" || t[0] == "imu" ? TimeRank::kPlain : TimeRank::kLog;
    ++i;
  }
  if (i >= t.size() ||
      !is_one_of(t[i], {"time", "timestamp", "timestamps", "t", "stamp", "ts", "utime"})) {
    return std::nullopt;
  }
  const bool utime = t[i] == "utime";
  ++i;
  std::string suffix = joined(t, i, t.size());
  if (!suffix.empty() && !time_unit_of(suffix)) return std::nullopt;  // time_zone, t_offset, …
  if (!n.unit.empty()) {
    tn.unit = time_unit_of(n.unit);
    if (!tn.unit) tn.unit_text = n.unit;
  } else if (!suffix.empty()) {
    tn.unit = time_unit_of(suffix);
  } else if (utime) {
    tn.unit = TimeUnit::kMicrosecond;  // LCM's utime
  } else if (n.underscores) {
    tn.unit = TimeUnit::kSecond;  // PlotJuggler's __time
    tn.dialect = "PlotJuggler";
  }
  return tn;
}

[[noreturn]] void fail(const TableLayout& layout, const std::string& what) {
  throw InputError(located_message(layout.path, layout.header_line, 0,
                                   what + " (columns found: " + layout.describe_columns() + ")"));
}

std::string_view sensor_text(Sensor s) { return s == Sensor::kGyro ? "gyro" : "accel"; }

/// The columns of SENSOR among AXES, in axis order; nullopt when there are none.
template <typename Unit>
std::optional<HeaderGroup<Unit>> group_of(const TableLayout& layout,
                                          const std::vector<std::optional<AxisName>>& names,
                                          Sensor sensor, bool kalibr,
                                          std::optional<Unit> (*unit_of)(const std::string&),
                                          Unit implied_ros) {
  std::vector<std::size_t> found;
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c] && names[c]->sensor == sensor) found.push_back(c);
  }
  if (found.empty()) return std::nullopt;
  const std::string_view what = sensor_text(sensor);
  // One IMU: every column from the same source, one column per axis.
  for (std::size_t c : found) {
    const AxisName& a = *names[c];
    const AxisName& first = *names[found.front()];
    if (a.source != first.source) {
      fail(layout, "two " + std::string(what) + " sensors: " + layout.column_label(found.front()) +
                       " and " + layout.column_label(c) + "; choose the columns with --" +
                       std::string(what) + "-cols");
    }
    for (std::size_t d : found) {
      if (d < c && names[d]->axis == a.axis) {
        fail(layout, "two " + std::string(what) + " " + "xyz"[a.axis] +
                         " columns: " + layout.column_label(d) + " and " + layout.column_label(c) +
                         "; choose the columns with --" + std::string(what) + "-cols");
      }
    }
  }
  std::sort(found.begin(), found.end(),
            [&](std::size_t a, std::size_t b) { return names[a]->axis < names[b]->axis; });
  HeaderGroup<Unit> g;
  std::optional<std::size_t> unit_column;
  for (std::size_t c : found) {
    const AxisName& a = *names[c];
    g.columns.push_back(c);
    g.axes.push_back(a.axis);
    std::optional<Unit> unit;
    if (!a.unit_text.empty()) {
      unit = unit_of(a.unit_text);
      if (!unit) {
        fail(layout, layout.column_label(c) + " states the unit '" + a.unit_text +
                         "', which is not a " + std::string(what) +
                         " unit imunoise knows; map the column with --" + std::string(what) +
                         "-cols and give --" + std::string(what) + "-unit");
      }
    } else if (a.ros_field || (a.kalibr && kalibr)) {
      unit = implied_ros;
    }
    if (!unit) continue;
    if (g.unit && *g.unit != *unit) {
      fail(layout, layout.column_label(*unit_column) + " and " + layout.column_label(c) +
                       " state different " + std::string(what) + " units");
    }
    g.unit = unit;
    unit_column = c;
  }
  return g;
}

/// The time column of rank BEST (with its nanoseconds, for a pair); its DIALECT.
HeaderTime chosen_time(const TableLayout& layout, const std::vector<std::optional<TimeName>>& times,
                       TimeRank best, std::string& dialect) {
  std::optional<std::size_t> chosen;
  for (std::size_t c = 0; c < times.size(); ++c) {
    const auto& t = times[c];
    if (!t || t->rank != best || t->part == TimeName::Part::kNanoseconds) continue;
    if (chosen) {
      fail(layout, "two time columns: " + layout.column_label(*chosen) + " and " +
                       layout.column_label(c) + "; choose one with --time-col");
    }
    chosen = c;
  }
  const TimeName& t = *times[*chosen];
  if (!t.unit_text.empty()) {
    fail(layout, layout.column_label(*chosen) + " states the unit '" + t.unit_text +
                     "', which is not a time unit imunoise knows (s, ms, us, ns); map it with "
                     "--time-col and --time-unit");
  }
  HeaderTime ht{*chosen, std::nullopt, t.unit};
  if (t.part == TimeName::Part::kSeconds) {
    for (std::size_t c = 0; c < times.size(); ++c) {
      if (times[c] && times[c]->part == TimeName::Part::kNanoseconds &&
          times[c]->prefix == t.prefix) {
        ht.nanoseconds_column = c;
      }
    }
    // Seconds alone: whole seconds.
    if (!ht.nanoseconds_column) ht.unit = TimeUnit::kSecond;
  }
  dialect = t.dialect;
  return ht;
}

}  // namespace

HeaderMapping map_imu_header(const TableLayout& layout) {
  HeaderMapping m;
  if (!layout.has_header()) return m;
  std::vector<Name> names;
  for (const std::string& raw : layout.column_names) names.push_back(parse_name(raw));

  std::vector<std::optional<AxisName>> axes(names.size());
  std::vector<std::optional<TimeName>> times(names.size());
  for (std::size_t c = 0; c < names.size(); ++c) {
    axes[c] = axis_name(names[c]);
    if (!axes[c]) times[c] = time_name(names[c]);
  }

  // Time: the best rank; a seconds + nanoseconds pair counts as one stamp.
  std::optional<TimeRank> best;
  for (const auto& t : times) {
    if (t && t->part != TimeName::Part::kNanoseconds && (!best || t->rank < *best)) best = t->rank;
  }
  if (best) {
    try {
      m.time = chosen_time(layout, times, *best, m.dialect);
    } catch (const InputError& e) {
      m.time_problem = e.what();
    }
  }

  // Kalibr: timestamp in ns, omega in rad/s, alpha in m/s² (its wiki's imu.csv layout).
  const bool omega = std::any_of(axes.begin(), axes.end(), [](const auto& a) {
    return a && a->kalibr && a->sensor == Sensor::kGyro;
  });
  const bool alpha = std::any_of(axes.begin(), axes.end(), [](const auto& a) {
    return a && a->kalibr && a->sensor == Sensor::kAccel;
  });
  const bool kalibr = omega && alpha && m.time && !m.time->nanoseconds_column &&
                      names[m.time->column].tokens == std::vector<std::string>{"timestamp"} &&
                      names[m.time->column].unit.empty();
  if (kalibr) {
    m.time->unit = TimeUnit::kNanosecond;
    m.dialect = "Kalibr";
  }
  try {
    m.gyro =
        group_of<GyroUnit>(layout, axes, Sensor::kGyro, kalibr, gyro_unit_of, GyroUnit::kRadPerS);
  } catch (const InputError& e) {
    m.gyro_problem = e.what();
  }
  try {
    m.accel = group_of<AccelUnit>(layout, axes, Sensor::kAccel, kalibr, accel_unit_of,
                                  AccelUnit::kMPerS2);
  } catch (const InputError& e) {
    m.accel_problem = e.what();
  }
  if (m.dialect.empty() && (m.gyro || m.accel)) {
    const std::size_t c = m.gyro ? m.gyro->columns.front() : m.accel->columns.front();
    const AxisName& a = *axes[c];
    m.dialect = a.source == "rs_s"                              ? "EuRoC/TUM-VI"
                : a.ros_field                                   ? "ROS message fields"
                : !names[c].unit.empty() || a.unit_text.empty() ? "named columns"
                                                                : "imunoise";
  }
  return m;
}

}  // namespace imunoise::io::csv_detail
