/// @file
/// @brief The report page of a results directory, built from what io/results_directory.h loaded
/// (pure: a ResultsDirectory in, the page and the text of the files behind its figures out;
/// report/write_report.h writes them). Sections, each only when its results are there:
/// "summary" (coefficient and Gauss–Markov tables), "allan" and "psd" (a figure per sensor),
/// "drift" (protocol, figure, consistency table), "sampling" (table, interval and gap figures),
/// then always "findings", "exports" (the files of the directory) and "commands" (to
/// reproduce).
#pragma once

#include <string>
#include <vector>

#include "io/results_directory.h"
#include "report/html_page.h"

namespace imunoise::report {

/// A file behind the page, to be written beside it.
struct ReportFile {
  std::string relative_path;  ///< relative to the results directory: "plots/NAME.svg" / ".csv"
  std::string text;
};

/// The report of a results directory, built but not written.
struct ReportDocument {
  ReportPage page;
  /// plots/NAME.svg (the SVG the page inlines) and plots/NAME.csv (figure_csv) of every
  /// figure, in page order.
  std::vector<ReportFile> plot_files;
};

/// Builds the report of RESULTS. WRITTEN is the time the page states it was written (e.g.
/// "2024-05-01 12:00 UTC"); every other part of the page comes from RESULTS.
/// @throws InputError from the figures and tables when RESULTS holds inconsistent data.
ReportDocument build_report_page(const io::ResultsDirectory& results, const std::string& written);

/// The number of figures on PAGE.
int figure_count(const ReportPage& page);

}  // namespace imunoise::report
