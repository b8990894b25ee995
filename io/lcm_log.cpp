/// @file
/// @brief LCM event-log reader (see lcm_log.h for the format and the error contract).
#include "io/lcm_log.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <imunoise/allan_curve_t.hpp>
#include <imunoise/drift_prediction_t.hpp>
#include <imunoise/imu_sample_t.hpp>
#include <imunoise/noise_model_t.hpp>
#include <span>
#include <string_view>
#include <system_error>
#include <utility>

#include "common/errors.h"
#include "io/lcm_fingerprint.h"
#include "io/lcm_messages.h"
#include "pipeline/imu_samples.h"

namespace imunoise::io {
namespace {

constexpr std::uint32_t kSyncWord = 0xEDA1DA01u;
constexpr std::uint64_t kHeaderBytes = 28;  // sync 4 + event number 8 + time 8 + lengths 4 + 4
constexpr std::uint64_t kFingerprintBytes = 8;
// LCM itself refuses channel names of 64 bytes or more when publishing; anything far beyond
// that in a log is corruption, not a name.
constexpr std::uint32_t kMaxChannelLength = 4096;

/// Big-endian loads by shifts (no aliasing, no alignment assumption).
std::uint32_t load_be32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}
std::uint64_t load_be64(const unsigned char* p) {
  return (std::uint64_t{load_be32(p)} << 32) | std::uint64_t{load_be32(p + 4)};
}

std::string hex32(std::uint32_t v) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out = "0x";
  for (int shift = 28; shift >= 0; shift -= 4) out.push_back(kDigits[(v >> shift) & 0xFu]);
  return out;
}

/// A channel name fit for a message: printable ASCII kept, other bytes as \xNN.
std::string printable(std::string_view name) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out = "'";
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7F && c != '\\') {
      out.push_back(c);
    } else {
      out.append("\\x").push_back(kDigits[u >> 4]);
      out.push_back(kDigits[u & 0xFu]);
    }
  }
  out.push_back('\'');
  return out;
}

struct KnownType {
  std::uint64_t fingerprint;
  const char* name;
};

/// Our message types (lcmtypes/), by fingerprint.
const std::array<KnownType, 4>& known_types() {
  static const std::array<KnownType, 4> types{{
      {static_cast<std::uint64_t>(imunoise::imu_sample_t::getHash()), "imunoise.imu_sample_t"},
      {static_cast<std::uint64_t>(imunoise::noise_model_t::getHash()), "imunoise.noise_model_t"},
      {static_cast<std::uint64_t>(imunoise::allan_curve_t::getHash()), "imunoise.allan_curve_t"},
      {static_cast<std::uint64_t>(imunoise::drift_prediction_t::getHash()),
       "imunoise.drift_prediction_t"},
  }};
  return types;
}

std::string type_name_of(std::uint64_t fingerprint) {
  for (const KnownType& t : known_types()) {
    if (t.fingerprint == fingerprint) return t.name;
  }
  return {};
}

/// Sequential reader of events. Every length is checked against the file size before any
/// allocation, so a corrupt length cannot make it allocate more than the file holds.
class EventScanner {
 public:
  explicit EventScanner(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    const auto status = std::filesystem::status(path_, ec);
    if (ec || !std::filesystem::exists(status)) fail_plain("cannot open: no such file");
    if (!std::filesystem::is_regular_file(status)) fail_plain("cannot open: not a regular file");
    size_ = std::filesystem::file_size(path_, ec);
    if (ec) fail_plain("cannot read the file size: " + ec.message());
    in_.open(path_, std::ios::binary);
    if (!in_) fail_plain("cannot open for reading");
  }

  const std::string& path() const { return path_; }

  /// Reads the next event; false at the end of the file (after a complete event).
  bool next() {
    if (pos_ == size_) return false;
    offset_ = pos_;
    const std::uint64_t remaining = size_ - pos_;
    std::array<unsigned char, kHeaderBytes> header{};
    const std::uint64_t got = std::min(remaining, kHeaderBytes);
    read_exact(header.data(), got);
    if (got >= 4) {
      const std::uint32_t sync = load_be32(header.data());
      if (sync != kSyncWord) {
        fail("bad sync word " + hex32(sync) + " (expected " + hex32(kSyncWord) + ")" +
             (offset_ == 0 ? ": not an LCM log file" : ": the log is corrupt here"));
      }
    }
    if (got < kHeaderBytes) {
      fail("truncated event: the file ends " + std::to_string(got) + " bytes into the " +
           std::to_string(kHeaderBytes) + "-byte event header");
    }
    event_number_ = static_cast<std::int64_t>(load_be64(header.data() + 4));
    const std::uint32_t channel_length = load_be32(header.data() + 20);
    const std::uint32_t data_length = load_be32(header.data() + 24);
    if (channel_length == 0 || channel_length > kMaxChannelLength) {
      fail("bad channel length " + std::to_string(channel_length) + " (expected 1 to " +
           std::to_string(kMaxChannelLength) + ")");
    }
    if (data_length > size_) {
      fail("data length " + std::to_string(data_length) + " is beyond the file size (" +
           std::to_string(size_) + " bytes)");
    }
    const std::uint64_t body = std::uint64_t{channel_length} + data_length;
    if (body > remaining - kHeaderBytes) {
      fail("truncated event: channel and data need " + std::to_string(body) +
           " bytes after the header, the file has " + std::to_string(remaining - kHeaderBytes));
    }
    channel_.resize(channel_length);
    read_exact(reinterpret_cast<unsigned char*>(channel_.data()), channel_length);
    data_.resize(data_length);
    read_exact(data_.data(), data_length);
    pos_ += kHeaderBytes + body;
    return true;
  }

  std::uint64_t offset() const { return offset_; }
  std::int64_t event_number() const { return event_number_; }
  const std::string& channel() const { return channel_; }
  std::span<const unsigned char> data() const { return data_; }
  /// The fingerprint of the current event's message, if it has 8 bytes.
  std::optional<std::uint64_t> fingerprint() const {
    if (data_.size() < kFingerprintBytes) return std::nullopt;
    return load_be64(data_.data());
  }

  /// InputError "PATH: byte offset N: problem" at the current event.
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(
        located_message(path_, 0, 0, "byte offset " + std::to_string(offset_) + ": " + problem));
  }
  [[noreturn]] void fail_plain(const std::string& problem) const {
    throw InputError(located_message(path_, 0, 0, problem));
  }

 private:
  void read_exact(unsigned char* out, std::uint64_t count) {
    if (count == 0) return;
    in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(count));
    if (static_cast<std::uint64_t>(in_.gcount()) != count) {
      fail("read error: the file ended early (was it changed while being read?)");
    }
  }

  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint64_t pos_ = 0;
  std::uint64_t offset_ = 0;
  std::int64_t event_number_ = 0;
  std::string channel_;
  std::vector<unsigned char> data_;
};

/// Channel statistics gathered while scanning.
class ChannelTally {
 public:
  void add(const std::string& name, std::optional<std::uint64_t> fingerprint) {
    // Consecutive events are mostly on the same channel: try the last one first.
    auto it = last_ < channels_.size() && channels_[last_].name == name
                  ? channels_.begin() + static_cast<std::ptrdiff_t>(last_)
                  : std::find_if(channels_.begin(), channels_.end(),
                                 [&](const LcmLogChannel& c) { return c.name == name; });
    if (it == channels_.end()) {
      LcmLogChannel c;
      c.name = name;
      c.fingerprint = fingerprint;
      if (fingerprint) c.type_name = type_name_of(*fingerprint);
      channels_.push_back(std::move(c));
      it = channels_.end() - 1;
    } else if (it->fingerprint != fingerprint) {
      ++it->other_fingerprint_count;
    }
    ++it->event_count;
    last_ = static_cast<std::size_t>(it - channels_.begin());
  }

  std::vector<LcmLogChannel> take() { return std::move(channels_); }

 private:
  std::vector<LcmLogChannel> channels_;  // few channels: a linear search is fine
  std::size_t last_ = 0;
};

/// Scans the whole log; every event on `channel` must carry `fingerprint` (else "wrong type on
/// channel …: expected EXPECTED, found …") and is passed to on_message(scanner). A channel
/// the log does not hold is an error listing the channels it does.
template <typename OnMessage>
void read_channel(const std::string& path, const std::string& channel, std::uint64_t fingerprint,
                  const std::string& expected, OnMessage on_message) {
  EventScanner scanner(path);
  ChannelTally tally;
  while (scanner.next()) {
    const auto found = scanner.fingerprint();
    tally.add(scanner.channel(), found);
    if (scanner.channel() != channel) continue;
    if (found != fingerprint) {
      std::string text;
      if (found) {
        const std::string name = type_name_of(*found);
        text = "fingerprint " + lcm_fingerprint_text(*found) +
               (name.empty() ? " (not one of imunoise's types)" : " (" + name + ")");
      } else {
        text = "a " + std::to_string(scanner.data().size()) +
               "-byte message, too short for a fingerprint";
      }
      scanner.fail("wrong type on channel " + printable(channel) + ": expected " + expected +
                   ", found " + text);
    }
    on_message(scanner);
  }
  const auto listed = tally.take();
  if (std::none_of(listed.begin(), listed.end(),
                   [&](const LcmLogChannel& c) { return c.name == channel; })) {
    throw InputError(located_message(
        path, 0, 0,
        "channel " + printable(channel) + " not found; " + describe_lcm_log_channels(listed)));
  }
}

/// read_lcm_imu_log for a user's own message type (options.user_type): the same scan, the
/// messages decoded by LcmUserImuDecoder.
pipeline::Recording read_user_type_log(const std::string& path, const std::string& channel,
                                       const LcmReadOptions& options) {
  LcmUserImuDecoder decoder(*options.user_type);
  const std::string expected = decoder.type_name() + " (fingerprint " +
                               lcm_fingerprint_text(decoder.fingerprint()) + ", from " +
                               decoder.definition_path() + ")";
  pipeline::ImuSampleColumns samples = decoder.make_columns();
  std::string error;
  read_channel(path, channel, decoder.fingerprint(), expected, [&](const EventScanner& scanner) {
    if (!decoder.append(scanner.data(), options.drop_non_finite, samples, error)) {
      scanner.fail(error + " (channel " + printable(channel) + ", event number " +
                   std::to_string(scanner.event_number()) + ")");
    }
  });
  return pipeline::recording_from_imu_samples(std::move(samples), path, channel);
}

}  // namespace

std::string only_imu_sample_channel(const std::string& path, std::string_view hint) {
  const std::vector<LcmLogChannel> channels = list_lcm_log_channels(path);
  std::vector<std::string> found;
  for (const LcmLogChannel& c : channels) {
    if (c.type_name == "imunoise.imu_sample_t") found.push_back(c.name);
  }
  if (found.size() == 1) return found.front();
  throw InputError(located_message(
      path, 0, 0,
      std::string(found.empty() ? "no imunoise.imu_sample_t channel"
                                : "several imunoise.imu_sample_t channels") +
          " in this LCM log; " + std::string(hint) + "; " + describe_lcm_log_channels(channels)));
}

std::string describe_lcm_log_channels(const std::vector<LcmLogChannel>& channels) {
  if (channels.empty()) return "the log holds no events";
  std::string out = "the log holds ";
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const LcmLogChannel& c = channels[i];
    if (i > 0) out.append(", ");
    out.append(printable(c.name)).append(" (");
    if (!c.type_name.empty()) {
      out.append(c.type_name);
    } else if (c.fingerprint) {
      out.append("unknown type, fingerprint ").append(lcm_fingerprint_text(*c.fingerprint));
    } else {
      out.append("unknown type, message shorter than a fingerprint");
    }
    out.append(", ")
        .append(std::to_string(c.event_count))
        .append(c.event_count == 1 ? " event)" : " events)");
  }
  return out;
}

std::vector<LcmLogChannel> list_lcm_log_channels(const std::string& path) {
  EventScanner scanner(path);
  ChannelTally tally;
  while (scanner.next()) tally.add(scanner.channel(), scanner.fingerprint());
  return tally.take();
}

pipeline::Recording read_lcm_imu_log(const std::string& path, const std::string& channel,
                                     const LcmReadOptions& options) {
  if (options.user_type) return read_user_type_log(path, channel, options);
  using imunoise::imu_sample_t;
  const auto fingerprint = static_cast<std::uint64_t>(imu_sample_t::getHash());
  const std::string expected_name = "imunoise.imu_sample_t";
  pipeline::ImuSampleColumns samples;
  std::optional<bool> increments;
  const auto on_message = [&](const EventScanner& scanner) {
    const auto data = scanner.data();
    if (data.size() > static_cast<std::size_t>(INT_MAX)) {
      scanner.fail("message of " + std::to_string(data.size()) + " bytes is too large");
    }
    imu_sample_t m{};
    const int decoded = m.decode(data.data(), 0, static_cast<int>(data.size()));
    if (decoded < 0) {
      scanner.fail("the " + std::to_string(data.size()) + "-byte message on channel " +
                   printable(channel) + " does not decode as " + expected_name);
    }
    if (static_cast<std::size_t>(decoded) != data.size()) {
      scanner.fail(std::to_string(data.size() - static_cast<std::size_t>(decoded)) +
                   " trailing bytes after the " + expected_name + " message");
    }
    const bool has_increments = m.has_increments != 0;
    if (!increments) {
      increments = has_increments;
    } else if (*increments != has_increments) {
      scanner.fail(std::string("has_increments is ") + (has_increments ? "true" : "false") +
                   " here but " + (*increments ? "true" : "false") +
                   " in the first message on channel " + printable(channel) +
                   " (a log must use one or the other)");
    }
    std::int64_t bad = 0;
    const std::string bad_field = first_non_finite_field(m, &bad);
    if (!bad_field.empty()) {
      if (!options.drop_non_finite) {
        scanner.fail("non-finite value in " + bad_field + " on channel " + printable(channel) +
                     " (event number " + std::to_string(scanner.event_number()) + ")");
      }
      samples.non_finite_dropped += bad;
      ++samples.rows_dropped;
      return;
    }
    append_imu_sample(m, samples);
  };
  read_channel(path, channel, fingerprint,
               expected_name + " (fingerprint " + lcm_fingerprint_text(fingerprint) + ")",
               on_message);
  return pipeline::recording_from_imu_samples(std::move(samples), path, channel);
}

}  // namespace imunoise::io
