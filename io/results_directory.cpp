/// @file
/// @brief A results directory loaded through the typed readers (see results_directory.h).
#include "io/results_directory.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "common/errors.h"
#include "io/drift_files.h"
#include "io/noise_model_yaml.h"

namespace imunoise::io {

namespace {

namespace fs = std::filesystem;

/// The drift results of R.dir (in DIR or DIR/drift), and the model a drift directory of its
/// own names.
void load_drift_results(ResultsDirectory& r) {
  const fs::path dir(r.dir);
  for (const fs::path& candidate : {dir, dir / "drift"}) {
    if (fs::exists(candidate / "drift_summary.json")) {
      r.drift_dir = candidate.string();
      break;
    }
  }
  if (r.drift_dir.empty()) return;
  const fs::path drift(r.drift_dir);
  r.drift_summary = read_drift_summary_json((drift / "drift_summary.json").string());
  if (fs::exists(drift / "drift_envelope.csv")) {
    r.drift_envelope = read_drift_envelope_csv((drift / "drift_envelope.csv").string());
  }
  if (fs::exists(drift / "drift_budget.csv")) {
    r.drift_budget = read_drift_budget_csv((drift / "drift_budget.csv").string());
  }
  if (fs::exists(drift / "drift_segments.csv")) {
    r.drift_segments = read_drift_segments_csv((drift / "drift_segments.csv").string());
  }
  // A drift directory of its own: its summary names the model it used.
  if (!r.model && !r.drift_summary->model.empty()) {
    const fs::path used = r.drift_summary->model;
    if (fs::exists(used)) r.model = load_model_yaml(used.string());
  }
}

/// The commands.txt of DIR and of its subdirectories (sorted), those imunoise wrote.
std::vector<CommandFileEntry> command_files(const fs::path& dir) {
  std::vector<fs::path> dirs{dir};
  std::error_code ec;
  std::vector<fs::path> subdirs;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_directory(ec)) subdirs.push_back(entry.path());
  }
  std::sort(subdirs.begin(), subdirs.end());
  dirs.insert(dirs.end(), subdirs.begin(), subdirs.end());
  std::vector<CommandFileEntry> out;
  for (const fs::path& d : dirs) {
    std::optional<CommandRecord> record;
    try {
      record = read_command_file(d.string());
    } catch (const InputError&) {
      continue;  // a commands.txt imunoise did not write (another tool's): not ours to show
    }
    if (!record) continue;
    out.push_back({fs::relative(d / "commands.txt", dir, ec).generic_string(), *record});
  }
  return out;
}

/// The files of DIR the report lists (see ResultsDirectory::files).
std::vector<ResultFileEntry> result_files(const fs::path& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it.depth() > 2) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    const std::string relative = fs::relative(it->path(), dir, ec).generic_string();
    if (relative.rfind("plots/", 0) == 0 || relative == "report.html" || relative == "report.png" ||
        relative.find(".tmp") != std::string::npos ||
        fs::path(relative).filename() == "commands.txt") {
      continue;
    }
    files.push_back(relative);
  }
  std::sort(files.begin(), files.end());
  std::vector<ResultFileEntry> out;
  for (const std::string& f : files) out.push_back({f, fs::file_size(dir / f, ec)});
  return out;
}

}  // namespace

ResultsDirectory load_results_directory(const std::string& dir_text) {
  ResultsDirectory r;
  r.dir = dir_text;
  const fs::path dir(dir_text);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw InputError(dir_text +
                     ": not a directory (give the -o DIR of 'imunoise analyze' or "
                     "'imunoise drift')");
  }
  const fs::path model_path = dir / "model.yaml";
  if (fs::exists(model_path)) r.model = load_model_yaml(model_path.string());
  if (r.model && fs::exists(dir / "allan.csv")) {
    r.allan = read_allan_csv((dir / "allan.csv").string(), r.model->confidence);
  }
  if (fs::exists(dir / "psd.csv")) r.psd = read_psd_csv((dir / "psd.csv").string());
  if (fs::exists(dir / "sampling_report.json")) {
    r.sampling = read_sampling_report_json((dir / "sampling_report.json").string());
  }
  load_drift_results(r);
  if (!r.model && r.drift_dir.empty()) {
    throw InputError(dir_text +
                     ": no imunoise results here (expected model.yaml from 'imunoise analyze' or "
                     "drift_summary.json from 'imunoise drift')");
  }
  r.commands = command_files(dir);
  r.files = result_files(dir);
  return r;
}

}  // namespace imunoise::io
