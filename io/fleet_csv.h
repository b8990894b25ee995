/// @file
/// @brief fleet.csv, what `imunoise fleet` found per unit, axis and term: its writer and its
/// reader over one typed content (the units and the entries of pipeline::FleetResult). One row
/// per unit, axis and term: the estimate and its interval in the SI unit the row names, the
/// robust z-score of log10(value) over the fleet and the outlier flag, and with a spec its
/// maximum and verdict. Numbers round-trip exactly (shortest_number_text); an empty field is a
/// value that does not exist (no spec, z-score undefined).
#pragma once

#include <string>
#include <vector>

#include "pipeline/fleet.h"

namespace imunoise::io {

/// What fleet.csv holds.
struct FleetTable {
  std::vector<std::string> units;  ///< in order of first appearance
  std::vector<pipeline::FleetEntry> entries;
};

/// The table of RESULT (its units and entries).
FleetTable fleet_table(const pipeline::FleetResult& result);

/// The text of fleet.csv.
std::string fleet_csv_text(const FleetTable& table);

/// Writes fleet.csv atomically (io/atomic_output.h).
void write_fleet_csv(const std::string& path, const FleetTable& table);

/// Parses TEXT written by fleet_csv_text; FILE names it in errors.
/// @throws InputError naming FILE, the line and the problem.
FleetTable parse_fleet_csv(const std::string& text, const std::string& file);

/// Reads fleet.csv. @throws InputError (unreadable file, or as parse_fleet_csv).
FleetTable read_fleet_csv(const std::string& path);

}  // namespace imunoise::io
