// Tests of report/drift_summary_text.h, the terminal summary of `imunoise drift`: the protocol
// line, the location and motion notes only when they apply, and one row per report time with
// the numbers of the summary (the Monte Carlo column only when it ran).
#include "report/drift_summary_text.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace imunoise::report {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

pipeline::DriftSummary example_summary() {
  pipeline::DriftSummary s;
  s.protocol.segments = 12;
  s.protocol.align_s = 60.0;
  s.protocol.navigation_s = 600.0;
  s.protocol.heading = "given: 0 deg";
  s.location.given = true;
  pipeline::DriftConsistency c;
  c.time_s = 300.0;
  c.predicted_drms_m = 1250.0;
  c.actual_rms_m = 1100.0;
  c.rms_ratio = 0.88;
  c.rms_ratio_ci_low = 0.7;
  c.rms_ratio_ci_high = 1.21;
  c.mean_nees = 1.9;
  c.nees_band_low = 1.45;
  c.nees_band_high = 2.64;
  c.nees_inside = true;
  c.coverage = {0.5, 0.75, 1.0};
  s.consistency.push_back(c);
  return s;
}

TEST(DriftSummaryText, ProtocolAndOneRowPerReportTime) {
  const std::vector<std::string> lines = lines_of(drift_summary_text(example_summary()));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "drift: 12 segments of 60 s alignment + 600 s navigation, height hold");
  EXPECT_EQ(lines[1], "heading: given: 0 deg");
  EXPECT_EQ(lines[2], "");
  EXPECT_EQ(lines[3].find("  time   predicted DRMS"), 0u);
  EXPECT_EQ(lines[3].find("MC RMS"), std::string::npos);
  EXPECT_EQ(lines[4],
            "  300 s   1250 m   1100 m   0.88 [0.7, 1.21]   1.9 [1.45, 2.64] inside   "
            "50/75/100 %");
}

TEST(DriftSummaryText, OneVerdictOverAllReportTimesFromTheJointBand) {
  pipeline::DriftSummary s = example_summary();
  s.consistency[0].nees_joint_band_low = 1.25;
  s.consistency[0].nees_joint_band_high = 2.875;
  s.consistency[0].nees_inside_joint_band = true;
  s.consistency.push_back(s.consistency[0]);
  s.consistency[1].time_s = 600.0;
  s.consistency[1].nees_inside = false;  // outside its own band, inside the joint one
  std::vector<std::string> lines = lines_of(drift_summary_text(s));
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[6],
            "  all 2 report times together: mean NEES inside the joint 95 % band ([1.25, 2.88] at "
            "each time)");
  s.consistency[1].nees_inside_joint_band = false;
  lines = lines_of(drift_summary_text(s));
  EXPECT_NE(lines[6].find("mean NEES OUTSIDE the joint 95 % band"), std::string::npos);
}

TEST(DriftSummaryText, NotesTheAssumedLocationTheForcedRunAndTheMonteCarlo) {
  pipeline::DriftSummary s = example_summary();
  s.location.given = false;
  s.motion.stationary = false;
  s.motion.reason = "gyro std 9x the model";
  s.monte_carlo = pipeline::DriftMonteCarlo{100, 1};
  s.consistency[0].nees_inside = false;
  s.consistency[0].monte_carlo_radial_rms_m = 1234.4;  // four significant digits
  const std::vector<std::string> lines = lines_of(drift_summary_text(s));
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[1], "location not given: assumed 45 deg N, 0 deg E, 0 m (--location LAT,LON,H)");
  EXPECT_EQ(lines[3], "WARNING: not stationary (gyro std 9x the model), forced");
  EXPECT_NE(lines[5].find("MC RMS"), std::string::npos);
  EXPECT_NE(lines[6].find("] OUTSIDE   "), std::string::npos);
  EXPECT_EQ(lines[6].substr(lines[6].size() - 11), " %   1234 m");
}

}  // namespace
}  // namespace imunoise::report
