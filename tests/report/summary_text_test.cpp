// Tests of report/summary_text.h, the terminal summary of `imunoise analyze`: the header line
// with the recording's facts, per sensor and term each axis's value and interval in datasheet
// units with the IEEE-952 read-off, the true value with inside/OUTSIDE when the simulator's
// model is given, then the failed PSD cross-checks and the data-quality lines.
#include "report/summary_text.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "common/number_text.h"
#include "models/datasheet_units.h"

namespace imunoise::report {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

/// The index of LINE in LINES (LINES.size() when absent).
std::size_t index_of(const std::vector<std::string>& lines, const std::string& line) {
  std::size_t i = 0;
  while (i < lines.size() && lines[i] != line) ++i;
  return i;
}

models::NoiseModel example_model() {
  models::NoiseModel m;
  m.source = "rec.csv";
  m.samples = 1440000;
  m.sample_rate_hz = 50.0;
  m.duration_s = 8.0 * 3600.0;
  m.confidence = 0.95;
  models::AxisModel gyro;
  gyro.name = "gyro_y";
  gyro.kind = SensorKind::gyro;
  gyro.terms[NoiseTerm::white_noise] = {1e-4, 9e-5, 1.1e-4, true, "wnnls-oavar", ""};
  gyro.terms[NoiseTerm::random_walk] = {0.0, 0.0, 3e-7, false, "", ""};
  gyro.readoff.slope[NoiseTerm::white_noise] = 1.05e-4;
  models::AxisModel accel;
  accel.name = "accel_x";
  accel.kind = SensorKind::accel;
  accel.terms[NoiseTerm::white_noise] = {2e-3, 1.9e-3, 2.1e-3, true, "wnnls-oavar", ""};
  accel.psd_check_pass = false;
  accel.psd_check_note = "model 5 dB below the PSD";
  m.axes = {gyro, accel};
  m.data_quality = {"2 gaps in the time stamps"};
  return m;
}

TEST(SummaryText, HeaderValuesInDatasheetUnitsAndFindings) {
  const std::vector<std::string> lines = lines_of(summary_text(example_model(), std::nullopt));
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines[0],
            "imunoise analyze: rec.csv — 1440000 samples at 50 Hz (8 h); coefficients with 95 % "
            "intervals, '-' = not identified (upper bound);");
  EXPECT_EQ(lines[1],
            "ieee952 = the graphical slope read-off of the OADEV curve, for traceability");
  const models::DatasheetUnit n = models::datasheet_unit(NoiseTerm::white_noise, SensorKind::gyro);
  const models::DatasheetUnit k = models::datasheet_unit(NoiseTerm::random_walk, SensorKind::gyro);
  const std::size_t gyro = index_of(lines, "gyro");
  const std::size_t accel = index_of(lines, "accel");
  ASSERT_LT(gyro, accel);
  ASSERT_LT(accel, lines.size());
  // Under gyro: one heading per term, each gyro axis beneath it.
  const std::size_t white = index_of(lines, "  white_noise [" + std::string(n.ascii) + "]");
  ASSERT_LT(white, accel);
  EXPECT_EQ(lines[white + 1], "    gyro_y: " + significant_number_text(1e-4 * n.factor, 4) + " [" +
                                  significant_number_text(9e-5 * n.factor, 3) + ", " +
                                  significant_number_text(1.1e-4 * n.factor, 3) + "]   ieee952 " +
                                  significant_number_text(1.05e-4 * n.factor, 4));
  const std::size_t walk = index_of(lines, "  random_walk [" + std::string(k.ascii) + "]");
  ASSERT_LT(walk, accel);
  EXPECT_EQ(lines[walk + 1],
            "    gyro_y: - (< " + significant_number_text(3e-7 * k.factor, 2) + ")");
  EXPECT_EQ(lines[index_of(lines, "  quantization [" +
                                      std::string(models::datasheet_unit(NoiseTerm::quantization,
                                                                         SensorKind::gyro)
                                                      .ascii) +
                                      "]") +
                  1],
            "    gyro_y: -");
  // accel_x is listed under accel only.
  for (std::size_t i = gyro; i < accel; ++i) EXPECT_EQ(lines[i].find("accel_x"), std::string::npos);
  // The verdict comes first, after the header and a blank line; the details follow it.
  EXPECT_EQ(lines[2], "");
  EXPECT_EQ(lines[3], "verdict");
  const std::size_t details = index_of(lines, "details: per sensor and term each axis");
  ASSERT_LT(details, gyro);
  // Each finding of the verdict (data quality, failed PSD check), then its cause and remedy.
  const std::size_t gap = index_of(lines, "  - recording: 2 gaps in the time stamps");
  const std::size_t psd = index_of(lines, "  - accel_x: model 5 dB below the PSD");
  ASSERT_LT(gap, details);
  ASSERT_LT(psd, details);
  for (std::size_t at : {gap, psd}) {
    EXPECT_EQ(lines[at + 1].rfind("      cause: ", 0), 0u) << lines[at + 1];
    std::size_t remedy = at + 2;  // after the cause's continuation lines
    while (remedy < details && lines[remedy].rfind("      remedy: ", 0) != 0 &&
           lines[remedy].rfind("      ", 0) == 0)
      ++remedy;
    EXPECT_EQ(lines[remedy].rfind("      remedy: ", 0), 0u) << lines[remedy];
  }
}

TEST(SummaryText, TheVerdictMatrixHasATermPerRowAndAnAxisPerColumn) {
  const std::vector<std::string> lines =
      lines_of(summary_text(example_model(), std::nullopt, "out/model.yaml"));
  const models::DatasheetUnit n = models::datasheet_unit(NoiseTerm::white_noise, SensorKind::gyro);
  const models::DatasheetUnit k = models::datasheet_unit(NoiseTerm::random_walk, SensorKind::gyro);
  const std::size_t head = index_of(lines, "  gyro               gyro_y");
  ASSERT_LT(head, lines.size());
  EXPECT_EQ(lines[head + 2], "  N [" + std::string(n.ascii) + "]    " +
                                 significant_number_text(1e-4 * n.factor, 3) + " [" +
                                 significant_number_text(9e-5 * n.factor, 3) + ", " +
                                 significant_number_text(1.1e-4 * n.factor, 3) + "]");
  EXPECT_EQ(lines[head + 4], "  K [" + std::string(k.ascii) + "]  < " +
                                 significant_number_text(3e-7 * k.factor, 2) + " (n.i.)");
  // The export guide names the model file the run wrote.
  EXPECT_LT(index_of(lines,
                     "export for your filter: imunoise export out/model.yaml --to FORMAT -o FILE, "
                     "with FORMAT for:"),
            lines.size());
}

TEST(SummaryText, TrueValuesAreMarkedInsideOrOutsideTheInterval) {
  std::array<NoiseCoefficients, 6> truth{};
  truth[1].white_noise = 1.05e-4;  // gyro_y: inside [9e-5, 1.1e-4]
  truth[3].white_noise = 3e-3;     // accel_x: outside [1.9e-3, 2.1e-3]
  const std::string text = summary_text(example_model(), truth);
  const models::DatasheetUnit gyro =
      models::datasheet_unit(NoiseTerm::white_noise, SensorKind::gyro);
  const models::DatasheetUnit accel =
      models::datasheet_unit(NoiseTerm::white_noise, SensorKind::accel);
  EXPECT_NE(
      text.find("   true " + significant_number_text(1.05e-4 * gyro.factor, 4) + "  (inside)\n"),
      std::string::npos)
      << text;
  EXPECT_NE(
      text.find("   true " + significant_number_text(3e-3 * accel.factor, 4) + "  (OUTSIDE)\n"),
      std::string::npos)
      << text;
  EXPECT_EQ(summary_text(example_model(), std::nullopt).find(" true "), std::string::npos);
}

}  // namespace
}  // namespace imunoise::report
