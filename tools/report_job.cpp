/// @file
/// @brief DIR/report.html from the saved results of DIR (see report_job.h).
#include "tools/report_job.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/allan_csv.h"
#include "io/atomic_output.h"
#include "io/commands_file.h"
#include "io/drift_files.h"
#include "io/noise_model_yaml.h"
#include "io/psd_csv.h"
#include "io/result_files.h"
#include "models/datasheet_units.h"
#include "models/noise_model.h"
#include "report/figures.h"
#include "report/html_page.h"
#include "tools/invocation.h"

namespace imunoise::tools {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// Everything found in the results directory.
struct SavedResults {
  fs::path dir;
  std::optional<models::NoiseModel> model;
  std::optional<io::AllanTable> allan;
  std::optional<io::PsdTable> psd;
  std::optional<json> sampling;
  fs::path drift_dir;  ///< empty = no drift results
  std::optional<pipeline::DriftSummary> drift_summary;
  std::optional<pipeline::DriftSeries> drift_envelope;
  std::vector<pipeline::DriftSegment> drift_segments;
};

json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path.string() + ": not valid JSON (" + e.what() + ")");
  }
}

/// A number of a JSON object, or NaN when absent or not a number.
double number_at(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : std::nan("");
}

SavedResults load_results(const std::string& dir_text) {
  SavedResults r;
  r.dir = fs::path(dir_text);
  std::error_code ec;
  if (!fs::is_directory(r.dir, ec)) {
    throw InputError(dir_text +
                     ": not a directory (give the -o DIR of 'imunoise analyze' or "
                     "'imunoise drift')");
  }
  const fs::path model_path = r.dir / "model.yaml";
  if (fs::exists(model_path)) r.model = io::load_model_yaml(model_path.string());
  if (r.model && fs::exists(r.dir / "allan.csv")) {
    r.allan = io::read_allan_csv((r.dir / "allan.csv").string(), r.model->confidence);
  }
  if (fs::exists(r.dir / "psd.csv")) r.psd = io::read_psd_csv((r.dir / "psd.csv").string());
  if (fs::exists(r.dir / "sampling_report.json")) {
    r.sampling = read_json(r.dir / "sampling_report.json");
  }
  for (const fs::path& candidate : {r.dir, r.dir / "drift"}) {
    if (fs::exists(candidate / "drift_summary.json")) {
      r.drift_dir = candidate;
      break;
    }
  }
  if (!r.drift_dir.empty()) {
    r.drift_summary = io::read_drift_summary_json((r.drift_dir / "drift_summary.json").string());
    if (fs::exists(r.drift_dir / "drift_envelope.csv")) {
      r.drift_envelope = io::read_drift_envelope_csv((r.drift_dir / "drift_envelope.csv").string());
    }
    if (fs::exists(r.drift_dir / "drift_segments.csv")) {
      r.drift_segments = io::read_drift_segments_csv((r.drift_dir / "drift_segments.csv").string());
    }
    // A drift directory of its own: its summary names the model it used.
    if (!r.model && !r.drift_summary->model.empty()) {
      const fs::path used = r.drift_summary->model;
      if (fs::exists(used)) r.model = io::load_model_yaml(used.string());
    }
  }
  if (!r.model && r.drift_dir.empty()) {
    throw InputError(dir_text +
                     ": no imunoise results here (expected model.yaml from 'imunoise analyze' or "
                     "drift_summary.json from 'imunoise drift')");
  }
  return r;
}

// ------------------------------------------------------------------------------- text helpers
std::string num(double v, int digits = 4) {
  return std::isfinite(v) ? significant_number_text(v, digits) : "—";
}

std::string term_label(NoiseTerm term, bool gyro) {
  switch (term) {
    case NoiseTerm::quantization:
      return "Q quantization";
    case NoiseTerm::white_noise:
      return gyro ? "N angle random walk" : "N velocity random walk";
    case NoiseTerm::bias_instability:
      return "B bias instability";
    case NoiseTerm::random_walk:
      return gyro ? "K rate random walk" : "K acceleration random walk";
    case NoiseTerm::ramp:
      return gyro ? "R rate ramp" : "R acceleration ramp";
  }
  return "";
}

std::string utc_now_text() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M UTC", &tm);
  return buffer;
}

// ------------------------------------------------------------------------------------ tables
report::Table summary_table(const models::NoiseModel& model) {
  report::Table t;
  t.id = "summary-table";
  const std::string level = num(100.0 * model.confidence, 3) + " %";
  t.caption = "Fitted coefficients with their " + level +
              " intervals, in SI and in datasheet units ('—' = not identified; the interval "
              "is then an upper bound)";
  t.header = {"axis",
              "term",
              "value (SI)",
              level + " interval (SI)",
              "SI unit",
              "value",
              level + " interval",
              "datasheet unit",
              "IEEE-952 read-off",
              "method"};
  for (const models::AxisModel& axis : model.axes) {
    for (NoiseTerm term : kNoiseTerms) {
      const models::Estimate& e = axis.terms[term];
      const models::DatasheetUnit unit = models::datasheet_unit(term, axis.gyro);
      const double f = unit.factor;
      const double readoff = axis.readoff.slope[term];
      std::vector<std::string> row{axis.name, term_label(term, axis.gyro)};
      if (e.identified) {
        row.push_back(num(e.value));
        row.push_back("[" + num(e.ci_low) + ", " + num(e.ci_high) + "]");
      } else {
        row.push_back("—");
        row.push_back(e.ci_high > 0.0 ? "< " + num(e.ci_high, 2) : "—");
      }
      row.push_back(std::string(models::term_si_unit(term, axis.gyro)));
      if (e.identified) {
        row.push_back(num(e.value * f));
        row.push_back("[" + num(e.ci_low * f) + ", " + num(e.ci_high * f) + "]");
      } else {
        row.push_back("—");
        row.push_back(e.ci_high > 0.0 ? "< " + num(e.ci_high * f, 2) : "—");
      }
      row.push_back(std::string(unit.unicode));
      row.push_back(readoff > 0.0 ? num(readoff * f) : "—");
      row.push_back(e.identified ? e.method : "not identified");
      t.rows.push_back(std::move(row));
    }
  }
  return t;
}

report::Table gauss_markov_table(const models::NoiseModel& model) {
  report::Table t;
  t.id = "gauss-markov-table";
  t.caption =
      "Bias instability B as one first-order Gauss–Markov term for filters "
      "(theory.md §4.4), per convention";
  t.header = {"axis", "convention", "σ (SI)", "SI unit", "correlation time T_c [s]"};
  for (const models::AxisModel& axis : model.axes) {
    for (const models::BiasInstabilityGm& gm : axis.bias_instability_gm) {
      t.rows.push_back({axis.name, gm.convention, num(gm.value.sigma),
                        axis.gyro ? "rad/s" : "m/s^2", num(gm.value.tau_c_s)});
    }
    for (const models::GaussMarkovEstimate& gm : axis.gauss_markov) {
      t.rows.push_back({axis.name, "fitted GM term",
                        num(gm.value.sigma) + " [" + num(gm.sigma_ci_low, 3) + ", " +
                            num(gm.sigma_ci_high, 3) + "]",
                        axis.gyro ? "rad/s" : "m/s^2",
                        num(gm.value.tau_c_s) + " [" + num(gm.tau_c_ci_low_s, 3) + ", " +
                            num(gm.tau_c_ci_high_s, 3) + "]"});
    }
  }
  return t;
}

report::Table sampling_table(const json& s) {
  report::Table t;
  t.id = "sampling-table";
  t.caption = "Sampling";
  t.header = {"quantity", "value"};
  const auto add = [&](const std::string& label, const char* key, const char* unit) {
    const double v = number_at(s, key);
    if (std::isfinite(v)) t.rows.push_back({label, num(v, 6) + (unit[0] ? " " : "") + unit});
  };
  add("samples", "samples", "");
  add("sample rate (1 / median interval)", "rate_hz", "Hz");
  add("mean rate", "mean_rate_hz", "Hz");
  add("duration", "duration_s", "s");
  add("gaps (> 1.5 × median interval)", "gap_count", "");
  add("longest gap", "longest_gap_s", "s");
  add("missing samples (in gaps)", "missing_samples", "");
  add("non-monotonic stamps", "non_monotonic_count", "");
  add("duplicate stamps", "duplicate_count", "");
  add("interval jitter, RMS", "jitter_rms_s", "s");
  add("interval jitter, max", "jitter_max_s", "s");
  add("rows dropped (NaN/Inf)", "rows_dropped", "");
  return t;
}

report::Table drift_table(const pipeline::DriftSummary& summary) {
  report::Table t;
  t.id = "drift-table";
  t.caption = "Recorded drift vs the model's prediction at the checkpoints";
  t.header = {"time [s]",        "predicted DRMS [m]", "recorded RMS [m]",     "RMS ratio [95 %]",
              "coverage 1/2/3σ", "expected",           "mean NEES [95 % band]"};
  const auto triple = [](const std::array<double, 3>& a) {
    std::string out;
    for (std::size_t i = 0; i < 3; ++i) {
      if (i) out.append(" / ");
      out.append(num(a[i], 2));
    }
    return out;
  };
  // A non-finite bound (null in the file) leaves the interval out.
  const auto pair = [](double low, double high) {
    if (!std::isfinite(low) || !std::isfinite(high)) return std::string("");
    return " [" + num(low, 3) + ", " + num(high, 3) + "]";
  };
  for (const pipeline::DriftConsistency& c : summary.consistency) {
    t.rows.push_back({num(c.time_s, 6), num(c.predicted_drms_m), num(c.actual_rms_m),
                      num(c.rms_ratio, 3) + pair(c.rms_ratio_ci_low, c.rms_ratio_ci_high),
                      triple(c.coverage), triple(c.expected_coverage),
                      num(c.mean_nees, 3) + pair(c.nees_band_low, c.nees_band_high)});
  }
  return t;
}

// ----------------------------------------------------------------------------------- figures
/// Files of the report, written only once the whole page has been built: a bad input file
/// leaves no partial report behind.
using PendingFiles = std::vector<std::pair<fs::path, std::string>>;

report::FigureBlock add_figure(const SavedResults& r, const report::Figure& figure,
                               PendingFiles& files) {
  const fs::path plots = r.dir / "plots";
  report::FigureBlock block;
  block.name = figure.name;
  block.svg = report::render_svg(figure.plot);
  block.caption = figure.caption;
  files.emplace_back(plots / (figure.name + ".svg"), block.svg);
  files.emplace_back(plots / (figure.name + ".csv"), report::figure_csv(figure));
  block.links = {{"data (CSV)", "plots/" + figure.name + ".csv"},
                 {"SVG", "plots/" + figure.name + ".svg"}};
  return block;
}

/// The gyro and the accelerometer figure MAKE(gyro) builds, each that has data.
template <typename Make>
void add_sensor_figures(const SavedResults& r, report::PageSection& section, Make make,
                        PendingFiles& files) {
  for (bool gyro : {true, false}) {
    const report::Figure f = make(gyro);
    if (!f.plot.series.empty()) section.figures.push_back(add_figure(r, f, files));
  }
}

std::vector<double> numbers_of(const json& j, const char* key) {
  std::vector<double> out;
  if (!j.contains(key) || !j[key].is_array()) return out;
  for (const json& v : j[key]) out.push_back(v.is_number() ? v.get<double>() : std::nan(""));
  return out;
}

// ----------------------------------------------------------------------------------- lists
std::string size_text(std::uintmax_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " B";
  if (bytes < 1024 * 1024) return num(static_cast<double>(bytes) / 1024.0, 3) + " KiB";
  return num(static_cast<double>(bytes) / (1024.0 * 1024.0), 3) + " MiB";
}

std::string describe_file(const std::string& relative) {
  const std::string name = fs::path(relative).filename().string();
  if (name == "model.yaml") return "the fitted model (native schema, SI units in every key)";
  if (name == "allan.csv") return "OADEV/OHDEV with intervals and the model ADEV, per axis";
  if (name == "psd.csv") return "log-binned PSD with dof and the model PSD, per axis";
  if (name == "sampling_report.json") return "sampling checks";
  if (name == "drift_segments.csv") return "recorded drift of every segment";
  if (name == "drift_envelope.csv") return "predicted drift envelope and recorded RMS";
  if (name == "drift_summary.json") return "drift consistency checks";
  if (relative.rfind("configs", 0) == 0) return "filter configuration";
  if (relative.rfind("discrete", 0) == 0) return "discrete state-space model";
  return "";
}

std::vector<std::string> export_list(const SavedResults& r) {
  std::vector<std::string> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(r.dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it.depth() > 2) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    const std::string relative = fs::relative(it->path(), r.dir, ec).generic_string();
    if (relative.rfind("plots/", 0) == 0 || relative == "report.html" || relative == "report.png" ||
        relative.find(".tmp") != std::string::npos ||
        fs::path(relative).filename() == "commands.txt") {
      continue;
    }
    files.push_back(relative);
  }
  std::sort(files.begin(), files.end());
  std::vector<std::string> out;
  for (const std::string& f : files) {
    std::string line = f + " (" + size_text(fs::file_size(r.dir / f, ec)) + ")";
    const std::string what = describe_file(f);
    if (!what.empty()) line.append(": ").append(what);
    out.push_back(line);
  }
  return out;
}

std::vector<std::string> command_lines(const SavedResults& r) {
  std::vector<std::string> out;
  std::vector<fs::path> dirs{r.dir};
  std::error_code ec;
  std::vector<fs::path> subdirs;
  for (const auto& entry : fs::directory_iterator(r.dir, ec)) {
    if (entry.is_directory(ec)) subdirs.push_back(entry.path());
  }
  std::sort(subdirs.begin(), subdirs.end());
  dirs.insert(dirs.end(), subdirs.begin(), subdirs.end());
  for (const fs::path& d : dirs) {
    std::optional<io::CommandRecord> record;
    try {
      record = io::read_command_file(d.string());
    } catch (const InputError&) {
      continue;  // a commands.txt imunoise did not write (another tool's): not ours to show
    }
    if (!record) continue;
    const std::vector<std::string> lines = io::command_file_lines(*record);
    const std::string where = fs::relative(d / "commands.txt", r.dir, ec).generic_string();
    out.push_back("# " + where);
    out.insert(out.end(), lines.begin(), lines.end());
  }
  out.push_back("# this report");
  out.push_back("imunoise report " + r.dir.string());
  return out;
}

std::vector<std::string> findings(const SavedResults& r) {
  std::vector<std::string> out;
  if (r.model) {
    for (const std::string& line : r.model->data_quality) out.push_back(line);
    for (const models::AxisModel& axis : r.model->axes) {
      if (axis.psd_check_pass && !*axis.psd_check_pass) {
        out.push_back(axis.name + ": the PSD cross-check failed: " + axis.psd_check_note);
      }
      if (!axis.fit_note.empty()) out.push_back(axis.name + " fit: " + axis.fit_note);
    }
  }
  if (r.drift_summary) {
    const pipeline::DriftSummary& s = *r.drift_summary;
    if (!s.motion.stationary) {
      out.push_back("drift: the recording does not look stationary: " + s.motion.reason);
    }
    for (const pipeline::DriftConsistency& c : s.consistency) {
      if (c.nees_inside) continue;
      out.push_back("drift at " + num(c.time_s, 6) + " s: mean NEES " + num(c.mean_nees, 3) +
                    " is outside its 95 % band: the model's prediction does not match the "
                    "recorded drift there");
    }
  }
  if (out.empty()) out.push_back("No data-quality or consistency problems were found.");
  return out;
}

}  // namespace

ReportOutput write_report(const std::string& dir) {
  const SavedResults r = load_results(dir);
  PendingFiles files;
  report::ReportPage page;
  std::string name = r.model ? r.model->sensor_name : std::string("drift");
  page.title = "imunoise report — " + name;
  if (r.model) {
    const models::NoiseModel& m = *r.model;
    page.facts = {{"recording", m.source},
                  {"samples", std::to_string(m.samples)},
                  {"sample rate", num(m.sample_rate_hz, 6) + " Hz"},
                  {"duration", num(m.duration_s / 3600.0, 4) + " h"},
                  {"interval level", num(100.0 * m.confidence, 3) + " %"}};
  }
  page.facts.push_back({"written", utc_now_text() + " by imunoise"});

  if (r.model) {
    report::PageSection s{"summary", "Noise coefficients", {}, {}, {}, {}, {}};
    s.paragraphs.push_back(
        "Estimated by the weighted fit of the whole model to the overlapping Allan variance "
        "(theory.md §4.3). The SI units are those of model.yaml; the datasheet units are for "
        "comparison with vendor specifications.");
    s.tables.push_back(summary_table(*r.model));
    report::Table gm = gauss_markov_table(*r.model);
    if (!gm.rows.empty()) s.tables.push_back(std::move(gm));
    page.sections.push_back(std::move(s));
  }
  if (r.model && r.allan) {
    report::PageSection s{"allan", "Allan deviation", {}, {}, {}, {}, {}};
    add_sensor_figures(
        r, s, [&](bool gyro) { return report::allan_figure(gyro, r.allan->axes, *r.model); },
        files);
    page.sections.push_back(std::move(s));
  }
  if (r.psd) {
    report::PageSection s{"psd", "Power spectral density", {}, {}, {}, {}, {}};
    add_sensor_figures(
        r, s, [&](bool gyro) { return report::psd_figure(gyro, r.psd->axes); }, files);
    page.sections.push_back(std::move(s));
  }
  if (!r.drift_dir.empty()) {
    report::PageSection s{"drift", "Free-inertial drift", {}, {}, {}, {}, {}};
    const pipeline::DriftSummary& summary = *r.drift_summary;
    const pipeline::DriftProtocol& p = summary.protocol;
    std::ostringstream text;
    text << "Protocol: " << p.segments << " segments, each aligned over " << num(p.align_s)
         << " s and navigated free-inertial for " << num(p.navigation_s) << " s; "
         << p.vertical_channel << ".";
    s.paragraphs.push_back(text.str());
    if (r.drift_envelope) {
      s.figures.push_back(
          add_figure(r, report::drift_figure(*r.drift_envelope, r.drift_segments), files));
    }
    report::Table t = drift_table(summary);
    if (!t.rows.empty()) s.tables.push_back(std::move(t));
    page.sections.push_back(std::move(s));
  }
  if (r.sampling) {
    const json& j = *r.sampling;
    report::PageSection s{"sampling", "Sampling", {}, {}, {}, {}, {}};
    s.tables.push_back(sampling_table(j));
    if (j.value("has_timestamps", false) && j.contains("interval_histogram")) {
      const json& h = j["interval_histogram"];
      std::vector<std::int64_t> counts;
      for (const json& c : h.value("counts", json::array())) {
        counts.push_back(c.is_number() ? c.get<std::int64_t>() : 0);
      }
      s.figures.push_back(add_figure(
          r,
          report::interval_figure(numbers_of(h, "bin_low_s"), numbers_of(h, "bin_high_s"), counts,
                                  number_at(j, "median_interval_s")),
          files));
      std::vector<double> start, length;
      for (const json& g : j.value("gaps", json::array())) {
        start.push_back(number_at(g, "start_s"));
        length.push_back(number_at(g, "length_s"));
      }
      const double gap_count = number_at(j, "gap_count");
      if (std::isfinite(gap_count) && gap_count > 0.0) {
        s.figures.push_back(
            add_figure(r,
                       report::gaps_figure(start, length, number_at(j, "duration_s"),
                                           static_cast<std::int64_t>(gap_count)),
                       files));
      } else {
        s.paragraphs.push_back("No gaps: no interval is longer than 1.5 × the median interval.");
      }
    } else {
      s.paragraphs.push_back(
          "The recording has no time stamps (a fixed rate was given): no "
          "interval histogram or gap plot.");
    }
    page.sections.push_back(std::move(s));
  }
  page.sections.push_back({"findings", "Findings", {}, {}, {}, findings(r), {}});
  page.sections.push_back({"exports",
                           "Files in this directory",
                           {"Every plot's data is in plots/NAME.csv next to its SVG."},
                           {},
                           {},
                           export_list(r),
                           {}});
  page.sections.push_back({"commands",
                           "Commands to reproduce",
                           {"Each output directory records the command that wrote it."},
                           {},
                           {},
                           {},
                           command_lines(r)});
  page.footer =
      "imunoise — stationary-IMU recordings to Kalman-filter-ready stochastic error "
      "models. All values in SI unless a column says otherwise.";
  const std::string html_path = (r.dir / "report.html").string();
  files.emplace_back(html_path, report::render_html(page));
  io::create_output_directory((r.dir / "plots").string());
  for (const auto& [path, text] : files) io::write_file_atomically(path.string(), text);
  int figures = 0;
  for (const report::PageSection& section : page.sections) {
    figures += static_cast<int>(section.figures.size());
  }
  return {html_path, figures};
}

}  // namespace imunoise::tools
