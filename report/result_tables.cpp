/// @file
/// @brief The report's tables of saved results (see result_tables.h).
#include "report/result_tables.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/number_text.h"
#include "common/sampling_gap.h"
#include "common/sensor_kind.h"
#include "models/datasheet_units.h"

namespace imunoise::report {

namespace {

std::string term_label(NoiseTerm term, SensorKind kind) {
  switch (term) {
    case NoiseTerm::quantization:
      return "Q quantization";
    case NoiseTerm::white_noise:
      return kind == SensorKind::gyro ? "N angle random walk" : "N velocity random walk";
    case NoiseTerm::bias_instability:
      return "B bias instability";
    case NoiseTerm::random_walk:
      return kind == SensorKind::gyro ? "K rate random walk" : "K acceleration random walk";
    case NoiseTerm::ramp:
      return kind == SensorKind::gyro ? "R rate ramp" : "R acceleration ramp";
  }
  return "";
}

std::string num(double v, int digits = 4) { return number_cell(v, digits); }

}  // namespace

std::string number_cell(double v, int digits) {
  return std::isfinite(v) ? significant_number_text(v, digits) : "—";
}

Table summary_table(const models::NoiseModel& model) {
  Table t;
  t.id = "summary-table";
  const std::string level = num(100.0 * model.confidence, 3) + " %";
  t.caption = "Fitted coefficients with their " + level +
              " intervals, in SI and in datasheet units ('—' = not identified; the interval "
              "is then an upper bound)";
  t.header = {"axis",
              "term",
              "value (SI)",
              level + " interval (SI)",
              "SI unit",
              "value",
              level + " interval",
              "datasheet unit",
              "IEEE-952 read-off",
              "method"};
  for (const models::AxisModel& axis : model.axes) {
    for (NoiseTerm term : kNoiseTerms) {
      const models::Estimate& e = axis.terms[term];
      const models::DatasheetUnit unit = models::datasheet_unit(term, axis.kind);
      const double f = unit.factor;
      const double readoff = axis.readoff.slope[term];
      std::vector<std::string> row{axis.name, term_label(term, axis.kind)};
      if (e.identified) {
        row.push_back(num(e.value));
        row.push_back("[" + num(e.ci_low) + ", " + num(e.ci_high) + "]");
      } else {
        row.push_back("—");
        row.push_back(e.ci_high > 0.0 ? "< " + num(e.ci_high, 2) : "—");
      }
      row.push_back(std::string(models::term_si_unit(term, axis.kind)));
      if (e.identified) {
        row.push_back(num(e.value * f));
        row.push_back("[" + num(e.ci_low * f) + ", " + num(e.ci_high * f) + "]");
      } else {
        row.push_back("—");
        row.push_back(e.ci_high > 0.0 ? "< " + num(e.ci_high * f, 2) : "—");
      }
      row.push_back(std::string(unit.unicode));
      row.push_back(readoff > 0.0 ? num(readoff * f) : "—");
      row.push_back(e.identified ? e.method : "not identified");
      t.rows.push_back(std::move(row));
    }
  }
  return t;
}

Table gauss_markov_table(const models::NoiseModel& model) {
  Table t;
  t.id = "gauss-markov-table";
  t.caption =
      "Bias instability B as one first-order Gauss–Markov term for filters "
      "(theory.md §4.4), per convention";
  t.header = {"axis", "convention", "σ (SI)", "SI unit", "correlation time T_c [s]"};
  for (const models::AxisModel& axis : model.axes) {
    for (const models::BiasInstabilityGm& gm : axis.bias_instability_gm) {
      t.rows.push_back({axis.name, gm.convention, num(gm.value.sigma),
                        std::string(si_rate_unit(axis.kind)), num(gm.value.tau_c_s)});
    }
    for (const models::GaussMarkovEstimate& gm : axis.gauss_markov) {
      t.rows.push_back({axis.name, "fitted GM term",
                        num(gm.value.sigma) + " [" + num(gm.sigma_ci_low, 3) + ", " +
                            num(gm.sigma_ci_high, 3) + "]",
                        std::string(si_rate_unit(axis.kind)),
                        num(gm.value.tau_c_s) + " [" + num(gm.tau_c_ci_low_s, 3) + ", " +
                            num(gm.tau_c_ci_high_s, 3) + "]"});
    }
  }
  return t;
}

Table sampling_table(const pipeline::SamplingReport& report) {
  const pipeline::TimingReport& timing = report.timing;
  Table t;
  t.id = "sampling-table";
  t.caption = "Sampling";
  t.header = {"quantity", "value"};
  const auto add = [&](const std::string& label, double v, const char* unit) {
    if (std::isfinite(v)) {
      t.rows.push_back({label, number_cell(v, 6) + (unit[0] ? " " : "") + unit});
    }
  };
  const auto count = [](std::int64_t n) { return static_cast<double>(n); };
  add("samples", count(report.samples), "");
  add("sample rate (1 / median interval)", timing.rate_hz, "Hz");
  add("mean rate", timing.mean_rate_hz, "Hz");
  add("duration", timing.duration_s, "s");
  add("gaps (> " + shortest_number_text(kGapFactor) + " × median interval)",
      count(timing.gap_count), "");
  add("longest gap", timing.longest_gap_s, "s");
  add("missing samples (in gaps)", count(timing.missing_samples), "");
  add("non-monotonic stamps", count(timing.non_monotonic_count), "");
  add("duplicate stamps", count(timing.duplicate_count), "");
  add("interval jitter, RMS", timing.jitter_rms_s, "s");
  add("interval jitter, max", timing.jitter_max_s, "s");
  add("rows dropped (NaN/Inf)", count(report.rows_dropped), "");
  return t;
}

Table drift_table(const pipeline::DriftSummary& summary) {
  Table t;
  t.id = "drift-table";
  t.caption = "Recorded drift vs the model's prediction at the checkpoints";
  t.header = {"time [s]",        "predicted DRMS [m]", "recorded RMS [m]",     "RMS ratio [95 %]",
              "coverage 1/2/3σ", "expected",           "mean NEES [95 % band]"};
  const auto triple = [](const std::array<double, 3>& a) {
    std::string out;
    for (std::size_t i = 0; i < 3; ++i) {
      if (i) out.append(" / ");
      out.append(num(a[i], 2));
    }
    return out;
  };
  // A non-finite bound (null in the file) leaves the interval out.
  const auto pair = [](double low, double high) {
    if (!std::isfinite(low) || !std::isfinite(high)) return std::string("");
    return " [" + num(low, 3) + ", " + num(high, 3) + "]";
  };
  for (const pipeline::DriftConsistency& c : summary.consistency) {
    t.rows.push_back({num(c.time_s, 6), num(c.predicted_drms_m), num(c.actual_rms_m),
                      num(c.rms_ratio, 3) + pair(c.rms_ratio_ci_low, c.rms_ratio_ci_high),
                      triple(c.coverage), triple(c.expected_coverage),
                      num(c.mean_nees, 3) + pair(c.nees_band_low, c.nees_band_high)});
  }
  return t;
}

Table drift_budget_table(const pipeline::DriftBudget& budget) {
  Table t;
  t.id = "drift-budget-table";
  t.caption =
      "Drift budget: each source's part of the predicted horizontal error at the report times "
      "(σ it alone gives, and its share of the variance)";
  t.header = {"source"};
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < budget.time_s.size(); ++i) {
    if (!budget.report_time[i]) continue;
    at.push_back(i);
    const std::string time = num(budget.time_s[i], 6) + " s";
    t.header.push_back("σ at " + time + " [m]");
    t.header.push_back("share at " + time + " [%]");
  }
  if (at.empty()) return t;
  for (std::size_t g = 0; g < ins::kDriftBudgetTerms; ++g) {
    const auto term = static_cast<ins::DriftBudgetTerm>(g);
    std::vector<std::string> row{std::string(ins::symbol_of(term))};
    for (const std::size_t i : at) {
      const double v = budget.variance_m2[i][g], total = budget.predicted_variance_m2[i];
      row.push_back(num(std::sqrt(std::max(v, 0.0))));
      row.push_back(num(total > 0.0 ? 100.0 * v / total : 0.0));
    }
    t.rows.push_back(std::move(row));
  }
  std::vector<std::string> total{"total (predicted DRMS)"};
  for (const std::size_t i : at) {
    total.push_back(num(std::sqrt(budget.predicted_variance_m2[i])));
    total.push_back("100");
  }
  t.rows.push_back(std::move(total));
  return t;
}

}  // namespace imunoise::report
