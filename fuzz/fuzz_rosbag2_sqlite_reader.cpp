// libFuzzer target: the bytes as a rosbag2 .db3 (SQLite) through io::list_rosbag2_sqlite_topics and
// io::read_rosbag2_sqlite_imu (io/rosbag2_sqlite_reader.h): the default topic, a named one, both
// time sources and dropping NaN/Inf. Only InputError / AnalysisError may escape.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/rosbag2_sqlite_reader.h"

using namespace imunoise;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fuzz::ScratchFile file("fuzz.db3");
  const std::string& path = file.write(data, size);
  std::vector<io::LogTopic> topics;
  fuzz::expect_only_typed_errors("list_rosbag2_sqlite_topics",
                                 [&] { topics = io::list_rosbag2_sqlite_topics(path); });
  (void)io::describe_log_topics(topics, "rosbag2 database");
  for (int variant = 0; variant < 3; ++variant) {
    io::LogReadOptions options;
    if (variant == 1 && !topics.empty()) options.topic = topics.front().name;
    if (variant == 2) {
      options.time_source = io::TimeSource::kLog;
      options.drop_non_finite = true;
    }
    fuzz::expect_only_typed_errors("read_rosbag2_sqlite_imu",
                                   [&] { (void)io::read_rosbag2_sqlite_imu(path, options); });
  }
  return 0;
}
