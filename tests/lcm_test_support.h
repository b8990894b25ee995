/// @file
/// @brief Test helpers for LCM: encode a generated message, and write logs with LCM's own
/// writer (lcm::LogFile, the code lcm-logger uses) — the independent side of the log tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <vector>

namespace imunoise::test {

using LcmBytes = std::vector<unsigned char>;

/// The encoded bytes of a generated LCM message (fingerprint first).
template <typename T>
LcmBytes lcm_encode(const T& message) {
  LcmBytes out(static_cast<std::size_t>(message.getEncodedSize()));
  EXPECT_EQ(message.encode(out.data(), 0, static_cast<int>(out.size())),
            static_cast<int>(out.size()));
  return out;
}

/// Writes a log with lcm::LogFile and records each event's byte offset.
class LcmLogFileWriter {
 public:
  /// Events are stamped `default_timestamp_us` unless write_raw is given a stamp.
  explicit LcmLogFileWriter(const std::filesystem::path& path,
                            std::int64_t default_timestamp_us = 1'700'000'000'000'000)
      : default_timestamp_us_(default_timestamp_us) {
    file_.emplace(path.string(), "w");
    EXPECT_TRUE(file_->good()) << path;
  }
  /// Flushes and closes the file (reading before this may see a partial log).
  void close() { file_.reset(); }
  void write_raw(const std::string& channel, LcmBytes data,
                 std::optional<std::int64_t> timestamp_us = std::nullopt) {
    lcm::LogEvent event{};
    event.eventnum = static_cast<std::int64_t>(offsets_.size());
    event.timestamp = timestamp_us.value_or(default_timestamp_us_);
    event.channel = channel;
    event.datalen = static_cast<std::int32_t>(data.size());
    event.data = data.data();
    ASSERT_TRUE(file_.has_value());
    ASSERT_EQ(file_->writeEvent(&event), 0);
    offsets_.push_back(next_offset_);
    next_offset_ += kEventHeaderBytes + channel.size() + data.size();
  }
  template <typename T>
  void write(const std::string& channel, const T& message,
             std::optional<std::int64_t> timestamp_us = std::nullopt) {
    write_raw(channel, lcm_encode(message), timestamp_us);
  }
  /// Byte offset of event i in the file, and the file size so far.
  std::uint64_t offset(std::size_t i) const { return offsets_.at(i); }
  std::uint64_t size() const { return next_offset_; }

  static constexpr std::uint64_t kEventHeaderBytes = 28;  // sync, number, time, two lengths

 private:
  std::int64_t default_timestamp_us_;
  std::optional<lcm::LogFile> file_;
  std::vector<std::uint64_t> offsets_;
  std::uint64_t next_offset_ = 0;
};

}  // namespace imunoise::test
