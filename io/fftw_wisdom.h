/// @file
/// @brief FFTW wisdom files: the saved plans that let analysis::WelchEstimator use a measured
/// (FFTW_MEASURE or FFTW_PATIENT) r2c plan without measuring in every run. The wisdom is
/// process-global in FFTW; both functions hold common/fftw_planner_lock.h's mutex.
#pragma once

#include <string>

namespace imunoise::io {

/// Imports the FFTW wisdom in PATH into the process (merged with what it already holds).
/// @throws InputError "PATH: cannot open the FFTW wisdom file (REASON)" when the file cannot
/// be opened, "PATH: cannot read the FFTW wisdom file (REASON)" on a read error (e.g. a
/// directory), and "PATH: not an FFTW wisdom file …" when FFTW rejects the content (garbage,
/// an empty file, or wisdom of another FFTW version or precision).
void import_fftw_wisdom(const std::string& path);

/// Writes all FFTW wisdom the process holds to PATH, atomically (temporary file + rename:
/// never a half-written file; an existing PATH stays as it was on failure).
/// @throws InputError naming PATH when it cannot be written.
void export_fftw_wisdom(const std::string& path);

}  // namespace imunoise::io
