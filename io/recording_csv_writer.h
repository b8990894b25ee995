/// @file
/// @brief A Recording as CSV (`imunoise convert -o FILE.csv`), in the columns `imunoise
/// simulate` writes, so that io::read_recording reads it back with default options to the same
/// values bit for bit: '#' provenance lines, the column line, then rows of shortest round-trip
/// numbers (std::to_chars). The row formatter is shared with io/simulation_output.
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "pipeline/recording.h"

namespace imunoise::io {

/// Room one number of a row takes: the longest shortest round-trip double (24 characters)
/// and its separator.
inline constexpr std::size_t kCsvFieldChars = 25;

/// Writes "TIME_S,V0,V1,…\n" at OUT, each number in its shortest round-trip form; OUT must
/// have room for (1 + VALUES.size()) × kCsvFieldChars characters. Returns the end of the row.
char* append_csv_row(char* out, double time_s, std::span<const double> values);

/// The CSV column of CHANNEL: NAME_rad_per_s for a channel in rad/s, NAME_m_per_s2 for one in
/// m/s^2 (the names a default read maps back to gyro_x … accel_z), else NAME.
std::string csv_column_name(const pipeline::Channel& channel);

/// Writes RECORDING to PATH atomically: '#' lines (source, sample_period_s, start_time_s,
/// samples, how time_s was made for a fixed rate, each channel's source column and unit), the
/// column line (time_s, then csv_column_name of each channel) and one row per sample, time_s
/// relative to the first sample (pipeline::sample_time_s).
/// @throws InputError naming PATH when it cannot be written.
void write_recording_csv(const pipeline::Recording& recording, const std::string& path);

}  // namespace imunoise::io
