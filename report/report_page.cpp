/// @file
/// @brief The report page of a results directory (see report_page.h).
#include "report/report_page.h"

#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/number_text.h"
#include "common/sampling_gap.h"
#include "common/sensor_kind.h"
#include "models/noise_model.h"
#include "report/figures.h"
#include "report/result_tables.h"
#include "report/svg_plot.h"
#include "report/verdict.h"

namespace imunoise::report {

namespace {

std::string num(double v, int digits = 4) { return number_cell(v, digits); }

/// The figure block of FIGURE on the page; its SVG and CSV join FILES.
FigureBlock add_figure(const Figure& figure, std::vector<ReportFile>& files) {
  FigureBlock block;
  block.name = figure.name;
  block.svg = render_svg(figure.plot);
  block.caption = figure.caption;
  files.push_back({"plots/" + figure.name + ".svg", block.svg});
  files.push_back({"plots/" + figure.name + ".csv", figure_csv(figure)});
  block.links = {{"data (CSV)", "plots/" + figure.name + ".csv"},
                 {"SVG", "plots/" + figure.name + ".svg"}};
  return block;
}

/// The gyro and the accelerometer figure MAKE(kind) builds, each that has data.
template <typename Make>
void add_sensor_figures(PageSection& section, Make make, std::vector<ReportFile>& files) {
  for (const SensorKind kind : kSensorKinds) {
    const Figure f = make(kind);
    if (!f.plot.series.empty()) section.figures.push_back(add_figure(f, files));
  }
}

// ------------------------------------------------------------------------------- sections
PageSection summary_section(const models::NoiseModel& model) {
  PageSection s{"summary", "Noise coefficients", {}, {}, {}, {}, {}};
  s.paragraphs.push_back(
      "Estimated by the weighted fit of the whole model to the overlapping Allan variance "
      "(theory.md §4.3). The SI units are those of model.yaml; the datasheet units are for "
      "comparison with vendor specifications.");
  s.tables.push_back(summary_table(model));
  Table gm = gauss_markov_table(model);
  if (!gm.rows.empty()) s.tables.push_back(std::move(gm));
  for (Table& t : s.tables) t.folded = true;
  return s;
}

PageSection drift_section(const io::ResultsDirectory& r, std::vector<ReportFile>& files) {
  PageSection s{"drift", "Free-inertial drift", {}, {}, {}, {}, {}};
  const pipeline::DriftSummary& summary = *r.drift_summary;
  const pipeline::DriftProtocol& p = summary.protocol;
  std::ostringstream text;
  text << "Protocol: " << p.segments << " segments, each aligned over " << num(p.align_s)
       << " s and navigated free-inertial for " << num(p.navigation_s) << " s; "
       << p.vertical_channel << ".";
  s.paragraphs.push_back(text.str());
  if (r.drift_envelope) {
    s.figures.push_back(add_figure(drift_figure(*r.drift_envelope, r.drift_segments), files));
  }
  Table t = drift_table(summary);
  t.folded = true;
  if (!t.rows.empty()) s.tables.push_back(std::move(t));
  if (r.drift_budget && !r.drift_budget->time_s.empty()) {
    Table budget = drift_budget_table(*r.drift_budget);
    budget.folded = true;
    if (!budget.rows.empty()) s.tables.push_back(std::move(budget));
    s.figures.push_back(add_figure(drift_budget_figure(*r.drift_budget), files));
  }
  return s;
}

PageSection sampling_section(const pipeline::SamplingReport& report,
                             std::vector<ReportFile>& files) {
  const pipeline::TimingReport& timing = report.timing;
  PageSection s{"sampling", "Sampling", {}, {}, {}, {}, {}};
  s.tables.push_back(sampling_table(report));
  s.tables.back().folded = true;
  if (!timing.has_timestamps) {
    s.paragraphs.push_back(
        "The recording has no time stamps (a fixed rate was given): no "
        "interval histogram or gap plot.");
    return s;
  }
  const pipeline::IntervalHistogram& h = timing.interval_histogram;
  s.figures.push_back(add_figure(
      interval_figure(h.bin_low_s, h.bin_high_s, h.counts, timing.median_interval_s), files));
  if (timing.gap_count > 0) {
    std::vector<double> start, length;
    for (const pipeline::GapRecord& g : timing.gaps) {
      start.push_back(g.start_s);
      length.push_back(g.length_s);
    }
    s.figures.push_back(
        add_figure(gaps_figure(start, length, timing.duration_s, timing.gap_count), files));
  } else {
    s.paragraphs.push_back("No gaps: no interval is longer than " +
                           shortest_number_text(kGapFactor) + " × the median interval.");
  }
  return s;
}

/// The drift results' findings, one line each.
std::vector<std::string> drift_findings(const io::ResultsDirectory& r) {
  std::vector<std::string> out;
  if (!r.drift_summary) return out;
  const pipeline::DriftSummary& s = *r.drift_summary;
  if (!s.motion.stationary) {
    out.push_back("drift: the recording does not look stationary: " + s.motion.reason);
  }
  // Judged by the joint band (pipeline::DriftConsistency): with a 95 % band at each of K report
  // times a consistent model misses one of them in ~10–14 % of recordings at K = 3, too often
  // for a finding; the joint band is missed in at most 5 %.
  for (const pipeline::DriftConsistency& c : s.consistency) {
    if (c.nees_inside_joint_band) continue;
    out.push_back("drift at " + num(c.time_s, 6) + " s: mean NEES " + num(c.mean_nees, 3) +
                  " is outside its 95 % band for all report times together ([" +
                  num(c.nees_joint_band_low, 3) + ", " + num(c.nees_joint_band_high, 3) +
                  "]): the model's prediction does not match the recorded drift there");
  }
  return out;
}

/// The verdict: the matrices, what was identified, every finding with cause and remedy, and
/// which export suits which filter (report/verdict.h).
PageSection verdict_section(const io::ResultsDirectory& r) {
  PageSection s{"verdict", "Verdict", {}, {}, {}, {}, {}};
  const std::string model_path = (std::filesystem::path(r.dir) / "model.yaml").string();
  std::vector<ExplainedFinding> explained;
  if (r.model) {
    const models::NoiseModel& m = *r.model;
    s.paragraphs.push_back(std::to_string(m.axes.size()) + " axes fitted from " +
                           num(m.duration_s / 3600.0, 3) + " h at " + num(m.sample_rate_hz, 6) +
                           " Hz. The detail tables, figures and checks follow below (tables "
                           "folded: click to open).");
    for (const std::string& line : identification_lines(m)) s.paragraphs.push_back(line);
    for (const SensorKind kind : kSensorKinds) {
      Table t = verdict_matrix(m, kind);
      if (!t.rows.empty()) s.tables.push_back(std::move(t));
    }
    explained = verdict_findings(m, model_path);
  }
  for (const std::string& line : drift_findings(r)) {
    explained.push_back(
        explain_finding("drift", {line, r.model ? &*r.model : nullptr, nullptr, model_path}));
  }
  for (const ExplainedFinding& f : explained)
    s.findings.push_back({f.where, f.text, f.cause, f.remedy});
  if (explained.empty())
    s.paragraphs.push_back("No data-quality, fit or consistency finding: nothing to act on.");
  if (r.model) {
    Table guide = export_guide_table(model_path);
    guide.folded = true;
    s.tables.push_back(std::move(guide));
  }
  return s;
}

std::vector<std::string> findings(const io::ResultsDirectory& r) {
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
  for (std::string& line : drift_findings(r)) out.push_back(std::move(line));
  if (out.empty()) out.push_back("No data-quality or consistency problems were found.");
  return out;
}

// ----------------------------------------------------------------------------------- lists
std::string size_text(std::uintmax_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " B";
  if (bytes < 1024 * 1024) return num(static_cast<double>(bytes) / 1024.0, 3) + " KiB";
  return num(static_cast<double>(bytes) / (1024.0 * 1024.0), 3) + " MiB";
}

std::string describe_file(const std::string& relative) {
  const std::string name = std::filesystem::path(relative).filename().string();
  if (name == "model.yaml") return "the fitted model (native schema, SI units in every key)";
  if (name == "allan.csv") return "OADEV/OHDEV with intervals and the model ADEV, per axis";
  if (name == "psd.csv") return "log-binned PSD with dof and the model PSD, per axis";
  if (name == "sampling_report.json") return "sampling checks";
  if (name == "drift_segments.csv") return "recorded drift of every segment";
  if (name == "drift_envelope.csv") return "predicted drift envelope and recorded RMS";
  if (name == "drift_summary.json") return "drift consistency checks";
  if (name == "drift_budget.csv") return "predicted horizontal variance split by source";
  if (relative.rfind("configs", 0) == 0) return "filter configuration";
  if (relative.rfind("discrete", 0) == 0) return "discrete state-space model";
  return "";
}

std::vector<std::string> export_list(const io::ResultsDirectory& r) {
  std::vector<std::string> out;
  for (const io::ResultFileEntry& f : r.files) {
    std::string line = f.relative_path + " (" + size_text(f.size_bytes) + ")";
    const std::string what = describe_file(f.relative_path);
    if (!what.empty()) line.append(": ").append(what);
    out.push_back(line);
  }
  return out;
}

std::vector<std::string> command_lines(const io::ResultsDirectory& r) {
  std::vector<std::string> out;
  for (const io::CommandFileEntry& c : r.commands) {
    const std::vector<std::string> lines = io::command_file_lines(c.record);
    out.push_back("# " + c.relative_path);
    out.insert(out.end(), lines.begin(), lines.end());
  }
  out.push_back("# this report");
  out.push_back("imunoise report " + r.dir);
  return out;
}

}  // namespace

ReportDocument build_report_page(const io::ResultsDirectory& r, const std::string& written) {
  ReportDocument doc;
  ReportPage& page = doc.page;
  std::vector<ReportFile>& files = doc.plot_files;
  const std::string name = r.model ? r.model->sensor_name : std::string("drift");
  page.title = "imunoise report — " + name;
  if (r.model) {
    const models::NoiseModel& m = *r.model;
    page.facts = {{"recording", m.source},
                  {"samples", std::to_string(m.samples)},
                  {"sample rate", num(m.sample_rate_hz, 6) + " Hz"},
                  {"duration", num(m.duration_s / 3600.0, 4) + " h"},
                  {"interval level", num(100.0 * m.confidence, 3) + " %"}};
  }
  page.facts.push_back({"written", written + " by imunoise"});

  page.sections.push_back(verdict_section(r));
  if (r.model) page.sections.push_back(summary_section(*r.model));
  if (r.model && r.allan) {
    PageSection s{"allan", "Allan deviation", {}, {}, {}, {}, {}};
    add_sensor_figures(
        s, [&](SensorKind kind) { return allan_figure(kind, r.allan->axes, *r.model); }, files);
    page.sections.push_back(std::move(s));
  }
  if (r.psd) {
    PageSection s{"psd", "Power spectral density", {}, {}, {}, {}, {}};
    add_sensor_figures(
        s, [&](SensorKind kind) { return psd_figure(kind, r.psd->axes); }, files);
    page.sections.push_back(std::move(s));
  }
  if (r.drift_summary) page.sections.push_back(drift_section(r, files));
  if (r.sampling) page.sections.push_back(sampling_section(r.sampling->report, files));
  page.sections.push_back({"findings",
                           "Findings as written",
                           {"Each line as the analysis wrote it; the verdict above explains "
                            "them."},
                           {},
                           {},
                           findings(r),
                           {}});
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
  return doc;
}

int figure_count(const ReportPage& page) {
  int figures = 0;
  for (const PageSection& section : page.sections) {
    figures += static_cast<int>(section.figures.size());
  }
  return figures;
}

}  // namespace imunoise::report
