/// @file
/// @brief A results directory loaded: everything `imunoise analyze` and `imunoise drift` saved in
/// DIR (model.yaml, allan.csv, psd.csv, sampling_report.json, the drift files in DIR or
/// DIR/drift, the commands.txt of DIR and of its subdirectories) read through the typed reader
/// of each file, and the list of files DIR holds. What `imunoise report` builds its page from
/// (report/report_page.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/allan_csv.h"
#include "io/commands_file.h"
#include "io/psd_csv.h"
#include "io/sampling_report.h"
#include "models/noise_model.h"
#include "pipeline/drift_run.h"
#include "pipeline/drift_series.h"

namespace imunoise::io {

/// One file of the directory, as the report lists it.
struct ResultFileEntry {
  std::string relative_path;      ///< relative to the directory, '/'-separated (e.g. "drift/x.csv")
  std::uintmax_t size_bytes = 0;  ///< std::filesystem::file_size (uintmax_t(-1) when unknown)
};

/// A commands.txt of the directory or of one of its subdirectories.
struct CommandFileEntry {
  std::string relative_path;  ///< e.g. "commands.txt", "drift/commands.txt"
  CommandRecord record;
};

/// Everything found in a results directory; absent files leave their member empty.
struct ResultsDirectory {
  std::string dir;  ///< the directory as given
  /// DIR/model.yaml, or (for a drift directory of its own) the model its drift summary names,
  /// when that file exists.
  std::optional<models::NoiseModel> model;
  std::optional<AllanTable> allan;  ///< DIR/allan.csv, read only with a model (its confidence)
  std::optional<PsdTable> psd;      ///< DIR/psd.csv
  std::optional<SamplingReportFile> sampling;  ///< DIR/sampling_report.json
  /// The directory of the drift results: DIR when it holds drift_summary.json, else DIR/drift
  /// when that does; "" = no drift results. With it, drift_summary is set.
  std::string drift_dir;
  std::optional<pipeline::DriftSummary> drift_summary;
  std::optional<pipeline::DriftSeries> drift_envelope;  ///< drift_envelope.csv there
  std::vector<pipeline::DriftSegment> drift_segments;   ///< drift_segments.csv there
  std::optional<pipeline::DriftBudget> drift_budget;    ///< drift_budget.csv there
  /// The commands.txt imunoise wrote in DIR, then in its subdirectories (sorted by name);
  /// a commands.txt imunoise did not write (another tool's) is left out.
  std::vector<CommandFileEntry> commands;
  /// The regular files up to two levels below DIR, sorted by path, without the report's own
  /// files (plots/…, report.html, report.png), temporary files (".tmp" in the path) and
  /// commands.txt (listed in `commands`).
  std::vector<ResultFileEntry> files;
};

/// Loads the results directory DIR.
/// @throws InputError "DIR: not a directory (…)", "DIR: no imunoise results here (…)" when DIR
/// holds neither model.yaml nor a drift_summary.json, or the located error of the reader of a
/// malformed file (it names the file: "DIR/psd.csv:3: …").
ResultsDirectory load_results_directory(const std::string& dir);

}  // namespace imunoise::io
