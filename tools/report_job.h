/// @file
/// @brief `DIR/report.html` from the results saved in DIR — what `imunoise analyze` and
/// `imunoise drift` write at their end and `imunoise report DIR` rewrites. Reads model.yaml,
/// allan.csv, psd.csv, sampling_report.json, the drift results (in DIR or DIR/drift),
/// commands.txt files and the list of exports; writes DIR/plots/NAME.svg and NAME.csv per
/// figure and the self-contained report.html, each atomically.
#pragma once

#include <string>

namespace imunoise::tools {

/// What write_report produced.
struct ReportOutput {
  std::string html_path;  ///< DIR/report.html
  int figures = 0;
};

/// Builds the report of DIR. Results that are absent are left out of the page; throws
/// InputError when DIR holds no imunoise results at all (neither model.yaml nor
/// drift_summary.json), or naming the file when one of them is malformed.
ReportOutput write_report(const std::string& dir);

}  // namespace imunoise::tools
