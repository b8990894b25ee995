// Tests of io/binary_recording.h: the write → read round trip is bit-identical in every field,
// the written bytes follow docs/binary-format.md (checked byte by byte here, independently of
// the reader), the sampling report equals the CSV reader's for the same data, and every
// corruption of a file is an InputError naming the file and the problem.
#include "io/binary_recording.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "io/csv_reader.h"
#include "io/sampling_report.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using test::error_of;
using test::read_file_bytes;
using ::testing::HasSubstr;

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::uint64_t align64(std::uint64_t x) { return (x + 63) / 64 * 64; }

template <class T>
void put(std::string& bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof value);
}

template <class T>
T get(const std::string& bytes, std::size_t offset) {
  T value{};
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

/// A file built by hand from docs/binary-format.md (not by the writer under test): preamble,
/// JSON text, zero padding to 64, then each column 64-aligned and zero-padded.
std::string hand_made_file(const std::string& json, const std::vector<std::vector<double>>& columns,
                           std::uint32_t version = 1) {
  std::string bytes("\x89IMNB\r\n\x1a", 8);
  bytes.resize(24);
  put<std::uint32_t>(bytes, 8, version);
  put<std::uint32_t>(bytes, 12, 0);
  put<std::uint64_t>(bytes, 16, json.size());
  bytes += json;
  bytes.resize(align64(bytes.size()), '\0');
  for (const auto& column : columns) {
    const std::size_t at = bytes.size();
    bytes.resize(at + align64(column.size() * 8), '\0');
    if (!column.empty()) std::memcpy(bytes.data() + at, column.data(), column.size() * 8);
  }
  return bytes;
}

/// The header of a 4-sample recording with time and two gyro channels, as JSON.
nlohmann::json small_header() {
  return nlohmann::json{{"created_by", "test"},
                        {"source_path", "orig.csv"},
                        {"sample_count", 4},
                        {"sample_period_s", 0.01},
                        {"has_time", true},
                        {"start_time_s", 100.0},
                        {"channels",
                         {{{"name", "gyro_x"},
                           {"unit", "rad/s"},
                           {"source_column", "gx"},
                           {"source_unit", "deg/s"},
                           {"from_increments", false}},
                          {{"name", "gyro_y"},
                           {"unit", "rad/s"},
                           {"source_column", "gy"},
                           {"source_unit", "deg/s"},
                           {"from_increments", false}}}}};
}

const std::vector<std::vector<double>> kSmallColumns{
    {0.0, 0.01, 0.02, 0.03}, {1.0, 2.0, 3.0, 4.0}, {-1.0, -2.0, -3.0, -4.0}};

/// Writes BYTES to a fresh file and returns the InputError of reading it.
std::string read_error(const std::string& bytes, const std::string& name = "bad.imnb") {
  const auto path = test::make_temp_dir("binrec-bad") / name;
  write_bytes(path, bytes);
  const std::string what = error_of([&] { (void)read_binary_recording(path.string()); });
  EXPECT_THAT(what, HasSubstr(path.string()));
  return what;
}

std::string small_file_error(const nlohmann::json& header,
                             const std::vector<std::vector<double>>& columns = kSmallColumns) {
  return read_error(hand_made_file(header.dump(), columns));
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void expect_same_values(const std::vector<double>& a, const std::vector<double>& b,
                        const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(same_bits(a[i], b[i])) << what << " sample " << i << ": " << a[i] << " vs " << b[i];
  }
}

/// A recording with time stamps, the six IMU channels and an extra channel; awkward values
/// (−0, subnormals, extremes) to catch any lossy conversion.
pipeline::Recording awkward_recording(std::size_t n) {
  pipeline::Recording rec;
  rec.source_path = "/data/imu run (1).csv";
  rec.sample_period_s = 0.0025000000000000001;
  rec.start_time_s = 1700000000.123456;
  for (std::size_t i = 0; i < n; ++i) rec.time_s.push_back(static_cast<double>(i) / 400.0);
  const std::vector<double> special{-0.0, 5e-324, -1.7976931348623157e308, 0.1, 1.0 / 3.0};
  for (std::size_t c = 0; c < 6; ++c) {
    pipeline::Channel ch;
    ch.name = pipeline::kImuChannelNames[c];
    ch.kind = pipeline::kImuChannelKinds[c];
    ch.source_column = "column " + std::to_string(c + 2);
    ch.source_unit = c < 3 ? "rad" : "m/s";
    ch.from_increments = true;
    for (std::size_t i = 0; i < n; ++i) {
      ch.values.push_back(i < special.size() && c == 1
                              ? special[i]
                              : std::sin(0.37 * static_cast<double>(i * (c + 1))));
    }
    rec.channels.push_back(ch);
  }
  pipeline::Channel temperature{"temperature", std::nullopt, {}, "temp_degc", "", false};
  for (std::size_t i = 0; i < n; ++i)
    temperature.values.push_back(20.0 + 0.001 * static_cast<double>(i));
  rec.channels.push_back(temperature);
  rec.report.non_finite_dropped = 3;
  rec.report.rows_dropped = 1;
  return rec;
}

void expect_same_recording(const pipeline::Recording& expected, const pipeline::Recording& got) {
  EXPECT_TRUE(same_bits(expected.sample_period_s, got.sample_period_s));
  EXPECT_TRUE(same_bits(expected.start_time_s, got.start_time_s));
  expect_same_values(expected.time_s, got.time_s, "time_s");
  ASSERT_EQ(expected.channels.size(), got.channels.size());
  for (std::size_t c = 0; c < got.channels.size(); ++c) {
    const pipeline::Channel& e = expected.channels[c];
    const pipeline::Channel& g = got.channels[c];
    EXPECT_EQ(e.name, g.name);
    EXPECT_EQ(e.unit(), g.unit());
    EXPECT_EQ(e.source_column, g.source_column);
    EXPECT_EQ(e.source_unit, g.source_unit);
    EXPECT_EQ(e.from_increments, g.from_increments);
    expect_same_values(e.values, g.values, e.name);
  }
  EXPECT_EQ(expected.report.non_finite_dropped, got.report.non_finite_dropped);
  EXPECT_EQ(expected.report.rows_dropped, got.report.rows_dropped);
}

/// sampling_report_to_json without the file lines (a binary file has none).
nlohmann::ordered_json report_without_lines(const pipeline::SamplingReport& report) {
  nlohmann::ordered_json j = sampling_report_to_json(report, "same");
  std::function<void(nlohmann::ordered_json&)> strip = [&](nlohmann::ordered_json& node) {
    if (node.is_object()) {
      node.erase("line");
      for (auto& [key, value] : node.items()) strip(value);
    } else if (node.is_array()) {
      for (auto& value : node) strip(value);
    }
  };
  strip(j);
  return j;
}

TEST(BinaryRecording, RoundTripWithTimeAndExtraChannelIsBitIdentical) {
  const auto path = test::make_temp_dir("binrec") / "rec.imnb";
  const pipeline::Recording rec = awkward_recording(1000);
  write_binary_recording(path.string(), rec);
  const pipeline::Recording back = read_binary_recording(path.string());
  EXPECT_EQ(back.source_path, path.string());
  expect_same_recording(rec, back);
  // The header keeps the original source and says who wrote it.
  const BinaryRecordingHeader header = read_binary_header(path.string());
  EXPECT_EQ(header.source_path, rec.source_path);
  EXPECT_EQ(header.created_by, kBinaryCreatedBy);
  // The report is computed from the stamps as analyze_timing does.
  const pipeline::TimingReport timing = pipeline::analyze_timing(rec.time_s);
  EXPECT_EQ(back.report.samples, 1000);
  EXPECT_TRUE(back.report.timing.has_timestamps);
  EXPECT_EQ(back.report.timing.median_interval_s, timing.median_interval_s);
  EXPECT_EQ(back.report.timing.jitter_rms_s, timing.jitter_rms_s);
  ASSERT_EQ(back.report.channels.size(), 7U);
  EXPECT_EQ(back.report.channels[6].name, "temperature");
  EXPECT_DOUBLE_EQ(back.report.channels[6].max, 20.999);
}

TEST(BinaryRecording, ReportStatesTheHeaderPeriodTheAnalysisUses) {
  // Stamps 0.10, 0.10, 0.11 s apart: the mean interval differs from the median by 3 %. The
  // reader takes the header's period, so the report says "from the mean" only when the header
  // holds the mean.
  pipeline::Recording rec = awkward_recording(300);
  rec.time_s.assign(1, 0.0);
  for (std::size_t i = 1; i < 300; ++i)
    rec.time_s.push_back(rec.time_s.back() + (i % 3 == 0 ? 0.11 : 0.10));
  const pipeline::TimingReport stamps = pipeline::analyze_timing(rec.time_s);
  ASSERT_TRUE(stamps.period_from_mean);
  const auto dir = test::make_temp_dir("binrec_period");
  for (const bool header_is_mean : {false, true}) {
    rec.sample_period_s = header_is_mean ? stamps.mean_interval_s : stamps.median_interval_s;
    const auto path = dir / (header_is_mean ? "mean.imnb" : "median.imnb");
    write_binary_recording(path.string(), rec);
    const pipeline::Recording back = read_binary_recording(path.string());
    EXPECT_EQ(back.sample_period_s, rec.sample_period_s);
    EXPECT_EQ(back.report.timing.sample_period_s, rec.sample_period_s);
    EXPECT_EQ(back.report.timing.period_from_mean, header_is_mean);
    EXPECT_EQ(back.report.timing.rate_hz, 1.0 / rec.sample_period_s);
  }
}

TEST(BinaryRecording, ThreadCountChangesNeitherTheRecordNorTheReport) {
  // Columns are read in parallel (pread, 1 MiB chunks) and the sampling checks run beside the
  // timing checks: 300 000 samples span three chunks per column.
  const auto path = test::make_temp_dir("binrec-threads") / "rec.imnb";
  const pipeline::Recording rec = awkward_recording(300'000);
  write_binary_recording(path.string(), rec);
  BinaryReadOptions options;
  options.threads = 1;
  const pipeline::Recording one = read_binary_recording(path.string(), options);
  expect_same_recording(rec, one);
  const std::string one_report = report_without_lines(one.report).dump();
  for (unsigned threads : {2u, 3u, 8u}) {
    options.threads = threads;
    const pipeline::Recording many = read_binary_recording(path.string(), options);
    expect_same_recording(rec, many);
    EXPECT_EQ(report_without_lines(many.report).dump(), one_report) << threads << " threads";
  }
}

TEST(BinaryRecording, WrittenBytesFollowTheDocumentedLayout) {
  const auto path = test::make_temp_dir("binrec-layout") / "rec.imnb";
  const pipeline::Recording rec = awkward_recording(5);
  write_binary_recording(path.string(), rec);
  const std::string bytes = read_file_bytes(path);
  ASSERT_GE(bytes.size(), 24U);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89IMNB\r\n\x1a", 8));
  EXPECT_EQ(get<std::uint32_t>(bytes, 8), 1U);
  EXPECT_EQ(get<std::uint32_t>(bytes, 12), 0U);
  const auto json_bytes = get<std::uint64_t>(bytes, 16);
  const nlohmann::json header = nlohmann::json::parse(bytes.substr(24, json_bytes));
  EXPECT_EQ(header["sample_count"], 5);
  EXPECT_EQ(header["has_time"], true);
  EXPECT_EQ(header["sample_period_s"].get<double>(), rec.sample_period_s);
  EXPECT_EQ(header["source_path"], rec.source_path);
  ASSERT_EQ(header["channels"].size(), 7U);
  EXPECT_EQ(header["channels"][6]["name"], "temperature");
  EXPECT_EQ(header["channels"][0]["unit"], "rad/s");
  EXPECT_EQ(header["channels"][3]["unit"], "m/s^2");
  const std::uint64_t data = align64(24 + json_bytes);
  const std::uint64_t stride = align64(5 * 8);  // 64
  ASSERT_EQ(bytes.size(), data + 8 * stride);   // time + 7 channels, exactly
  for (std::size_t column = 0; column < 8; ++column) {
    const std::vector<double>& expected =
        column == 0 ? rec.time_s : rec.channels[column - 1].values;
    for (std::size_t i = 0; i < 5; ++i) {
      EXPECT_TRUE(same_bits(get<double>(bytes, data + column * stride + i * 8), expected[i]))
          << "column " << column << " sample " << i;
    }
    for (std::size_t b = 5 * 8; b < stride; ++b) EXPECT_EQ(bytes[data + column * stride + b], 0);
  }
  for (std::size_t b = 24 + json_bytes; b < data; ++b) EXPECT_EQ(bytes[b], 0);
}

TEST(BinaryRecording, HandMadeFileReads) {
  const auto path = test::make_temp_dir("binrec-hand") / "hand.imnb";
  write_bytes(path, hand_made_file(small_header().dump(), kSmallColumns));
  const pipeline::Recording rec = read_binary_recording(path.string());
  EXPECT_EQ(rec.sample_period_s, 0.01);
  EXPECT_EQ(rec.start_time_s, 100.0);
  EXPECT_EQ(rec.time_s, kSmallColumns[0]);
  ASSERT_EQ(rec.channels.size(), 2U);
  EXPECT_EQ(rec.channels[1].name, "gyro_y");
  EXPECT_EQ(rec.channels[1].source_unit, "deg/s");
  EXPECT_EQ(rec.channels[1].values, kSmallColumns[2]);
}

TEST(BinaryRecording, RoundTripFixedRateKeepsTheGivenRate) {
  const auto dir = test::make_temp_dir("binrec-rate");
  const auto csv = dir / "rate.csv";
  test::write_text(csv, "a,b\n1,2\n3,4\n5,6\n");
  InputConfig config;
  config.rate_hz = 3.0;  // 1 / (1/3) is not 3: the rate must be carried, not re-derived
  config.gyro_columns = {"a", "b"};
  const pipeline::Recording rec = read_recording(csv.string(), config);
  ASSERT_TRUE(rec.time_s.empty());
  const auto path = dir / "rate.imnb";
  write_binary_recording(path.string(), rec);
  const pipeline::Recording back = read_binary_recording(path.string());
  expect_same_recording(rec, back);
  EXPECT_TRUE(back.time_s.empty());
  EXPECT_EQ(report_without_lines(back.report), report_without_lines(rec.report));
  EXPECT_EQ(back.report.timing.rate_hz, 3.0);
}

TEST(BinaryRecording, OneSampleRoundTrips) {
  const auto path = test::make_temp_dir("binrec-one") / "one.imnb";
  const pipeline::Recording rec = awkward_recording(1);
  write_binary_recording(path.string(), rec);
  expect_same_recording(rec, read_binary_recording(path.string()));
  EXPECT_EQ(std::filesystem::file_size(path) % 64, 0U);
}

TEST(BinaryRecording, WriterRefusesNoChannelsAndLeavesNoFile) {
  const auto path = test::make_temp_dir("binrec-empty") / "empty.imnb";
  pipeline::Recording rec;
  rec.sample_period_s = 0.01;
  const std::string what = error_of([&] { write_binary_recording(path.string(), rec); });
  EXPECT_THAT(what, HasSubstr(path.string()));
  EXPECT_THAT(what, HasSubstr("at least one channel"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(BinaryRecording, WriterRefusesNonFiniteAndLeavesNoFile) {
  const auto dir = test::make_temp_dir("binrec-nan-write");
  const auto path = dir / "nan.imnb";
  pipeline::Recording rec = awkward_recording(10);
  rec.channels[2].values[7] = std::numeric_limits<double>::quiet_NaN();
  const std::string what = error_of([&] { write_binary_recording(path.string(), rec); });
  EXPECT_THAT(what, HasSubstr("gyro_z sample 7"));
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "no file, no temporary file";
}

TEST(BinaryRecording, WriterLeavesNoFileWhenTheDirectoryIsMissing) {
  const auto dir = test::make_temp_dir("binrec-nodir");
  const auto path = dir / "missing" / "rec.imnb";
  const std::string what =
      error_of([&] { write_binary_recording(path.string(), awkward_recording(3)); });
  EXPECT_THAT(what, HasSubstr(path.string()));
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(BinaryRecording, SamplingReportEqualsTheCsvReadersWithAGap) {
  const auto dir = test::make_temp_dir("binrec-gap");
  const auto csv = dir / "gap.csv";
  std::string text =
      "time_ms,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
      "accel_y_m_per_s2,accel_z_m_per_s2\n";
  const std::vector<double> noise = test::white_noise(600, 1.0, 5);
  std::int64_t t_ms = 5000;
  for (int i = 0; i < 100; ++i) {
    if (i == 60) t_ms += 70;  // a gap of 7 missing samples
    if (i == 80) t_ms -= 20;  // and a step back
    text += std::to_string(t_ms);
    for (int c = 0; c < 6; ++c) {
      // Quantised values so the LSB estimate has something to find.
      // (append, not "," + …: GCC 12 raises a false -Wrestrict on that.)
      text.append(",").append(
          std::to_string(std::round(noise[static_cast<std::size_t>(i * 6 + c)] * 100) / 100));
    }
    text += "\n";
    t_ms += 10;
  }
  test::write_text(csv, text);
  const pipeline::Recording from_csv = read_recording(csv.string(), InputConfig{});
  ASSERT_EQ(from_csv.report.timing.gap_count, 1);
  ASSERT_EQ(from_csv.report.timing.non_monotonic_count, 1);
  const auto bin = dir / "gap.imnb";
  write_binary_recording(bin.string(), from_csv);
  const pipeline::Recording from_bin = read_binary_recording(bin.string());
  expect_same_recording(from_csv, from_bin);
  EXPECT_EQ(report_without_lines(from_bin.report), report_without_lines(from_csv.report));
  // Non-monotonic stamps are reported (as for CSV), not fatal, at the same sample.
  ASSERT_TRUE(from_bin.report.timing.first_non_monotonic.has_value());
  EXPECT_EQ(from_bin.report.timing.first_non_monotonic->index,
            from_csv.report.timing.first_non_monotonic->index);
  EXPECT_EQ(from_bin.report.timing.first_gap->index, 60);
}

TEST(BinaryRecording, FullScaleOptionsReachTheChannelReport) {
  const auto path = test::make_temp_dir("binrec-fs") / "fs.imnb";
  write_binary_recording(path.string(), awkward_recording(50));
  BinaryReadOptions options;
  options.gyro_full_scale_rad_per_s = 0.5;
  const pipeline::Recording rec = read_binary_recording(path.string(), options);
  EXPECT_EQ(rec.report.channels[0].full_scale, 0.5);
  EXPECT_GT(rec.report.channels[0].beyond_full_scale, 0);
  EXPECT_FALSE(rec.report.channels[3].full_scale.has_value());
}

TEST(BinaryRecording, MagicDetection) {
  const auto dir = test::make_temp_dir("binrec-magic");
  write_binary_recording((dir / "a.imnb").string(), awkward_recording(2));
  test::write_text(dir / "b.csv", "time_s,x\n0,1\n");
  EXPECT_TRUE(is_binary_recording_file((dir / "a.imnb").string()));
  EXPECT_FALSE(is_binary_recording_file((dir / "b.csv").string()));
  EXPECT_FALSE(is_binary_recording_file((dir / "none").string()));
}

// ---- corrupt files: each an InputError naming the file and the problem ----

TEST(BinaryRecordingErrors, TruncatedData) {
  std::string bytes = hand_made_file(small_header().dump(), kSmallColumns);
  bytes.resize(bytes.size() - 64);
  const std::string what = read_error(bytes);
  EXPECT_THAT(what, HasSubstr("truncated data"));
  EXPECT_THAT(what, HasSubstr("implies exactly"));
}

TEST(BinaryRecordingErrors, OneByteTooMany) {
  const std::string what = read_error(hand_made_file(small_header().dump(), kSmallColumns) + "x");
  EXPECT_THAT(what, HasSubstr("trailing bytes"));
}

TEST(BinaryRecordingErrors, BadMagic) {
  std::string bytes = hand_made_file(small_header().dump(), kSmallColumns);
  bytes[1] = 'X';
  EXPECT_THAT(read_error(bytes), HasSubstr("byte 0: not an imunoise binary recording (bad magic"));
  EXPECT_THAT(read_error("time_s,gyro_x\n0,1\n"), HasSubstr("bad magic"));
  EXPECT_THAT(read_error(""), HasSubstr("bad magic"));
}

TEST(BinaryRecordingErrors, Version2) {
  const std::string what = read_error(hand_made_file(small_header().dump(), kSmallColumns, 2));
  EXPECT_THAT(what, HasSubstr("byte 8: format version 2 is not supported"));
}

TEST(BinaryRecordingErrors, ShorterThanThePreamble) {
  EXPECT_THAT(read_error(std::string("\x89IMNB\r\n\x1a\x01\0\0", 11)),
              HasSubstr("file ends inside the 24-byte preamble"));
}

TEST(BinaryRecordingErrors, HeaderLengthBeyondTheFile) {
  std::string bytes = hand_made_file(small_header().dump(), kSmallColumns);
  put<std::uint64_t>(bytes, 16, bytes.size());
  EXPECT_THAT(read_error(bytes), HasSubstr("byte 16: JSON header length"));
  put<std::uint64_t>(bytes, 16, std::numeric_limits<std::uint64_t>::max());
  EXPECT_THAT(read_error(bytes), HasSubstr("runs past the end of the file"));
}

TEST(BinaryRecordingErrors, MalformedJson) {
  std::string json = small_header().dump();
  json[json.size() / 2] = '{';
  const std::string what = read_error(hand_made_file(json, kSmallColumns));
  EXPECT_THAT(what, HasSubstr("malformed JSON header"));
  EXPECT_THAT(what, HasSubstr(": byte "));
  EXPECT_THAT(read_error(hand_made_file("[1,2]", kSmallColumns)), HasSubstr("must be an object"));
  // A number beyond double range is nlohmann's out_of_range, not a parse_error.
  EXPECT_THAT(read_error(hand_made_file(R"({"sample_period_s":1e999})", kSmallColumns)),
              HasSubstr("malformed JSON header"));
}

TEST(BinaryRecordingErrors, MissingKey) {
  nlohmann::json h = small_header();
  h.erase("sample_period_s");
  EXPECT_THAT(small_file_error(h), HasSubstr("header key 'sample_period_s': missing"));
  h = small_header();
  h["channels"][1].erase("unit");
  EXPECT_THAT(small_file_error(h), HasSubstr("header key 'channels[1].unit': missing"));
}

TEST(BinaryRecordingErrors, WrongTypesAndValues) {
  nlohmann::json h = small_header();
  h["sample_count"] = -4;
  EXPECT_THAT(small_file_error(h), HasSubstr("'sample_count': expected a non-negative integer"));
  h = small_header();
  h["sample_period_s"] = 0.0;
  EXPECT_THAT(small_file_error(h), HasSubstr("'sample_period_s': must be a finite number > 0"));
  h = small_header();
  h["channels"][0]["unit"] = "deg/s";
  EXPECT_THAT(small_file_error(h), HasSubstr("unknown unit 'deg/s'"));
  h = small_header();
  h["channels"][0]["unit"] = "m/s^2";
  EXPECT_THAT(small_file_error(h), HasSubstr("channel 'gyro_x' must be in \"rad/s\""));
  h = small_header();
  h["channels"][0]["name"] = "";
  EXPECT_THAT(small_file_error(h), HasSubstr("'channels[0].name': must not be empty"));
  h = small_header();
  h["colour"] = "blue";
  EXPECT_THAT(small_file_error(h), HasSubstr("header key 'colour': unknown key"));
  h = small_header();
  h["has_time"] = false;
  EXPECT_THAT(small_file_error(h), HasSubstr("'rate_hz': is required when has_time is false"));
  h = small_header();
  h["channels"] = nlohmann::json::array();
  EXPECT_THAT(small_file_error(h, {{0.0, 0.01, 0.02, 0.03}}),
              HasSubstr("at least one channel is required"));
}

TEST(BinaryRecordingErrors, HugeSampleCountIsRefusedBeforeAnyAllocation) {
  // 2^62 samples × 8 bytes overflows 64 bits; 2^50 does not, and fails the size check. Either
  // would be a bad_alloc (not an InputError) if the reader allocated first.
  nlohmann::json h = small_header();
  h["sample_count"] = std::uint64_t{1} << 62;
  EXPECT_THAT(small_file_error(h), HasSubstr("overflow 64-bit sizes"));
  h["sample_count"] = std::uint64_t{1} << 50;
  EXPECT_THAT(small_file_error(h), HasSubstr("implies exactly"));
  h["sample_count"] = std::numeric_limits<std::uint64_t>::max();
  EXPECT_THAT(small_file_error(h), HasSubstr("overflow"));
}

TEST(BinaryRecordingErrors, DuplicateChannelNames) {
  nlohmann::json h = small_header();
  h["channels"][1]["name"] = "gyro_x";
  EXPECT_THAT(small_file_error(h),
              HasSubstr("header key 'channels[1].name': duplicate channel name 'gyro_x'"));
}

TEST(BinaryRecordingErrors, NanInDataNamesChannelAndSample) {
  auto columns = kSmallColumns;
  columns[2][2] = std::numeric_limits<double>::quiet_NaN();
  const std::string what = small_file_error(small_header(), columns);
  EXPECT_THAT(what, HasSubstr("NaN in channel 'gyro_y' at sample 2"));
  columns = kSmallColumns;
  columns[0][3] = std::numeric_limits<double>::infinity();
  EXPECT_THAT(small_file_error(small_header(), columns), HasSubstr("Inf in 'time_s' at sample 3"));
}

TEST(BinaryRecordingErrors, TheFirstBadColumnInFileOrderIsNamedAtAnyThreadCount) {
  // Columns are read in parallel; the error of the earliest column wins, whatever the sample
  // index or which thread finished first.
  auto columns = kSmallColumns;
  columns[2][0] = std::numeric_limits<double>::quiet_NaN();
  columns[1][3] = -std::numeric_limits<double>::infinity();
  const auto path = test::make_temp_dir("binrec-first-error") / "bad.imnb";
  write_bytes(path, hand_made_file(small_header().dump(), columns));
  for (unsigned threads : {1u, 2u, 3u}) {
    BinaryReadOptions options;
    options.threads = threads;
    const std::string what = error_of([&] { (void)read_binary_recording(path.string(), options); });
    EXPECT_THAT(what, HasSubstr("Inf in channel 'gyro_x' at sample 3")) << threads;
  }
}

TEST(BinaryRecordingErrors, NonZeroPadding) {
  std::string bytes = hand_made_file(small_header().dump(), kSmallColumns);
  bytes[bytes.size() - 1] = 1;  // padding after the last column
  EXPECT_THAT(read_error(bytes), HasSubstr("padding after channel 'gyro_y' must be 0"));
}

TEST(BinaryRecordingErrors, TimeThatNeverIncreases) {
  auto columns = kSmallColumns;
  columns[0] = {0.0, 0.0, 0.0, 0.0};
  EXPECT_THAT(small_file_error(small_header(), columns), HasSubstr("never increase"));
  columns[0] = {1.0, 2.0, 3.0, 4.0};
  EXPECT_THAT(small_file_error(small_header(), columns), HasSubstr("time_s must start at 0"));
}

TEST(BinaryRecordingErrors, MissingFileAndDirectory) {
  const auto dir = test::make_temp_dir("binrec-missing");
  EXPECT_THAT(error_of([&] { (void)read_binary_recording((dir / "none.imnb").string()); }),
              HasSubstr("cannot open"));
  EXPECT_THAT(error_of([&] { (void)read_binary_recording(dir.string()); }),
              HasSubstr("not a regular file"));
}

}  // namespace
}  // namespace imunoise::io
