/// @file
/// @brief Readers of imunoise's own CSV results (see result_files.h).
#include "io/result_files.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <system_error>

#include "common/errors.h"
#include "pipeline/recording.h"

namespace imunoise::io {

namespace {

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

}  // namespace

std::optional<std::size_t> NumericTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return i;
  }
  return std::nullopt;
}

NumericTable read_numeric_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(located_message(path, 0, 0, "cannot open for reading"));
  NumericTable table;
  std::string line;
  std::int64_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> cells = split_commas(line);
    if (table.columns.empty()) {
      table.columns = std::move(cells);
      continue;
    }
    if (cells.size() != table.columns.size()) {
      throw InputError(located_message(path, line_number, 0,
                                       std::to_string(cells.size()) + " fields, the header has " +
                                           std::to_string(table.columns.size())));
    }
    std::vector<std::optional<double>> row;
    row.reserve(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].empty()) {
        row.emplace_back();
        continue;
      }
      double v = 0.0;
      const char* first = cells[c].data();
      const char* last = first + cells[c].size();
      const auto [end, ec] = std::from_chars(first, last, v);
      if (ec != std::errc() || end != last || !std::isfinite(v)) {
        std::string problem = "column '";
        problem.append(table.columns[c]).append("': '").append(cells[c]);
        problem.append("' is not a finite number");
        throw InputError(located_message(path, line_number, 0, problem));
      }
      row.emplace_back(v);
    }
    table.rows.push_back(std::move(row));
  }
  if (table.columns.empty()) throw InputError(located_message(path, 0, 0, "empty file"));
  return table;
}

std::size_t require_column(const NumericTable& table, const std::string& path,
                           const std::string& name, const std::string& what) {
  if (const auto i = table.find(name)) return *i;
  std::string problem = "no column '";
  problem.append(name).append("' (is this ").append(what).append(" written by imunoise?)");
  throw InputError(located_message(path, 1, 0, problem));
}

std::vector<DeviationSeries> read_allan_csv(const std::string& path, double confidence) {
  const NumericTable t = read_numeric_table(path);
  const std::size_t tau = require_column(t, path, "tau_s", "an allan.csv");
  std::vector<DeviationSeries> out;
  for (const char* axis : pipeline::kImuChannelNames) {
    const bool gyro = std::string(axis).rfind("gyro", 0) == 0;
    const std::string unit_suffix = gyro ? "rad_per_s" : "m_per_s2";
    for (const char* statistic : {"oadev", "ohdev"}) {
      const std::string base = std::string(axis) + "_" + statistic + "_";
      const auto value = t.find(base + unit_suffix);
      if (!value) continue;  // an axis that was not analysed
      const std::size_t low = require_column(t, path, base + "ci_low_" + unit_suffix, "allan.csv");
      const std::size_t high =
          require_column(t, path, base + "ci_high_" + unit_suffix, "allan.csv");
      DeviationSeries s;
      s.axis_name = axis;
      s.statistic = statistic;
      s.unit = gyro ? "rad/s" : "m/s^2";
      s.confidence = confidence;
      for (const auto& row : t.rows) {
        if (!row[*value] || !row[tau]) continue;
        s.tau_s.push_back(*row[tau]);
        s.deviation.push_back(*row[*value]);
        s.ci_low.push_back(row[low].value_or(0.0));
        s.ci_high.push_back(row[high].value_or(0.0));
      }
      out.push_back(std::move(s));
    }
  }
  if (out.empty()) {
    throw InputError(located_message(path, 1, 0, "no <axis>_oadev_/_ohdev_ columns found"));
  }
  return out;
}

std::vector<PsdSeries> read_psd_csv(const std::string& path) {
  const NumericTable t = read_numeric_table(path);
  const std::size_t frequency = require_column(t, path, "frequency_hz", "a psd.csv");
  std::vector<PsdSeries> out;
  for (const char* axis : pipeline::kImuChannelNames) {
    const bool gyro = std::string(axis).rfind("gyro", 0) == 0;
    const std::string unit_suffix = gyro ? "rad2_per_s2_per_hz" : "m2_per_s4_per_hz";
    const auto value = t.find(std::string(axis) + "_psd_" + unit_suffix);
    if (!value) continue;
    const std::size_t model =
        require_column(t, path, std::string(axis) + "_model_psd_" + unit_suffix, "a psd.csv");
    PsdSeries s;
    s.axis_name = axis;
    s.gyro = gyro;
    for (const auto& row : t.rows) {
      if (!row[*value] || !row[frequency]) continue;
      s.frequency_hz.push_back(*row[frequency]);
      s.density.push_back(*row[*value]);
      s.model_density.push_back(row[model].value_or(std::nan("")));
    }
    out.push_back(std::move(s));
  }
  if (out.empty()) throw InputError(located_message(path, 1, 0, "no <axis>_psd_ columns found"));
  return out;
}

}  // namespace imunoise::io
