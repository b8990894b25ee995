/// @file
/// @brief End-to-end tests of the report (report/write_report.cpp, `imunoise report`): analyze and
/// drift write DIR/report.html with the figures, the CSV behind each, the coefficient table,
/// findings, exports and commands; every embedded SVG is well-formed XML; the plotted data
/// equal the analysis outputs; a directory without results is a clear error with no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"
#include "xml_check.h"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The text between <table id="ID"> and its </table>.
std::string table_text(const std::string& html, const std::string& id) {
  const std::size_t at = html.find("<table id=\"" + id + "\">");
  if (at == std::string::npos) return "";
  return html.substr(at, html.find("</table>", at) - at);
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// One shared analysis (30 min of the reference IMU at 50 Hz; no bootstrap: the report, not
/// the intervals, is under test) plus a short drift run into DIR/drift.
class ReportCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = make_temp_dir("report-cli");
    rec_ = dir_ / "rec.csv";
    out_ = dir_ / "out";
    const fs::path model = fs::path(IMUNOISE_SOURCE_DIR) / "configs" / "reference-imu.yaml";
    auto r = run_imunoise("simulate " + model.string() +
                          " --duration 30min --rate 50 --seed 5 -o " + rec_.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    analyze_ = run_imunoise("analyze " + rec_.string() + " --bootstrap 0 -o " + out_.string());
    ASSERT_EQ(analyze_.exit_code, 0) << analyze_.err;
  }
  static fs::path dir_, rec_, out_;
  static CommandResult analyze_;
};
fs::path ReportCli::dir_, ReportCli::rec_, ReportCli::out_;
CommandResult ReportCli::analyze_;

TEST_F(ReportCli, AnalyzeWritesTheReportWithEveryFigureAndItsData) {
  const fs::path html_path = out_ / "report.html";
  ASSERT_TRUE(fs::exists(html_path));
  EXPECT_NE(analyze_.out.find("report: " + html_path.string()), std::string::npos);
  const std::string html = read_all(html_path);
  EXPECT_NE(html.find("<title>imunoise report — rec.csv</title>"), std::string::npos);
  for (const char* name :
       {"allan-gyro", "allan-accel", "psd-gyro", "psd-accel", "sampling-intervals"}) {
    SCOPED_TRACE(name);
    EXPECT_NE(html.find(std::string("<figure id=\"fig-") + name + "\">"), std::string::npos);
    EXPECT_NE(html.find(std::string("<a href=\"plots/") + name + ".csv\">"), std::string::npos);
    EXPECT_TRUE(fs::exists(out_ / "plots" / (std::string(name) + ".csv")));
    const std::string svg = read_all(out_ / "plots" / (std::string(name) + ".svg"));
    EXPECT_NE(html.find(svg), std::string::npos);  // the page inlines the same SVG
  }
  const auto svgs = svg_elements(html);
  EXPECT_EQ(svgs.size(), 5u);
  // A gap-free recording: a sentence, not an empty gap plot.
  EXPECT_EQ(html.find("fig-sampling-gaps"), std::string::npos);
  EXPECT_NE(html.find("No gaps"), std::string::npos);
  for (const std::string& svg : svgs) {
    const auto check = check_xml(svg);
    EXPECT_TRUE(check.ok) << check.message;
    EXPECT_EQ(svg.find("nan"), std::string::npos);
  }
  // 6 axes × 5 terms, in SI and datasheet units.
  const std::string summary = table_text(html, "summary-table");
  EXPECT_EQ(count_of(summary, "<tr>"), 1u + 30u);
  EXPECT_NE(summary.find("°/√h"), std::string::npos);
  EXPECT_NE(summary.find("µg/√Hz"), std::string::npos);
  EXPECT_NE(summary.find("rad/s^0.5"), std::string::npos);
  for (const char* id : {"findings", "exports", "commands", "sampling", "allan", "psd"}) {
    EXPECT_NE(html.find(std::string("<section id=\"") + id + "\">"), std::string::npos) << id;
  }
  EXPECT_NE(html.find("imunoise analyze " + rec_.string() + " --bootstrap 0 -o " + out_.string()),
            std::string::npos);
  EXPECT_NE(html.find("model.yaml ("), std::string::npos);  // in the list of files
  EXPECT_EQ(html.find("<script"), std::string::npos);
}

TEST_F(ReportCli, PlottedDataEqualTheAnalysisOutputs) {
  // allan.csv's gyro_y OADEV column and the plot's "gyro_y oadev" rows: same numbers, same order.
  const auto allan = read_csv_rows(out_ / "allan.csv");
  ASSERT_GT(allan.size(), 2u);
  std::size_t tau_col = 0, value_col = 0;
  for (std::size_t c = 0; c < allan[0].size(); ++c) {
    if (allan[0][c] == "tau_s") tau_col = c;
    if (allan[0][c] == "gyro_y_oadev_rad_per_s") value_col = c;
  }
  ASSERT_GT(value_col, 0u);
  std::vector<std::pair<double, double>> expected;
  for (std::size_t r = 1; r < allan.size(); ++r) {
    if (!allan[r][value_col].empty()) {
      expected.emplace_back(std::stod(allan[r][tau_col]), std::stod(allan[r][value_col]));
    }
  }
  std::vector<std::pair<double, double>> plotted;
  const auto plot = read_csv_rows(out_ / "plots" / "allan-gyro.csv");
  ASSERT_EQ(plot[0][0], "series");
  EXPECT_EQ(plot[0][1], "tau_s");
  EXPECT_EQ(plot[0][2], "adev_rad_per_s");
  for (std::size_t r = 1; r < plot.size(); ++r) {
    if (plot[r][0] == "gyro_y oadev")
      plotted.emplace_back(std::stod(plot[r][1]), std::stod(plot[r][2]));
  }
  EXPECT_EQ(plotted, expected);
  // The interval histogram counts every regular interval: N − 1 for a gap-free recording.
  const auto hist = read_csv_rows(out_ / "plots" / "sampling-intervals.csv");
  double total = 0.0;
  for (std::size_t r = 1; r < hist.size(); r += 1) {
    if (hist[r][0] == "histogram") total += std::stod(hist[r][2]);
  }
  EXPECT_EQ(total, 30.0 * 60.0 * 50.0 - 1.0);
}

TEST_F(ReportCli, DriftResultsJoinTheReportOfTheAnalysisDirectory) {
  const fs::path drift = out_ / "drift";
  const auto d =
      run_imunoise("drift " + rec_.string() + " --model " + (out_ / "model.yaml").string() +
                   " --heading 0 --align 30s --segment 90s --report-times 30,90 "
                   "--monte-carlo 0 -o " +
                   drift.string());
  ASSERT_EQ(d.exit_code, 0) << d.err;
  // drift's own report, with the model it used
  const std::string own = read_all(drift / "report.html");
  EXPECT_NE(own.find("<figure id=\"fig-drift-horizontal\">"), std::string::npos);
  EXPECT_NE(own.find("<table id=\"summary-table\">"), std::string::npos);
  EXPECT_TRUE(check_xml(read_all(drift / "plots" / "drift-horizontal.svg")).ok);

  const auto r = run_imunoise("report " + out_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(7 figures)"), std::string::npos) << r.out;  // drift + its budget
  const std::string html = read_all(out_ / "report.html");
  EXPECT_NE(html.find("<figure id=\"fig-drift-horizontal\">"), std::string::npos);
  EXPECT_NE(html.find("<figure id=\"fig-drift-budget\">"), std::string::npos);
  EXPECT_EQ(count_of(table_text(html, "drift-budget-table"), "<tr>"), 1u + 7u + 1u);  // sources
  EXPECT_EQ(count_of(table_text(html, "drift-table"), "<tr>"), 1u + 2u);  // 30 s and 90 s
  EXPECT_NE(html.find("drift/drift_summary.json ("), std::string::npos);
  EXPECT_NE(html.find("# drift/commands.txt"), std::string::npos);
  for (const std::string& svg : svg_elements(html)) EXPECT_TRUE(check_xml(svg).ok);
  // Rewriting gives the same plots, byte for byte.
  const std::string before = read_all(out_ / "plots" / "allan-accel.svg");
  ASSERT_EQ(run_imunoise("report " + out_.string()).exit_code, 0);
  EXPECT_EQ(read_all(out_ / "plots" / "allan-accel.svg"), before);
}

TEST_F(ReportCli, AnOutputPathThatIsAFileIsAnInputError) {
  const fs::path file = dir_ / "not-a-dir";
  write_text(file, "x");
  const auto r = run_imunoise("analyze " + rec_.string() + " --bootstrap 0 -o " + file.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(file.string() + ": cannot create the output directory"), std::string::npos)
      << r.err;
}

TEST(ReportCliErrors, NoResultsMissingDirectoryAndBadFilesAreClearErrors) {
  const fs::path dir = make_temp_dir("report-errors");
  auto r = run_imunoise("report " + dir.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no imunoise results here"), std::string::npos) << r.err;
  r = run_imunoise("report " + (dir / "missing").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not a directory"), std::string::npos) << r.err;
  write_text(dir / "model.yaml", "format: imunoise-noise-model\nformat_version: 1\naxes: [\n");
  r = run_imunoise("report " + dir.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("model.yaml"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "report.html"));
  EXPECT_FALSE(fs::exists(dir / "plots"));
}

}  // namespace
}  // namespace imunoise::test
