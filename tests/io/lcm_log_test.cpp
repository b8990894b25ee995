// Tests of io/lcm_log.h: logs written by LCM's own writer (lcm::LogFile, the code lcm-logger
// uses) read back bit-exact, the channel listing, the increments path, every malformed-log
// error (file, byte offset, problem), and robustness on arbitrary bytes. Also a memq://
// round trip of the generated imu_sample_t through the LCM runtime.
#include "io/lcm_log.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <imunoise/allan_curve_t.hpp>
#include <imunoise/drift_prediction_t.hpp>
#include <imunoise/imu_sample_t.hpp>
#include <imunoise/noise_model_t.hpp>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"
#include "io/lcm_fingerprint.h"
#include "lcm_test_support.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;
using Bytes = test::LcmBytes;
using LogWriter = test::LcmLogFileWriter;

constexpr std::int64_t kEpochUs = 1'700'000'000'000'000;  // 2023-11-14, µs since the epoch
constexpr std::int64_t kStepUs = 5'000;                   // 200 Hz
constexpr std::uint64_t kHeaderBytes = 28;                // LCM event header

/// Sample i: distinctive values (different per axis and field, some not representable in few
/// decimal digits) so a mix-up or a rounding shows.
imunoise::imu_sample_t sample(int i, bool increments, bool temperature) {
  imunoise::imu_sample_t m{};
  m.utime = kEpochUs + i * kStepUs;
  for (int a = 0; a < 3; ++a) {
    m.angular_rate_rad_per_s[a] = (a + 1) * 1e-3 + i * std::sqrt(2.0) * 1e-7 + 1.0 / (7 + a);
    m.specific_force_m_per_s2[a] = (a == 2 ? -9.80665 : 0.01 * (a + 1)) + i * 1e-6 / 3.0;
    m.delta_angle_rad[a] = m.angular_rate_rad_per_s[a] * 0.005 + std::ldexp(1.0, -40 - a);
    m.delta_velocity_m_per_s[a] = m.specific_force_m_per_s2[a] * 0.005 - std::ldexp(1.0, -38);
  }
  m.has_increments = increments;
  m.has_temperature = temperature;
  m.temperature_degc = 25.0 + i / 1024.0;
  return m;
}

std::filesystem::path temp_log(const std::string& name) {
  return test::make_temp_dir("lcm") / name;
}

/// A log of `count` imu_sample_t messages on "IMU".
std::filesystem::path imu_log(const std::string& name, int count, bool increments = false,
                              bool temperature = true) {
  const auto path = temp_log(name);
  LogWriter writer(path);
  for (int i = 0; i < count; ++i) writer.write("IMU", sample(i, increments, temperature));
  return path;
}

Bytes read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
void write_bytes(const std::filesystem::path& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}
void put_be32(Bytes& bytes, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) bytes.at(at + k) = static_cast<unsigned char>(v >> (24 - 8 * k));
}

using test::error_of;

std::string hash_text(std::int64_t hash) {
  return lcm_fingerprint_text(static_cast<std::uint64_t>(hash));
}

TEST(LcmLog, ReadsRatesBitExactFromLcmLogFile) {
  constexpr int kCount = 64;
  const auto path = imu_log("rates.lcmlog", kCount);
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "IMU");

  ASSERT_EQ(rec.sample_count(), static_cast<std::size_t>(kCount));
  EXPECT_EQ(rec.source_path, path.string());
  EXPECT_EQ(rec.start_time_s, static_cast<double>(kEpochUs) * 1e-6);
  EXPECT_NEAR(rec.sample_period_s, 0.005, 1e-15);
  ASSERT_EQ(rec.time_s.size(), static_cast<std::size_t>(kCount));
  const char* names[] = {"gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"};
  ASSERT_EQ(rec.channels.size(), 7u);  // six axes + temperature
  for (int c = 0; c < 6; ++c) {
    const pipeline::Channel& ch = rec.channels[c];
    EXPECT_EQ(ch.name, names[c]);
    EXPECT_EQ(ch.unit(), c < 3 ? "rad/s" : "m/s^2");
    EXPECT_EQ(ch.source_unit, c < 3 ? "rad/s" : "m/s^2");
    EXPECT_FALSE(ch.from_increments);
  }
  EXPECT_EQ(rec.channels[0].source_column, "IMU.angular_rate_rad_per_s[0]");
  EXPECT_EQ(rec.channels[5].source_column, "IMU.specific_force_m_per_s2[2]");
  for (int i = 0; i < kCount; ++i) {
    const auto m = sample(i, false, true);
    EXPECT_EQ(rec.time_s[i], static_cast<double>(i * kStepUs) * 1e-6) << i;
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(rec.channels[a].values[i], m.angular_rate_rad_per_s[a]) << i;
      EXPECT_EQ(rec.channels[3 + a].values[i], m.specific_force_m_per_s2[a]) << i;
    }
    EXPECT_EQ(rec.channels[6].values[i], m.temperature_degc) << i;
  }
  EXPECT_EQ(rec.channels[6].name, "temperature");
  EXPECT_EQ(rec.channels[6].source_unit, "degC");

  // The sampling report is the one CSV input gets (io/sampling_report.h).
  EXPECT_EQ(rec.report.samples, kCount);
  EXPECT_TRUE(rec.report.timing.has_timestamps);
  EXPECT_NEAR(rec.report.timing.rate_hz, 200.0, 1e-9);
  EXPECT_EQ(rec.report.timing.gap_count, 0);
  ASSERT_EQ(rec.report.channels.size(), 7u);
  EXPECT_EQ(rec.report.channels[2].name, "gyro_z");
}

TEST(LcmLog, IncrementsAreDividedByTheMedianSamplePeriod) {
  constexpr int kCount = 40;
  const auto path = imu_log("inc.lcmlog", kCount, /*increments=*/true, /*temperature=*/false);
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "IMU");
  ASSERT_EQ(rec.channels.size(), 6u);  // no temperature channel without has_temperature
  const double dt = rec.sample_period_s;
  EXPECT_NEAR(dt, 0.005, 1e-15);
  for (int c = 0; c < 6; ++c) {
    EXPECT_TRUE(rec.channels[c].from_increments);
    EXPECT_EQ(rec.channels[c].source_unit, c < 3 ? "rad" : "m/s");
  }
  EXPECT_EQ(rec.channels[1].source_column, "IMU.delta_angle_rad[1]");
  EXPECT_EQ(rec.channels[4].source_column, "IMU.delta_velocity_m_per_s[1]");
  for (int i = 0; i < kCount; ++i) {
    const auto m = sample(i, true, false);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(rec.channels[a].values[i], m.delta_angle_rad[a] / dt) << i;
      EXPECT_EQ(rec.channels[3 + a].values[i], m.delta_velocity_m_per_s[a] / dt) << i;
    }
  }
}

/// Writes one event per known type and some foreign ones, interleaved with IMU samples.
struct MixedLog {
  std::filesystem::path path;
  Bytes foreign;
};
MixedLog mixed_log() {
  MixedLog log{temp_log("mixed.lcmlog"), {0x12, 0x34, 0x56, 0x78, 0x9a, 0xbc, 0xde, 0xf0, 1, 2}};
  LogWriter writer(log.path);
  imunoise::noise_model_t model{};
  model.sensor_name = "adis";
  model.n_axes = 0;
  imunoise::allan_curve_t curve{};
  curve.n = 2;
  curve.tau_s = {0.1, 1.0};
  curve.deviation = curve.ci_low = curve.ci_high = {1e-3, 3e-4};
  imunoise::drift_prediction_t drift{};
  drift.n = 1;
  drift.time_s = drift.horizontal_sigma_m = drift.vertical_sigma_m = drift.attitude_sigma_rad =
      drift.actual_horizontal_m = {1.0};
  for (int i = 0; i < 10; ++i) {
    writer.write("IMU", sample(i, false, false));
    if (i == 2) writer.write("NOISE_MODEL", model);
    if (i == 3) writer.write("ALLAN_GYRO_X", curve);
    if (i % 4 == 0) writer.write("DRIFT", drift);
    if (i == 5) writer.write_raw("FOREIGN", log.foreign);
    if (i == 6) writer.write_raw("SHORT", {1, 2, 3});
    if (i == 7) writer.write("DRIFT", model);  // a second type on one channel
  }
  return log;
}

TEST(LcmLog, ListsChannelsTypesAndFingerprintsInOrderOfAppearance) {
  const MixedLog log = mixed_log();
  const auto channels = list_lcm_log_channels(log.path.string());
  ASSERT_EQ(channels.size(), 6u);
  EXPECT_EQ(channels[0].name, "IMU");
  EXPECT_EQ(channels[0].event_count, 10);
  EXPECT_EQ(channels[0].fingerprint, static_cast<std::uint64_t>(imunoise::imu_sample_t::getHash()));
  EXPECT_EQ(channels[0].type_name, "imunoise.imu_sample_t");
  EXPECT_EQ(channels[0].other_fingerprint_count, 0);
  EXPECT_EQ(channels[1].name, "DRIFT");
  EXPECT_EQ(channels[1].event_count, 4);
  EXPECT_EQ(channels[1].type_name, "imunoise.drift_prediction_t");
  EXPECT_EQ(channels[1].other_fingerprint_count, 1);
  EXPECT_EQ(channels[2].name, "NOISE_MODEL");
  EXPECT_EQ(channels[2].type_name, "imunoise.noise_model_t");
  EXPECT_EQ(channels[2].fingerprint,
            static_cast<std::uint64_t>(imunoise::noise_model_t::getHash()));
  EXPECT_EQ(channels[3].name, "ALLAN_GYRO_X");
  EXPECT_EQ(channels[3].type_name, "imunoise.allan_curve_t");
  EXPECT_EQ(channels[4].name, "FOREIGN");
  EXPECT_EQ(channels[4].fingerprint, 0x123456789abcdef0u);
  EXPECT_EQ(channels[4].type_name, "");
  EXPECT_EQ(channels[5].name, "SHORT");
  EXPECT_EQ(channels[5].fingerprint, std::nullopt);

  // The IMU channel reads the same among the others.
  const pipeline::Recording rec = read_lcm_imu_log(log.path.string(), "IMU");
  ASSERT_EQ(rec.sample_count(), 10u);
  EXPECT_EQ(rec.channels[3].values[9], sample(9, false, false).specific_force_m_per_s2[0]);
}

TEST(LcmLog, AgreesEventForEventWithLcmOwnReader) {
  const MixedLog log = mixed_log();
  lcm::LogFile reader(log.path.string(), "r");
  ASSERT_TRUE(reader.good());
  std::vector<std::pair<std::string, std::int64_t>> counts;
  while (const lcm::LogEvent* event = reader.readNextEvent()) {
    auto it = std::find_if(counts.begin(), counts.end(),
                           [&](const auto& c) { return c.first == event->channel; });
    if (it == counts.end()) {
      counts.emplace_back(event->channel, 1);
    } else {
      ++it->second;
    }
  }
  const auto channels = list_lcm_log_channels(log.path.string());
  ASSERT_EQ(channels.size(), counts.size());
  for (std::size_t i = 0; i < counts.size(); ++i) {
    EXPECT_EQ(channels[i].name, counts[i].first);
    EXPECT_EQ(channels[i].event_count, counts[i].second);
  }
}

TEST(LcmLog, ChannelNotFoundListsTheChannelsAndTheirTypes) {
  const MixedLog log = mixed_log();
  const std::string what = error_of([&] { read_lcm_imu_log(log.path.string(), "IMU_RAW"); });
  EXPECT_THAT(what, HasSubstr("mixed.lcmlog: channel 'IMU_RAW' not found; the log holds 'IMU' "
                              "(imunoise.imu_sample_t, 10 events), 'DRIFT' "
                              "(imunoise.drift_prediction_t, 4 events), 'NOISE_MODEL' "
                              "(imunoise.noise_model_t, 1 event)"));
  EXPECT_THAT(what, HasSubstr("'FOREIGN' (unknown type, fingerprint 0x123456789abcdef0, 1 event)"));
  EXPECT_THAT(what,
              HasSubstr("'SHORT' (unknown type, message shorter than a fingerprint, 1 event)"));

  const auto empty = temp_log("empty.lcmlog");
  write_bytes(empty, {});
  EXPECT_TRUE(list_lcm_log_channels(empty.string()).empty());
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(empty.string(), "IMU"); }),
              HasSubstr("empty.lcmlog: channel 'IMU' not found; the log holds no events"));
}

TEST(LcmLog, WrongTypeOnTheChannelNamesBothFingerprints) {
  const auto path = temp_log("wrong.lcmlog");
  LogWriter writer(path);
  writer.write("IMU", sample(0, false, false));
  imunoise::noise_model_t model{};
  writer.write("IMU", model);
  writer.close();
  const std::string what = error_of([&] { read_lcm_imu_log(path.string(), "IMU"); });
  EXPECT_THAT(
      what, HasSubstr("wrong.lcmlog: byte offset " + std::to_string(writer.offset(1)) +
                      ": wrong type on channel 'IMU': expected imunoise.imu_sample_t "
                      "(fingerprint " +
                      hash_text(imunoise::imu_sample_t::getHash()) + "), found fingerprint " +
                      hash_text(imunoise::noise_model_t::getHash()) + " (imunoise.noise_model_t)"));

  const auto foreign = temp_log("foreign.lcmlog");
  LogWriter foreign_writer(foreign);
  foreign_writer.write_raw("IMU", {0xde, 0xad, 0xbe, 0xef, 0, 0, 0, 1, 42});
  foreign_writer.write_raw("IMU", {1});
  foreign_writer.close();
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(foreign.string(), "IMU"); }),
              HasSubstr("byte offset 0: wrong type on channel 'IMU': expected "
                        "imunoise.imu_sample_t (fingerprint " +
                        hash_text(imunoise::imu_sample_t::getHash()) +
                        "), found fingerprint 0xdeadbeef00000001 (not one of imunoise's types)"));

  const auto tiny = temp_log("tiny.lcmlog");
  LogWriter(tiny).write_raw("IMU", {1, 2});
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(tiny.string(), "IMU"); }),
              HasSubstr("found a 2-byte message, too short for a fingerprint"));
}

TEST(LcmLog, RightFingerprintButBadBodyIsNamed) {
  Bytes good = test::lcm_encode(sample(0, false, false));
  const auto cut = temp_log("cut.lcmlog");
  LogWriter(cut).write_raw("IMU", Bytes(good.begin(), good.end() - 1));
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(cut.string(), "IMU"); }),
              HasSubstr("cut.lcmlog: byte offset 0: the " + std::to_string(good.size() - 1) +
                        "-byte message on channel 'IMU' does not decode as "
                        "imunoise.imu_sample_t"));
  const auto trailing = temp_log("trailing.lcmlog");
  good.push_back(0);
  LogWriter(trailing).write_raw("IMU", good);
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(trailing.string(), "IMU"); }),
              HasSubstr("byte offset 0: 1 trailing bytes after the imunoise.imu_sample_t message"));
}

TEST(LcmLog, TruncatedEventNamesItsOffsetAtEveryCut) {
  const auto path = imu_log("full.lcmlog", 3);
  const Bytes full = read_bytes(path);
  const std::uint64_t event = full.size() / 3;  // all events have the same size
  const std::uint64_t channel_end = kHeaderBytes + 3;
  struct Cut {
    std::uint64_t keep;
    std::string problem;
  };
  const std::vector<Cut> cuts = {
      {event + 2, "truncated event: the file ends 2 bytes into the 28-byte event header"},
      {event + 4, "truncated event: the file ends 4 bytes into the 28-byte event header"},
      {event + 27, "truncated event: the file ends 27 bytes into the 28-byte event header"},
      {event + kHeaderBytes, "truncated event: channel and data need " +
                                 std::to_string(event - kHeaderBytes) +
                                 " bytes after the header, the file has 0"},
      {event + channel_end - 1, "the file has 2"},
      {event + channel_end + 10, "the file has 13"},
      {2 * event - 1, "the file has " + std::to_string(event - kHeaderBytes - 1)},
  };
  for (const Cut& cut : cuts) {
    const auto truncated = temp_log("cut.lcmlog");
    write_bytes(truncated,
                Bytes(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(cut.keep)));
    const std::string prefix = "cut.lcmlog: byte offset " + std::to_string(event) + ": ";
    EXPECT_THAT(error_of([&] { read_lcm_imu_log(truncated.string(), "IMU"); }),
                HasSubstr(prefix + (cut.problem.starts_with("truncated") ? cut.problem : "")))
        << cut.keep;
    EXPECT_THAT(error_of([&] { list_lcm_log_channels(truncated.string()); }),
                HasSubstr(cut.problem))
        << cut.keep;
  }
}

TEST(LcmLog, BadSyncWordIsNamedWithItsOffset) {
  const auto path = imu_log("sync.lcmlog", 3);
  Bytes bytes = read_bytes(path);
  const std::size_t event = bytes.size() / 3;

  Bytes first = bytes;
  first[0] ^= 0xFF;
  write_bytes(path, first);
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(path.string(), "IMU"); }),
              HasSubstr("sync.lcmlog: byte offset 0: bad sync word 0x12a1da01 (expected "
                        "0xeda1da01): not an LCM log file"));

  Bytes second = bytes;
  put_be32(second, event, 0x01020304u);
  write_bytes(path, second);
  EXPECT_THAT(error_of([&] { list_lcm_log_channels(path.string()); }),
              HasSubstr("byte offset " + std::to_string(event) +
                        ": bad sync word 0x01020304 (expected 0xeda1da01): the log is corrupt "
                        "here"));

  const auto text = temp_log("notes.txt");
  test::write_text(text, "time_s,gyro_x\n0,1\n");
  EXPECT_THAT(error_of([&] { list_lcm_log_channels(text.string()); }),
              HasSubstr("notes.txt: byte offset 0: bad sync word 0x74696d65"));
}

TEST(LcmLog, DataOrChannelLengthBeyondTheFileIsNamed) {
  const auto path = imu_log("huge.lcmlog", 3);
  const Bytes bytes = read_bytes(path);
  const std::size_t event = bytes.size() / 3;
  for (const std::uint32_t length : {0x7FFFFFF0u, 0xFFFFFFFFu, 0x80000000u}) {
    Bytes huge = bytes;
    put_be32(huge, event + 24, length);
    write_bytes(path, huge);
    EXPECT_THAT(error_of([&] { read_lcm_imu_log(path.string(), "IMU"); }),
                HasSubstr("huge.lcmlog: byte offset " + std::to_string(event) + ": data length " +
                          std::to_string(length) + " is beyond the file size (" +
                          std::to_string(bytes.size()) + " bytes)"));
  }
  for (const std::uint32_t length : {0u, 5000u, 0xFFFFFFFFu}) {
    Bytes bad = bytes;
    put_be32(bad, 20, length);  // channel length field
    write_bytes(path, bad);
    EXPECT_THAT(error_of([&] { list_lcm_log_channels(path.string()); }),
                HasSubstr("byte offset 0: bad channel length " + std::to_string(length) +
                          " (expected 1 to 4096)"));
  }
}

TEST(LcmLog, NonFiniteValuesAreAnErrorOrDroppedAndCounted) {
  const auto path = temp_log("nan.lcmlog");
  LogWriter writer(path);
  for (int i = 0; i < 5; ++i) {
    auto m = sample(i, false, false);
    if (i == 2) {
      m.specific_force_m_per_s2[1] = std::numeric_limits<double>::quiet_NaN();
      m.specific_force_m_per_s2[2] = std::numeric_limits<double>::infinity();
    }
    m.angular_rate_rad_per_s[0] = i == 3 ? -std::numeric_limits<double>::infinity() : 0.1;
    writer.write("IMU", m);
  }
  writer.close();
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(path.string(), "IMU"); }),
              HasSubstr("nan.lcmlog: byte offset " + std::to_string(writer.offset(2)) +
                        ": non-finite value in specific_force_m_per_s2[1] (NaN) on channel 'IMU' "
                        "(event number 2)"));
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "IMU", {.drop_non_finite = true});
  EXPECT_EQ(rec.sample_count(), 3u);
  EXPECT_EQ(rec.report.rows_dropped, 2);
  EXPECT_EQ(rec.report.non_finite_dropped, 3);
  EXPECT_EQ(rec.time_s.back(), static_cast<double>(4 * kStepUs) * 1e-6);
}

TEST(LcmLog, MixedIncrementFlagIsAnError) {
  const auto path = temp_log("mixedinc.lcmlog");
  LogWriter writer(path);
  writer.write("IMU", sample(0, true, false));
  writer.write("IMU", sample(1, true, false));
  writer.write("IMU", sample(2, false, false));
  writer.close();
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(path.string(), "IMU"); }),
              HasSubstr("byte offset " + std::to_string(writer.offset(2)) +
                        ": has_increments is false here but true in the first message on "
                        "channel 'IMU'"));
}

TEST(LcmLog, TooFewSamplesOrStampsThatNeverIncreaseAreErrors) {
  const auto one = imu_log("one.lcmlog", 1);
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(one.string(), "IMU"); }),
              HasSubstr("one.lcmlog: too few samples: 1 (need at least 2"));
  const auto path = temp_log("flat.lcmlog");
  LogWriter writer(path);
  for (int i = 0; i < 4; ++i) {
    auto m = sample(i, false, false);
    m.utime = kEpochUs;
    writer.write("IMU", m);
  }
  writer.close();
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(path.string(), "IMU"); }),
              HasSubstr("flat.lcmlog: cannot estimate the sample rate: the utime stamps on "
                        "channel 'IMU' never increase"));
  EXPECT_THAT(error_of([&] { read_lcm_imu_log((path.parent_path() / "absent").string(), "IMU"); }),
              HasSubstr("absent: cannot open: no such file"));
  EXPECT_THAT(error_of([&] { read_lcm_imu_log(path.parent_path().string(), "IMU"); }),
              HasSubstr("cannot open: not a regular file"));
}

TEST(LcmLog, ExtremeTimeStampsDoNotOverflow) {
  const auto path = temp_log("extreme.lcmlog");
  LogWriter writer(path);
  const std::int64_t stamps[] = {std::numeric_limits<std::int64_t>::min(), 0,
                                 std::numeric_limits<std::int64_t>::max()};
  for (int i = 0; i < 3; ++i) {
    auto m = sample(i, false, false);
    m.utime = stamps[i];
    writer.write("IMU", m);
  }
  writer.close();
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "IMU");
  EXPECT_DOUBLE_EQ(rec.time_s[1], 9223372036854.775808);
  EXPECT_GT(rec.time_s[2], rec.time_s[1]);
}

// Fuzz regression (sampling report): 1 µs steps, then two gaps of ~9.2e12 s. gap / median is
// beyond int64, where llround has no defined result, and the missing-sample sum overflowed
// (UBSan abort; -2 in a plain build). The count saturates.
TEST(LcmLog, MissingSamplesOfAbsurdGapsSaturate) {
  const auto path = temp_log("absurd_gaps.lcmlog");
  LogWriter writer(path);
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  const std::int64_t stamps[] = {kMin, kMin + 1, kMin + 2, kMin + 3, 0, kMax};
  for (int i = 0; i < 6; ++i) {
    auto m = sample(i, false, false);
    m.utime = stamps[i];
    writer.write("IMU", m);
  }
  writer.close();
  const pipeline::Recording rec = read_lcm_imu_log(path.string(), "IMU");
  EXPECT_EQ(rec.report.timing.gap_count, 2);
  EXPECT_EQ(rec.report.timing.missing_samples, kMax);
}

// Random corruptions of a valid log (fixed seed): every call either succeeds or throws
// InputError; nothing else escapes, nothing crashes (run under the sanitizers too).
TEST(LcmLog, NeverCrashesOnCorruptedBytes) {
  const MixedLog log = mixed_log();
  const Bytes original = read_bytes(log.path);
  std::mt19937_64 rng(20240606);
  const auto path = temp_log("fuzz.lcmlog");
  int accepted = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Bytes bytes = original;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % bytes.size();
      switch (rng() % 3) {
        case 0:
          bytes[at] = static_cast<unsigned char>(rng());
          break;
        case 1:
          bytes[at] ^= static_cast<unsigned char>(1u << (rng() % 8));
          break;
        default:
          bytes.resize(at);
          break;
      }
      if (bytes.empty()) break;
    }
    write_bytes(path, bytes);
    for (const char* channel : {"IMU", "DRIFT", "FOREIGN"}) {
      try {
        (void)read_lcm_imu_log(path.string(), channel);
        ++accepted;
      } catch (const InputError&) {
      }
    }
    try {
      (void)list_lcm_log_channels(path.string());
    } catch (const InputError&) {
    }
  }
  EXPECT_GT(accepted, 0);  // some edits (in IMU values or other channels' data) stay readable
}

// The generated type through the LCM runtime: publish and receive on the in-process memq://
// provider (no network traffic).
// subscribeFunction (a plain function and a context pointer): UBSan flags LCM 1.3.1's
// member-function subscription template (lcm-cpp-impl.hpp) with a null-pointer member access.
void on_imu_sample(const lcm::ReceiveBuffer*, const std::string&, const imunoise::imu_sample_t* m,
                   std::vector<imunoise::imu_sample_t>* received) {
  received->push_back(*m);
}

TEST(LcmMemq, ImuSampleRoundTripsThroughTheRuntime) {
  lcm::LCM lc("memq://");
  ASSERT_TRUE(lc.good());
  std::vector<imunoise::imu_sample_t> received;
  ASSERT_NE(lc.subscribeFunction("IMU", &on_imu_sample, &received), nullptr);
  const auto sent = sample(7, true, true);
  ASSERT_EQ(lc.publish("IMU", &sent), 0);
  EXPECT_GT(lc.handleTimeout(1000), 0);
  ASSERT_EQ(received.size(), 1u);
  const auto& got = received.front();
  EXPECT_EQ(got.utime, sent.utime);
  EXPECT_EQ(got.has_increments, 1);
  EXPECT_EQ(got.has_temperature, 1);
  EXPECT_EQ(got.temperature_degc, sent.temperature_degc);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(got.angular_rate_rad_per_s[a], sent.angular_rate_rad_per_s[a]);
    EXPECT_EQ(got.specific_force_m_per_s2[a], sent.specific_force_m_per_s2[a]);
    EXPECT_EQ(got.delta_angle_rad[a], sent.delta_angle_rad[a]);
    EXPECT_EQ(got.delta_velocity_m_per_s[a], sent.delta_velocity_m_per_s[a]);
  }
  EXPECT_EQ(std::memcmp(test::lcm_encode(got).data(), test::lcm_encode(sent).data(),
                        test::lcm_encode(sent).size()),
            0);
}

}  // namespace
}  // namespace imunoise::io
