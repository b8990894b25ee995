/// @file
/// @brief psd.csv, the spectra of `imunoise analyze`: its writer and its reader over one typed
/// table. One row per log bin (the union of the axes' bin frequencies: every axis of one record
/// has the same bins); per axis the one-sided PSD, its dof and the fitted model's PSD, the unit
/// in every column name (`gyro_x_psd_rad2_per_s2_per_hz`).
#pragma once

#include <string>
#include <vector>

#include "analysis/psd.h"
#include "pipeline/axis_analysis.h"

namespace imunoise::io {

/// One axis of psd.csv.
struct PsdAxis {
  std::string name;  ///< gyro_x … accel_z (its sensor kind gives the unit of the columns)
  /// The log-binned one-sided PSD: frequency_hz, density and dof (nothing else is stored).
  analysis::Spectrum psd;
  /// The fitted model's one-sided PSD at each of psd.frequency_hz (theory.md §5.3).
  std::vector<double> model_density;
};

/// Everything psd.csv holds.
struct PsdTable {
  std::vector<double> frequency_hz;  ///< the rows' frequencies [Hz], ascending
  std::vector<PsdAxis> axes;         ///< in column order
};

/// The table of the analysed AXES of a record of sample period TAU0_S (the model PSD in its
/// one-sided form, analysis::model_psd_one_sided).
PsdTable psd_table(const std::vector<pipeline::AxisAnalysis>& axes, double tau0_s);

/// Writes TABLE to PATH (atomically; shortest round-trip numbers, empty cells where an axis has
/// no bin at a row's frequency). Throws InputError naming PATH when it cannot be written.
void write_psd_csv(const std::string& path, const PsdTable& table);

/// Reads a psd.csv: every axis whose `<axis>_psd_<unit>` column exists, with its dof and model
/// columns required. Throws InputError "PATH:LINE: problem" for a missing column, a cell that is
/// not a finite number or a file without any axis.
PsdTable read_psd_csv(const std::string& path);

}  // namespace imunoise::io
