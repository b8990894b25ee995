/// @file
/// @brief The page and summary of `imunoise fleet` (see fleet_page.h).
#include "report/fleet_page.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "common/number_text.h"
#include "models/datasheet_units.h"
#include "report/result_tables.h"

namespace imunoise::report {

namespace {

using pipeline::FleetEntry;
using pipeline::FleetResult;
using pipeline::SpecVerdict;

std::string ds(double si, SensorKind sensor, NoiseTerm term, int digits = 3) {
  return number_cell(si * models::datasheet_unit(term, sensor).factor, digits);
}

std::string unit_text(SensorKind sensor, NoiseTerm term) {
  return std::string(models::datasheet_unit(term, sensor).unicode);
}

/// "K 12.3 [11, 14] °/h/√h > max 10" or "… (not identified, < 3)".
std::string entry_text(const FleetEntry& e) {
  // Built with append() only: GCC 12 raises a false -Wrestrict on `" " + std::string(…)`.
  std::string out = e.axis;
  out.append(" ").append(term_symbol(e.term)).append(" ");
  if (e.estimate.identified) {
    out.append(ds(e.estimate.value, e.sensor, e.term))
        .append(" [")
        .append(ds(e.estimate.ci_low, e.sensor, e.term))
        .append(", ")
        .append(ds(e.estimate.ci_high, e.sensor, e.term))
        .append("]");
  } else {
    out.append("< ").append(ds(e.estimate.ci_high, e.sensor, e.term)).append(" (not identified)");
  }
  out.append(" ").append(unit_text(e.sensor, e.term));
  if (e.spec_max_si) out.append(", max ").append(ds(*e.spec_max_si, e.sensor, e.term));
  return out;
}

/// The entries of UNIT with VERDICT, as text.
std::vector<std::string> entries_with(const FleetResult& r, std::size_t unit, SpecVerdict verdict) {
  std::vector<std::string> out;
  for (const FleetEntry& e : r.entries)
    if (e.unit == unit && e.spec_verdict == verdict) out.push_back(entry_text(e));
  return out;
}

std::vector<std::string> outliers_of(const FleetResult& r, std::size_t unit) {
  std::vector<std::string> out;
  for (const FleetEntry& e : r.entries)
    if (e.unit == unit && e.outlier)
      out.push_back(e.axis + " " + term_symbol(e.term) + " (z " + number_cell(e.robust_z, 2) + ")");
  return out;
}

std::string joined(const std::vector<std::string>& v, const char* sep = "; ") {
  std::string out;
  for (const std::string& s : v) out.append(out.empty() ? "" : sep).append(s);
  return out;
}

std::string verdict_counts(const FleetResult& r) {
  std::size_t pass = 0, fail = 0, undecided = 0;
  for (SpecVerdict v : r.unit_verdicts) {
    pass += v == SpecVerdict::pass;
    fail += v == SpecVerdict::fail;
    undecided += v == SpecVerdict::undecided;
  }
  return std::to_string(pass) + " pass, " + std::to_string(fail) + " fail, " +
         std::to_string(undecided) + " undecided";
}

Table units_table(const FleetResult& r) {
  Table t;
  t.id = "fleet-units";
  t.caption = r.spec ? "Each unit against " + (r.spec->name.empty() ? "the spec" : r.spec->name) +
                           ": pass = interval below every maximum, fail = interval above one, "
                           "undecided = an interval straddles a maximum (record longer)"
                     : "Each unit (no spec given: --spec FILE judges them)";
  t.header = {"unit", "verdict", "fails", "undecided", "robust outliers"};
  for (std::size_t u = 0; u < r.units.size(); ++u) {
    t.rows.push_back({r.units[u], r.spec ? pipeline::spec_verdict_name(r.unit_verdicts[u]) : "—",
                      joined(entries_with(r, u, SpecVerdict::fail)),
                      joined(entries_with(r, u, SpecVerdict::undecided)),
                      joined(outliers_of(r, u))});
  }
  return t;
}

Table distribution_table(const FleetResult& r, SensorKind sensor) {
  Table t;
  t.id = std::string("fleet-") + std::string(sensor_name(sensor));
  t.caption = std::string(sensor_name(sensor)) +
              ": per axis and term over the units that identified it — median, range, spread "
              "(σ of log10 from the MAD: ×10^σ), outliers (|robust z| > " +
              number_cell(pipeline::kOutlierRobustZ, 2) + ")";
  t.header = {"axis",  "term",     "unit",     "identified", "median",
              "range", "spread ×", "outliers", "spec max"};
  for (const pipeline::TermDistribution& d : r.distributions) {
    if (d.sensor != sensor) continue;
    std::vector<std::string> outliers;
    for (std::size_t u : d.outliers) outliers.push_back(r.units[u]);
    std::string max = "—";
    if (r.spec)
      for (const pipeline::SpecLimit& l : r.spec->limits)
        if (l.sensor == sensor && l.term == d.term) max = ds(l.max_si, sensor, d.term);
    const bool any = d.identified > 0;
    t.rows.push_back(
        {d.axis, std::string(term_symbol(d.term)) + " " + std::string(term_name(d.term)),
         unit_text(sensor, d.term), std::to_string(d.identified) + " of " + std::to_string(d.units),
         any ? ds(d.median_si, sensor, d.term) : "—",
         any ? "[" + ds(d.min_si, sensor, d.term) + ", " + ds(d.max_si, sensor, d.term) + "]" : "—",
         d.identified >= 2 ? number_cell(std::pow(10.0, d.log10_spread), 3) : "—",
         outliers.empty() ? "none" : joined(outliers, ", "), max});
  }
  return t;
}

Table entries_table(const FleetResult& r) {
  Table t;
  t.id = "fleet-entries";
  t.caption = "Every unit's coefficients with their intervals, in datasheet units";
  t.header = {"unit", "axis", "term", "value [interval]", "robust z", "spec verdict"};
  for (const FleetEntry& e : r.entries) {
    t.rows.push_back({r.units[e.unit], e.axis, std::string(term_symbol(e.term)),
                      entry_text(e).substr(e.axis.size() + 3),
                      std::isfinite(e.robust_z) ? number_cell(e.robust_z, 2) : "—",
                      e.spec_verdict ? pipeline::spec_verdict_name(*e.spec_verdict) : "—"});
  }
  t.folded = true;
  return t;
}

}  // namespace

ReportPage build_fleet_page(const FleetResult& r, const std::string& written) {
  ReportPage page;
  page.title = "imunoise fleet — " + std::to_string(r.units.size()) + " units";
  page.facts = {{"units", std::to_string(r.units.size())}};
  if (r.spec) {
    page.facts.push_back({"spec", r.spec->name.empty() ? "(unnamed)" : r.spec->name});
    page.facts.push_back({"verdicts", verdict_counts(r)});
  }
  page.facts.push_back({"written", written + " by imunoise"});
  PageSection verdict{"verdict", "Verdict", {}, {}, {}, {}, {}};
  std::size_t flagged = 0;
  for (std::size_t u = 0; u < r.units.size(); ++u) flagged += !outliers_of(r, u).empty() ? 1 : 0;
  verdict.paragraphs.push_back(
      (r.spec ? verdict_counts(r) + " against the spec; " : std::string("no spec given; ")) +
      std::to_string(flagged) + " unit(s) with a robust outlier among their coefficients.");
  verdict.tables.push_back(units_table(r));
  page.sections.push_back(std::move(verdict));
  PageSection dist{"distributions", "Distributions over the units", {}, {}, {}, {}, {}};
  for (const SensorKind sensor : kSensorKinds) {
    Table t = distribution_table(r, sensor);
    if (!t.rows.empty()) dist.tables.push_back(std::move(t));
  }
  page.sections.push_back(std::move(dist));
  PageSection all{"entries", "Every unit", {}, {}, {}, {}, {}};
  all.tables.push_back(entries_table(r));
  page.sections.push_back(std::move(all));
  page.footer = "imunoise fleet — fleet.csv beside this page holds every number in SI.";
  return page;
}

std::string fleet_summary_text(const FleetResult& r) {
  std::ostringstream out;
  out << "imunoise fleet: " << r.units.size() << " units";
  if (r.spec)
    out << " against " << (r.spec->name.empty() ? "the spec" : r.spec->name) << ": "
        << verdict_counts(r);
  out << "\n";
  for (std::size_t u = 0; u < r.units.size(); ++u) {
    out << "  " << r.units[u];
    if (r.spec) out << ": " << pipeline::spec_verdict_name(r.unit_verdicts[u]);
    out << "\n";
    for (const std::string& s : entries_with(r, u, SpecVerdict::fail))
      out << "      fails: " << s << "\n";
    for (const std::string& s : entries_with(r, u, SpecVerdict::undecided))
      out << "      undecided: " << s << "\n";
    for (const std::string& s : outliers_of(r, u)) out << "      outlier: " << s << "\n";
  }
  return out.str();
}

}  // namespace imunoise::report
