/// @file
/// @brief Reading back the CSV results imunoise writes (allan.csv, psd.csv; the drift files are
/// io/drift_files.h), for `imunoise publish` and `imunoise report`. Every reader checks the
/// columns it needs and reports a bad file as InputError "FILE:LINE: problem".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/lcm_messages.h"

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

/// The OADEV and OHDEV curves of allan.csv (imunoise analyze): one series per axis and
/// statistic, at the rows where the statistic has a value; intervals at level CONFIDENCE.
std::vector<DeviationSeries> read_allan_csv(const std::string& path, double confidence);

/// One axis of psd.csv: the measured one-sided PSD and the fitted model's, per frequency.
struct PsdSeries {
  std::string axis_name;  ///< gyro_x … accel_z
  bool gyro = true;       ///< unit (rad/s)²/Hz, else (m/s²)²/Hz
  std::vector<double> frequency_hz, density, model_density;
};

/// The axes of psd.csv (imunoise analyze), at the rows where the axis has a value.
std::vector<PsdSeries> read_psd_csv(const std::string& path);

}  // namespace imunoise::io
