// Tests of io/deviation_curve_text.h: the JSON object's keys and values, and the text table's
// header lines, EDF model per statistic and one row per point.
#include "io/deviation_curve_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

analysis::DeviationCurve two_point_curve(analysis::DeviationType type) {
  analysis::DeviationCurve curve;
  curve.type = type;
  curve.tau0_s = 0.01;
  curve.n_phase = 101;
  curve.confidence = 0.683;
  curve.points.push_back({1, 0.01, 2.5, 99, 0, 80.5, 2.25, 2.75});
  curve.points.push_back({2, 0.02, 1.75, 97, -1, 40.25, 1.5, 2.0});
  return curve;
}

SeriesCurveInfo info() {
  SeriesCurveInfo i;
  i.data = "rate";
  i.source = "gyro.txt";
  i.column = "gyro_z";
  i.n_samples = 100;
  i.tau0_source = "--tau0";
  return i;
}

TEST(SeriesCurveJson, HoldsTheCurveAndWhereItCameFrom) {
  const nlohmann::ordered_json j =
      series_curve_json(two_point_curve(analysis::DeviationType::oadev), info());
  EXPECT_THAT(j.dump(), StartsWith(R"({"type":"oadev","data":"rate","tau0_s":0.01,"n_samples":100,)"
                                   R"("confidence":0.683,"tau0_source":"--tau0",)"));
  EXPECT_EQ(j["tau0_source"], "--tau0");
  EXPECT_EQ(j["source"], "gyro.txt");
  EXPECT_EQ(j["column"], "gyro_z");
  EXPECT_EQ(j["n_phase"], 101);
  EXPECT_EQ(j["value_unit"], "input unit");
  EXPECT_EQ(j["bias_corrected"], false);
  ASSERT_EQ(j["points"].size(), 2u);
  EXPECT_EQ(j["points"][1].dump(),
            R"({"m":2,"tau_s":0.02,"value":1.75,"n_terms":97,"alpha":-1,"edf":40.25,)"
            R"("ci_low":1.5,"ci_high":2.0})");
}

TEST(SeriesCurveJson, TimeStatisticsAreInInputUnitSecondsAndBiasCorrectionNeedsATotalType) {
  SeriesCurveInfo i = info();
  i.bias_corrected = true;
  EXPECT_EQ(series_curve_json(two_point_curve(analysis::DeviationType::tdev), i)["value_unit"],
            "input unit * s");
  EXPECT_EQ(series_curve_json(two_point_curve(analysis::DeviationType::tdev), i)["bias_corrected"],
            false);
  EXPECT_EQ(
      series_curve_json(two_point_curve(analysis::DeviationType::mtotdev), i)["bias_corrected"],
      true);
}

TEST(SeriesCurveTable, HeaderNamesTheSourceAndTheEdfModel) {
  SeriesCurveInfo i = info();
  i.non_finite_dropped = 3;
  const std::string table = series_curve_table(two_point_curve(analysis::DeviationType::oadev), i);
  EXPECT_THAT(table, StartsWith("# oadev of gyro.txt column 'gyro_z' (rate data, tau0 = 0.01 s "
                                "from --tau0, 100 samples, 101 phase points)\n"
                                "# confidence interval: 68.3 % two-sided chi-square, EDF by "
                                "Greenhall-Riley, alpha identified per tau (lag-1 ACF)\n"
                                "# 3 NaN/Inf values dropped\n"));
  EXPECT_THAT(table, HasSubstr("         m         tau_s    n_terms alpha         edf        "
                               "ci_low         value       ci_high\n"));
  EXPECT_THAT(table, HasSubstr("\n         1  1.000000e-02         99     0        80.5  "
                               "2.250000e+00  2.500000e+00  2.750000e+00\n"));
  i.alpha = -2;
  EXPECT_THAT(series_curve_table(two_point_curve(analysis::DeviationType::totdev), i),
              HasSubstr("EDF of SP 1065 (TOTDEV), alpha fixed at -2\n"));
  EXPECT_THAT(series_curve_table(two_point_curve(analysis::DeviationType::ttotdev), i),
              HasSubstr("EDF of SP 1065 Table 8 (MTOT)"));
  EXPECT_THAT(series_curve_table(two_point_curve(analysis::DeviationType::htotdev), i),
              HasSubstr("EDF by Greenhall-Riley (OHDEV model)"));
  EXPECT_THAT(series_curve_table(two_point_curve(analysis::DeviationType::theo1), i),
              HasSubstr("EDF of SP 1065 (Theo1)"));
}

}  // namespace
}  // namespace imunoise::io
