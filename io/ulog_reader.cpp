/// @file
/// @brief PX4 ULog reader (see ulog_reader.h for the topics read and the error contract).
#include "io/ulog_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <span>
#include <utility>

#include "common/errors.h"
#include "io/binary_file.h"
#include "io/ulog_format.h"

namespace imunoise::io {
namespace {

constexpr std::uint64_t kHeaderBytes = 16;  // magic 7, version 1, timestamp 8
constexpr std::uint64_t kMessageHead = 3;   // uint16 msg_size, uint8 msg_type
constexpr std::int64_t kNsPerUs = 1000;
constexpr std::string_view kFileKind = "ULog file";
// The largest µs stamp whose ns value fits in int64 (about 292 years after boot).
constexpr std::uint64_t kMaxStampUs = static_cast<std::uint64_t>(INT64_MAX / kNsPerUs);

using Bytes = std::span<const std::uint8_t>;

struct Subscription {
  std::string name;  // the message (format) name
  int multi_id = 0;
  std::int64_t messages = 0;
};

/// The sequential parse of a ULog file.
class UlogFile {
 public:
  explicit UlogFile(const std::string& path) : file_(path) {
    std::vector<std::uint8_t> head;
    file_.read_some(0, kHeaderBytes, head);
    if (head.size() < kUlogMagic.size() ||
        std::string_view(reinterpret_cast<const char*>(head.data()), kUlogMagic.size()) !=
            kUlogMagic) {
      file_.fail(0, "not a ULog file (no \"ULog\" magic)");
    }
    if (head.size() < kHeaderBytes) {
      file_.fail(0, "truncated ULog header: the file has " + std::to_string(head.size()) +
                        " of its 16 bytes");
    }
  }

  const std::string& path() const { return file_.path(); }
  std::uint64_t file_size() const { return file_.size(); }
  const std::vector<Subscription>& subscriptions() const { return subs_; }
  UlogFormats& formats() { return formats_; }
  [[noreturn]] void fail(std::uint64_t offset, const std::string& problem) const {
    file_.fail(offset, problem);
  }

  /// Parses every message; ON_DATA(subscription index, data after the msg_id, offset) for each
  /// data message.
  template <typename OnData>
  void scan(OnData&& on_data) {
    std::map<std::uint16_t, std::size_t> ids;
    std::uint64_t pos = kHeaderBytes;
    while (pos < file_.size()) {
      if (file_.size() - pos < kMessageHead) {
        fail(pos, "truncated message: the file ends " + std::to_string(file_.size() - pos) +
                      " bytes into its 3-byte header");
      }
      const Bytes head = file_.view(pos, kMessageHead, "message header");
      const std::uint16_t size = load_le16(head.data());
      const char type = static_cast<char>(head[2]);
      if (size > file_.size() - pos - kMessageHead) {
        fail(pos, std::string("truncated message '") + printable_bytes(std::string_view(&type, 1)) +
                      "': it needs " + std::to_string(size) + " bytes, the file has " +
                      std::to_string(file_.size() - pos - kMessageHead) + " after its header");
      }
      const Bytes m = file_.view(pos + kMessageHead, size, "message");
      const std::string_view text(reinterpret_cast<const char*>(m.data()), m.size());
      if (type == 'F') {
        if (const std::string e = formats_.add(text); !e.empty()) fail(pos, e);
      } else if (type == 'A') {
        if (m.size() < 4) fail(pos, "a subscription message of " + std::to_string(size) + " bytes");
        Subscription s;
        s.multi_id = m[0];
        s.name = std::string(text.substr(3));
        ids[load_le16(m.data() + 1)] = subs_.size();
        subs_.push_back(std::move(s));
      } else if (type == 'R') {
        if (m.size() >= 2) ids.erase(load_le16(m.data()));
      } else if (type == 'D') {
        if (m.size() < 2) fail(pos, "a data message of " + std::to_string(size) + " bytes");
        const std::uint16_t id = load_le16(m.data());
        const auto it = ids.find(id);
        if (it == ids.end()) {
          fail(pos, "data of msg_id " + std::to_string(id) + ", which no subscription defines");
        }
        ++subs_[it->second].messages;
        on_data(it->second, m.subspan(2), pos);
      } else if (type == 'B') {
        // compat_flags[8], incompat_flags[8], appended_offsets[3]: only bit 0 of the first
        // incompatible byte ("data appended", read here in file order) is known.
        if (m.size() < 16) fail(pos, "a flag-bits message of " + std::to_string(size) + " bytes");
        const bool unknown = (m[8] & 0xFEu) != 0 ||
                             std::any_of(m.begin() + 9, m.begin() + 16, [](auto b) { return b; });
        if (unknown) fail(pos, "the file sets incompatible flags this reader does not know");
      }
      pos += kMessageHead + size;
    }
  }

 private:
  BinaryFile file_;
  UlogFormats formats_;
  std::vector<Subscription> subs_;
};

std::vector<LogTopic> topics_of(const std::vector<Subscription>& subs) {
  std::vector<LogTopic> topics;
  for (const Subscription& s : subs) {
    auto it = std::find_if(topics.begin(), topics.end(), [&](const LogTopic& t) {
      return t.name == s.name && t.instance == s.multi_id;
    });
    if (it == topics.end()) {
      LogTopic t;
      t.name = s.name;
      t.type = s.name;
      t.instance = s.multi_id;
      t.is_imu =
          s.name == "sensor_combined" || s.name == "sensor_gyro" || s.name == "sensor_gyro_fifo";
      topics.push_back(std::move(t));
      it = topics.end() - 1;
    }
    it->message_count += s.messages;
  }
  return topics;
}

/// One sensor's samples: sample time, log time [ns] and x, y, z in SI.
struct Samples {
  std::vector<std::int64_t> t_sample, t_log;
  std::vector<std::array<double, 3>> xyz;
};

/// The fields of one IMU topic, found once per format.
struct Layout {
  const UlogField* timestamp = nullptr;
  const UlogField* timestamp_sample = nullptr;
  std::array<const UlogField*, 3> xyz{};  // x, y, z (or gyro_rad / accelerometer_m_s2 twice)
  const UlogField* accel = nullptr;       // sensor_combined: accelerometer_m_s2
  const UlogField* dt = nullptr;          // FIFO
  const UlogField* scale = nullptr;
  const UlogField* samples = nullptr;
};

Layout layout_of(UlogFile& file, const std::string& name, std::uint64_t offset) {
  std::string error;
  const UlogFormat* format = file.formats().resolve(name, error);
  if (format == nullptr) file.fail(offset, "topic " + quoted_bytes(name) + ": " + error);
  const auto need = [&](std::string_view field, std::string_view type, std::size_t count) {
    const UlogField* f = find_ulog_field(*format, field, type, count, error);
    if (f == nullptr) file.fail(offset, error);
    return f;
  };
  Layout l;
  l.timestamp = need("timestamp", "uint64_t", 1);
  if (name == "sensor_combined") {
    const UlogField* gyro = need("gyro_rad", "float", 3);
    l.xyz = {gyro, gyro, gyro};
    l.accel = need("accelerometer_m_s2", "float", 3);
    return l;
  }
  l.timestamp_sample = need("timestamp_sample", "uint64_t", 1);
  const bool fifo = name.ends_with("_fifo");
  for (std::size_t k = 0; k < 3; ++k) {
    l.xyz[k] =
        need(std::string(1, static_cast<char>('x' + k)), fifo ? "int16_t" : "float", fifo ? 0 : 1);
  }
  if (fifo) {
    l.dt = need("dt", "float", 1);
    l.scale = need("scale", "float", 1);
    l.samples = need("samples", "uint8_t", 1);
  }
  return l;
}

/// Appends the samples of one data message of a sensor_gyro / sensor_accel (FIFO or not) topic.
void append_samples(const Layout& l, Bytes data, std::uint64_t offset, const UlogFile& file,
                    Samples& out) {
  std::uint64_t ts = 0, ts_sample = 0;
  const auto short_message = [&] {
    file.fail(offset, "a data message of " + std::to_string(data.size()) +
                          " bytes is too short for its format");
  };
  if (!read_ulog_u64(data, *l.timestamp, ts) ||
      !read_ulog_u64(data, *l.timestamp_sample, ts_sample)) {
    short_message();
  }
  if (ts > kMaxStampUs || ts_sample > kMaxStampUs) {
    file.fail(offset, "a timestamp beyond " + std::to_string(kMaxStampUs) + " µs");
  }
  const auto t_sample = static_cast<std::int64_t>(ts_sample) * kNsPerUs;
  const auto t_log = static_cast<std::int64_t>(ts) * kNsPerUs;
  if (l.samples == nullptr) {
    std::array<double, 3> v{};
    for (std::size_t k = 0; k < 3; ++k) {
      if (!read_ulog_number(data, *l.xyz[k], 0, v[k])) short_message();
    }
    out.t_sample.push_back(t_sample);
    out.t_log.push_back(t_log);
    out.xyz.push_back(v);
    return;
  }
  double n = 0, dt_us = 0, scale = 0;
  if (!read_ulog_number(data, *l.samples, 0, n) || !read_ulog_number(data, *l.dt, 0, dt_us) ||
      !read_ulog_number(data, *l.scale, 0, scale)) {
    short_message();
  }
  if (!(dt_us >= 0.0 && dt_us <= 1e6)) {
    file.fail(offset,
              "a FIFO message with dt " + std::to_string(dt_us) + " µs (expected 0 to 1 s)");
  }
  const auto count = static_cast<std::size_t>(n);
  if (count > l.xyz[0]->count) {
    file.fail(offset, "a FIFO message of " + std::to_string(count) + " samples, its arrays hold " +
                          std::to_string(l.xyz[0]->count));
  }
  for (std::size_t i = 0; i < count; ++i) {
    std::array<double, 3> v{};
    for (std::size_t k = 0; k < 3; ++k) {
      if (!read_ulog_number(data, *l.xyz[k], i, v[k])) short_message();
      v[k] *= scale;
    }
    // Sample i of n: timestamp_sample is the last one's time.
    const auto back = static_cast<std::int64_t>(static_cast<double>(count - 1 - i) * dt_us *
                                                static_cast<double>(kNsPerUs));
    if (back > t_sample) file.fail(offset, "a FIFO sample before time 0");
    out.t_sample.push_back(t_sample - back);
    out.t_log.push_back(t_log);
    out.xyz.push_back(v);
  }
}

/// Pairs each gyro sample with the accelerometer sample nearest in sample time, within half
/// the median gyro interval, each accelerometer sample used once.
void pair_samples(const Samples& gyro, const Samples& accel, const std::string& path,
                  const std::string& label, ImuSampleCollector& samples) {
  std::vector<std::int64_t> intervals;
  for (std::size_t i = 1; i < gyro.t_sample.size(); ++i) {
    intervals.push_back(gyro.t_sample[i] - gyro.t_sample[i - 1]);
  }
  std::int64_t half = 0;
  if (!intervals.empty()) {
    std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
    half = std::max<std::int64_t>(intervals[intervals.size() / 2] / 2, 0);
  }
  std::size_t j = 0;
  std::size_t paired = 0;
  const auto gap = [](std::int64_t a, std::int64_t b) { return a > b ? a - b : b - a; };
  for (std::size_t i = 0; i < gyro.t_sample.size() && j < accel.t_sample.size(); ++i) {
    const std::int64_t t = gyro.t_sample[i];
    while (j + 1 < accel.t_sample.size() &&
           gap(accel.t_sample[j + 1], t) <= gap(accel.t_sample[j], t)) {
      ++j;
    }
    if (gap(accel.t_sample[j], t) > half) continue;
    ImuMessage m;
    m.stamp_ns = t;
    for (std::size_t k = 0; k < 3; ++k) {
      m.values[k] = gyro.xyz[i][k];
      m.values[3 + k] = accel.xyz[j][k];
    }
    if (const std::string* bad = samples.add(m, gyro.t_log[i])) {
      throw InputError(located_message(path, 0, 0,
                                       label + ": non-finite value in " + *bad +
                                           " (give --drop-non-finite to drop such samples)"));
    }
    ++paired;
    ++j;
  }
  if (paired * 2 < gyro.t_sample.size()) {
    throw InputError(located_message(
        path, 0, 0,
        label + ": only " + std::to_string(paired) + " of " + std::to_string(gyro.t_sample.size()) +
            " gyro samples have an accelerometer sample at the same time (within half the gyro "
            "interval); the two topics do not sample together"));
  }
}

}  // namespace

bool is_ulog_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kUlogMagic.size(), '\0');
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size()))) return false;
  return head == kUlogMagic;
}

std::vector<LogTopic> list_ulog_topics(const std::string& path) {
  UlogFile file(path);
  file.scan([](std::size_t, Bytes, std::uint64_t) {});
  return topics_of(file.subscriptions());
}

pipeline::Recording read_ulog_imu(const std::string& path, const LogReadOptions& options) {
  const std::vector<LogTopic> topics = list_ulog_topics(path);
  LogReadOptions choice = options;
  if (choice.topic == "sensor_accel" || choice.topic == "sensor_accel_fifo") {
    choice.topic = choice.topic == "sensor_accel" ? "sensor_gyro" : "sensor_gyro_fifo";
  }
  if (choice.topic.empty()) {
    const auto combined = std::find_if(topics.begin(), topics.end(), [&](const LogTopic& t) {
      return t.name == "sensor_combined" && t.message_count > 0 &&
             (!options.instance || t.instance == options.instance);
    });
    if (combined != topics.end()) choice.topic = combined->name;
  }
  const LogTopic& topic = select_imu_topic(path, topics, choice, kFileKind);
  const int instance = topic.instance.value_or(0);
  const bool combined = topic.name == "sensor_combined";
  const std::string accel_name = topic.name == "sensor_gyro" ? "sensor_accel" : "sensor_accel_fifo";
  if (!combined && std::none_of(topics.begin(), topics.end(), [&](const LogTopic& t) {
        return t.name == accel_name && t.instance == instance && t.message_count > 0;
      })) {
    throw InputError(located_message(path, 0, 0,
                                     "topic " + quoted_bytes(topic.name) + " instance " +
                                         std::to_string(instance) + " has no " + accel_name +
                                         " of the same instance with messages; " +
                                         describe_log_topics(topics, kFileKind)));
  }

  UlogFile file(path);
  std::map<std::size_t, Layout> layouts;  // per subscription index
  Samples gyro, accel;
  std::array<std::string, 6> fields;
  if (combined) {
    fields = {"sensor_combined.gyro_rad[0]",           "sensor_combined.gyro_rad[1]",
              "sensor_combined.gyro_rad[2]",           "sensor_combined.accelerometer_m_s2[0]",
              "sensor_combined.accelerometer_m_s2[1]", "sensor_combined.accelerometer_m_s2[2]"};
  } else {
    for (std::size_t k = 0; k < 3; ++k) {
      fields[k] = topic.name + "." + std::string(1, static_cast<char>('x' + k));
      fields[3 + k] = accel_name + "." + std::string(1, static_cast<char>('x' + k));
    }
  }
  ImuSampleCollector samples(options, fields, si_imu_units());
  if (combined) samples.reserve(topic.message_count, file.file_size());
  ImuMessage message;
  file.scan([&](std::size_t sub, Bytes data, std::uint64_t offset) {
    const Subscription& s = file.subscriptions()[sub];
    if (s.multi_id != instance) return;
    const bool is_gyro = s.name == topic.name;
    if (!is_gyro && (combined || s.name != accel_name)) return;
    auto it = layouts.find(sub);
    if (it == layouts.end()) it = layouts.emplace(sub, layout_of(file, s.name, offset)).first;
    const Layout& l = it->second;
    if (!combined) {
      append_samples(l, data, offset, file, is_gyro ? gyro : accel);
      return;
    }
    std::uint64_t ts = 0;
    bool ok = read_ulog_u64(data, *l.timestamp, ts);
    for (std::size_t k = 0; k < 3 && ok; ++k) {
      ok = read_ulog_number(data, *l.xyz[0], k, message.values[k]) &&
           read_ulog_number(data, *l.accel, k, message.values[3 + k]);
    }
    if (!ok) {
      file.fail(offset, "a sensor_combined message of " + std::to_string(data.size()) +
                            " bytes is too short for its format");
    }
    if (ts > kMaxStampUs)
      file.fail(offset, "a timestamp beyond " + std::to_string(kMaxStampUs) + " µs");
    message.stamp_ns = static_cast<std::int64_t>(ts) * kNsPerUs;
    if (const std::string* bad = samples.add(message, message.stamp_ns)) {
      file.fail(offset, "non-finite value in sensor_combined." + *bad +
                            " (give --drop-non-finite to drop such messages)");
    }
  });
  const std::string label = topic.name + " instance " + std::to_string(instance);
  if (!combined) pair_samples(gyro, accel, path, label, samples);
  return samples.finish(path, "");
}

}  // namespace imunoise::io
