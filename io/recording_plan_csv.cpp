#include "io/recording_plan_csv.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>
#include <tuple>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/csv_fields.h"

namespace imunoise::io {

namespace {

constexpr const char* kHeader =
    "kind,axis,term,rate_hz,duration_s,present,identified,relative_halfwidth_percent,"
    "target_percent";
constexpr std::size_t kColumns = 9;

std::string number(double value) {
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  return shortest_number_text(value);
}

std::string percent(double fraction) { return number(fraction * 100.0); }

/// Reads the cells of one data row with messages "SOURCE:LINE: column 'NAME': problem".
class Row {
 public:
  Row(std::vector<std::string> fields, const std::string& source, std::int64_t line)
      : fields_(std::move(fields)), source_(source), line_(line) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(source_ + ":" + std::to_string(line_) + ": " + problem);
  }
  const std::string& text(std::size_t column) const { return fields_[column]; }
  double number(std::size_t column, const char* name) const {
    const std::string& cell = fields_[column];
    if (cell == "inf") return std::numeric_limits<double>::infinity();
    double value = 0.0;
    const char* end = cell.data() + cell.size();
    const auto [ptr, ec] = std::from_chars(cell.data(), end, value);
    if (cell.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
      fail(std::string("column '") + name + "': '" + cell + "' is not a number");
    }
    return value;
  }
  bool flag(std::size_t column, const char* name) const {
    if (fields_[column] == "1") return true;
    if (fields_[column] == "0") return false;
    fail(std::string("column '") + name + "': expected 0 or 1, got '" + fields_[column] + "'");
  }
  NoiseTerm term() const {
    for (NoiseTerm t : kNoiseTerms) {
      if (fields_[2] == term_symbol(t)) return t;
    }
    fail("column 'term': '" + fields_[2] + "' is not Q, N, B, K or R");
  }

 private:
  std::vector<std::string> fields_;
  const std::string& source_;
  std::int64_t line_;
};

}  // namespace

std::string format_plan_csv(const pipeline::RecordingPlan& plan) {
  std::ostringstream out;
  out << kHeader << "\n";
  const std::string rate = number(plan.rate_hz);
  for (const pipeline::AxisPlan& axis : plan.axes) {
    for (std::size_t d = 0; d < plan.durations_s.size() && d < axis.table.size(); ++d) {
      for (NoiseTerm t : kNoiseTerms) {
        const pipeline::TermPrecision& p = axis.table[d][t];
        out << "expected," << csv_field(axis.name) << "," << term_symbol(t) << "," << rate << ","
            << number(plan.durations_s[d]) << "," << (p.present ? 1 : 0) << ","
            << (p.identified ? 1 : 0) << "," << percent(p.relative_halfwidth) << ",\n";
      }
    }
  }
  for (const pipeline::AxisPlan& axis : plan.axes) {
    for (NoiseTerm t : kNoiseTerms) {
      if (!std::isnan(axis.identify_duration_s[t])) {
        out << "identify," << csv_field(axis.name) << "," << term_symbol(t) << "," << rate << ","
            << number(axis.identify_duration_s[t]) << ",1,,,\n";
      }
    }
    for (const pipeline::PlanTarget& target : plan.targets) {
      const double d = axis.target_duration_s[target.term];
      if (!std::isnan(d)) {
        out << "target," << csv_field(axis.name) << "," << term_symbol(target.term) << "," << rate
            << "," << number(d) << ",1,,," << percent(target.relative_halfwidth) << "\n";
      }
    }
  }
  for (const pipeline::PlanTarget& target : plan.targets) {
    out << "goal,all," << term_symbol(target.term) << "," << rate << ",,,,,"
        << percent(target.relative_halfwidth) << "\n";
  }
  if (!std::isnan(plan.all_targets_duration_s)) {
    out << "all_targets,all,all," << rate << "," << number(plan.all_targets_duration_s) << ",,,,\n";
  }
  return out.str();
}

void write_plan_csv(const pipeline::RecordingPlan& plan, const std::string& path) {
  write_file_atomically(path, format_plan_csv(plan));
}

pipeline::RecordingPlan parse_plan_csv(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line.empty()) {
    throw InputError(source + ": empty file (is this a plan.csv written by imunoise plan?)");
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != kHeader) {
    throw InputError(source + ":1: unexpected header '" + line + "'; expected '" + kHeader +
                     "' (is this a plan.csv written by imunoise plan?)");
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  pipeline::RecordingPlan plan;
  bool have_rate = false;
  std::map<std::string, std::size_t> axis_index;
  std::map<double, std::size_t> duration_index;
  // Cells of the expected rows, filled as they come: (axis, duration, term) → precision.
  std::map<std::tuple<std::size_t, std::size_t, std::size_t>, pipeline::TermPrecision> cells;
  const auto axis_of = [&](const Row& row) -> pipeline::AxisPlan& {
    const std::string& name = row.text(1);
    if (name.empty() || name == "all") row.fail("column 'axis': an axis name is needed");
    auto [it, added] = axis_index.emplace(name, plan.axes.size());
    if (added) {
      pipeline::AxisPlan a;
      a.name = name;
      a.identify_duration_s.fill(kNaN);
      a.target_duration_s.fill(kNaN);
      plan.axes.push_back(a);
    }
    return plan.axes[it->second];
  };
  std::int64_t line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> fields;
    const bool closed = split_csv_fields(line, fields);
    Row row(fields, source, line_number);
    if (!closed) row.fail("a quoted field is not closed");
    if (fields.size() != kColumns) {
      row.fail(std::to_string(fields.size()) + " fields, the header has " +
               std::to_string(kColumns));
    }
    const double rate = row.number(3, "rate_hz");
    if (!(rate > 0.0) || std::isinf(rate)) row.fail("column 'rate_hz': must be > 0");
    if (have_rate && rate != plan.rate_hz) row.fail("column 'rate_hz': differs from line 2");
    plan.rate_hz = rate;
    have_rate = true;
    const std::string& kind = fields[0];
    if (kind == "expected") {
      pipeline::AxisPlan& axis = axis_of(row);
      const std::size_t a = axis_index.at(axis.name);
      const double duration = row.number(4, "duration_s");
      if (!(duration > 0.0) || std::isinf(duration)) row.fail("column 'duration_s': must be > 0");
      const auto [it, added] = duration_index.emplace(duration, plan.durations_s.size());
      if (added) plan.durations_s.push_back(duration);
      pipeline::TermPrecision p;
      p.present = row.flag(5, "present");
      p.identified = row.flag(6, "identified");
      p.relative_halfwidth = row.number(7, "relative_halfwidth_percent") / 100.0;
      const auto key = std::make_tuple(a, it->second, static_cast<std::size_t>(row.term()));
      if (!cells.emplace(key, p).second) row.fail("a second row for this axis, duration and term");
    } else if (kind == "identify" || kind == "target") {
      pipeline::AxisPlan& axis = axis_of(row);
      const double duration = row.number(4, "duration_s");
      if (!(duration > 0.0)) row.fail("column 'duration_s': must be > 0");
      const NoiseTerm term = row.term();
      if (kind == "identify") {
        axis.identify_duration_s[term] = duration;
      } else {
        axis.target_duration_s[term] = duration;
      }
    } else if (kind == "goal") {
      const NoiseTerm term = row.term();
      const double target = row.number(8, "target_percent") / 100.0;
      if (!(target > 0.0)) row.fail("column 'target_percent': must be > 0");
      plan.targets.push_back({term, target});
    } else if (kind == "all_targets") {
      plan.all_targets_duration_s = row.number(4, "duration_s");
    } else {
      row.fail("column 'kind': '" + kind +
               "' is not expected, identify, target, goal or all_targets");
    }
  }
  if (!have_rate)
    throw InputError(source + ": no rows (is this a plan.csv written by imunoise plan?)");
  for (std::size_t d = 1; d < plan.durations_s.size(); ++d) {
    if (!(plan.durations_s[d] > plan.durations_s[d - 1])) {
      throw InputError(source + ": the durations of the expected rows are not ascending");
    }
  }
  for (std::size_t a = 0; a < plan.axes.size(); ++a) {
    plan.axes[a].table.assign(plan.durations_s.size(), PerTerm<pipeline::TermPrecision>{});
    for (std::size_t d = 0; d < plan.durations_s.size(); ++d) {
      for (std::size_t t = 0; t < kNoiseTerms.size(); ++t) {
        const auto it = cells.find(std::make_tuple(a, d, t));
        if (it == cells.end()) {
          throw InputError(source + ": axis " + plan.axes[a].name + " has no expected row for " +
                           term_symbol(kNoiseTerms[t]) + " at " +
                           shortest_number_text(plan.durations_s[d]) + " s");
        }
        plan.axes[a].table[d][t] = it->second;
      }
    }
  }
  return plan;
}

pipeline::RecordingPlan read_plan_csv(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the plan file");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_plan_csv(text.str(), path);
}

}  // namespace imunoise::io
