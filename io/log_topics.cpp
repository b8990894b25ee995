/// @file
/// @brief Topics, options and sample collection of the robotics-log readers (see log_topics.h).
#include "io/log_topics.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/errors.h"
#include "io/binary_file.h"

namespace imunoise::io {
namespace {

std::string topic_label(const LogTopic& t) {
  std::string out = quoted_bytes(t.name);
  if (t.instance) out.append(" instance ").append(std::to_string(*t.instance));
  return out;
}

[[noreturn]] void refuse(const std::string& path, const std::string& problem,
                         const std::vector<LogTopic>& topics, std::string_view file_kind) {
  throw InputError(
      located_message(path, 0, 0,
                      problem + "; give --topic NAME" +
                          (std::any_of(topics.begin(), topics.end(),
                                       [](const LogTopic& t) { return t.instance.has_value(); })
                               ? " (and --instance N)"
                               : "") +
                          "; " + describe_log_topics(topics, file_kind)));
}

}  // namespace

std::string_view time_source_name(TimeSource source) {
  return source == TimeSource::kHeader ? "header" : "log";
}

std::optional<TimeSource> parse_time_source(std::string_view text) {
  if (text == "header") return TimeSource::kHeader;
  if (text == "log") return TimeSource::kLog;
  return std::nullopt;
}

std::string describe_log_topics(const std::vector<LogTopic>& topics, std::string_view file_kind) {
  std::string out = "the " + std::string(file_kind);
  if (topics.empty()) return out + " holds no topics";
  out.append(" holds ");
  for (std::size_t i = 0; i < topics.size(); ++i) {
    const LogTopic& t = topics[i];
    if (i > 0) out.append(", ");
    out.append(topic_label(t))
        .append(" (")
        .append(t.type.empty() ? "unknown type" : printable_bytes(t.type))
        .append(", ")
        .append(std::to_string(t.message_count))
        .append(t.message_count == 1 ? " message)" : " messages)");
  }
  return out;
}

const LogTopic& select_imu_topic(const std::string& path, const std::vector<LogTopic>& topics,
                                 const LogReadOptions& options, std::string_view file_kind) {
  const LogTopic* chosen = nullptr;
  if (options.topic.empty()) {
    // The IMU topics with messages are the candidates.
    std::size_t imu_topics = 0;
    std::size_t empty_imu_topics = 0;
    for (const LogTopic& t : topics) {
      if (!t.is_imu || (options.instance && t.instance != options.instance)) continue;
      if (t.message_count == 0) {
        ++empty_imu_topics;
        continue;
      }
      ++imu_topics;
      chosen = &t;
    }
    if (imu_topics != 1) {
      refuse(path,
             imu_topics > 1         ? std::to_string(imu_topics) + " IMU topics, which one?"
             : empty_imu_topics > 0 ? "no IMU topic with messages"
                                    : "no IMU topic (sensor_msgs/Imu, or a PX4 IMU topic) found",
             topics, file_kind);
    }
  } else {
    std::size_t matches = 0;
    for (const LogTopic& t : topics) {
      if (t.name != options.topic || (options.instance && t.instance != options.instance)) {
        continue;
      }
      ++matches;
      chosen = &t;
    }
    if (matches == 0) {
      refuse(path,
             "topic " + quoted_bytes(options.topic) +
                 (options.instance ? " instance " + std::to_string(*options.instance) : "") +
                 " not found",
             topics, file_kind);
    }
    if (matches > 1) {
      refuse(path, "topic " + quoted_bytes(options.topic) + " has several instances, which one?",
             topics, file_kind);
    }
    if (!chosen->is_imu) {
      refuse(path,
             "topic " + topic_label(*chosen) + " is of type " + quoted_bytes(chosen->type) +
                 ", which imunoise does not read as an IMU",
             topics, file_kind);
    }
  }
  if (chosen->message_count == 0) {
    refuse(path, "topic " + topic_label(*chosen) + " has no messages", topics, file_kind);
  }
  return *chosen;
}

ImuSampleCollector::ImuSampleCollector(const LogReadOptions& options,
                                       const std::array<std::string, 6>& fields,
                                       const std::array<std::string, 6>& units)
    : time_source_(options.time_source), drop_non_finite_(options.drop_non_finite) {
  columns_.source_fields = fields;
  columns_.source_units = units;
}

const std::string* ImuSampleCollector::add(const ImuMessage& message, std::int64_t log_time_ns) {
  int bad = 0;
  std::size_t first_bad = 0;
  for (std::size_t c = 0; c < 6; ++c) {
    if (!std::isfinite(message.values[c])) {
      if (bad++ == 0) first_bad = c;
    }
  }
  if (bad > 0) {
    if (!drop_non_finite_) return &columns_.source_fields[first_bad];
    columns_.non_finite_dropped += bad;
    ++columns_.rows_dropped;
    return nullptr;
  }
  columns_.stamp_ns.push_back(time_source_ == TimeSource::kHeader ? message.stamp_ns : log_time_ns);
  for (std::size_t c = 0; c < 6; ++c) columns_.values[c].push_back(message.values[c]);
  return nullptr;
}

void ImuSampleCollector::reserve(std::int64_t count, std::uint64_t file_bytes) {
  const std::uint64_t bound = file_bytes / 16;
  const std::size_t n =
      count <= 0 ? 0 : static_cast<std::size_t>(std::min(static_cast<std::uint64_t>(count), bound));
  columns_.stamp_ns.reserve(n);
  for (std::vector<double>& v : columns_.values) v.reserve(n);
}

pipeline::Recording ImuSampleCollector::finish(const std::string& path, const std::string& topic) {
  const std::string stamp_name = time_source_ == TimeSource::kHeader ? "header" : "log time";
  return pipeline::recording_from_stamped_samples(std::move(columns_), path, topic, stamp_name);
}

const std::array<std::string, 6>& si_imu_units() {
  static const std::array<std::string, 6> units{"rad/s", "rad/s", "rad/s",
                                                "m/s^2", "m/s^2", "m/s^2"};
  return units;
}

}  // namespace imunoise::io
