#include "io/lcm_log_writer.h"

#include <array>
#include <stdexcept>

namespace imunoise::io {

namespace {

void put_be32(unsigned char* p, std::uint32_t v) {
  for (int i = 3; i >= 0; --i, v >>= 8) p[i] = static_cast<unsigned char>(v & 0xFFu);
}
void put_be64(unsigned char* p, std::uint64_t v) {
  put_be32(p, static_cast<std::uint32_t>(v >> 32));
  put_be32(p + 4, static_cast<std::uint32_t>(v));
}

}  // namespace

void LcmLogWriter::write(std::string_view channel, std::int64_t timestamp_us,
                         std::span<const unsigned char> data) {
  if (channel.empty() || channel.size() > 4096 || data.size() > 0xFFFFFFFFu) {
    // Callers pass their own channel names and messages: a bad one is a bug, not bad input.
    throw std::invalid_argument("LcmLogWriter: channel of 1 to 4096 bytes and data < 4 GiB");
  }
  // Event header (LCM eventlog format, big-endian): sync, event number, timestamp, lengths.
  std::array<unsigned char, 28> header{};
  put_be32(header.data(), 0xEDA1DA01u);
  put_be64(header.data() + 4, static_cast<std::uint64_t>(next_event_));
  put_be64(header.data() + 12, static_cast<std::uint64_t>(timestamp_us));
  put_be32(header.data() + 20, static_cast<std::uint32_t>(channel.size()));
  put_be32(header.data() + 24, static_cast<std::uint32_t>(data.size()));
  out_.write(reinterpret_cast<const char*>(header.data()), header.size());
  out_.write(channel.data(), static_cast<std::streamsize>(channel.size()));
  out_.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  ++next_event_;
}

}  // namespace imunoise::io
