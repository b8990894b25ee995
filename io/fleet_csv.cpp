/// @file
/// @brief fleet.csv (see fleet_csv.h).
#include "io/fleet_csv.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/csv_fields.h"

namespace imunoise::io {

namespace {

constexpr const char* kHeader =
    "unit,axis,term,si_unit,identified,value_si,ci_low_si,ci_high_si,robust_z_log10,outlier,"
    "spec_max_si,spec_verdict";
constexpr std::size_t kColumns = 12;

std::string number(double v) { return std::isfinite(v) ? shortest_number_text(v) : ""; }

[[noreturn]] void fail(const std::string& file, std::int64_t line, const std::string& what) {
  throw InputError(located_message(file, line, 0, what));
}

double parse_number(const std::string& s, const std::string& file, std::int64_t line,
                    const char* column) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
    fail(file, line, std::string(column) + ": '" + s + "' is not a finite number");
  return v;
}

bool parse_bool(const std::string& s, const std::string& file, std::int64_t line,
                const char* column) {
  if (s == "true") return true;
  if (s == "false") return false;
  fail(file, line, std::string(column) + ": '" + s + "' is neither true nor false");
}

}  // namespace

FleetTable fleet_table(const pipeline::FleetResult& result) {
  return {result.units, result.entries};
}

std::string fleet_csv_text(const FleetTable& table) {
  std::ostringstream out;
  out << kHeader << "\n";
  for (const pipeline::FleetEntry& e : table.entries) {
    IMUNOISE_EXPECT(e.unit < table.units.size(), "fleet.csv: entry of unit " +
                                                     std::to_string(e.unit) + " of " +
                                                     std::to_string(table.units.size()));
    out << csv_field(table.units[e.unit]) << "," << csv_field(e.axis) << "," << term_name(e.term)
        << "," << models::term_si_unit(e.term, e.sensor) << ","
        << (e.estimate.identified ? "true" : "false") << "," << number(e.estimate.value) << ","
        << number(e.estimate.ci_low) << "," << number(e.estimate.ci_high) << ","
        << number(e.robust_z) << "," << (e.outlier ? "true" : "false") << ","
        << (e.spec_max_si ? number(*e.spec_max_si) : "") << ","
        << (e.spec_verdict ? pipeline::spec_verdict_name(*e.spec_verdict) : "") << "\n";
  }
  return out.str();
}

void write_fleet_csv(const std::string& path, const FleetTable& table) {
  write_file_atomically(path, fleet_csv_text(table));
}

FleetTable parse_fleet_csv(const std::string& text, const std::string& file) {
  FleetTable t;
  std::istringstream in(text);
  std::string line;
  std::int64_t number_of_line = 0;
  std::vector<std::string> f;
  if (!std::getline(in, line))
    fail(file, 1, "empty file; expected the header '" + std::string(kHeader) + "'");
  ++number_of_line;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != kHeader)
    fail(file, 1, "not a fleet.csv header: expected '" + std::string(kHeader) + "'");
  while (std::getline(in, line)) {
    ++number_of_line;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (!split_csv_fields(line, f)) fail(file, number_of_line, "a quoted field is not closed");
    if (f.size() != kColumns)
      fail(file, number_of_line,
           std::to_string(f.size()) + " fields, the header has " + std::to_string(kColumns));
    pipeline::FleetEntry e;
    std::size_t unit = 0;
    while (unit < t.units.size() && t.units[unit] != f[0]) ++unit;
    if (unit == t.units.size()) t.units.push_back(f[0]);
    e.unit = unit;
    e.axis = f[1];
    bool term_found = false;
    for (NoiseTerm term : kNoiseTerms) {
      if (f[2] == term_name(term)) {
        e.term = term;
        term_found = true;
      }
    }
    if (!term_found) fail(file, number_of_line, "term: unknown term '" + f[2] + "'");
    if (f[3] == models::term_si_unit(e.term, SensorKind::gyro)) {
      e.sensor = SensorKind::gyro;
    } else if (f[3] == models::term_si_unit(e.term, SensorKind::accel)) {
      e.sensor = SensorKind::accel;
    } else {
      fail(file, number_of_line, "si_unit: '" + f[3] + "' is not a unit of " + f[2]);
    }
    e.estimate.identified = parse_bool(f[4], file, number_of_line, "identified");
    e.estimate.value = parse_number(f[5], file, number_of_line, "value_si");
    e.estimate.ci_low = parse_number(f[6], file, number_of_line, "ci_low_si");
    e.estimate.ci_high = parse_number(f[7], file, number_of_line, "ci_high_si");
    e.robust_z =
        f[8].empty() ? std::nan("") : parse_number(f[8], file, number_of_line, "robust_z_log10");
    e.outlier = parse_bool(f[9], file, number_of_line, "outlier");
    if (!f[10].empty()) e.spec_max_si = parse_number(f[10], file, number_of_line, "spec_max_si");
    if (!f[11].empty()) {
      bool found = false;
      for (auto v : {pipeline::SpecVerdict::pass, pipeline::SpecVerdict::fail,
                     pipeline::SpecVerdict::undecided}) {
        if (f[11] == pipeline::spec_verdict_name(v)) {
          e.spec_verdict = v;
          found = true;
        }
      }
      if (!found)
        fail(file, number_of_line, "spec_verdict: '" + f[11] + "' is not pass, fail or undecided");
    }
    if (e.spec_max_si.has_value() != e.spec_verdict.has_value())
      fail(file, number_of_line, "spec_max_si and spec_verdict must be both given or both empty");
    t.entries.push_back(std::move(e));
  }
  return t;
}

FleetTable read_fleet_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_fleet_csv(text.str(), path);
}

}  // namespace imunoise::io
