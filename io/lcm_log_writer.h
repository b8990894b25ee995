/// @file
/// @brief Writer of LCM event logs (the format lcm-logger writes and io/lcm_log.h reads), on
/// any std::ostream — so callers write through io::AtomicOutputFile and a failed run leaves no
/// half-written log. No LCM runtime needed.
#pragma once

#include <cstdint>
#include <ostream>
#include <span>
#include <string_view>

namespace imunoise::io {

/// Appends events with increasing event numbers (from 0).
class LcmLogWriter {
 public:
  explicit LcmLogWriter(std::ostream& out) : out_(out) {}

  /// One event: `channel` (1 to 4096 bytes), the encoded message `data` (starting with its
  /// type's fingerprint), stamped `timestamp_us` (lcm-logger stamps the receive time in µs
  /// since the Unix epoch; lcm-logplayer replays by the differences).
  void write(std::string_view channel, std::int64_t timestamp_us,
             std::span<const unsigned char> data);

  std::int64_t events() const { return next_event_; }

 private:
  std::ostream& out_;
  std::int64_t next_event_ = 0;
};

}  // namespace imunoise::io
