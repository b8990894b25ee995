/// @file
/// @brief Readers of imunoise's own CSV results (see result_files.h).
#include "io/result_files.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <system_error>

#include "common/errors.h"
#include "common/units.h"
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

void require_cells(const NumericTable& t, const std::string& path, std::size_t r,
                   std::initializer_list<std::size_t> columns) {
  for (std::size_t c : columns) {
    if (!t.rows[r][c]) {
      std::string problem = "empty cell in column '";
      problem.append(t.columns[c]).append("'");
      throw InputError(located_message(path, file_line_of_row(r), 0, problem));
    }
  }
}

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

}  // namespace imunoise::io
