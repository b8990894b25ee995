// Tests of io/lcm_user_imu_decoder.h: a user's own IMU type (tests/io/lcm_user_types/) in
// read_lcm_imu_log on logs written by lcm::LogFile — values in SI, fields in degrees and g,
// nanosecond stamps, increments, the wrong type on the channel, undecodable messages,
// non-finite values and bad mappings.
#include "io/lcm_user_imu_decoder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <delta_imu_t.hpp>
#include <filesystem>
#include <imunoise/imu_sample_t.hpp>
#include <limits>
#include <string>
#include <usertest/ins_t.hpp>
#include <usertest/scalar_imu_t.hpp>
#include <vector>

#include "common/number_text.h"
#include "io/lcm_fingerprint.h"
#include "io/lcm_log.h"
#include "io/lcm_user_types_test_support.h"
#include "lcm_test_support.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using Bytes = test::LcmBytes;
using LogWriter = test::LcmLogFileWriter;
using namespace lcm_user_types_test;  // the test types, a decoder of one, random messages

constexpr std::int64_t kEpochUs = 1'700'000'000'000'000;  // 2023-11-14, µs since the epoch
constexpr std::int64_t kStepUs = 5'000;                   // 200 Hz
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr double kG = 9.80665;

// ---- files and logs

usertest::ins_t ins_sample(int i) {
  usertest::ins_t m{};
  m.utime = kEpochUs + i * kStepUs;
  m.device_time = 1000 + i;
  m.quat[0] = 1.0;
  for (int a = 0; a < 3; ++a) {
    m.gyro[a] = (a + 1) * 1e-3 + i * std::sqrt(2.0) * 1e-7 + 1.0 / (7 + a);
    m.accel[a] = (a == 2 ? -9.80665 : 0.01 * (a + 1)) + i * 1e-6 / 3.0;
    m.mag[a] = 0.2 * a;
  }
  m.pressure = 101325.0 + i;
  m.rel_alt = -1.5;
  return m;
}

LcmUserType ins_user_type() {
  LcmUserType t;
  t.definition_path = type_file("usertest_ins.lcm");
  t.type_name = "usertest.ins_t";
  t.gyro_fields = {"gyro"};
  t.accel_fields = {"accel"};
  return t;
}

std::filesystem::path ins_log(const std::string& name, int count) {
  const auto path = test::make_temp_dir("lcmuser") / name;
  LogWriter writer(path);
  for (int i = 0; i < count; ++i) writer.write("INS", ins_sample(i));
  return path;
}

LcmReadOptions with_user_type(const LcmUserType& t, bool drop_non_finite = false) {
  LcmReadOptions options;
  options.drop_non_finite = drop_non_finite;
  options.user_type = t;
  return options;
}

TEST(LcmUserType, InsTypeLogGivesTheMessagesValuesInSi) {
  const auto path = ins_log("ins.lcmlog", 50);
  const pipeline::Recording rec =
      read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type()));
  ASSERT_EQ(rec.sample_count(), 50u);
  ASSERT_EQ(rec.channels.size(), 6u);
  EXPECT_NEAR(rec.sample_period_s, 0.005, 1e-15);  // the median of time_s differences
  EXPECT_EQ(rec.start_time_s, static_cast<double>(kEpochUs) * 1e-6);
  for (std::size_t c = 0; c < 6; ++c) {
    const pipeline::Channel& ch = rec.channels[c];
    EXPECT_EQ(ch.name, pipeline::kImuChannelNames[c]);
    EXPECT_EQ(ch.source_column,
              "INS." + std::string(c < 3 ? "gyro" : "accel") + "[" + std::to_string(c % 3) + "]");
    EXPECT_EQ(ch.source_unit, c < 3 ? "rad/s" : "m/s^2");
    EXPECT_FALSE(ch.from_increments);
    for (int i = 0; i < 50; ++i) {
      const usertest::ins_t m = ins_sample(i);
      EXPECT_EQ(ch.values[static_cast<std::size_t>(i)], c < 3 ? m.gyro[c] : m.accel[c - 3]);
    }
  }
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(rec.time_s[static_cast<std::size_t>(i)], static_cast<double>(i * kStepUs) * 1e-6);
  }
}

TEST(LcmUserType, ScalarFieldsInDegreesAndGWithNanosecondStamps) {
  LcmUserType t;
  t.definition_path = type_file("usertest_scalar_imu.lcm");
  t.time_field = "timestamp_ns";
  t.time_unit_s = 1e-9;
  t.gyro_fields = {"gx", "gy", "gz"};
  t.accel_fields = {"ax", "ay", "az"};
  t.gyro_scale_to_si = kDegToRad;
  t.accel_scale_to_si = kG;
  const auto message = [](int i) {
    usertest::scalar_imu_t m{};
    // ns beyond 2^53 with sub-µs parts: 499 ns rounds down, 500 ns rounds up.
    m.timestamp_ns = kEpochUs * 1000 + i * kStepUs * 1000 + (i % 2 == 0 ? 499 : 500);
    m.gx = 0.1 + i * 1e-3;
    m.gy = -0.2;
    m.gz = 1.0 / 3.0;
    m.ax = 0.001 * i;
    m.ay = -0.002;
    m.az = -1.0;
    m.temperature = 25.0f;
    m.sequence = i;
    return m;
  };
  const auto path = test::make_temp_dir("lcmuser") / "scalar.lcmlog";
  {
    LogWriter writer(path);
    for (int i = 0; i < 20; ++i) writer.write("IMU", message(i));
  }
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "IMU", with_user_type(t));
  ASSERT_EQ(rec.sample_count(), 20u);
  for (int i = 0; i < 20; ++i) {
    const usertest::scalar_imu_t m = message(i);
    const auto k = static_cast<std::size_t>(i);
    const double want[6] = {m.gx * kDegToRad, m.gy * kDegToRad, m.gz * kDegToRad,
                            m.ax * kG,        m.ay * kG,        m.az * kG};
    for (std::size_t c = 0; c < 6; ++c) EXPECT_EQ(rec.channels[c].values[k], want[c]);
    // Exact µs: i·5000 + (0 for +499 ns, 1 for +500 ns).
    EXPECT_EQ(rec.time_s[k], static_cast<double>(i * kStepUs + i % 2) * 1e-6);
  }
  EXPECT_EQ(rec.channels[0].source_column, "IMU.gx");
  EXPECT_EQ(rec.channels[0].source_unit, shortest_number_text(kDegToRad) + " rad/s");
  EXPECT_EQ(rec.channels[5].source_unit, "9.80665 m/s^2");

  // The exact stamps, through the decoder itself.
  LcmUserImuDecoder decoder(t);
  pipeline::ImuSampleColumns columns = decoder.make_columns();
  std::string error;
  for (int i = 0; i < 2; ++i)
    ASSERT_TRUE(decoder.append(test::lcm_encode(message(i)), false, columns, error));
  EXPECT_EQ(columns.utime_us, (std::vector<std::int64_t>{kEpochUs, kEpochUs + kStepUs + 1}));
}

TEST(LcmUserType, IncrementsWithoutPackageAreDividedByTheSamplePeriod) {
  LcmUserType t;
  t.definition_path = type_file("delta_imu.lcm");
  t.time_field = "t_us";
  t.gyro_fields = {"dtheta"};
  t.accel_fields = {"dvel"};
  t.increments = true;
  const auto message = [](int i) {
    delta_imu_t m{};
    m.t_us = kEpochUs + i * 2'500;  // 400 Hz
    for (int a = 0; a < 3; ++a) {
      m.dtheta[a] = static_cast<float>(1e-5 * (a + 1) + 1e-8 * i);
      m.dvel[a] = static_cast<float>(a == 2 ? -0.0245 : 1e-4 * i);
    }
    return m;
  };
  const auto path = test::make_temp_dir("lcmuser") / "delta.lcmlog";
  {
    LogWriter writer(path);
    for (int i = 0; i < 30; ++i) writer.write("DELTA", message(i));
  }
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "DELTA", with_user_type(t));
  ASSERT_EQ(rec.sample_count(), 30u);
  ASSERT_NEAR(rec.sample_period_s, 0.0025, 1e-15);
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_TRUE(rec.channels[c].from_increments);
    EXPECT_EQ(rec.channels[c].source_unit, c < 3 ? "rad" : "m/s");
    for (int i = 0; i < 30; ++i) {
      const delta_imu_t m = message(i);
      const double increment = c < 3 ? m.dtheta[c] : m.dvel[c - 3];
      EXPECT_EQ(rec.channels[c].values[static_cast<std::size_t>(i)],
                increment / rec.sample_period_s);
    }
  }
}

TEST(LcmUserType, WrongTypeOnTheChannelNamesBothFingerprints) {
  const auto path = test::make_temp_dir("lcmuser") / "ours.lcmlog";
  {
    LogWriter writer(path);
    imunoise::imu_sample_t m{};
    writer.write("INS", m);
  }
  const std::string message = test::error_of(
      [&] { read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type())); });
  EXPECT_THAT(message, HasSubstr(path.string() + ": byte offset 0: wrong type on channel 'INS'"));
  EXPECT_THAT(
      message,
      HasSubstr("expected usertest.ins_t (fingerprint " +
                lcm_fingerprint_text(static_cast<std::uint64_t>(usertest::ins_t::getHash()))));
  EXPECT_THAT(message, HasSubstr("found fingerprint " +
                                 lcm_fingerprint_text(static_cast<std::uint64_t>(
                                     imunoise::imu_sample_t::getHash())) +
                                 " (imunoise.imu_sample_t)"));
}

TEST(LcmUserType, UndecodableMessageAndUnknownChannelAreNamed) {
  const auto path = test::make_temp_dir("lcmuser") / "short.lcmlog";
  {
    LogWriter writer(path);
    writer.write("INS", ins_sample(0));
    const Bytes full = test::lcm_encode(ins_sample(1));
    writer.write_raw("INS", Bytes(full.begin(), full.end() - 3));
  }
  const std::string offset = std::to_string(28 + 3 + test::lcm_encode(ins_sample(0)).size());
  EXPECT_THAT(test::error_of(
                  [&] { read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type())); }),
              HasSubstr(path.string() + ": byte offset " + offset +
                        ": the message does not decode as usertest.ins_t"));
  EXPECT_THAT(test::error_of(
                  [&] { read_lcm_imu_log(path.string(), "IMU", with_user_type(ins_user_type())); }),
              HasSubstr("channel 'IMU' not found; the log holds 'INS' (unknown type"));
}

TEST(LcmUserType, NonFiniteValuesAreAnErrorOrDroppedAndCounted) {
  const auto path = test::make_temp_dir("lcmuser") / "nan.lcmlog";
  {
    LogWriter writer(path);
    for (int i = 0; i < 10; ++i) {
      usertest::ins_t m = ins_sample(i);
      if (i == 4) m.gyro[1] = std::numeric_limits<double>::quiet_NaN();
      if (i == 6) m.mag[0] = std::numeric_limits<double>::infinity();  // not a used field
      writer.write("INS", m);
    }
  }
  EXPECT_THAT(test::error_of(
                  [&] { read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type())); }),
              HasSubstr("non-finite value in gyro[1] (NaN) (channel 'INS', event number 4)"));
  const pipeline::Recording rec =
      read_lcm_imu_log(path.string(), "INS", with_user_type(ins_user_type(), true));
  EXPECT_EQ(rec.sample_count(), 9u);
  EXPECT_EQ(rec.report.rows_dropped, 1);
  EXPECT_EQ(rec.report.non_finite_dropped, 1);
}

TEST(LcmUserType, ValueOverflowingWhenScaledIsNonFinite) {
  LcmUserType t;
  t.definition_path = type_file("usertest_scalar_imu.lcm");
  t.time_field = "timestamp_ns";
  t.time_unit_s = 1e-9;
  t.gyro_fields = {"gx", "gy", "gz"};
  t.accel_fields = {"ax", "ay", "az"};
  t.accel_scale_to_si = kG;
  usertest::scalar_imu_t m{};
  m.ax = 1e308;  // finite in g, Inf in m/s²
  LcmUserImuDecoder decoder(t);
  pipeline::ImuSampleColumns columns = decoder.make_columns();
  std::string error;
  EXPECT_FALSE(decoder.append(test::lcm_encode(m), false, columns, error));
  EXPECT_EQ(error, "non-finite value in ax (Inf) after scaling to SI");
  EXPECT_TRUE(decoder.append(test::lcm_encode(m), true, columns, error));
  EXPECT_EQ(columns.size(), 0u);
  EXPECT_EQ(columns.rows_dropped, 1);
}

TEST(LcmUserType, BadMappingsAreInputErrors) {
  const auto with = [](auto change) {
    LcmUserType t = ins_user_type();
    change(t);
    return test::error_of([&] { LcmUserImuDecoder decoder(t); });
  };
  EXPECT_THAT(with([](LcmUserType& t) { t.gyro_fields.clear(); }),
              HasSubstr("no gyro fields given"));
  EXPECT_THAT(with([](LcmUserType& t) { t.accel_fields = {"quat"}; }),
              HasSubstr("accel fields give 4 value(s); x, y, z need 3"));
  EXPECT_THAT(with([](LcmUserType& t) {
                t.gyro_fields = {"gyro[0]", "gyro[1]"};
              }),
              HasSubstr("gyro fields give 2 value(s)"));
  EXPECT_THAT(with([](LcmUserType& t) {
                t.gyro_fields = {"gyro", "mag", "quat"};
              }),
              HasSubstr("gyro field 'gyro' is an array"));
  EXPECT_THAT(with([](LcmUserType& t) { t.accel_fields = {"acc"}; }),
              HasSubstr("field 'acc': struct 'usertest.ins_t' has no member 'acc'; its members: "
                        "utime, device_time, quat[4], gyro[3], accel[3], mag[3], pressure, "
                        "rel_alt"));
  EXPECT_THAT(with([](LcmUserType& t) { t.time_field = "stamp"; }), HasSubstr("no member 'stamp'"));
  EXPECT_THAT(with([](LcmUserType& t) { t.time_field = "quat"; }),
              HasSubstr("time field 'quat' must be one number"));
  EXPECT_THAT(with([](LcmUserType& t) { t.time_unit_s = 0.0; }),
              HasSubstr("time unit 0 s is not a positive number"));
  EXPECT_THAT(with([](LcmUserType& t) { t.gyro_scale_to_si = std::nan(""); }),
              HasSubstr("gyro scale nan is not a finite non-zero factor"));
  EXPECT_THAT(with([](LcmUserType& t) { t.type_name = "ins"; }),
              HasSubstr("no struct 'ins' in the file; it defines: usertest.ins_t"));
  EXPECT_THAT(with([](LcmUserType& t) { t.definition_path = "/nonexistent.lcm"; }),
              HasSubstr("/nonexistent.lcm: cannot open"));
  // The whole read fails the same way, before the log is opened.
  LcmUserType t = ins_user_type();
  t.gyro_fields.clear();
  EXPECT_THAT(
      test::error_of([&] { read_lcm_imu_log("/nonexistent.lcmlog", "INS", with_user_type(t)); }),
      HasSubstr("no gyro fields given"));
}

}  // namespace
}  // namespace imunoise::io
