// libFuzzer target: the bytes as a CSV/TXT table file through io::read_recording and
// io::read_series (io/csv_reader.h). The first byte picks the reader configuration; the rest
// of the input is the file. Only InputError / AnalysisError may escape.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/csv_reader.h"
#include "io/input_config.h"

using namespace imunoise;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fuzz::ScratchFile file("table.csv");
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::string& path = file.write(data + 1, size - 1);

  static constexpr io::Delimiter kDelimiters[] = {io::Delimiter::kAuto, io::Delimiter::kComma,
                                                  io::Delimiter::kTab, io::Delimiter::kSemicolon,
                                                  io::Delimiter::kWhitespace};
  io::InputConfig config;
  const unsigned delimiter = (mode >> 3) % 6;  // 5 = leave unset
  if (delimiter < 5) config.delimiter = kDelimiters[delimiter];
  if ((mode & 0x04) != 0) config.drop_non_finite = true;
  switch (mode & 0x03) {
    case 0:  // automatic: header names (time_s|ms|us|ns, the columns simulate writes)
      break;
    case 1:  // fixed rate, positional gyro and accel columns, rates in deg/s and g
      config.rate_hz = 100.0;
      config.gyro_columns = {"1", "2", "3"};
      config.gyro_unit = io::GyroUnit::kDegPerS;
      config.accel_columns = {"4", "5", "6"};
      config.accel_unit = io::AccelUnit::kG;
      config.gyro_full_scale_rad_per_s = 8.0;
      break;
    case 2:  // time column in ms, angle and velocity increments, one extra column
      config.time_column = "1";
      config.time_unit = io::TimeUnit::kMillisecond;
      config.gyro_columns = {"2", "3", "4"};
      config.gyro_unit = io::GyroUnit::kRadIncrement;
      config.accel_columns = {"5"};
      config.accel_unit = io::AccelUnit::kMPerSIncrement;
      config.extra_columns = {{"temperature", "6"}};
      break;
    default:  // time column in ns (exact integer path), one gyro axis in deg/h
      config.time_column = "1";
      config.time_unit = io::TimeUnit::kNanosecond;
      config.gyro_columns = {"2"};
      config.gyro_unit = io::GyroUnit::kDegPerHour;
      config.accel_full_scale_m_per_s2 = 20.0;
      break;
  }
  fuzz::expect_only_typed_errors("read_recording", [&] { (void)io::read_recording(path, config); });

  io::SeriesReadOptions series;
  series.drop_non_finite = (mode & 0x04) != 0;
  series.read_time = (mode & 0x40) != 0;
  series.column = (mode & 0x80) != 0 ? "2" : "";
  if (delimiter < 5) series.delimiter = kDelimiters[delimiter];
  fuzz::expect_only_typed_errors("read_series", [&] { (void)io::read_series(path, series); });
  return 0;
}
