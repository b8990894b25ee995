/// @file
/// @brief Writers and readers of drift_envelope.csv, drift_segments.csv and drift_summary.json
/// (see drift_files.h).
#include "io/drift_files.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "common/errors.h"
#include "common/number_text.h"
#include "common/units.h"
#include "io/atomic_output.h"
#include "io/result_files.h"

namespace imunoise::io {

namespace {

using nlohmann::json;
using pipeline::DriftSegment;
using pipeline::DriftSeries;

/// One column of drift_envelope.csv: its name, the vector of DriftSeries it holds and the
/// unit of the file (value in the file = value / unit).
struct EnvelopeColumn {
  const char* name;
  std::vector<double> DriftSeries::*values;
  double unit;
};

constexpr const char* kEnvelopeTime = "time_s";
const std::array<EnvelopeColumn, 7> kPredictedColumns{{
    {"predicted_north_sigma_m", &DriftSeries::predicted_north_sigma_m, 1.0},
    {"predicted_east_sigma_m", &DriftSeries::predicted_east_sigma_m, 1.0},
    {"predicted_horizontal_drms_m", &DriftSeries::predicted_drms_m, 1.0},
    {"predicted_horizontal_velocity_drms_m_per_s", &DriftSeries::predicted_velocity_drms_m_per_s,
     1.0},
    {"predicted_roll_sigma_deg", &DriftSeries::predicted_roll_sigma_rad, units::kDeg},
    {"predicted_pitch_sigma_deg", &DriftSeries::predicted_pitch_sigma_rad, units::kDeg},
    {"predicted_heading_sigma_deg", &DriftSeries::predicted_heading_sigma_rad, units::kDeg},
}};
const std::array<EnvelopeColumn, 1> kRecordedColumns{{
    {"actual_rms_horizontal_error_m", &DriftSeries::recorded_rms_m, 1.0},
}};
const std::array<EnvelopeColumn, 4> kMonteCarloColumns{{
    {"mc_radial_p50_m", &DriftSeries::mc_radial_p50_m, 1.0},
    {"mc_radial_p68_m", &DriftSeries::mc_radial_p68_m, 1.0},
    {"mc_radial_p95_m", &DriftSeries::mc_radial_p95_m, 1.0},
    {"mc_radial_rms_m", &DriftSeries::mc_radial_rms_m, 1.0},
}};

/// The columns of drift_segments.csv.
constexpr std::array<const char*, 10> kSegmentColumns{"segment",
                                                      "start_s",
                                                      "time_s",
                                                      "north_error_m",
                                                      "east_error_m",
                                                      "horizontal_error_m",
                                                      "horizontal_velocity_error_m_per_s",
                                                      "attitude_error_north_deg",
                                                      "attitude_error_east_deg",
                                                      "attitude_error_down_deg"};

/// Column I of an optional group of drift_envelope.csv, or nullopt when the group is absent.
/// One column of a group requires the others.
template <std::size_t N>
std::optional<std::array<std::size_t, N>> optional_group(const NumericTable& t,
                                                         const std::string& path,
                                                         const std::array<EnvelopeColumn, N>& g,
                                                         const std::string& what) {
  bool any = false;
  for (const EnvelopeColumn& c : g) any = any || t.find(c.name).has_value();
  if (!any) return std::nullopt;
  std::array<std::size_t, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = require_column(t, path, g[i].name, what);
  return out;
}

/// Fills the vectors of an optional group from T, or leaves them all empty when a row lacks
/// one of its values.
template <std::size_t N>
void read_group(const NumericTable& t, const std::array<EnvelopeColumn, N>& g,
                const std::array<std::size_t, N>& index, DriftSeries& s) {
  for (const auto& row : t.rows) {
    for (std::size_t c : index) {
      if (!row[c]) return;
    }
  }
  for (std::size_t i = 0; i < N; ++i) {
    for (const auto& row : t.rows) (s.*g[i].values).push_back(*row[index[i]] * g[i].unit);
  }
}

// ----------------------------------------------------------------------------- JSON helpers
/// Reads the keys of one JSON object of drift_summary.json, naming the file and the key path
/// in its errors.
class JsonReader {
 public:
  JsonReader(const json& object, std::string path, std::string where)
      : object_(object), path_(std::move(path)), where_(std::move(where)) {
    if (!object_.is_object()) fail("", "is not an object");
  }

  bool has(const char* key) const { return object_.contains(key); }

  const json& at(const char* key) const {
    const auto it = object_.find(key);
    if (it == object_.end())
      fail(key, "missing (is this a drift_summary.json written by imunoise?)");
    return *it;
  }
  JsonReader object(const char* key) const { return JsonReader(at(key), path_, name(key)); }

  double number(const char* key) const { return number_value(at(key), key); }
  std::string text(const char* key) const {
    const json& v = at(key);
    if (!v.is_string()) fail(key, "is not a string");
    return v.get<std::string>();
  }
  bool boolean(const char* key) const {
    const json& v = at(key);
    if (!v.is_boolean()) fail(key, "is not true or false");
    return v.get<bool>();
  }
  std::uint64_t count(const char* key) const {
    const json& v = at(key);
    if (!v.is_number_unsigned()) fail(key, "is not a non-negative integer");
    return v.get<std::uint64_t>();
  }
  template <std::size_t N>
  std::array<double, N> numbers(const char* key) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != N) fail(key, "is not an array of " + std::to_string(N));
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = number_value(v[i], key);
    return out;
  }
  const json& array(const char* key) const {
    const json& v = at(key);
    if (!v.is_array()) fail(key, "is not an array");
    return v;
  }
  const std::string& path() const { return path_; }
  std::string name(const char* key) const {
    return where_.empty() ? std::string(key) : where_ + "." + key;
  }

 private:
  double number_value(const json& v, const char* key) const {
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v.is_number()) fail(key, "is not a number");
    return v.get<double>();
  }
  [[noreturn]] void fail(const char* key, const std::string& problem) const {
    const std::string at_key = *key ? name(key) : where_;
    throw InputError(path_ + ": " + (at_key.empty() ? std::string() : at_key + ": ") + problem);
  }

  const json& object_;
  std::string path_, where_;
};

}  // namespace

// ----------------------------------------------------------------------- drift_envelope.csv
std::string format_drift_envelope_csv(const DriftSeries& s) {
  const std::size_t n = s.time_s.size();
  const auto check = [&](const EnvelopeColumn& c, bool required) {
    const std::size_t size = (s.*c.values).size();
    IMUNOISE_EXPECT(size == n || (!required && size == 0),
                    std::string("drift envelope: ") + c.name + " has " + std::to_string(size) +
                        " values for " + std::to_string(n) + " times");
  };
  for (const auto& c : kPredictedColumns) check(c, true);
  for (const auto& c : kRecordedColumns) check(c, false);
  for (const auto& c : kMonteCarloColumns) check(c, false);
  IMUNOISE_EXPECT(s.mc_radial_p50_m.size() == s.mc_radial_p68_m.size() &&
                      s.mc_radial_p50_m.size() == s.mc_radial_p95_m.size() &&
                      s.mc_radial_p50_m.size() == s.mc_radial_rms_m.size(),
                  "drift envelope: the Monte Carlo vectors differ in length");
  std::vector<const EnvelopeColumn*> columns;
  for (const auto& c : kPredictedColumns) columns.push_back(&c);
  if (!s.recorded_rms_m.empty()) columns.push_back(&kRecordedColumns[0]);
  if (!s.mc_radial_rms_m.empty()) {
    for (const auto& c : kMonteCarloColumns) columns.push_back(&c);
  }
  std::ostringstream out;
  out << kEnvelopeTime;
  for (const EnvelopeColumn* c : columns) out << ',' << c->name;
  out << '\n';
  for (std::size_t i = 0; i < n; ++i) {
    out << shortest_number_text(s.time_s[i]);
    for (const EnvelopeColumn* c : columns) {
      out << ',' << shortest_number_text((s.*c->values)[i] / c->unit);
    }
    out << '\n';
  }
  return out.str();
}

void write_drift_envelope_csv(const std::string& path, const DriftSeries& series) {
  write_file_atomically(path, format_drift_envelope_csv(series));
}

DriftSeries read_drift_envelope_csv(const std::string& path) {
  const NumericTable t = read_numeric_table(path);
  const std::string what = "a drift_envelope.csv";
  const std::size_t time = require_column(t, path, kEnvelopeTime, what);
  std::array<std::size_t, kPredictedColumns.size()> predicted{};
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    predicted[i] = require_column(t, path, kPredictedColumns[i].name, what);
  }
  DriftSeries s;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    require_cells(t, path, r, {time});
    for (std::size_t c : predicted) require_cells(t, path, r, {c});
    s.time_s.push_back(*row[time]);
    for (std::size_t i = 0; i < predicted.size(); ++i) {
      const EnvelopeColumn& c = kPredictedColumns[i];
      (s.*c.values).push_back(*row[predicted[i]] * c.unit);
    }
    // The total from the degrees of the file, then in rad (what the LCM message carries).
    const double roll = *row[predicted[4]], pitch = *row[predicted[5]];
    const double heading = *row[predicted[6]];
    s.predicted_attitude_sigma_rad.push_back(
        units::kDeg * std::sqrt(roll * roll + pitch * pitch + heading * heading));
  }
  if (const auto recorded = optional_group(t, path, kRecordedColumns, what)) {
    read_group(t, kRecordedColumns, *recorded, s);
  }
  if (const auto mc = optional_group(t, path, kMonteCarloColumns, what)) {
    read_group(t, kMonteCarloColumns, *mc, s);
  }
  return s;
}

// ----------------------------------------------------------------------- drift_segments.csv
std::string format_drift_segments_csv(const std::vector<DriftSegment>& segments) {
  std::ostringstream out;
  for (std::size_t c = 0; c < kSegmentColumns.size(); ++c) {
    out << (c ? "," : "") << kSegmentColumns[c];
  }
  out << '\n';
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const DriftSegment& s = segments[k];
    const std::size_t n = s.time_s.size();
    IMUNOISE_EXPECT(s.position_error_ne_m.size() == n &&
                        s.velocity_error_horizontal_m_per_s.size() == n &&
                        s.attitude_error_ned_rad.size() == n,
                    "drift segment " + std::to_string(k) + ": its vectors differ in length");
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d& e = s.position_error_ne_m[i];
      out << k << ',' << shortest_number_text(s.start_s) << ',' << shortest_number_text(s.time_s[i])
          << ',' << shortest_number_text(e(0)) << ',' << shortest_number_text(e(1)) << ','
          << shortest_number_text(e.norm()) << ','
          << shortest_number_text(s.velocity_error_horizontal_m_per_s[i]);
      for (int a = 0; a < 3; ++a) {
        out << ',' << shortest_number_text(s.attitude_error_ned_rad[i](a) / units::kDeg);
      }
      out << '\n';
    }
  }
  return out.str();
}

void write_drift_segments_csv(const std::string& path, const std::vector<DriftSegment>& segments) {
  write_file_atomically(path, format_drift_segments_csv(segments));
}

std::vector<DriftSegment> read_drift_segments_csv(const std::string& path) {
  const NumericTable t = read_numeric_table(path);
  const std::string what = "a drift_segments.csv";
  std::array<std::size_t, kSegmentColumns.size()> c{};
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (i == 5) continue;  // horizontal_error_m: |north, east|
    c[i] = require_column(t, path, kSegmentColumns[i], what);
  }
  std::vector<DriftSegment> out;
  std::optional<double> current;  // the segment number of the rows being read
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    require_cells(t, path, r, {c[0], c[1], c[2], c[3], c[4], c[6], c[7], c[8], c[9]});
    if (!current || *current != *row[c[0]]) {
      current = *row[c[0]];
      out.emplace_back();
      out.back().start_s = *row[c[1]];
    }
    DriftSegment& s = out.back();
    s.time_s.push_back(*row[c[2]]);
    s.position_error_ne_m.emplace_back(*row[c[3]], *row[c[4]]);
    s.velocity_error_horizontal_m_per_s.push_back(*row[c[6]]);
    s.attitude_error_ned_rad.emplace_back(*row[c[7]] * units::kDeg, *row[c[8]] * units::kDeg,
                                          *row[c[9]] * units::kDeg);
  }
  return out;
}

// ------------------------------------------------------------------------- drift_budget.csv
namespace {

std::string budget_column(std::size_t term) {
  return std::string(ins::name_of(static_cast<ins::DriftBudgetTerm>(term))) + "_variance_m2";
}
constexpr const char* kBudgetTotal = "predicted_horizontal_variance_m2";
constexpr const char* kBudgetReportTime = "report_time";

}  // namespace

std::string format_drift_budget_csv(const pipeline::DriftBudget& b) {
  const std::size_t n = b.time_s.size();
  IMUNOISE_EXPECT(
      b.variance_m2.size() == n && b.predicted_variance_m2.size() == n && b.report_time.size() == n,
      "drift budget: its vectors differ in length");
  std::ostringstream out;
  out << "time_s," << kBudgetReportTime;
  for (std::size_t g = 0; g < ins::kDriftBudgetTerms; ++g) out << ',' << budget_column(g);
  out << ',' << kBudgetTotal << '\n';
  for (std::size_t i = 0; i < n; ++i) {
    out << shortest_number_text(b.time_s[i]) << ',' << (b.report_time[i] ? 1 : 0);
    for (const double v : b.variance_m2[i]) out << ',' << shortest_number_text(v);
    out << ',' << shortest_number_text(b.predicted_variance_m2[i]) << '\n';
  }
  return out.str();
}

void write_drift_budget_csv(const std::string& path, const pipeline::DriftBudget& budget) {
  write_file_atomically(path, format_drift_budget_csv(budget));
}

pipeline::DriftBudget read_drift_budget_csv(const std::string& path) {
  const NumericTable t = read_numeric_table(path);
  const std::string what = "a drift_budget.csv";
  std::vector<std::size_t> c{require_column(t, path, "time_s", what)};
  const std::size_t flag = require_column(t, path, kBudgetReportTime, what);
  for (std::size_t g = 0; g < ins::kDriftBudgetTerms; ++g)
    c.push_back(require_column(t, path, budget_column(g), what));
  c.push_back(require_column(t, path, kBudgetTotal, what));
  pipeline::DriftBudget b;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    for (const std::size_t column : c) require_cells(t, path, r, {column});
    require_cells(t, path, r, {flag});
    const auto& row = t.rows[r];
    const double is_report = *row[flag];
    IMUNOISE_CHECK(is_report == 0.0 || is_report == 1.0, InputError,
                   path + ":" + std::to_string(r + 2) + ": report_time must be 0 or 1 (got " +
                       shortest_number_text(is_report) + ")");
    b.report_time.push_back(is_report == 1.0);
    b.time_s.push_back(*row[c[0]]);
    ins::DriftBudgetRow v{};
    for (std::size_t g = 0; g < ins::kDriftBudgetTerms; ++g) v[g] = *row[c[1 + g]];
    b.variance_m2.push_back(v);
    b.predicted_variance_m2.push_back(*row[c.back()]);
  }
  return b;
}

// ----------------------------------------------------------------------- drift_summary.json
namespace {

json consistency_json(const std::vector<pipeline::DriftConsistency>& consistency) {
  json stats = json::array();
  for (const pipeline::DriftConsistency& c : consistency) {
    json e = {{"time_s", c.time_s},
              {"predicted_north_sigma_m", c.predicted_north_sigma_m},
              {"predicted_east_sigma_m", c.predicted_east_sigma_m},
              {"predicted_horizontal_drms_m", c.predicted_drms_m},
              {"actual_rms_horizontal_error_m", c.actual_rms_m},
              {"mean_nees", c.mean_nees},
              {"mean_nees_band_95", {c.nees_band_low, c.nees_band_high}},
              {"nees_inside_band", c.nees_inside},
              {"mean_nees_joint_band_95", {c.nees_joint_band_low, c.nees_joint_band_high}},
              {"nees_inside_joint_band", c.nees_inside_joint_band},
              {"coverage_1_2_3_sigma", c.coverage},
              {"expected_coverage_1_2_3_sigma", c.expected_coverage},
              {"rms_ratio", c.rms_ratio},
              {"rms_ratio_ci_95", {c.rms_ratio_ci_low, c.rms_ratio_ci_high}}};
    IMUNOISE_EXPECT(
        c.monte_carlo_radial_rms_m.has_value() == c.monte_carlo_radial_p95_m.has_value(),
        "drift summary: the Monte Carlo RMS and 95th percentile go together");
    if (c.monte_carlo_radial_rms_m) {
      e["monte_carlo_radial_rms_m"] = *c.monte_carlo_radial_rms_m;
      e["monte_carlo_radial_p95_m"] = *c.monte_carlo_radial_p95_m;
    }
    stats.push_back(e);
  }
  return stats;
}

}  // namespace

std::string format_drift_summary_json(const pipeline::DriftSummary& s) {
  const pipeline::DriftProtocol& p = s.protocol;
  const pipeline::MotionCheck& m = s.motion;
  json j;
  j["recording"] = s.recording;
  j["model"] = s.model;
  j["location"] = {{"latitude_deg", s.location.latitude_deg},
                   {"longitude_deg", s.location.longitude_deg},
                   {"height_m", s.location.height_m},
                   {"given", s.location.given}};
  j["protocol"] = {{"align_s", p.align_s},
                   {"navigation_s", p.navigation_s},
                   {"warmup_s", p.warmup_s},
                   {"segments", p.segments},
                   {"vertical_channel", p.vertical_channel},
                   {"gyro_bias", p.gyro_bias},
                   {"heading", p.heading},
                   {"bias_instability_as_gm", p.bias_instability_as_gm},
                   {"bias_states", p.bias_states}};
  j["motion_check"] = {{"stationary", m.stationary},
                       {"reason", m.reason},
                       {"forced", s.forced},
                       {"max_gyro_std_ratio", m.max_gyro_std_ratio},
                       {"max_accel_std_ratio", m.max_accel_std_ratio},
                       {"max_force_deviation_m_per_s2", m.max_force_deviation_m_per_s2},
                       {"max_tilt_change_deg", m.max_tilt_change_rad / units::kDeg},
                       {"max_rotation_deg_per_s", m.max_rotation_rad_per_s / units::kDeg}};
  j["consistency"] = consistency_json(s.consistency);
  if (s.holdout)
    j["holdout"] = {{"fitted_on", s.holdout->fitted_on},
                    {"judged_on", s.holdout->judged_on},
                    {"segments", s.holdout->segments},
                    {"consistency", consistency_json(s.holdout->consistency)}};
  if (s.monte_carlo)
    j["monte_carlo"] = {{"runs", s.monte_carlo->runs}, {"seed", s.monte_carlo->seed}};
  return j.dump(2) + "\n";
}

void write_drift_summary_json(const std::string& path, const pipeline::DriftSummary& summary) {
  write_file_atomically(path, format_drift_summary_json(summary));
}

namespace {

std::vector<pipeline::DriftConsistency> read_consistency(const JsonReader& parent, const char* key,
                                                         const std::string& path) {
  std::vector<pipeline::DriftConsistency> out;
  const json& consistency = parent.array(key);
  for (std::size_t i = 0; i < consistency.size(); ++i) {
    const JsonReader c(consistency[i], path, parent.name(key) + "[" + std::to_string(i) + "]");
    pipeline::DriftConsistency d;
    d.time_s = c.number("time_s");
    d.predicted_north_sigma_m = c.number("predicted_north_sigma_m");
    d.predicted_east_sigma_m = c.number("predicted_east_sigma_m");
    d.predicted_drms_m = c.number("predicted_horizontal_drms_m");
    d.actual_rms_m = c.number("actual_rms_horizontal_error_m");
    d.mean_nees = c.number("mean_nees");
    const auto band = c.numbers<2>("mean_nees_band_95");
    d.nees_band_low = band[0];
    d.nees_band_high = band[1];
    d.nees_inside = c.boolean("nees_inside_band");
    const auto joint = c.numbers<2>("mean_nees_joint_band_95");
    d.nees_joint_band_low = joint[0];
    d.nees_joint_band_high = joint[1];
    d.nees_inside_joint_band = c.boolean("nees_inside_joint_band");
    d.coverage = c.numbers<3>("coverage_1_2_3_sigma");
    d.expected_coverage = c.numbers<3>("expected_coverage_1_2_3_sigma");
    d.rms_ratio = c.number("rms_ratio");
    const auto ci = c.numbers<2>("rms_ratio_ci_95");
    d.rms_ratio_ci_low = ci[0];
    d.rms_ratio_ci_high = ci[1];
    if (c.has("monte_carlo_radial_rms_m") || c.has("monte_carlo_radial_p95_m")) {
      d.monte_carlo_radial_rms_m = c.number("monte_carlo_radial_rms_m");
      d.monte_carlo_radial_p95_m = c.number("monte_carlo_radial_p95_m");
    }
    out.push_back(d);
  }
  return out;
}

}  // namespace

pipeline::DriftSummary read_drift_summary_json(const std::string& path) {
  json j;
  {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open for reading");
    try {
      j = json::parse(in);
    } catch (const json::exception& e) {
      throw InputError(path + ": not valid JSON (" + e.what() + ")");
    }
  }
  const JsonReader top(j, path, "");
  pipeline::DriftSummary s;
  s.recording = top.text("recording");
  s.model = top.text("model");
  const JsonReader location = top.object("location");
  s.location.latitude_deg = location.number("latitude_deg");
  s.location.longitude_deg = location.number("longitude_deg");
  s.location.height_m = location.number("height_m");
  s.location.given = location.boolean("given");
  const JsonReader protocol = top.object("protocol");
  s.protocol.align_s = protocol.number("align_s");
  s.protocol.navigation_s = protocol.number("navigation_s");
  s.protocol.warmup_s = protocol.number("warmup_s");
  s.protocol.segments = protocol.count("segments");
  s.protocol.vertical_channel = protocol.text("vertical_channel");
  s.protocol.gyro_bias = protocol.text("gyro_bias");
  s.protocol.heading = protocol.text("heading");
  s.protocol.bias_instability_as_gm = protocol.text("bias_instability_as_gm");
  if (protocol.has("bias_states")) s.protocol.bias_states = protocol.text("bias_states");
  const JsonReader motion = top.object("motion_check");
  s.motion.stationary = motion.boolean("stationary");
  s.motion.reason = motion.text("reason");
  s.forced = motion.boolean("forced");
  s.motion.max_gyro_std_ratio = motion.number("max_gyro_std_ratio");
  s.motion.max_accel_std_ratio = motion.number("max_accel_std_ratio");
  s.motion.max_force_deviation_m_per_s2 = motion.number("max_force_deviation_m_per_s2");
  s.motion.max_tilt_change_rad = motion.number("max_tilt_change_deg") * units::kDeg;
  s.motion.max_rotation_rad_per_s = motion.number("max_rotation_deg_per_s") * units::kDeg;
  s.consistency = read_consistency(top, "consistency", path);
  if (top.has("holdout")) {
    const JsonReader h = top.object("holdout");
    pipeline::DriftHoldout holdout;
    holdout.fitted_on = h.text("fitted_on");
    holdout.judged_on = h.text("judged_on");
    holdout.segments = h.count("segments");
    holdout.consistency = read_consistency(h, "consistency", path);
    s.holdout = std::move(holdout);
  }
  if (top.has("monte_carlo")) {
    const JsonReader mc = top.object("monte_carlo");
    s.monte_carlo = pipeline::DriftMonteCarlo{static_cast<int>(mc.count("runs")), mc.count("seed")};
  }
  return s;
}

}  // namespace imunoise::io
