/// @file
/// @brief `DIR/report.html` from the results saved in DIR — what `imunoise analyze` and
/// `imunoise drift` write at their end and `imunoise report DIR` rewrites: the directory loaded
/// (io/results_directory.h), the page built (report/report_page.h), then DIR/plots/NAME.svg and
/// NAME.csv per figure and the self-contained report.html written, each atomically. The one
/// part of report/ that touches the disk.
#pragma once

#include <string>

#include "pipeline/fleet.h"

namespace imunoise::report {

/// What write_report produced.
struct ReportOutput {
  std::string html_path;  ///< DIR/report.html
  int figures = 0;
};

/// Builds and writes the report of DIR. Results that are absent are left out of the page.
/// Nothing is written until the whole page is built: a bad input file leaves no partial report.
/// @throws InputError when DIR holds no imunoise results at all (neither model.yaml nor
/// drift_summary.json), naming the file when one of them is malformed, or naming the path
/// when a file cannot be written.
ReportOutput write_report(const std::string& dir);

/// Writes DIR/fleet.html, the page of `imunoise fleet` (report/fleet_page.h), atomically; the
/// directory must exist. Returns the path.
std::string write_fleet_report(const std::string& dir, const pipeline::FleetResult& result);

}  // namespace imunoise::report
