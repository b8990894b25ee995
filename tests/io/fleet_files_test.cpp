// Tests of io/fleet_csv.h and io/fleet_spec.h: fleet.csv written and read back to the same
// units and entries (names with commas and quotes, undefined z-scores, rows with and without a
// spec), its errors located at their line; the spec YAML read with its datasheet units turned
// into SI (factors of models/datasheet_units.h), written and read back, and its errors named
// at their line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/errors.h"
#include "io/fleet_csv.h"
#include "io/fleet_spec.h"
#include "models/datasheet_units.h"

namespace imunoise::io {
namespace {

pipeline::FleetEntry entry(std::size_t unit, const char* axis, SensorKind sensor, NoiseTerm term,
                           bool with_spec) {
  pipeline::FleetEntry e;
  e.unit = unit;
  e.axis = axis;
  e.sensor = sensor;
  e.term = term;
  e.estimate = {1.2345678901234567e-5, 1.1e-5, 1.3e-5, true, "", ""};
  e.robust_z = -0.3;
  if (with_spec) {
    e.spec_max_si = 2e-5;
    e.spec_verdict = pipeline::SpecVerdict::pass;
  }
  return e;
}

TEST(FleetCsv, RoundTripKeepsUnitsAndEntries) {
  FleetTable t;
  t.units = {"unit 1", "lab, \"bench\" 2"};
  t.entries.push_back(entry(0, "gyro_x", SensorKind::gyro, NoiseTerm::white_noise, true));
  pipeline::FleetEntry n = entry(1, "accel_z", SensorKind::accel, NoiseTerm::random_walk, false);
  n.estimate = {0.0, 0.0, 3e-4, false, "", ""};
  n.robust_z = std::nan("");
  t.entries.push_back(n);
  pipeline::FleetEntry out = entry(1, "gyro_x", SensorKind::gyro, NoiseTerm::white_noise, true);
  out.outlier = true;
  out.spec_verdict = pipeline::SpecVerdict::fail;
  t.entries.push_back(out);
  const std::string text = fleet_csv_text(t);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "unit,axis,term,si_unit,identified,value_si,ci_low_si,ci_high_si,robust_z_log10,"
            "outlier,spec_max_si,spec_verdict");
  EXPECT_NE(text.find("\"lab, \"\"bench\"\" 2\",accel_z,random_walk,m/s^2.5"), std::string::npos)
      << text;
  const FleetTable back = parse_fleet_csv(text, "fleet.csv");
  EXPECT_EQ(back.units, t.units);
  ASSERT_EQ(back.entries.size(), t.entries.size());
  for (std::size_t i = 0; i < t.entries.size(); ++i) {
    const pipeline::FleetEntry& a = t.entries[i];
    const pipeline::FleetEntry& b = back.entries[i];
    EXPECT_EQ(b.unit, a.unit);
    EXPECT_EQ(b.axis, a.axis);
    EXPECT_EQ(b.sensor, a.sensor);
    EXPECT_EQ(b.term, a.term);
    EXPECT_EQ(b.estimate.identified, a.estimate.identified);
    EXPECT_EQ(b.estimate.value, a.estimate.value);  // exact: shortest round-trip text
    EXPECT_EQ(b.estimate.ci_low, a.estimate.ci_low);
    EXPECT_EQ(b.estimate.ci_high, a.estimate.ci_high);
    EXPECT_EQ(std::isnan(b.robust_z), std::isnan(a.robust_z));
    if (!std::isnan(a.robust_z)) {
      EXPECT_EQ(b.robust_z, a.robust_z);
    }
    EXPECT_EQ(b.outlier, a.outlier);
    EXPECT_EQ(b.spec_max_si, a.spec_max_si);
    EXPECT_EQ(b.spec_verdict, a.spec_verdict);
  }
  EXPECT_EQ(fleet_csv_text(back), text);
}

TEST(FleetCsv, ErrorsNameTheFileAndLine) {
  const std::string header =
      "unit,axis,term,si_unit,identified,value_si,ci_low_si,ci_high_si,robust_z_log10,outlier,"
      "spec_max_si,spec_verdict\n";
  const auto message = [](const std::string& text) {
    try {
      parse_fleet_csv(text, "f.csv");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("a,b\n").find("f.csv:1:"), std::string::npos);
  EXPECT_NE(message(header + "u,gyro_x,white_noise,rad/s^0.5,true,1,0.9,1.1,,false,,\n" +
                    "u,gyro_x,white_noise,rad/s^0.5,maybe,1,0.9,1.1,,false,,\n")
                .find("f.csv:3: identified: 'maybe'"),
            std::string::npos);
  EXPECT_NE(message(header + "u,gyro_x,white_noise,m/s,true,1,0.9,1.1,,false,,\n")
                .find("f.csv:2: si_unit: 'm/s' is not a unit of white_noise"),
            std::string::npos);
  EXPECT_NE(message(header + "u,gyro_x,white_noise,rad/s^0.5,true,x,0.9,1.1,,false,,\n")
                .find("value_si: 'x' is not a finite number"),
            std::string::npos);
  EXPECT_NE(message(header + "u,gyro_x,white_noise,rad/s^0.5,true,1,0.9,1.1,,false,2,\n")
                .find("both given or both empty"),
            std::string::npos);
  EXPECT_NE(message(header + "\"u,gyro_x\n").find("not closed"), std::string::npos);
}

TEST(FleetSpec, ReadsDatasheetUnitsIntoSiAndRoundTrips) {
  const std::string text =
      "# a datasheet\n"
      "name: ACME IMU-100\n"
      "gyro:\n"
      "  arw_deg_per_sqrt_h: 0.15\n"
      "  bias_instability_deg_per_h: 10\n"
      "accel:\n"
      "  vrw_ug_per_sqrt_hz: 80\n";
  const pipeline::FleetSpec spec = parse_fleet_spec(text, "spec.yaml");
  EXPECT_EQ(spec.name, "ACME IMU-100");
  ASSERT_EQ(spec.limits.size(), 3u);
  // 0.15 °/√h = 0.15 · (π/180)/60 rad/√s (theory.md §1.3).
  EXPECT_EQ(spec.limits[0].sensor, SensorKind::gyro);
  EXPECT_EQ(spec.limits[0].term, NoiseTerm::white_noise);
  EXPECT_NEAR(spec.limits[0].max_si, 0.15 * (M_PI / 180.0) / 60.0, 1e-18);
  // 80 µg/√Hz = 80e-6 · 9.80665 m/s²/√Hz.
  EXPECT_EQ(spec.limits[2].sensor, SensorKind::accel);
  EXPECT_NEAR(spec.limits[2].max_si, 80e-6 * 9.80665, 1e-15);
  const pipeline::FleetSpec back = parse_fleet_spec(fleet_spec_text(spec), "again.yaml");
  EXPECT_EQ(back.name, spec.name);
  ASSERT_EQ(back.limits.size(), spec.limits.size());
  for (std::size_t i = 0; i < spec.limits.size(); ++i) {
    EXPECT_EQ(back.limits[i].sensor, spec.limits[i].sensor);
    EXPECT_EQ(back.limits[i].term, spec.limits[i].term);
    // SI → datasheet → SI: one multiplication and one division, a few roundings.
    EXPECT_NEAR(back.limits[i].max_si / spec.limits[i].max_si, 1.0, 4e-16);
  }
}

TEST(FleetSpec, ErrorsNameTheLineAndTheKey) {
  const auto message = [](const std::string& text) {
    try {
      parse_fleet_spec(text, "s.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("gyro:\n  arw_deg_per_h: 1\n")
                .find("s.yaml:2:3: gyro: unknown key "
                      "'arw_deg_per_h' (one of quantization_urad"),
            std::string::npos);
  EXPECT_NE(message("gyro:\n  arw_deg_per_sqrt_h: -1\n")
                .find("s.yaml:2:23: gyro.arw_deg_per_sqrt_h: the maximum must be finite and > 0"),
            std::string::npos);
  EXPECT_NE(message("gyro:\n  arw_deg_per_sqrt_h: abc\n").find("expected a number"),
            std::string::npos);
  EXPECT_NE(message("magnetometer:\n  x: 1\n").find("s.yaml:1:1: unknown key 'magnetometer'"),
            std::string::npos);
  EXPECT_NE(message("name: x\n").find("gives no maximum"), std::string::npos);
  EXPECT_NE(message("gyro: [1, 2\n").find("s.yaml:"), std::string::npos);
}

}  // namespace
}  // namespace imunoise::io
