/// @file
/// @brief Tests of pipeline/datasheet_check.h: the decimation finding from the datasheet's
/// white-noise density. Truth: white noise decimated by d without averaging has √d·N (the
/// battery's decimated class, docs/validation.md), so an axis whose interval lies at or above
/// √2 × the datasheet gets the finding with the ratio and d ≈ ratio², and one within it does not.
#include "pipeline/datasheet_check.h"

#include <gtest/gtest.h>

#include <string>

namespace imunoise::pipeline {
namespace {

models::AxisModel axis_with_white_noise(const char* name, SensorKind kind, double n, double low,
                                        double high, bool identified = true) {
  models::AxisModel axis;
  axis.name = name;
  axis.kind = kind;
  models::Estimate& e = axis.terms[NoiseTerm::white_noise];
  e.value = n;
  e.ci_low = low;
  e.ci_high = high;
  e.identified = identified;
  return axis;
}

FleetSpec datasheet(double gyro_n) {
  FleetSpec spec;
  spec.name = "ACME IMU-100 rev B";
  spec.limits.push_back({SensorKind::gyro, NoiseTerm::white_noise, gyro_n});
  spec.limits.push_back({SensorKind::gyro, NoiseTerm::bias_instability, 1e-5});
  return spec;
}

TEST(DatasheetCheck, WhiteNoiseTwiceTheDatasheetIsADecimationByFour) {
  models::NoiseModel model;
  model.axes.push_back(axis_with_white_noise("gyro_x", SensorKind::gyro, 2e-4, 1.98e-4, 2.02e-4));
  const std::vector<std::string> findings = datasheet_findings(model, datasheet(1e-4));
  ASSERT_EQ(findings.size(), 1u);
  const std::string& f = findings[0];
  EXPECT_EQ(f.rfind("gyro_x: output likely decimated without averaging", 0), 0u) << f;
  EXPECT_NE(f.find(" is 2x the datasheet's"), std::string::npos) << f;
  EXPECT_NE(f.find("interval 1.98x"), std::string::npos) << f;
  EXPECT_NE(f.find("decimation by about 4"), std::string::npos) << f;
  EXPECT_NE(f.find("(ACME IMU-100 rev B)"), std::string::npos) << f;
  // In datasheet units: 2e-4 rad/√s = 0.688 deg/√h.
  EXPECT_NE(f.find("0.688 deg/sqrt(h)"), std::string::npos) << f;
  EXPECT_NE(f.find("; cause: "), std::string::npos) << f;
  EXPECT_NE(f.find("; remedy: "), std::string::npos) << f;
}

TEST(DatasheetCheck, AxesWithinTheirDatasheetOrUndecidedGetNone) {
  models::NoiseModel model;
  // The spread of a typical value (1.2x, the battery's y axes), a ratio whose interval reaches
  // below √2, an axis whose N is not identified, and a sensor the spec has no density for.
  model.axes.push_back(axis_with_white_noise("gyro_x", SensorKind::gyro, 1.2e-4, 1.1e-4, 1.3e-4));
  model.axes.push_back(axis_with_white_noise("gyro_y", SensorKind::gyro, 1.6e-4, 1.4e-4, 1.8e-4));
  model.axes.push_back(
      axis_with_white_noise("gyro_z", SensorKind::gyro, 0.0, 0.0, 5e-4, /*identified=*/false));
  model.axes.push_back(axis_with_white_noise("accel_x", SensorKind::accel, 1.0, 1.0, 1.0));
  EXPECT_TRUE(datasheet_findings(model, datasheet(1e-4)).empty());
  // The interval's lower end decides: just below √2 none, just above the finding.
  model.axes[1].terms[NoiseTerm::white_noise].ci_low = 1.413e-4;
  EXPECT_TRUE(datasheet_findings(model, datasheet(1e-4)).empty());
  model.axes[1].terms[NoiseTerm::white_noise].ci_low = 1.415e-4;
  EXPECT_EQ(datasheet_findings(model, datasheet(1e-4)).size(), 1u);
}

}  // namespace
}  // namespace imunoise::pipeline
