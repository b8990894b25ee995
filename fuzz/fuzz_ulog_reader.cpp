// libFuzzer target: the bytes as a PX4 ULog through io::list_ulog_topics and
// io::read_ulog_imu (io/ulog_reader.h): the default topic, a named one, both time
// sources and dropping NaN/Inf (the last topic with its instance: the gyro/accelerometer
// pairing of sensor_gyro(_fifo)). Only InputError / AnalysisError may escape.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/ulog_reader.h"

using namespace imunoise;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fuzz::ScratchFile file("fuzz.ulg");
  const std::string& path = file.write(data, size);
  std::vector<io::LogTopic> topics;
  fuzz::expect_only_typed_errors("list_ulog_topics", [&] { topics = io::list_ulog_topics(path); });
  (void)io::describe_log_topics(topics, "ULog file");
  for (int variant = 0; variant < 3; ++variant) {
    io::LogReadOptions options;
    if (variant == 1 && !topics.empty()) {
      options.topic = topics.back().name;  // e.g. a sensor_accel(_fifo): its gyro pair
      options.instance = topics.back().instance;
    }
    if (variant == 2) {
      options.time_source = io::TimeSource::kLog;
      options.drop_non_finite = true;
    }
    fuzz::expect_only_typed_errors("read_ulog_imu",
                                   [&] { (void)io::read_ulog_imu(path, options); });
  }
  return 0;
}
