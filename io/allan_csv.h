/// @file
/// @brief allan.csv, the deviation curves of `imunoise analyze`: its writer and its reader over
/// one typed table. One row per averaging factor (the union of every axis's OADEV and OHDEV
/// factors); per axis the OADEV with its interval, EDF and α, the fitted model's ADEV and the
/// OHDEV with its interval; the unit in every column name (`gyro_x_oadev_rad_per_s`).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/deviation.h"
#include "pipeline/axis_analysis.h"

namespace imunoise::io {

/// One axis of allan.csv.
struct AllanAxis {
  std::string name;  ///< gyro_x … accel_z (its sensor kind gives the unit of the columns)
  /// OADEV: per point m, τ, value, ci_low, ci_high, EDF and α (n_terms is not stored).
  analysis::DeviationCurve oadev;
  /// OHDEV: per point m, τ, value, ci_low, ci_high (EDF, α and n_terms are not stored).
  analysis::DeviationCurve ohdev;
  /// The fitted model's ADEV at the τ of every row of the table (AllanTable::tau_s).
  std::vector<double> model_adev;
};

/// Everything allan.csv holds.
struct AllanTable {
  std::vector<std::int64_t> m;  ///< the rows' averaging factors, ascending
  std::vector<double> tau_s;    ///< τ of each row [s]
  std::vector<AllanAxis> axes;  ///< in column order
};

/// The table of the analysed AXES of a record of sample period TAU0_S: τ = m·τ0 per row, the
/// model ADEV from each axis's fitted coefficients (theory.md §4.1).
AllanTable allan_table(const std::vector<pipeline::AxisAnalysis>& axes, double tau0_s);

/// Writes TABLE to PATH (atomically; shortest round-trip numbers, empty cells where an axis has
/// no point at a row's factor). Throws InputError naming PATH when it cannot be written.
void write_allan_csv(const std::string& path, const AllanTable& table);

/// Reads an allan.csv: every axis whose `<axis>_oadev_<unit>` column exists, with all its
/// columns required; the curves' confidence is CONFIDENCE (model.yaml's: the file does not
/// state it). Throws InputError "PATH:LINE: problem" for a missing column, a cell that is not a
/// finite number or a file without any axis.
AllanTable read_allan_csv(const std::string& path, double confidence);

}  // namespace imunoise::io
