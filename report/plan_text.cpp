#include "report/plan_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace imunoise::report {

namespace {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string percent_text(double fraction) {
  const double p = 100.0 * fraction;
  return p < 9.95 ? format("%.1f", p) : format("%.0f", p);
}

std::string padded(const std::string& text, std::size_t width) {
  // Column widths count code points, not bytes ("≤", "—" are 3 bytes in UTF-8).
  std::size_t points = 0;
  for (unsigned char c : text) points += (c & 0xC0) != 0x80 ? 1 : 0;
  return text + std::string(points < width ? width - points : 1, ' ');
}

/// "gyro" of "gyro_x"; the whole name when it has no '_'.
std::string sensor_of(const std::string& axis) { return axis.substr(0, axis.find('_')); }
/// "x" of "gyro_x"; the whole name when it has no '_'.
std::string short_axis(const std::string& axis) {
  const std::size_t u = axis.find('_');
  return u == std::string::npos ? axis : axis.substr(u + 1);
}

std::string required_text(double seconds, double shortest) {
  if (std::isinf(seconds)) return "> range";
  if (seconds <= shortest * (1.0 + 1e-9)) return "≤ " + human_duration(seconds);
  return human_duration(seconds);
}

std::string targets_line(const pipeline::RecordingPlan& plan) {
  std::string line;
  for (const pipeline::PlanTarget& t : plan.targets) {
    line += std::string(line.empty() ? "" : ", ") + term_symbol(t.term) + " ±" +
            percent_text(t.relative_halfwidth) + " %";
  }
  return line;
}

/// Per sensor, the (axis index, term) columns of the terms its axes have.
/// Sensors in the order of their first axis.
std::vector<std::pair<std::string, std::vector<std::pair<std::size_t, NoiseTerm>>>> sensor_columns(
    const pipeline::RecordingPlan& plan) {
  std::vector<std::pair<std::string, std::vector<std::pair<std::size_t, NoiseTerm>>>> out;
  for (std::size_t a = 0; a < plan.axes.size(); ++a) {
    const pipeline::AxisPlan& axis = plan.axes[a];
    const std::string sensor = sensor_of(axis.name);
    if (out.empty() || out.back().first != sensor) out.push_back({sensor, {}});
    for (NoiseTerm t : kNoiseTerms) {
      if (!axis.table.empty() && axis.table.front()[t].present) {
        out.back().second.emplace_back(a, t);
      }
    }
  }
  return out;
}

std::string cell_text(const pipeline::TermPrecision& p) {
  return p.identified && std::isfinite(p.relative_halfwidth) ? percent_text(p.relative_halfwidth)
                                                             : "n.i.";
}

}  // namespace

std::string human_duration(double seconds) {
  const double a = std::fabs(seconds);
  if (a < 60.0) return format("%.3g s", seconds);
  if (a < 3600.0) return format("%.3g min", seconds / 60.0);
  if (a < 2.0 * 86400.0) return format("%.3g h", seconds / 3600.0);
  return format("%.3g d", seconds / 86400.0);
}

std::string plan_text(const pipeline::RecordingPlan& plan, const std::string& source) {
  std::ostringstream out;
  const double shortest = plan.durations_s.empty() ? 0.0 : plan.durations_s.front();
  const double longest = plan.durations_s.empty() ? 0.0 : plan.durations_s.back();
  out << "imunoise plan: " << source << " at " << format("%g", plan.rate_hz) << " Hz, table "
      << human_duration(shortest) << " to " << human_duration(longest)
      << "; intervals as the default analyze makes them (95 %, 200 OAVAR draws)\n";
  if (!plan.targets.empty()) {
    out << "targets (relative half-width of the 95 % interval): " << targets_line(plan) << "\n";
    std::string limiting;
    for (const pipeline::AxisPlan& axis : plan.axes) {
      for (const pipeline::PlanTarget& t : plan.targets) {
        if (axis.target_duration_s[t.term] == plan.all_targets_duration_s && limiting.empty()) {
          limiting = axis.name + " " + term_symbol(t.term);
        }
      }
    }
    if (std::isinf(plan.all_targets_duration_s)) {
      out << "shortest recording meeting every target: beyond " << human_duration(longest) << " ("
          << limiting << "); loosen that target or raise the search range\n";
    } else {
      out << "shortest recording meeting every target: "
          << required_text(plan.all_targets_duration_s, shortest) << " (set by " << limiting
          << ")\n";
    }
  }
  out << "\nduration to identify each term";
  if (!plan.targets.empty()) out << " / to meet its target";
  out << " (— not in the model)\n" << padded("axis", 10);
  for (NoiseTerm t : kNoiseTerms) out << padded(term_symbol(t), 20);
  out << "\n";
  double horizon = 0.0;
  for (const pipeline::AxisPlan& axis : plan.axes) {
    out << padded(axis.name, 10);
    for (NoiseTerm t : kNoiseTerms) {
      const double id = axis.identify_duration_s[t];
      std::string cell = std::isnan(id) ? "—" : required_text(id, shortest);
      if (std::isfinite(id)) horizon = std::max(horizon, id);
      const double target = axis.target_duration_s[t];
      if (!std::isnan(target)) {
        cell += " / " + required_text(target, shortest);
        if (std::isfinite(target)) horizon = std::max(horizon, target);
      }
      out << padded(cell, 20);
    }
    out << "\n";
  }
  // Table rows up to the first duration at or above every finite required duration.
  std::size_t rows = plan.durations_s.size();
  for (std::size_t d = 0; d < plan.durations_s.size(); ++d) {
    if (plan.durations_s[d] >= horizon) {
      rows = std::min(plan.durations_s.size(), d + 2);
      break;
    }
  }
  for (const auto& [sensor, columns] : sensor_columns(plan)) {
    out << "\n"
        << sensor << ": expected relative half-width of the 95 % interval [%] (n.i. not "
        << "identified)\n"
        << padded("duration", 10);
    for (const auto& [a, t] : columns) {
      out << padded(short_axis(plan.axes[a].name) + "." + term_symbol(t), 8);
    }
    out << "\n";
    for (std::size_t d = 0; d < rows; ++d) {
      out << padded(human_duration(plan.durations_s[d]), 10);
      for (const auto& [a, t] : columns) out << padded(cell_text(plan.axes[a].table[d][t]), 8);
      out << "\n";
    }
  }
  return out.str();
}

std::string precision_text(const pipeline::RecordingPlan& plan, const std::string& source) {
  std::ostringstream out;
  const double duration = plan.durations_s.empty() ? 0.0 : plan.durations_s.front();
  out << "imunoise plan: " << source << " at " << format("%g", plan.rate_hz) << " Hz for "
      << human_duration(duration)
      << "; intervals as the default analyze makes them (95 %, 200 OAVAR draws)\n";
  if (!plan.targets.empty()) {
    out << "targets (relative half-width of the 95 % interval): " << targets_line(plan) << "\n";
  }
  out << "\nexpected relative half-width of the 95 % interval [%] (n.i. not identified, — not "
         "in the model)\n"
      << padded("axis", 10);
  for (NoiseTerm t : kNoiseTerms) out << padded(term_symbol(t), 8);
  out << "\n";
  std::vector<std::string> missed;
  for (const pipeline::AxisPlan& axis : plan.axes) {
    out << padded(axis.name, 10);
    for (NoiseTerm t : kNoiseTerms) {
      const pipeline::TermPrecision& p = axis.table.front()[t];
      out << padded(p.present ? cell_text(p) : "—", 8);
    }
    out << "\n";
    for (const pipeline::PlanTarget& t : plan.targets) {
      const pipeline::TermPrecision& p = axis.table.front()[t.term];
      if (p.present && !pipeline::meets_target(p, t)) {
        missed.push_back(axis.name + " " + term_symbol(t.term));
      }
    }
  }
  if (!plan.targets.empty()) {
    if (missed.empty()) {
      out << "every target is met\n";
    } else {
      out << "targets not met: ";
      for (std::size_t k = 0; k < missed.size(); ++k) out << (k ? ", " : "") << missed[k];
      out << "\n";
    }
  }
  return out.str();
}

}  // namespace imunoise::report
