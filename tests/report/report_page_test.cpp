// Tests of report/report_page.h on a constructed io::ResultsDirectory: the facts under the
// title, the sections in order (each only when its results are there), each section's tables,
// figures and paragraphs, the findings, the list of files with their sizes and descriptions, the
// commands to reproduce, and the plot files behind the figures (the SVG the page inlines and
// the CSV of the figure).
#include "report/report_page.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/number_text.h"
#include "common/sampling_gap.h"
#include "report/figures.h"

namespace imunoise::report {
namespace {

const PageSection* section_of(const ReportPage& page, const std::string& id) {
  for (const PageSection& s : page.sections) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

std::vector<std::string> section_ids(const ReportPage& page) {
  std::vector<std::string> ids;
  for (const PageSection& s : page.sections) ids.push_back(s.id);
  return ids;
}

std::vector<std::string> figure_names(const PageSection& s) {
  std::vector<std::string> names;
  for (const FigureBlock& f : s.figures) names.push_back(f.name);
  return names;
}

std::vector<std::string> table_ids(const PageSection& s) {
  std::vector<std::string> ids;
  for (const Table& t : s.tables) ids.push_back(t.id);
  return ids;
}

models::AxisModel axis_model(const std::string& name, SensorKind kind, double white) {
  models::AxisModel a;
  a.name = name;
  a.kind = kind;
  a.terms[NoiseTerm::white_noise] = {white, 0.9 * white, 1.1 * white, true, "wnnls-oavar", ""};
  return a;
}

io::AllanAxis allan_axis(const std::string& name, double white) {
  io::AllanAxis a;
  a.name = name;
  for (double tau = 0.01; tau < 100.0; tau *= 4.0) {
    analysis::DeviationPoint p;
    p.tau_s = tau;
    p.value = white / std::sqrt(tau);
    p.ci_low = 0.9 * p.value;
    p.ci_high = 1.1 * p.value;
    a.oadev.points.push_back(p);
  }
  return a;
}

io::PsdAxis psd_axis(const std::string& name, double white) {
  io::PsdAxis a;
  a.name = name;
  a.psd.frequency_hz = {0.1, 1.0, 10.0};
  a.psd.density = {white * white, white * white, white * white};
  a.psd.dof = {2.0, 20.0, 200.0};
  a.model_density = a.psd.density;
  return a;
}

/// An analysis directory with a drift run: every section has its results.
io::ResultsDirectory full_results() {
  io::ResultsDirectory r;
  r.dir = "out";
  models::NoiseModel m;
  m.sensor_name = "rec.csv";
  m.source = "data/rec.csv";
  m.sample_rate_hz = 100.0;
  m.duration_s = 7200.0;
  m.samples = 720000;
  m.confidence = 0.95;
  m.data_quality = {"2 gaps in the time stamps"};
  m.axes = {axis_model("gyro_x", SensorKind::gyro, 1e-4),
            axis_model("accel_z", SensorKind::accel, 2e-3)};
  m.axes[0].bias_instability_gm = {{"peak_match", {2e-5, 30.0}}};
  m.axes[1].psd_check_pass = false;
  m.axes[1].psd_check_note = "model 5 dB below the PSD";
  m.axes[1].fit_note = "K not identified";
  r.model = m;
  r.allan = io::AllanTable{};
  r.allan->axes = {allan_axis("gyro_x", 1e-4), allan_axis("accel_z", 2e-3)};
  r.psd = io::PsdTable{};
  r.psd->axes = {psd_axis("gyro_x", 1e-4), psd_axis("accel_z", 2e-3)};
  // 10 s at 100 Hz with one 0.5 s gap after 2 s.
  std::vector<double> stamps;
  for (int i = 0; i < 1000; ++i) stamps.push_back(0.01 * i + (i > 200 ? 0.5 : 0.0));
  r.sampling = io::SamplingReportFile{};
  r.sampling->report.samples = 1000;
  r.sampling->report.timing = pipeline::analyze_timing(stamps);
  r.drift_dir = "out/drift";
  pipeline::DriftSummary s;
  s.protocol = {60.0, 600.0, 5.0, 3, "height hold", "removed", "given heading", "peak_match"};
  s.motion.stationary = false;
  s.motion.reason = "the IMU tilts by 3 deg";
  for (double t : {60.0, 600.0}) {
    pipeline::DriftConsistency c;
    c.time_s = t;
    c.mean_nees = t < 100.0 ? 1.3 : 9.5;
    c.nees_inside = false;                 // 60 s: outside its own band …
    c.nees_inside_joint_band = t < 100.0;  // … but inside the joint one: no finding
    c.nees_joint_band_low = 1.2;
    c.nees_joint_band_high = 3.0;
    s.consistency.push_back(c);
  }
  r.drift_summary = s;
  pipeline::DriftSeries e;
  e.time_s = {1.0, 10.0, 100.0};
  e.predicted_north_sigma_m = {0.1, 1.0, 10.0};
  e.predicted_east_sigma_m = {0.1, 1.0, 10.0};
  e.predicted_drms_m = {0.14, 1.4, 14.0};
  e.predicted_velocity_drms_m_per_s = {0.1, 0.1, 0.1};
  e.predicted_roll_sigma_rad = {1e-5, 1e-5, 1e-5};
  e.predicted_pitch_sigma_rad = {1e-5, 1e-5, 1e-5};
  e.predicted_heading_sigma_rad = {1e-3, 1e-3, 1e-3};
  e.predicted_attitude_sigma_rad = {1e-3, 1e-3, 1e-3};
  r.drift_envelope = e;
  pipeline::DriftBudget b;
  b.time_s = {1.0, 60.0, 600.0};
  b.variance_m2 = {{1, 0, 0, 0, 0, 1, 0}, {2, 1, 1, 0, 0, 1, 0}, {10, 20, 30, 10, 0, 30, 0}};
  b.predicted_variance_m2 = {2, 5, 100};
  b.report_time = {false, true, true};
  r.drift_budget = b;
  r.commands = {{"commands.txt", {"/home/me", {"analyze", "rec.csv", "-o", "out"}}},
                {"drift/commands.txt", {"", {"drift", "rec.csv"}}}};
  r.files = {{"configs/openvins.yaml", 2048},
             {"drift/drift_summary.json", 3 * 1024 * 1024},
             {"model.yaml", 100},
             {"notes.txt", 5}};
  return r;
}

TEST(ReportPage, FactsUnderTheTitleComeFromTheModel) {
  const ReportPage page = build_report_page(full_results(), "2024-05-01 12:00 UTC").page;
  EXPECT_EQ(page.title, "imunoise report — rec.csv");
  using Fact = std::pair<std::string, std::string>;
  EXPECT_EQ(page.facts, (std::vector<Fact>{{"recording", "data/rec.csv"},
                                           {"samples", "720000"},
                                           {"sample rate", "100 Hz"},
                                           {"duration", "2 h"},
                                           {"interval level", "95 %"},
                                           {"written", "2024-05-01 12:00 UTC by imunoise"}}));
  EXPECT_NE(page.footer.find("Kalman-filter-ready"), std::string::npos);
}

TEST(ReportPage, EverySectionInOrderWithItsTablesAndFigures) {
  const ReportDocument doc = build_report_page(full_results(), "now");
  const ReportPage& page = doc.page;
  EXPECT_EQ(section_ids(page),
            (std::vector<std::string>{"verdict", "summary", "allan", "psd", "drift", "sampling",
                                      "findings", "exports", "commands"}));
  EXPECT_EQ(table_ids(*section_of(page, "summary")),
            (std::vector<std::string>{"summary-table", "gauss-markov-table"}));
  EXPECT_EQ(section_of(page, "summary")->tables[0].rows.size(), 2u * 5u);  // axes × terms
  EXPECT_EQ(figure_names(*section_of(page, "allan")),
            (std::vector<std::string>{"allan-gyro", "allan-accel"}));
  EXPECT_EQ(figure_names(*section_of(page, "psd")),
            (std::vector<std::string>{"psd-gyro", "psd-accel"}));

  const PageSection& drift = *section_of(page, "drift");
  EXPECT_EQ(drift.paragraphs,
            (std::vector<std::string>{"Protocol: 3 segments, each aligned over 60 s and navigated "
                                      "free-inertial for 600 s; height hold."}));
  EXPECT_EQ(figure_names(drift), (std::vector<std::string>{"drift-horizontal", "drift-budget"}));
  EXPECT_EQ(table_ids(drift), (std::vector<std::string>{"drift-table", "drift-budget-table"}));
  EXPECT_EQ(drift.tables[0].rows.size(), 2u);              // the checkpoints
  EXPECT_EQ(drift.tables[1].header.size(), 1u + 2u * 2u);  // two report times

  const PageSection& sampling = *section_of(page, "sampling");
  EXPECT_EQ(table_ids(sampling), (std::vector<std::string>{"sampling-table"}));
  EXPECT_EQ(figure_names(sampling),
            (std::vector<std::string>{"sampling-intervals", "sampling-gaps"}));
  EXPECT_TRUE(sampling.paragraphs.empty());
  EXPECT_EQ(figure_count(page), 2 + 2 + 2 + 2);
}

TEST(ReportPage, PlotFilesAreWhatThePageShows) {
  const ReportDocument doc = build_report_page(full_results(), "now");
  std::vector<std::string> expected;
  for (const PageSection& s : doc.page.sections) {
    for (const FigureBlock& f : s.figures) {
      expected.push_back("plots/" + f.name + ".svg");
      expected.push_back("plots/" + f.name + ".csv");
      EXPECT_EQ(f.links, (std::vector<std::pair<std::string, std::string>>{
                             {"data (CSV)", "plots/" + f.name + ".csv"},
                             {"SVG", "plots/" + f.name + ".svg"}}));
      for (const ReportFile& file : doc.plot_files) {
        if (file.relative_path == "plots/" + f.name + ".svg") {
          EXPECT_EQ(file.text, f.svg);
        }
      }
    }
  }
  std::vector<std::string> written;
  for (const ReportFile& file : doc.plot_files) written.push_back(file.relative_path);
  EXPECT_EQ(written, expected);
  // The CSV is the figure's own.
  const io::ResultsDirectory r = full_results();
  const std::string psd_csv = figure_csv(psd_figure(SensorKind::gyro, r.psd->axes));
  bool found = false;
  for (const ReportFile& file : doc.plot_files) {
    if (file.relative_path == "plots/psd-gyro.csv") {
      EXPECT_EQ(file.text, psd_csv);
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(ReportPage, FindingsCollectTheModelAndTheDriftProblems) {
  const ReportPage page = build_report_page(full_results(), "now").page;
  EXPECT_EQ(section_of(page, "findings")->bullets,
            (std::vector<std::string>{
                "2 gaps in the time stamps",
                "accel_z: the PSD cross-check failed: model 5 dB below the PSD",
                "accel_z fit: K not identified",
                "drift: the recording does not look stationary: the IMU tilts by 3 deg",
                "drift at 600 s: mean NEES 9.5 is outside its 95 % band for all report times "
                "together ([1.2, 3]): the model's prediction does not match the recorded drift "
                "there"}));
  io::ResultsDirectory clean;
  clean.dir = "out";
  clean.model = models::NoiseModel{};
  EXPECT_EQ(section_of(build_report_page(clean, "now").page, "findings")->bullets,
            (std::vector<std::string>{"No data-quality or consistency problems were found."}));
}

TEST(ReportPage, TheVerdictComesFirstWithMatricesFindingsAndTheExportGuide) {
  const ReportPage page = build_report_page(full_results(), "now").page;
  ASSERT_FALSE(page.sections.empty());
  const PageSection& verdict = page.sections.front();
  EXPECT_EQ(verdict.id, "verdict");
  // One matrix per sensor (terms down, axes across), then the folded export guide.
  EXPECT_EQ(table_ids(verdict),
            (std::vector<std::string>{"verdict-gyro", "verdict-accel", "export-guide"}));
  EXPECT_FALSE(verdict.tables[0].folded);
  EXPECT_TRUE(verdict.tables[2].folded);
  EXPECT_EQ(verdict.tables[0].header, (std::vector<std::string>{"term [unit]", "gyro_x"}));
  EXPECT_EQ(verdict.tables[0].rows.size(), 5u);
  // Every finding of the model and of the drift run, each with a cause and a remedy.
  std::vector<std::string> where;
  for (const FindingItem& f : verdict.findings) {
    where.push_back(f.where);
    EXPECT_FALSE(f.cause.empty()) << f.text;
    EXPECT_FALSE(f.remedy.empty()) << f.text;
  }
  EXPECT_EQ(where, (std::vector<std::string>{"recording", "accel_z", "accel_z", "drift", "drift"}));
  EXPECT_EQ(verdict.findings[1].text, "model 5 dB below the PSD");
  EXPECT_EQ(verdict.findings[2].text, "K not identified");
  // The detail tables of the other sections are folded.
  for (const PageSection& s : page.sections) {
    if (s.id == "verdict") continue;
    for (const Table& t : s.tables) EXPECT_TRUE(t.folded) << t.id;
  }
  // The HTML: the verdict is the first section after the header.
  const std::string html = render_html(page);
  const std::size_t header_end = html.find("</header>");
  ASSERT_NE(header_end, std::string::npos);
  EXPECT_EQ(html.find("<section", header_end), html.find("<section id=\"verdict\">"));
  EXPECT_NE(html.find("<details><summary>Which export for which filter"), std::string::npos);
}

TEST(ReportPage, ExportsListEachFileWithItsSizeAndWhatItIs) {
  const ReportPage page = build_report_page(full_results(), "now").page;
  EXPECT_EQ(section_of(page, "exports")->bullets,
            (std::vector<std::string>{
                "configs/openvins.yaml (2 KiB): filter configuration",
                "drift/drift_summary.json (3 MiB): drift consistency checks",
                "model.yaml (100 B): the fitted model (native schema, SI units in every key)",
                "notes.txt (5 B)"}));
}

TEST(ReportPage, CommandsOfEachDirectoryThenThisReport) {
  const ReportPage page = build_report_page(full_results(), "now").page;
  EXPECT_EQ(
      section_of(page, "commands")->code_lines,
      (std::vector<std::string>{"# commands.txt", "cd /home/me", "imunoise analyze rec.csv -o out",
                                "# drift/commands.txt", "imunoise drift rec.csv", "# this report",
                                "imunoise report out"}));
}

TEST(ReportPage, SamplingWithoutGapsOrTimeStampsSaysSo) {
  io::ResultsDirectory r = full_results();
  std::vector<double> stamps;
  for (int i = 0; i < 1000; ++i) stamps.push_back(0.01 * i);
  r.sampling->report.timing = pipeline::analyze_timing(stamps);
  const PageSection gap_free = *section_of(build_report_page(r, "now").page, "sampling");
  EXPECT_EQ(figure_names(gap_free), (std::vector<std::string>{"sampling-intervals"}));
  EXPECT_EQ(gap_free.paragraphs, (std::vector<std::string>{"No gaps: no interval is longer than " +
                                                           shortest_number_text(kGapFactor) +
                                                           " × the median interval."}));
  EXPECT_EQ(gap_free.paragraphs[0],
            "No gaps: no interval is longer than 1.5 × the median interval.");
  r.sampling->report.timing = pipeline::fixed_rate_timing(100.0, 1000);
  const PageSection fixed = *section_of(build_report_page(r, "now").page, "sampling");
  EXPECT_TRUE(fixed.figures.empty());
  EXPECT_EQ(fixed.paragraphs, (std::vector<std::string>{
                                  "The recording has no time stamps (a fixed rate was given): no "
                                  "interval histogram or gap plot."}));
  EXPECT_EQ(table_ids(fixed), (std::vector<std::string>{"sampling-table"}));
}

TEST(ReportPage, OnlyTheSectionsWhoseResultsAreThere) {
  // A drift directory without its model: the drift section and the three lists.
  io::ResultsDirectory r = full_results();
  r.model.reset();
  r.allan.reset();
  r.psd.reset();
  r.sampling.reset();
  r.drift_envelope.reset();
  r.drift_budget.reset();
  const ReportDocument doc = build_report_page(r, "now");
  EXPECT_EQ(doc.page.title, "imunoise report — drift");
  EXPECT_EQ(doc.page.facts,
            (std::vector<std::pair<std::string, std::string>>{{"written", "now by imunoise"}}));
  EXPECT_EQ(section_ids(doc.page),
            (std::vector<std::string>{"verdict", "drift", "findings", "exports", "commands"}));
  // Without a model the verdict holds the drift findings only.
  const PageSection& verdict = doc.page.sections.front();
  EXPECT_TRUE(verdict.tables.empty());
  EXPECT_EQ(verdict.findings.size(), 2u);
  EXPECT_TRUE(section_of(doc.page, "drift")->figures.empty());
  EXPECT_TRUE(doc.plot_files.empty());
  EXPECT_EQ(figure_count(doc.page), 0);
}

}  // namespace
}  // namespace imunoise::report
