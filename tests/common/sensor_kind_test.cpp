/// @file
/// @brief Tests of common/sensor_kind.h: the parses of the on-disk spellings invert the
/// writers' names and units exactly, and refuse every other text.
#include "common/sensor_kind.h"

#include <gtest/gtest.h>

namespace imunoise {
namespace {

TEST(SensorKind, ParseSensorNameInvertsSensorName) {
  for (const SensorKind kind : kSensorKinds) EXPECT_EQ(parse_sensor_name(sensor_name(kind)), kind);
  EXPECT_EQ(parse_sensor_name("gyro"), SensorKind::gyro);
  EXPECT_EQ(parse_sensor_name("accel"), SensorKind::accel);
}

TEST(SensorKind, ParseSensorNameRefusesOtherSpellings) {
  for (const char* text :
       {"", "Gyro", "GYRO", "gyro ", " accel", "acc", "accelerometer", "gyroscope", "gyro_x"}) {
    EXPECT_FALSE(parse_sensor_name(text).has_value()) << "'" << text << "'";
  }
}

TEST(SensorKind, ParseSiRateUnitInvertsSiRateUnit) {
  for (const SensorKind kind : kSensorKinds)
    EXPECT_EQ(parse_si_rate_unit(si_rate_unit(kind)), kind);
  EXPECT_EQ(parse_si_rate_unit("rad/s"), SensorKind::gyro);
  EXPECT_EQ(parse_si_rate_unit("m/s^2"), SensorKind::accel);
}

TEST(SensorKind, ParseSiRateUnitRefusesOtherUnits) {
  for (const char* text : {"", "deg/s", "rad", "m/s", "m/s2", "m/s²", "rad/s ", "RAD/S", "g"}) {
    EXPECT_FALSE(parse_si_rate_unit(text).has_value()) << "'" << text << "'";
  }
}

TEST(SensorKind, ParsesAreConstexpr) {
  static_assert(parse_sensor_name("gyro") == SensorKind::gyro);
  static_assert(!parse_si_rate_unit("deg/s"));
  SUCCEED();
}

}  // namespace
}  // namespace imunoise
