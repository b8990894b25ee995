/// @file
/// @brief The numeric CSV tables of imunoise's own results, read with located errors by the
/// readers of io/allan_csv.h, io/psd_csv.h and io/drift_files.h. Every reader checks the
/// columns it needs and reports a bad file as InputError "FILE:LINE: problem".
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>


namespace imunoise::io {

/// A CSV file of numbers with a header row; empty cells are allowed (a point one curve lacks).
struct NumericTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::optional<double>>> rows;

  std::optional<std::size_t> find(const std::string& name) const;
};

/// Reads PATH. Throws InputError for a missing/empty file, a row with another field count than
/// the header, or a cell that is not a finite number.
NumericTable read_numeric_table(const std::string& path);

/// The index of column NAME, or InputError "PATH:1: no column 'NAME' (is this WHAT written by
/// imunoise?)".
std::size_t require_column(const NumericTable& table, const std::string& path,
                           const std::string& name, const std::string& what);

/// The file line of data row R of a NumericTable (the header is line 1).
inline std::int64_t file_line_of_row(std::size_t row) { return static_cast<std::int64_t>(row) + 2; }

/// InputError "PATH:LINE: empty cell in column 'NAME'" unless row R of T has a value in each
/// of COLUMNS.
void require_cells(const NumericTable& t, const std::string& path, std::size_t r,
                   std::initializer_list<std::size_t> columns);

}  // namespace imunoise::io
