// Tests of io/input_config.h: unit spellings and SI factors, YAML loading with located errors,
// flag-over-file merging, and that configs/example_input.yaml loads.
#include "io/input_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/errors.h"
#include "common/units.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string error_of(const std::string& yaml) {
  try {
    parse_input_config(yaml, "in.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << yaml;
  return {};
}

TEST(Units, FactorsMatchTheoryTable) {
  // Values from theory.md §1.3, checked by value rather than by name.
  EXPECT_NEAR(si_factor(GyroUnit::kDegPerHour), 4.848137e-6, 5e-13);
  EXPECT_NEAR(si_factor(GyroUnit::kDegPerS), 1.745329e-2, 5e-9);
  EXPECT_NEAR(si_factor(GyroUnit::kDegIncrement), 1.745329e-2, 5e-9);
  EXPECT_EQ(si_factor(GyroUnit::kRadPerS), 1.0);
  EXPECT_EQ(si_factor(AccelUnit::kG), 9.80665);
  EXPECT_NEAR(si_factor(AccelUnit::kMilliG), 9.80665e-3, 1e-18);
  EXPECT_EQ(si_factor(TimeUnit::kNanosecond), 1e-9);
  EXPECT_EQ(si_factor(TimeUnit::kMicrosecond), 1e-6);
  EXPECT_EQ(si_factor(TimeUnit::kMillisecond), 1e-3);
  EXPECT_TRUE(is_increment(GyroUnit::kRadIncrement));
  EXPECT_FALSE(is_increment(GyroUnit::kDegPerHour));
  EXPECT_TRUE(is_increment(AccelUnit::kMPerSIncrement));
}

TEST(Units, SpellingsRoundTrip) {
  for (auto u : {GyroUnit::kRadPerS, GyroUnit::kDegPerS, GyroUnit::kDegPerHour,
                 GyroUnit::kRadIncrement, GyroUnit::kDegIncrement}) {
    EXPECT_EQ(parse_gyro_unit(to_string(u)), u);
  }
  for (auto u :
       {AccelUnit::kMPerS2, AccelUnit::kG, AccelUnit::kMilliG, AccelUnit::kMPerSIncrement}) {
    EXPECT_EQ(parse_accel_unit(to_string(u)), u);
  }
  for (auto u :
       {TimeUnit::kSecond, TimeUnit::kMillisecond, TimeUnit::kMicrosecond, TimeUnit::kNanosecond}) {
    EXPECT_EQ(parse_time_unit(to_string(u)), u);
  }
  EXPECT_EQ(parse_accel_unit("m/s2"), AccelUnit::kMPerS2);
  EXPECT_EQ(parse_delimiter(","), Delimiter::kComma);
  EXPECT_EQ(parse_delimiter("tab"), Delimiter::kTab);
  EXPECT_EQ(parse_delimiter("space"), Delimiter::kWhitespace);
  EXPECT_FALSE(parse_gyro_unit("dps").has_value());
}

TEST(ParseInputConfig, FullSchema) {
  const InputConfig c = parse_input_config(R"(
delimiter: semicolon
time:
  column: stamp
  unit: us
gyro:
  columns: [gx, 3, gz]
  unit: deg/h
  full_scale_deg_per_s: 2000
accel:
  columns: [5, 6, 7]
  unit: mg
  full_scale_g: 16
drop_non_finite: true
extra_columns:
  temperature_degc: 8
)",
                                           "in.yaml");
  EXPECT_EQ(c.delimiter, Delimiter::kSemicolon);
  EXPECT_EQ(c.time_column, "stamp");
  EXPECT_EQ(c.time_unit, TimeUnit::kMicrosecond);
  EXPECT_FALSE(c.rate_hz.has_value());
  EXPECT_THAT(c.gyro_columns, ElementsAre("gx", "3", "gz"));
  EXPECT_EQ(c.gyro_unit, GyroUnit::kDegPerHour);
  EXPECT_DOUBLE_EQ(*c.gyro_full_scale_rad_per_s, 2000.0 * units::kDegPerS);
  EXPECT_THAT(c.accel_columns, ElementsAre("5", "6", "7"));
  EXPECT_EQ(c.accel_unit, AccelUnit::kMilliG);
  EXPECT_DOUBLE_EQ(*c.accel_full_scale_m_per_s2, 16.0 * units::kG);
  EXPECT_EQ(c.drop_non_finite, true);
  ASSERT_EQ(c.extra_columns.size(), 1u);
  EXPECT_EQ(c.extra_columns[0].name, "temperature_degc");
  EXPECT_EQ(c.extra_columns[0].column, "8");
}

TEST(ParseInputConfig, EmptyDocumentMeansDefaults) {
  const InputConfig c = parse_input_config("# nothing here\n", "in.yaml");
  EXPECT_FALSE(c.delimiter.has_value());
  EXPECT_TRUE(c.gyro_columns.empty());
}

TEST(ParseInputConfigErrors, UnknownKeyNamesKeyAndPosition) {
  EXPECT_THAT(error_of("gyro:\n  colums: [1, 2, 3]\n"),
              HasSubstr("in.yaml:2:3: unknown key 'gyro.colums' (known keys: columns, unit, "
                        "full_scale_deg_per_s)"));
  EXPECT_THAT(error_of("rate: 100\n"), HasSubstr("in.yaml:1:1: unknown key 'rate'"));
}

TEST(ParseInputConfigErrors, WrongTypes) {
  EXPECT_THAT(error_of("rate_hz: fast\n"),
              HasSubstr("in.yaml:1:10: 'rate_hz' must be a number, got 'fast'"));
  EXPECT_THAT(error_of("rate_hz: -5\n"),
              HasSubstr("'rate_hz' must be a positive finite number, got '-5'"));
  EXPECT_THAT(error_of("gyro:\n  columns: 2\n"),
              HasSubstr("in.yaml:2:12: 'gyro.columns' must be a list of 1 to 3 columns"));
  EXPECT_THAT(error_of("accel:\n  columns: [1, 2, 3, 4]\n"),
              HasSubstr("'accel.columns' must list 1 to 3 columns (x, y, z), got 4"));
  EXPECT_THAT(error_of("time: 3\n"), HasSubstr("in.yaml:1:7: 'time' must be a mapping"));
  EXPECT_THAT(error_of("drop_non_finite: maybe\n"),
              HasSubstr("'drop_non_finite' must be true or false, got 'maybe'"));
  EXPECT_THAT(error_of("gyro:\n  unit: [deg/s]\n"),
              HasSubstr("in.yaml:2:9: 'gyro.unit' must be a single value"));
}

TEST(ParseInputConfigErrors, UnknownUnits) {
  EXPECT_THAT(error_of("gyro:\n  unit: dps\n"),
              HasSubstr("in.yaml:2:9: unknown unit 'dps' for 'gyro.unit' (expected rad/s, deg/s, "
                        "deg/h, or rad / deg for angle increments per sample)"));
  EXPECT_THAT(error_of("accel:\n  unit: G\n"), HasSubstr("unknown unit 'G' for 'accel.unit'"));
  EXPECT_THAT(error_of("time:\n  unit: sec\n"), HasSubstr("unknown unit 'sec' for 'time.unit'"));
  EXPECT_THAT(error_of("delimiter: pipe\n"), HasSubstr("unknown delimiter 'pipe'"));
}

TEST(ParseInputConfigErrors, RateAndTimeColumnExcludeEachOther) {
  EXPECT_THAT(error_of("time:\n  column: t\nrate_hz: 100\n"),
              HasSubstr("in.yaml:3:10: give either 'time.column' or 'rate_hz', not both"));
}

TEST(ParseInputConfigErrors, SyntaxErrorIsLocated) {
  EXPECT_THAT(error_of("gyro: [1, 2\n"), HasSubstr("in.yaml:"));
  EXPECT_THAT(error_of("gyro: [1, 2\n"), HasSubstr("invalid YAML"));
}

TEST(LoadInputConfig, MissingFile) {
  try {
    load_input_config("/nonexistent/in.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/in.yaml: cannot open config file"));
  }
}

TEST(LoadInputConfig, ExampleConfigLoads) {
  const InputConfig c =
      load_input_config(std::string(IMUNOISE_SOURCE_DIR) + "/configs/example_input.yaml");
  EXPECT_FALSE(c.gyro_columns.empty());
  EXPECT_TRUE(c.gyro_unit.has_value());
}

TEST(MergeInputConfigs, FlagsOverrideFileFieldByField) {
  InputConfig file;
  file.time_column = "t";
  file.gyro_columns = {"1", "2", "3"};
  file.gyro_unit = GyroUnit::kDegPerS;
  file.accel_unit = AccelUnit::kG;
  InputConfig flags;
  flags.gyro_unit = GyroUnit::kRadIncrement;
  flags.rate_hz = 400.0;
  const InputConfig merged = merge_input_configs(file, flags);
  EXPECT_EQ(merged.gyro_unit, GyroUnit::kRadIncrement);
  EXPECT_THAT(merged.gyro_columns, ElementsAre("1", "2", "3"));
  EXPECT_EQ(merged.accel_unit, AccelUnit::kG);
  EXPECT_EQ(merged.rate_hz, 400.0);
  EXPECT_TRUE(merged.time_column.empty());  // the flag's rate replaces the file's time column
}

}  // namespace
}  // namespace imunoise::io
